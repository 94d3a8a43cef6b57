//! How one pixel's ray is shown: where it hit and every query it and its shadow ray made.

use super::probe::Probe;
use crate::render::PixelStats;
use crate::traverse::HitMiss;
use crate::Counters;
use egui::Ui;

/// The hovered ray's details; `rendered` is what the frame recorded for that pixel.
pub fn probe_ui(ui: &mut Ui, probe: &Probe, rendered: Option<&PixelStats>) {
    ui.set_max_width(340.0);
    ui.strong(format!("Pixel ({}, {})", probe.pixel.0, probe.pixel.1));
    let [dx, dy, dz] = probe.ray.dir();
    ui.label(format!("direction ({dx:.3}, {dy:.3}, {dz:.3})"));
    hit_ui(ui, probe);
    ui.separator();
    egui::Grid::new("probe queries")
        .num_columns(3)
        .striped(true)
        .show(ui, |ui| {
            ui.label("queries E/N");
            ui.label("primary");
            ui.label("shadow");
            ui.end_row();
            let shadow = probe.shadow.as_ref().map(|s| s.counters);
            for (name, pick) in QUERY_KINDS {
                ui.label(*name);
                ui.label(hit_miss(pick(&probe.primary.counters)));
                ui.label(shadow.map_or("-".into(), |c| hit_miss(pick(&c))));
                ui.end_row();
            }
        });
    if let Some(stats) = rendered {
        ui.label(format!(
            "in the frame: {} blocks, {} runs, {} cells, {} triangles",
            stats.blocks, stats.runs, stats.cells, stats.triangles
        ));
    }
    ui.weak(format!(
        // (Hence fewer block or run queries in the frame than in the table above.)
        "traced again alone in {:.3} ms; with the mipmap or hierarchical runs, the frame's rays start behind their tile's beam",
        probe.elapsed.as_secs_f64() * 1e3
    ));
}

/// Where the ray hit, and what its shadow query found.
fn hit_ui(ui: &mut Ui, probe: &Probe) {
    match &probe.primary.hit {
        Some(hit) => {
            let [x, y, z] = hit.point;
            ui.label(format!("hit at t = {:.4}", hit.t));
            if let Some(exact) = &hit.t_exact {
                let text = exact.to_string();
                let shown = if text.len() > 60 {
                    format!("{}…", &text[..60])
                } else {
                    text
                };
                ui.label(format!("exact t = {shown}"));
            }
            ui.label(format!("point ({x:.3}, {y:.3}, {z:.3})"));
            ui.label(format!(
                "cell ({}, {}), triangle T{}",
                hit.cell[0], hit.cell[1], hit.triangle
            ));
            let shadow = match probe.shadowed() {
                Some(true) => "in shadow",
                Some(false) => "lit (nothing towards the sun)",
                None => "not asked",
            };
            ui.label(format!("shadow query: {shadow}"));
        }
        None => {
            ui.label("miss: the ray leaves the terrain (sky)");
        }
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
