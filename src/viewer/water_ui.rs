//! The Height map panel's water: on or off, its level in the map's height units (metres on a
//! DEM), and its colour.

use super::state::Model;
use super::widgets::named;
use crate::render::effects::Water;
use crate::render::{
    bytes_from_hex, bytes_from_linear, level_in_map_units, level_z, linear_from_bytes,
    DEFAULT_WATER_COLOUR,
};
use egui::{DragValue, Ui};

/// The water checkbox, level and colour, editing the settings' water.
pub fn water_ui(ui: &mut Ui, model: &mut Model) {
    let terrain = model.shown.terrain.clone();
    let field = terrain.field();
    let (lo, hi) = terrain.z_range();
    let mut on = model.settings.effects.water.is_some();
    let checkbox = ui.checkbox(&mut on, "water");
    named(&mut model.widgets, "water", checkbox);
    if !on {
        model.settings.effects.water = None;
        return;
    }
    let mut water = model.settings.effects.water.unwrap_or_else(|| Water {
        // A quarter of the way up the relief floods the valleys.
        level: lo + 0.25 * (hi - lo),
        colour: linear_from_bytes(bytes_from_hex(DEFAULT_WATER_COLOUR).unwrap_or_default()),
    });
    let mut level = level_in_map_units(field, water.level);
    let span = level_in_map_units(field, hi) - level_in_map_units(field, lo);
    // In the map's height unit, as scenes write the level (feet on a map in feet).
    let unit = field
        .georef()
        .map(|g| format!(" {}", g.height_unit.symbol()))
        .unwrap_or_default();
    let mut bytes = bytes_from_linear(water.colour);
    ui.horizontal(|ui| {
        let drag = DragValue::new(&mut level)
            .speed((span * 0.002).max(1e-3))
            .prefix("level ")
            .suffix(unit);
        named(&mut model.widgets, "water_level", ui.add(drag));
        ui.color_edit_button_srgb(&mut bytes);
    });
    water.level = level_z(field, level);
    water.colour = linear_from_bytes(bytes);
    model.settings.effects.water = Some(water);
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
