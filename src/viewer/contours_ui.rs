//! The Height map panel's contour lines: on or off, their interval in the map's height unit
//! (metres on a DEM, as a scene's `[overlay] contours` gives it) and how often an index line
//! comes. The interval stays in the map's unit; the render takes it to grid heights through
//! the field it draws on, so a rescaled relief keeps the lines on the same ground.

use super::state::{ContourControls, Model, Widgets};
use super::widgets::named;
use crate::compact::Compact;
use crate::heightfield::{Heightfield, Quantisation};
use crate::render::{level_in_map_units, level_z, Contours};
use crate::Terrain;
use egui::{DragValue, Ui};

/// About this many lines span a map's relief when the interval is picked for it.
const LINES_OVER_RELIEF: f64 = 20.0;

/// A round interval (1, 2 or 5 times a power of ten) that draws about
/// [`LINES_OVER_RELIEF`] lines over `span` of height, at most that many.
pub fn round_interval(span: f64) -> f64 {
    let share = span / LINES_OVER_RELIEF;
    if !(share.is_finite() && share > 0.0) {
        return 1.0;
    }
    let power = 10f64.powi(share.log10().floor() as i32);
    let step = [5.0, 2.0, 1.0]
        .into_iter()
        .find(|&m| m * power <= share)
        .unwrap_or(1.0);
    step * power
}

/// The span of `terrain`'s heights in its map's height unit.
fn relief_span(terrain: &Terrain) -> f64 {
    let field = terrain.field();
    let (lo, hi) = terrain.z_range();
    level_in_map_units(field, hi) - level_in_map_units(field, lo)
}

/// The unit a map's heights are given in, when it is one a length can be said in: a
/// georeferenced raster of heights. An integer image's heights are fractions of its z scale.
fn height_unit(field: &Heightfield) -> Option<f64> {
    match field.quantisation() {
        Quantisation::Offset { .. } => field.georef().map(|g| g.height_unit.metres),
        Quantisation::Maxval(_) => None,
    }
}

/// Keeps the lines on the same ground after the map on screen changed from `was` (rescaled,
/// or a `new_map` opened without a scene). Lines stay on or off.
pub fn follow_map(model: &mut Model, was: &Heightfield, new_map: bool) {
    let controls = &mut model.widgets.contours;
    if controls.interval > 0.0 {
        let interval = interval_after(controls.interval, was, &model.shown.terrain, new_map);
        if interval != controls.interval {
            controls.set_interval(interval);
        }
    }
}

/// The interval on `now` of lines every `interval` on `was`: a rescaled integer image's
/// heights (its map unit) scale with its z scale, so the interval does too; a new map keeps
/// the interval only when it is in the same unit (100 m means the same on any DEM in metres)
/// and otherwise gets a round one for its relief.
fn interval_after(interval: f64, was: &Heightfield, now: &Terrain, new_map: bool) -> f64 {
    let field = now.field();
    if new_map {
        let unit = height_unit(field);
        if unit.is_some() && unit == height_unit(was) {
            return interval;
        }
        return round_interval(relief_span(now));
    }
    match field.quantisation() {
        Quantisation::Maxval(_) if was.z_scale() > 0.0 => {
            interval * field.z_scale() / was.z_scale()
        }
        _ => interval,
    }
}

/// The contours checkbox, the interval field and the index line count, for lines on
/// `terrain`. Returns why a typed interval was refused.
pub fn contours_ui(ui: &mut Ui, widgets: &mut Widgets, terrain: &Terrain) -> Option<IntervalError> {
    let checkbox = ui
        .checkbox(&mut widgets.contours.on, "contour lines")
        .on_hover_text("lines of equal height, every index-th one wider, as printed maps draw");
    named(widgets, "contours", checkbox);
    if !widgets.contours.on {
        return None;
    }
    if widgets.contours.interval <= 0.0 {
        let picked = round_interval(relief_span(terrain));
        widgets.contours.set_interval(picked);
    }
    let field = terrain.field();
    let unit = field
        .georef()
        .map(|g| format!(" {}", g.height_unit.symbol()))
        .unwrap_or_default();
    let mut refused = None;
    ui.horizontal(|ui| {
        ui.label("every");
        let text = egui::TextEdit::singleline(&mut widgets.contours.text).desired_width(60.0);
        let text = ui.add(text);
        let text = named(widgets, "contour_interval", text);
        ui.label(unit);
        if text.lost_focus() {
            refused = take_interval(&mut widgets.contours, field);
        }
        let index = DragValue::new(&mut widgets.contours.index_every)
            .range(0..=50)
            .prefix("index every ");
        let index = ui
            .add(index)
            .on_hover_text("every this many lines is wider (0: none)");
        named(widgets, "contour_index", index);
    });
    refused
}

/// Takes the typed interval, or shows the one in use again and says why the typed one is
/// refused.
fn take_interval(controls: &mut ContourControls, field: &Heightfield) -> Option<IntervalError> {
    let typed = controls.text.trim();
    // A huge interval in a unit the z scale enlarges may be no finite grid height.
    let taken = parse_interval(typed).and_then(|interval| {
        Contours::new(level_z(field, interval), 0)
            .map(|_| interval)
            .ok_or_else(|| IntervalError::TooLarge(typed.to_owned()))
    });
    match taken {
        Ok(interval) => {
            controls.set_interval(interval);
            None
        }
        Err(message) => {
            let interval = controls.interval;
            controls.set_interval(interval);
            Some(message)
        }
    }
}

/// Why a typed contour interval is refused.
#[derive(Clone, Debug, thiserror::Error, PartialEq)]
pub enum IntervalError {
    /// Zero, negative or infinite.
    #[error("The contour interval must be a finite height above 0, not {}", Compact(*.0))]
    NotAHeight(f64),
    /// Not a number.
    #[error("The contour interval must be a number (a height above 0), not {0:?}")]
    NotANumber(String),
    /// So large that its grid height is not finite.
    #[error("The contour interval {0} is too large for this map")]
    TooLarge(String),
}

/// A contour interval as typed: a finite height above 0.
fn parse_interval(typed: &str) -> Result<f64, IntervalError> {
    match typed.parse::<f64>() {
        Ok(interval) if interval.is_finite() && interval > 0.0 => Ok(interval),
        Ok(interval) => Err(IntervalError::NotAHeight(interval)),
        Err(_) => Err(IntervalError::NotANumber(typed.to_owned())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Heights in metres stored as `value = sample`, shown at half their size: 0 .. 1234 m.
    fn metres_map() -> Heightfield {
        let samples = (0..4 * 4).map(|k| (k * 1234 / 15) as u16).collect();
        let quantisation = Quantisation::Offset {
            lowest: 0.0,
            step: 1.0,
        };
        Heightfield::new(4, 4, samples, quantisation, 0.5, None).expect("a field")
    }

    #[test]
    fn lines_are_at_the_interval_in_the_maps_unit_scaled_to_grid_heights() {
        let mut controls = ContourControls::default();
        controls.adopt(Some((100.0, 4)));
        // 100 m at a z scale of 0.5 is 50 grid units between lines.
        assert_eq!(controls.lines(&metres_map()), Contours::new(50.0, 4));
        assert_eq!(
            controls.scene_keys(&metres_map()).as_deref(),
            Some("contours = 100.0\nindex_every = 4\n")
        );
        controls.on = false;
        assert_eq!(controls.lines(&metres_map()), None);
        assert_eq!(controls.scene_keys(&metres_map()), None);
    }

    #[test]
    fn a_picked_interval_is_round_and_draws_at_most_twenty_lines() {
        let terrain = Terrain::new(metres_map());
        // 1234 m / 20 is 61.7 m: the round step below it is 50 m.
        assert_eq!(relief_span(&terrain), 1234.0);
        assert_eq!(round_interval(1234.0), 50.0);
        assert_eq!(round_interval(30.0), 1.0);
        assert_eq!(round_interval(10.0), 0.5);
        assert_eq!(round_interval(0.0), 1.0);
        assert_eq!(round_interval(f64::NAN), 1.0);
    }

    #[test]
    fn the_interval_follows_a_rescaled_image_and_a_new_map_in_another_unit_gets_its_own() {
        let image =
            Heightfield::from_fn(3, 3, 255, 120.0, |i, j| (i * 100 + j) as u16).expect("a field");
        let halved = Terrain::new(image.with_z_scale(60.0).expect("rescaled"));
        // An image's heights halve with its z scale: lines every 10 of them are every 5.
        assert_eq!(interval_after(10.0, &image, &halved, false), 5.0);
        let metres = Terrain::new(metres_map());
        // Heights in their own unit stay as they are under any z scale.
        let rescaled = Terrain::new(metres_map().with_z_scale(2.0).expect("rescaled"));
        assert_eq!(
            interval_after(100.0, metres.field(), &rescaled, false),
            100.0
        );
        // A new map not in the same unit as a georeferenced one gets 1234 m / 20, made round.
        assert_eq!(interval_after(10.0, &image, &metres, true), 50.0);
    }

    #[test]
    fn a_typed_interval_that_is_not_a_height_above_0_is_refused() {
        assert_eq!(parse_interval("25"), Ok(25.0));
        for typed in ["0", "-5", "inf", "NaN", "", "ten"] {
            let refused = parse_interval(typed).expect_err(typed).to_string();
            assert!(refused.contains("contour interval"), "{refused}");
        }
    }
}
