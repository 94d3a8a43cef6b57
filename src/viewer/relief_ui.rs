//! The height map panel's controls and lines for a georeferenced map: its relief as an
//! exaggeration of true scale, its cells and extent, its heights in metres.

use crate::heightfield::{place, relief, Heightfield};
use crate::Terrain;
use egui::{DragValue, Ui};

/// For a georeferenced map, an exaggeration control that sets the z scale field; whether it
/// changed.
pub fn exaggeration_ui(ui: &mut Ui, z_scale: &mut f64, field: &Heightfield) -> bool {
    let Some(mut exaggeration) = relief::exaggeration_at(field, *z_scale) else {
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
        if let Some(true_z_scale) = relief::true_z_scale(field, exaggeration) {
            *z_scale = true_z_scale;
        }
    }
    changed
}

/// The map's cells, extent and heights in metres (or why its georeferencing is not used).
pub fn georeferencing_ui(ui: &mut Ui, terrain: &Terrain) {
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
