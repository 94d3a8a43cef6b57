//! The Height map panel's water: on or off, its level in the map's height units (metres on a
//! DEM), and its colour.

use super::state::{Model, Widgets};
use super::widgets::named;
use crate::render::effects::Water;
use crate::render::{
    bytes_from_hex, bytes_from_linear, level_in_map_units, level_z, linear_from_bytes,
    DEFAULT_WATER_COLOUR,
};
use crate::Terrain;
use egui::{DragValue, Ui};

/// The water checkbox, level and colour, editing the settings' water over `terrain`.
pub fn water_ui(ui: &mut Ui, water: &mut Option<Water>, widgets: &mut Widgets, terrain: &Terrain) {
    let field = terrain.field();
    let (lo, hi) = terrain.z_range();
    let mut on = water.is_some();
    let checkbox = ui.checkbox(&mut on, "water");
    named(widgets, "water", checkbox);
    if !on {
        *water = None;
        return;
    }
    let mut shown = water.unwrap_or_else(|| Water {
        // A quarter of the way up the relief floods the valleys.
        level: lo + 0.25 * (hi - lo),
        colour: linear_from_bytes(bytes_from_hex(DEFAULT_WATER_COLOUR).unwrap_or_default()),
    });
    let mut level = level_in_map_units(field, shown.level);
    let span = level_in_map_units(field, hi) - level_in_map_units(field, lo);
    // In the map's height unit, as scenes write the level (feet on a map in feet).
    let unit = field
        .georef()
        .map(|g| format!(" {}", g.height_unit.symbol()))
        .unwrap_or_default();
    let mut bytes = bytes_from_linear(shown.colour);
    ui.horizontal(|ui| {
        let drag = DragValue::new(&mut level)
            .speed((span * 0.002).max(1e-3))
            .prefix("level ")
            .suffix(unit);
        named(widgets, "water_level", ui.add(drag));
        ui.color_edit_button_srgb(&mut bytes);
    });
    shown.level = level_z(field, level);
    shown.colour = linear_from_bytes(bytes);
    *water = Some(shown);
}

/// Keeps the water on the same contour of the map on screen after its relief was rescaled
/// from `z_scale_was`: every height scales with the z scale.
pub fn follow_relief(model: &mut Model, z_scale_was: f64) {
    let z_scale = model.shown.terrain.field().z_scale();
    if let Some(water) = &mut model.settings.effects.water {
        if z_scale_was > 0.0 {
            water.level *= z_scale / z_scale_was;
        }
    }
}
