//! How one pixel's ray is shown: where it hit and every query it and its shadow ray made.

use super::probe::Probe;
use crate::heightfield::place;
use crate::render::PixelStats;
use crate::traverse::HitMiss;
use crate::{Counters, Face, Heightfield};
use egui::Ui;

/// The hovered ray's details, compact: where it hit, then a table of its queries (rows that
/// are zero for both rays are left out); `rendered` is what the frame recorded for the pixel,
/// on `field`.
pub fn probe_ui(ui: &mut Ui, probe: &Probe, field: &Heightfield, rendered: Option<&PixelStats>) {
    ui.set_max_width(260.0);
    ui.spacing_mut().item_spacing.y = 2.0;
    hit_ui(ui, probe, field);
    egui::Grid::new("probe queries")
        .num_columns(3)
        .striped(true)
        .show(ui, |ui| {
            ui.strong("queries");
            ui.strong("ray hit / miss");
            ui.strong("shadow");
            ui.end_row();
            let shadow = probe.shadowed().map(|_| probe.sample.secondary);
            for (name, pick) in QUERY_KINDS {
                let own = pick(&probe.sample.primary);
                let other = shadow.map(|c| pick(&c));
                if own.total() + other.map_or(0, |h| h.total()) == 0 {
                    continue;
                }
                ui.label(*name);
                ui.label(hit_miss(own));
                ui.label(other.map_or("-".into(), hit_miss));
                ui.end_row();
            }
        });
    ui.weak("hit: the ray may meet the surface there, so look closer; miss: ruled out");
    if let Some(stats) = rendered {
        // (The same rays as the frame's, each from its wedge's clearance.)
        ui.weak(format!(
            "in the frame: {} blocks, {} runs, {} cells, {} triangles (traced again in {:.2} ms)",
            stats.blocks,
            stats.runs,
            stats.cells,
            stats.triangles,
            probe.elapsed.as_secs_f64() * 1e3
        ));
    }
}

/// Where the ray hit (on a georeferenced map also in map coordinates), and what its shadow
/// query found.
fn hit_ui(ui: &mut Ui, probe: &Probe, field: &Heightfield) {
    let (px, py) = probe.pixel;
    let Some(hit) = &probe.hit else {
        ui.strong(format!(
            "pixel ({px}, {py}): miss, the ray leaves the terrain"
        ));
        return;
    };
    let [x, y, z] = hit.point;
    let shadow = match probe.shadowed() {
        Some(true) => ", in shadow",
        Some(false) => ", lit",
        None => "",
    };
    let what = match hit.face {
        Face::Terrain => format!("cell ({}, {}) T{}", hit.cell[0], hit.cell[1], hit.triangle),
        Face::Wall(side) => format!("the base's {} wall", side.name()),
        Face::Floor => "the base's floor (under no data)".to_owned(),
    };
    ui.strong(format!("pixel ({px}, {py}): {what}{shadow}"));
    ui.label(format!("at ({x:.2}, {y:.2}, {z:.2}), t = {:.4}", hit.t));
    if let Some(position) = place::describe_point(field, hit.point) {
        ui.label(position);
    }
    if let Some(exact) = &hit.t_exact {
        let text = exact.to_string();
        let shown = if text.chars().count() > 40 {
            format!("{}…", text.chars().take(40).collect::<String>())
        } else {
            text
        };
        ui.weak(format!("exact t = {shown}"));
    }
}

/// Picks one kind of query out of the counters.
type Pick = fn(&Counters) -> HitMiss;

/// The four query kinds of the counters ([`Counters`]), by name.
pub const QUERY_KINDS: &[(&str, Pick)] = &[
    ("bbox", |c| c.bbox),
    ("block", |c| c.block),
    ("run", |c| c.run),
    ("cell", |c| c.cell),
    ("triangle", |c| c.triangle),
];

fn hit_miss(h: HitMiss) -> String {
    format!("{} / {}", h.hit, h.miss)
}
