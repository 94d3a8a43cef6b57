//! A small plot beside the table: time per ray against pixels differing from exact, both on
//! log scales (zero differing pixels on a line of its own below one).

use super::measure::{label, ns_per_ray, Measurement};
use super::panel::DIFFERING;
use egui::{Align2, Color32, FontId, Pos2, Rect, Sense, Stroke, Ui, Vec2};

/// Where zero differing pixels sit on the log axis (one pixel is at 0).
const ZERO_AT: f64 = -0.6;

pub fn plot_ui(ui: &mut Ui, measurement: &Measurement) {
    let points: Vec<(String, f64, f64)> = measurement
        .rows
        .iter()
        .map(|row| {
            let differing = if row.differing == 0 {
                ZERO_AT
            } else {
                (row.differing as f64).log10()
            };
            (
                label(row.arith).replace("rational ", ""),
                ns_per_ray(row).max(1.0).log10(),
                differing,
            )
        })
        .collect();
    if points.len() < 2 {
        return;
    }
    // Never wider than the panel: a wider plot would widen it, and so change the view.
    let width = ui.available_width().min(420.0);
    let (response, painter) = ui.allocate_painter(Vec2::new(width, 150.0), Sense::hover());
    let frame = response.rect;
    painter.rect_filled(frame, 3.0, Color32::from_gray(24));
    let area = Rect::from_min_max(
        frame.min + Vec2::new(34.0, 8.0),
        frame.max - Vec2::new(12.0, 30.0),
    );
    let (x_lo, x_hi) = span(points.iter().map(|p| p.1));
    let y_hi = (measurement.rows.first().map_or(1, |r| r.pixels) as f64)
        .log10()
        .max(1.0);
    let at = |x: f64, y: f64| {
        Pos2::new(
            area.left() + area.width() * ((x - x_lo) / (x_hi - x_lo)) as f32,
            area.bottom() - area.height() * ((y - ZERO_AT) / (y_hi - ZERO_AT)) as f32,
        )
    };
    let axis = Stroke::new(1.0, Color32::from_gray(110));
    painter.line_segment([area.left_bottom(), area.right_bottom()], axis);
    painter.line_segment([area.left_bottom(), area.left_top()], axis);
    let font = FontId::proportional(10.0);
    let grey = Color32::from_gray(170);
    let label = |pos: Pos2, align, text: String| painter.text(pos, align, text, font.clone(), grey);
    // The axes' labels, which the points' labels keep clear of.
    let taken = [
        label(
            at(x_lo, ZERO_AT) + Vec2::new(-4.0, 0.0),
            Align2::RIGHT_CENTER,
            "0".into(),
        ),
        label(
            at(x_lo, 0.0) + Vec2::new(-4.0, 0.0),
            Align2::RIGHT_CENTER,
            "1".into(),
        ),
        label(
            at(x_lo, y_hi) + Vec2::new(-4.0, 0.0),
            Align2::RIGHT_CENTER,
            format!("{:.0}", 10f64.powf(y_hi)),
        ),
        label(
            at(x_lo, ZERO_AT) + Vec2::new(0.0, 3.0),
            Align2::LEFT_TOP,
            format!("{:.0} ns", 10f64.powf(x_lo)),
        ),
        label(
            at(x_hi, ZERO_AT) + Vec2::new(0.0, 3.0),
            Align2::RIGHT_TOP,
            format!("{:.0} ns", 10f64.powf(x_hi)),
        ),
        label(
            Pos2::new(area.center().x, frame.bottom() - 2.0),
            Align2::CENTER_BOTTOM,
            "time per ray (log) vs pixels ≠ exact (log)".into(),
        ),
    ];
    // Points that coincide (f64, exact and the fine rationals often do) share one label.
    let mut marks: Vec<(Pos2, String)> = Vec::new();
    for (name, x, y) in &points {
        let p = at(*x, *y);
        painter.circle_filled(p, 3.5, DIFFERING);
        match marks.iter_mut().find(|(q, _)| q.distance(p) < 4.0) {
            Some((_, names)) => *names += &format!(", {name}"),
            None => marks.push((p, name.clone())),
        }
    }
    let galleys: Vec<_> = marks
        .iter()
        .map(|(_, names)| painter.layout_no_wrap(names.clone(), font.clone(), Color32::WHITE))
        .collect();
    let anchors: Vec<(Pos2, Vec2)> = marks
        .iter()
        .zip(&galleys)
        .map(|((p, _), g)| (*p, g.size()))
        .collect();
    for (spot, galley) in place_labels(&anchors, frame, &taken)
        .into_iter()
        .zip(galleys)
    {
        if let Some(spot) = spot {
            painter.galley(spot, galley, Color32::WHITE);
        }
    }
}

/// Where to put each label of `size` next to its point: the first spot around it that stays
/// inside `bounds` and clear of `taken` and of the labels placed before it (`None`: no room,
/// the table has it anyway).
fn place_labels(anchors: &[(Pos2, Vec2)], bounds: Rect, taken: &[Rect]) -> Vec<Option<Pos2>> {
    let mut placed: Vec<Rect> = taken.to_vec();
    anchors
        .iter()
        .map(|&(p, size)| {
            let (right, left) = (5.0, -5.0 - size.x);
            let (above, below) = (-2.0 - size.y, 2.0);
            let offsets = [
                Vec2::new(right, above),
                Vec2::new(right, below),
                Vec2::new(left, above),
                Vec2::new(left, below),
                Vec2::new(right, above - size.y),
                Vec2::new(right, below + size.y),
            ];
            let spot = offsets
                .iter()
                .map(|&offset| Rect::from_min_size(p + offset, size))
                .find(|r| bounds.contains_rect(*r) && placed.iter().all(|q| !q.intersects(*r)))?;
            placed.push(spot);
            Some(spot.min)
        })
        .collect()
}

/// The range of `values` with a margin, never empty.
fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let margin = ((hi - lo) * 0.08).max(0.1);
    (lo - margin, hi + margin)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_do_not_overlap_and_stay_inside() {
        let bounds = Rect::from_min_max(Pos2::ZERO, Pos2::new(200.0, 100.0));
        let size = Vec2::new(40.0, 10.0);
        // Three points close together, one near the right edge.
        let anchors = [
            (Pos2::new(50.0, 50.0), size),
            (Pos2::new(56.0, 52.0), size),
            (Pos2::new(60.0, 48.0), size),
            (Pos2::new(195.0, 50.0), size),
        ];
        // An axis label just below the first point.
        let axis = Rect::from_min_size(Pos2::new(40.0, 52.0), Vec2::new(30.0, 12.0));
        let spots = place_labels(&anchors, bounds, &[axis]);
        let rects: Vec<Rect> = spots
            .iter()
            .zip(&anchors)
            .map(|(spot, (_, size))| Rect::from_min_size(spot.expect("room for each"), *size))
            .collect();
        for (k, a) in rects.iter().enumerate() {
            assert!(bounds.contains_rect(*a), "{a:?}");
            assert!(!a.intersects(axis), "{a:?} covers the axis label");
            for b in &rects[k + 1..] {
                assert!(!a.intersects(*b), "{a:?} and {b:?}");
            }
        }
        // The one at the right edge goes to the left of its point.
        assert!(rects[3].max.x <= 195.0);
    }
}
