//! The height map panel's controls and lines for a georeferenced map: its relief as an
//! exaggeration of true scale, its cells and extent, its heights in metres.

use super::state::Model;
use crate::heightfield::{place, relief};
use egui::{DragValue, Ui};

/// For a georeferenced map, an exaggeration control that sets the z scale; whether it changed.
pub fn exaggeration_ui(ui: &mut Ui, model: &mut Model) -> bool {
    let field = model.shown.terrain.field();
    let Some(mut exaggeration) = relief::exaggeration_at(field, model.widgets.z_scale) else {
        return false;
    };
    let changed = ui
        .add(
            DragValue::new(&mut exaggeration)
                .range(0.0..=1000.0)
                .speed(0.01)
                .prefix("exaggeration x"),
        )
        .on_hover_text("1 shows heights at their true proportion to the map's cells")
        .changed();
    if changed {
        if let Some(z_scale) = relief::true_z_scale(field, exaggeration) {
            model.widgets.z_scale = z_scale;
        }
    }
    changed
}

/// The map's cells, extent and heights in metres (or why its georeferencing is not used).
pub fn georeferencing_ui(ui: &mut Ui, model: &Model) {
    let terrain = &model.shown.terrain;
    let field = terrain.field();
    if let Some(line) = place::describe_georeferencing(field) {
        ui.label(line);
    }
    let (lo, hi) = terrain.z_range();
    if let (Some(lo), Some(hi)) = (
        place::elevation_metres(field, lo),
        place::elevation_metres(field, hi),
    ) {
        ui.label(format!("elevations {lo:.1} .. {hi:.1} m"));
    }
}
