//! The Statistics section: the frame's totals, queries per primary ray, hit/miss ratios,
//! times, pass progress, input latency and the heat-map mode.

use super::probe_ui::QUERY_KINDS;
use super::settings::HeatMode;
use super::state::{StoreFigures, Telemetry, Widgets};
use super::widgets::named;
use super::worker::RenderedFrame;
use crate::render::effects::{Around, Effects, Summary};
use crate::render::{FrameStats, PASS_BLOCKS};
use crate::traverse::{Counters, HitMiss};
use crate::Method;
use egui::Ui;

/// Says what the hit and miss counts are, wherever they are shown.
pub const HIT_MISS: &str = "hit: the query found that the ray may meet the surface in that \
    box, block, run, cell or triangle (and looks closer); miss: it ruled it out";

/// The probe toggle, the heat map chosen under `method`, and the figures of the frame on
/// screen (`latest`) and of the `telemetry`.
pub fn statistics_ui(
    ui: &mut Ui,
    widgets: &mut Widgets,
    (heat, method): (&mut HeatMode, Method),
    latest: Option<&RenderedFrame>,
    telemetry: &Telemetry,
) {
    let probe = ui
        .checkbox(
            &mut widgets.show_probe,
            "probe the ray under the resting pointer",
        )
        .on_hover_text("where it hits, and every query it and its shadow ray make");
    named(widgets, "probe_toggle", probe);
    heat_map_ui(ui, widgets, heat, method);
    store_ui(ui, telemetry.store.as_ref());
    let Some(latest) = latest else {
        ui.label("no frame yet");
        return;
    };
    let frame = &latest.frame;
    let elapsed = latest.elapsed().as_secs_f64();
    let passes = frame.passes_done;
    let label = if let Some(level) = latest.preview {
        format!(
            "pass {passes}/{} over a 1:{} preview while the map is read, {:.0} ms so far",
            PASS_BLOCKS.len(),
            1u64 << level,
            elapsed * 1e3
        )
    } else if frame.complete() {
        format!("complete in {:.0} ms", elapsed * 1e3)
    } else {
        format!(
            "pass {passes}/{}, {:.0} ms so far",
            PASS_BLOCKS.len(),
            elapsed * 1e3
        )
    };
    ui.add(egui::ProgressBar::new(passes as f32 / PASS_BLOCKS.len() as f32).text(label));
    let (done, asked) = latest.samples;
    if asked > 0 {
        let bar = egui::ProgressBar::new(done as f32 / asked as f32);
        let still = match latest.sampling {
            0 => String::new(),
            n => format!(", {n} pixels sampling"),
        };
        ui.add(bar.text(format!("{done} / {asked} samples{still}")));
    }
    let pass_ms: Vec<String> = latest
        .pass_times
        .iter()
        .map(|t| format!("{:.0}", t.as_secs_f64() * 1e3))
        .collect();
    ui.weak(format!("passes ended at {} ms", pass_ms.join(", ")));
    let totals = &frame.totals;
    let rays = totals.primary_rays + totals.shadow_rays;
    ui.label(format!(
        "{:.3} Mrays/s ({} {}), {} x {} pixels",
        rays as f64 / elapsed.max(1e-9) / 1e6,
        latest.job.method,
        latest.job.arith,
        frame.width,
        frame.height
    ));
    if let Some(capped) = telemetry.capped {
        ui.label(capped.to_string());
    }
    ui.label(format!(
        "build {:.1} ms (acceleration data)",
        latest.job.terrain.build_time().as_secs_f64() * 1e3
    ));
    totals_ui(ui, totals);
    queries_ui(ui, totals);
    latency_ui(ui, telemetry);
}

/// The tile store on screen, if the map is one: its size, the memory resident now and at most,
/// and how often a page the walks asked for was in memory (the page cache's hit rate).
pub fn store_ui(ui: &mut Ui, figures: Option<&StoreFigures>) {
    let Some(f) = figures else {
        return;
    };
    ui.label(format!(
        "tile store: {:.3} G samples, {:.2} GB",
        f.samples as f64 / 1e9,
        f.bytes as f64 / 1e9
    ));
    ui.label(format!(
        "resident memory {:.0} MB, peak {:.0} MB (the store's pages {:.0} MB, peak {:.0} MB)",
        f.memory.resident as f64 / 1e6,
        f.memory.peak_resident as f64 / 1e6,
        f.residency.resident as f64 / 1e6,
        f.residency.peak as f64 / 1e6
    ));
    let hits = f.memory.hit_rate().map_or("none yet".to_owned(), |rate| {
        format!("{:.2}% from memory", rate * 100.0)
    });
    ui.label(format!(
        "page faults: {hits} ({} read from disk)",
        f.memory.major_faults
    ))
    .on_hover_text(
        "a page a walk touches that is not mapped yet faults: served from the page cache \
         (the tile cache) or read from the disk",
    );
}

fn totals_ui(ui: &mut Ui, totals: &FrameStats) {
    egui::Grid::new("frame totals")
        .num_columns(2)
        .show(ui, |ui| {
            let percent = |n: u64, of: u64| 100.0 * n as f64 / of.max(1) as f64;
            let rows = [
                ("primary rays", totals.primary_rays.to_string()),
                (
                    "hits",
                    format!(
                        "{} ({:.1}%)",
                        totals.primary_hits,
                        percent(totals.primary_hits, totals.primary_rays)
                    ),
                ),
                (
                    "of which the base",
                    format!(
                        "{} (walls or floor, {:.1}%)",
                        totals.base_hits,
                        percent(totals.base_hits, totals.primary_rays)
                    ),
                ),
                ("shadow rays", totals.shadow_rays.to_string()),
                (
                    "in shadow",
                    format!(
                        "{} ({:.1}%)",
                        totals.shadowed,
                        percent(totals.shadowed, totals.shadow_rays)
                    ),
                ),
                (
                    "skipped: facing away",
                    totals.skipped.facing_away.to_string(),
                ),
                (
                    "skipped: above terrain",
                    totals.skipped.above_terrain.to_string(),
                ),
                (
                    "skipped: no shadow possible",
                    totals.skipped.no_shadow_possible.to_string(),
                ),
            ];
            for (name, value) in rows {
                ui.label(name);
                ui.label(value);
                ui.end_row();
            }
        });
}

/// The heat-map choice; maps the traversal method cannot fill are offered disabled, with why.
fn heat_map_ui(ui: &mut Ui, widgets: &mut Widgets, heat: &mut HeatMode, method: Method) {
    let combo = egui::ComboBox::from_label("heat map")
        .selected_text(heat.label())
        .show_ui(ui, |ui| {
            for mode in HeatMode::ALL {
                let why = mode.unavailable(method);
                let chosen = *heat == mode;
                let item = ui.add_enabled(
                    why.is_none(),
                    egui::Button::selectable(chosen, mode.label()),
                );
                widgets.rects.insert(mode.widget_name(), item.rect);
                if let Some(why) = why {
                    item.on_disabled_hover_text(why);
                } else if item.clicked() {
                    *heat = mode;
                }
            }
        });
    named(widgets, "heat_map", combo.response);
    // Chosen under another method: say why the map is empty rather than show a blank view.
    if let Some(why) = heat.unavailable(method) {
        ui.colored_label(
            egui::Color32::from_rgb(230, 180, 80),
            format!("{why}: this map is empty"),
        );
    }
}

/// Totals, per primary ray and misses per hit of each query kind, primary and shadow together.
fn queries_ui(ui: &mut Ui, totals: &FrameStats) {
    let all = totals.queries();
    let per_ray = |n: u64| n as f64 / totals.primary_rays.max(1) as f64;
    egui::Grid::new("frame queries")
        .num_columns(4)
        .striped(true)
        .show(ui, |ui| {
            // Short headings keep the table inside the panel; hovering explains them.
            let headings = [
                (
                    "query",
                    "the four query kinds, and the camera rays' wedge look-ups",
                ),
                (
                    "total",
                    "queries of the frame, camera and shadow rays together",
                ),
                (
                    "per ray",
                    "per camera (primary) ray, its shadow ray's included",
                ),
                ("miss/hit", HIT_MISS),
            ];
            for (heading, meaning) in headings {
                ui.strong(heading).on_hover_text(meaning);
            }
            ui.end_row();
            // One look-up per camera ray (miss: a certain miss, settled with no walk).
            let wedge: (&str, fn(&Counters) -> HitMiss) = ("wedge", |c| c.wedge);
            for (name, pick) in QUERY_KINDS.iter().chain([&wedge]) {
                let h = pick(&all);
                ui.label(*name);
                ui.label(h.total().to_string());
                ui.label(format!("{:.2}", per_ray(h.total())));
                ui.label(format!("{:.2}", h.miss as f64 / h.hit.max(1) as f64));
                ui.end_row();
            }
        });
}

fn latency_ui(ui: &mut Ui, telemetry: &Telemetry) {
    let latency = &telemetry.latency;
    match (latency.last_ms(), latency.percentiles()) {
        (Some(last), Some((median, p95))) => {
            ui.label(format!(
                "input to first frame: last {last:.1} ms, median {median:.1}, p95 {p95:.1}, max {:.1} ({} moves)",
                latency.max_ms, latency.count
            ));
        }
        _ => {
            ui.weak("input to first frame: drag the view to measure");
        }
    }
}

/// Each kind of ray's share of the frame's rays and of its thread time, where effects cast
/// any or took time, and each effect's counters; the frame was rendered with `asked`.
pub(super) fn effect_shares(ui: &mut egui::Ui, totals: &FrameStats, asked: &Effects) {
    let around = Around {
        asked,
        shadow_rays: totals.shadow_rays,
        settled: totals.skipped.settled(),
    };
    let effects = totals.effects.each(&around);
    let mut kinds = vec![
        ("camera", totals.primary_rays),
        ("shadow", totals.shadow_rays),
    ];
    kinds.extend(effects.iter().map(|e| (e.label, e.rays)));
    let all: u64 = kinds.iter().map(|(_, n)| n).sum();
    let percent = |share: f64| format!("{:.0}%", 100.0 * share);
    let effect_rays: u64 = effects.iter().map(|e| e.rays).sum();
    if effect_rays > 0 && all > 0 {
        let shares: Vec<String> = kinds
            .iter()
            .filter(|(_, n)| *n > 0)
            .map(|(kind, n)| format!("{kind} {}", percent(*n as f64 / all as f64)))
            .collect();
        ui.label(format!("rays: {}", shares.join(", ")));
    }
    if let Some(time) = totals
        .time
        .shares()
        .filter(|t| t.camera < 1.0 || t.later_samples > 0.0)
    {
        let parts = [("camera and shading", time.camera)].into_iter();
        let shares: Vec<String> = parts
            .chain(time.effects.iter().copied())
            .filter(|(_, share)| *share > 0.0)
            .map(|(kind, share)| format!("{kind} {}", percent(share)))
            .collect();
        let label = ui.label(format!("time: {}", shares.join(", ")));
        label.on_hover_text(
            "thread time, measured around each effect's part of every sample; camera and \
             shading is the rest (camera rays, hard shadows, colours)",
        );
        if time.later_samples > 0.0 {
            ui.label(format!(
                "samples after each pixel's first: {} of the time (their effects included)",
                percent(time.later_samples)
            ));
        }
    }
    if effect_rays == 0 {
        return;
    }
    let left_out: Vec<String> = effects
        .iter()
        .filter_map(|e| Some(format!("{} {}", e.label, percent(e.culled?))))
        .collect();
    ui.weak(format!(
        "left out (provably clear or blocked): {}; {} whole sun cones provably clear",
        left_out.join(", "),
        totals.skipped.horizon_clear,
    ));
    for effect in effects.iter().filter(|e| e.rays > 0) {
        counters_ui(ui, effect);
    }
}

/// An effect's counters, by their names in the statistics.
fn counters_ui(ui: &mut Ui, effect: &Summary) {
    let Some(counters) = effect.counters.as_object() else {
        return;
    };
    egui::CollapsingHeader::new(format!("{} counters", effect.label))
        .id_salt(effect.name)
        .show(ui, |ui| {
            egui::Grid::new(effect.name).num_columns(2).show(ui, |ui| {
                for (name, value) in counters {
                    ui.label(name.replace('_', " "));
                    ui.label(value.to_string());
                    ui.end_row();
                }
            });
        });
}
