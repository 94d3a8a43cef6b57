//! The height legend: a vertical bar of the colour ramp in the view's bottom-right corner,
//! labelled with the lowest and highest heights, and sea level where the ramp shows a sea.

use super::settings::HeatMode;
use super::worker::RenderedFrame;
use crate::heightfield::place;
use crate::render::{HeightSpan, Ramp};
use egui::{Align2, Color32, FontId, Rect, Ui, Vec2};

/// Bar width, and the longest the bar grows, in points.
const BAR: Vec2 = Vec2::new(14.0, 150.0);
/// Share of the view's height the bar takes when that is less than its longest.
const BAR_SHARE: f32 = 0.25;
/// Bands the bar is painted in.
const BANDS: usize = 75;
/// Closest two labels may come, in points, before the inner one is left out.
const LABEL_GAP: f32 = 14.0;

/// Draws the legend of the frame on screen (`latest`), except in heat-map mode (`heat` not
/// off), whose own legend the view shows instead.
pub fn height_legend_ui(ui: &Ui, rect: Rect, latest: Option<&RenderedFrame>, heat: HeatMode) {
    let Some(latest) = latest else {
        return;
    };
    // An opaque overlay colours the map instead of the ramp: the legend would explain
    // colours not shown.
    let overlaid = latest
        .job
        .terrain
        .field()
        .drape()
        .is_some_and(|d| d.opacity() >= 1.0);
    if heat != HeatMode::Off || overlaid {
        return;
    }
    let ramp = latest.job.lighting.ramp;
    let span = HeightSpan::of(&latest.job.terrain);
    let painter = ui.painter_at(rect);
    // Small views get a shorter bar, so the legend never hides much of the terrain.
    let size = Vec2::new(BAR.x, (rect.height() * BAR_SHARE).clamp(40.0, BAR.y));
    let bar = Rect::from_min_size(
        rect.right_bottom() - Vec2::new(16.0 + size.x, 24.0 + size.y),
        size,
    );
    let font = FontId::proportional(12.0);
    // A georeferenced map's heights are labelled in metres.
    let metres = place::elevation_metres(latest.job.terrain.field(), 1.0);
    let marks = marks(ramp, span, size.y, metres.unwrap_or(1.0));
    let label_width = marks
        .iter()
        .map(|(_, text)| {
            painter
                .layout_no_wrap(text.clone(), font.clone(), Color32::WHITE)
                .size()
                .x
        })
        .fold(0.0f32, f32::max);
    let title = match metres {
        Some(_) => "height (m)",
        None => "height",
    };
    let title = painter.layout_no_wrap(title.to_owned(), font.clone(), Color32::WHITE);
    // Labels on the bar's left; the title ends over the bar's right edge.
    let left = (bar.left() - label_width - 14.0).min(bar.right() - title.size().x - 8.0);
    let backdrop = Rect::from_min_max(
        egui::pos2(left, bar.top() - 26.0),
        bar.right_bottom() + Vec2::new(8.0, 10.0),
    );
    painter.rect_filled(backdrop, 4.0, Color32::from_black_alpha(170));
    painter.galley(
        bar.right_top() - Vec2::new(title.size().x, 8.0 + title.size().y),
        title,
        Color32::WHITE,
    );
    let HeightSpan { lo, hi, .. } = span;
    for k in 0..BANDS {
        // Band `k` counts from the bottom; its colour is the height at its middle.
        let z = lo + (hi - lo) * (k as f64 + 0.5) / BANDS as f64;
        let [r, g, b] = ramp.display_rgb(z, span);
        let y1 = bar.bottom() - size.y * k as f32 / BANDS as f32;
        let y0 = bar.bottom() - size.y * (k + 1) as f32 / BANDS as f32;
        painter.rect_filled(
            Rect::from_x_y_ranges(bar.x_range(), y0 - 0.5..=y1),
            0.0,
            Color32::from_rgb(r, g, b),
        );
    }
    for (up, text) in marks {
        let y = bar.bottom() - up;
        painter.line_segment(
            [egui::pos2(bar.left() - 4.0, y), egui::pos2(bar.left(), y)],
            egui::Stroke::new(1.0, Color32::WHITE),
        );
        painter.text(
            egui::pos2(bar.left() - 6.0, y),
            Align2::RIGHT_CENTER,
            text,
            font.clone(),
            Color32::WHITE,
        );
    }
}

/// The labelled heights, each as its distance up from the bar's bottom (of `length` points)
/// and its text: the lowest and highest heights, and 0 where the ramp shows a sea, unless it
/// would crowd one of the ends. Labels show heights times `unit` (metres per unit of height on
/// a georeferenced map).
fn marks(ramp: Ramp, span: HeightSpan, length: f32, unit: f64) -> Vec<(f32, String)> {
    let HeightSpan { lo, hi, .. } = span;
    let text = |z: f64| height_text(z * unit, (hi - lo) * unit);
    if hi <= lo {
        return vec![(0.0, text(lo))];
    }
    let mut marks = vec![(0.0, text(lo)), (length, text(hi))];
    if ramp.shows_sea(span) {
        let up = (length as f64 * -lo / (hi - lo)) as f32;
        if up >= LABEL_GAP && up <= length - LABEL_GAP {
            marks.push((up, text(0.0)));
        }
    }
    marks
}

/// A height with as many decimals as the span of heights needs to tell its marks apart.
fn height_text(z: f64, span: f64) -> String {
    let decimals = match span {
        s if s >= 100.0 => 0,
        s if s >= 1.0 => 1,
        s if s >= 0.01 => 3,
        _ => 6,
    };
    // (No "-0" for a height that rounds to zero.)
    let shown = format!("{z:.decimals$}");
    match shown
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        true => shown.trim_start_matches('-').to_owned(),
        false => shown,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sea_level_is_marked_where_it_lies_on_the_bar() {
        let marks = marks(Ramp::Hypsometric, span(-3000.0, 1000.0), 200.0, 1.0);
        assert_eq!(
            marks,
            vec![
                (0.0, "-3000".to_owned()),
                (200.0, "1000".to_owned()),
                (150.0, "0".to_owned())
            ]
        );
        // No sea on a data ramp, nor on a field without negative heights.
        assert_eq!(marks_len(Ramp::Viridis, (-3000.0, 1000.0)), 2);
        assert_eq!(marks_len(Ramp::Terrain, (0.0, 1000.0)), 2);
        // Sea level next to an end is left out rather than written over it.
        assert_eq!(marks_len(Ramp::Terrain, (-1.0, 1000.0)), 2);
    }

    fn marks_len(ramp: Ramp, (lo, hi): (f64, f64)) -> usize {
        marks(ramp, span(lo, hi), 200.0, 1.0).len()
    }

    fn span(lo: f64, hi: f64) -> HeightSpan {
        HeightSpan { lo, hi, shore: 0.5 }
    }

    #[test]
    fn heights_have_the_decimals_their_span_needs() {
        assert_eq!(height_text(1234.56, 4000.0), "1235");
        assert_eq!(height_text(12.345, 20.0), "12.3");
        assert_eq!(height_text(0.1234, 0.5), "0.123");
        assert_eq!(height_text(-0.0001, 0.5), "0.000");
        assert_eq!(height_text(-2.5, 20.0), "-2.5");
    }
}
