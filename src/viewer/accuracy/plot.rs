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
    label(
        at(x_lo, ZERO_AT) + Vec2::new(-4.0, 0.0),
        Align2::RIGHT_CENTER,
        "0".into(),
    );
    label(
        at(x_lo, 0.0) + Vec2::new(-4.0, 0.0),
        Align2::RIGHT_CENTER,
        "1".into(),
    );
    label(
        at(x_lo, y_hi) + Vec2::new(-4.0, 0.0),
        Align2::RIGHT_CENTER,
        format!("{:.0}", 10f64.powf(y_hi)),
    );
    label(
        at(x_lo, ZERO_AT) + Vec2::new(0.0, 3.0),
        Align2::LEFT_TOP,
        format!("{:.0} ns", 10f64.powf(x_lo)),
    );
    label(
        at(x_hi, ZERO_AT) + Vec2::new(0.0, 3.0),
        Align2::RIGHT_TOP,
        format!("{:.0} ns", 10f64.powf(x_hi)),
    );
    label(
        Pos2::new(area.center().x, frame.bottom() - 2.0),
        Align2::CENTER_BOTTOM,
        "time per ray (log) against pixels ≠ exact (log)".into(),
    );
    for (name, x, y) in &points {
        let p = at(*x, *y);
        painter.circle_filled(p, 3.5, DIFFERING);
        painter.text(
            p + Vec2::new(5.0, -2.0),
            Align2::LEFT_BOTTOM,
            name,
            font.clone(),
            Color32::WHITE,
        );
    }
}

/// The range of `values` with a margin, never empty.
fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let margin = ((hi - lo) * 0.08).max(0.1);
    (lo - margin, hi + margin)
}
