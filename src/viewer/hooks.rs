//! Screenshots, and what scripted tests read: a JSON report of the window's state, written
//! after every presented frame. The window, event loop and drawing are the interactive ones.

use super::accuracy::{ns_per_ray, AccuracyState, MeasureState};
use super::compose::PixelRect;
use super::state::{Decoding, Model};
use crate::heightfield::relief;
use crate::output_file::{self, FileError, SaveError};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// The test and automation hooks asked for on the command line.
#[derive(Clone, Debug, Default)]
pub struct Hooks {
    /// Quit after this many converged frames (all passes) have been presented.
    pub exit_after_frames: Option<u64>,
    /// With `exit_after_frames`: where the window's last frame is saved on exit.
    pub screenshot: Option<PathBuf>,
    /// Where to write the state report after each presented frame.
    pub report_state: Option<PathBuf>,
}

/// Counts the application keeps for the report.
#[derive(Clone, Debug, Default)]
pub struct Counts {
    pub frames_presented: u64,
    pub converged_frames: u64,
    pub submitted_generation: u64,
    pub x11_window: Option<u64>,
    pub view_rect: Option<PixelRect>,
    pub last_screenshot: Option<PathBuf>,
    pub busy: bool,
}

/// Saves 0x00RRGGBB pixels as a PNG, atomically.
pub fn save_png(pixels: &[u32], width: u32, height: u32, path: &Path) -> Result<(), SaveError> {
    output_file::save_rgb(path, pixels, (width, height))
}

/// Writes the report atomically (a reader never sees half a file).
pub fn write_report(path: &Path, model: &Model, counts: &Counts) -> Result<(), ReportError> {
    let text = serde_json::to_string_pretty(&report(model, counts))?;
    Ok(output_file::write_bytes(path, (text + "\n").as_bytes())?)
}

/// Why the state report could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// It would not encode as JSON.
    #[error("cannot encode the state report: {0}")]
    Encode(#[from] serde_json::Error),
    /// The file could not be written.
    #[error(transparent)]
    File(#[from] FileError),
}

fn report(model: &Model, counts: &Counts) -> Value {
    let orbit = &model.orbit;
    let field = model.shown.terrain.field();
    let latency = &model.telemetry.latency;
    let percentiles = latency.percentiles();
    json!({
        "frames_presented": counts.frames_presented,
        "converged_frames": counts.converged_frames,
        "submitted_generation": counts.submitted_generation,
        "rendering": counts.busy,
        "x11_window": counts.x11_window,
        "window_size": [model.window_size.0, model.window_size.1],
        "scale_factor": model.scale_factor,
        "view_rect": counts.view_rect.map(|r| [r.x, r.y, r.width, r.height]),
        "capped": model.telemetry.capped.map(|c| json!({
            "render": [c.render.0, c.render.1], "shown": [c.shown.0, c.shown.1],
            "text": c.to_string(),
        })),
        "frame": frame_report(model),
        "camera": {
            "yaw_deg": orbit.yaw_deg, "pitch_deg": orbit.pitch_deg, "distance": orbit.distance,
            "fov_y_deg": orbit.fov_y_deg, "target": orbit.target, "eye": orbit.eye().to_array(),
            "framed": model.framed.is_some(),
        },
        "sun": {
            "azimuth_deg": model.settings.sun_azimuth_deg,
            "elevation_deg": model.settings.sun_elevation_deg,
            "direction": model.settings.sun(),
            "clock": model.sun_clock.on.then(|| model.sun_clock.time_key()),
        },
        "lighting": lighting_report(model),
        "method": model.settings.method.to_string(),
        "export": {
            "folder": model.export.folder(), "running": model.export.running,
            "saved": model.export.saved, "last": model.export.last,
            "scene": model.export.last_scene,
        },
        "flythrough": {
            "keys": model.flythrough.keys.len(), "playing": model.flythrough.playing(),
        },
        "shadows": model.settings.shadows,
        "arith": model.settings.arith().to_string(),
        "accuracy": accuracy_report(&model.accuracy),
        "terrain": {
            "name": model.shown.source.label(), "width": field.width(), "height": field.height(),
            "z_scale": field.z_scale(), "nodata_count": field.nodata_count(),
            "exaggeration": relief::exaggeration(field), "cell_metres": field.cell_metres(),
            "decoded_as": decoding_report(model.shown.decoding),
            "overlay": field.drape().map(|d| d.path().display().to_string()),
        },
        "contours": {
            "on": model.widgets.contours.on, "interval": model.widgets.contours.interval,
            "index_every": model.widgets.contours.index_every,
        },
        "decoding": decoding_report(model.widgets.decoding),
        "path_field": model.widgets.path_text,
        "loading": model.telemetry.progress.as_ref().map(|p| p.label.clone()),
        "error": model.error,
        "notice": model.notice.as_ref().map(|n| n.text.clone()),
        "drop_hover": model.drop_hover,
        "panels_visible": model.widgets.panels_visible,
        "help_open": model.widgets.help_open,
        "show_probe": model.widgets.show_probe,
        "probe": model.probe.as_ref().map(|p| [p.pixel.0, p.pixel.1]),
        "heat_map": model.settings.heat.label(),
        "widgets": widget_report(model),
        "latency_ms": {
            "count": latency.count, "last": latency.last_ms(), "max": latency.max_ms,
            "median": percentiles.map(|p| p.0), "p95": percentiles.map(|p| p.1),
            "recent": latency.recent().collect::<Vec<_>>(),
        },
        "redraw_ms": {
            "last": model.telemetry.redraw.last_ms(), "max": model.telemetry.redraw.max_ms,
            "median": model.telemetry.redraw.percentiles().map(|p| p.0),
            "p95": model.telemetry.redraw.percentiles().map(|p| p.1),
        },
        "last_screenshot": counts.last_screenshot,
        "store": store_report(model),
    })
}

/// The tile store on screen: its size, the memory resident and the page faults.
fn store_report(model: &Model) -> Option<Value> {
    let s = model.telemetry.store?;
    Some(json!({
        "samples": s.samples, "bytes": s.bytes, "resident": s.memory.resident,
        "peak_resident": s.memory.peak_resident, "store_resident": s.residency.resident,
        "minor_faults": s.memory.minor_faults, "major_faults": s.memory.major_faults,
    }))
}

/// The frame on screen: size, passes, times and ray counts.
fn frame_report(model: &Model) -> Option<Value> {
    let latest = model.latest.as_ref()?;
    let pass_ms: Vec<f64> = latest
        .pass_times
        .iter()
        .map(|t| t.as_secs_f64() * 1e3)
        .collect();
    Some(json!({
        "generation": latest.generation,
        "width": latest.frame.width,
        "height": latest.frame.height,
        "passes_done": latest.frame.passes_done,
        "preview_level": latest.preview,
        "complete": latest.frame.complete(),
        "elapsed_ms": latest.elapsed().as_secs_f64() * 1e3,
        "pass_ms": pass_ms,
        "primary_rays": latest.frame.totals.primary_rays,
        "shadow_rays": latest.frame.totals.shadow_rays,
    }))
}

/// The measurement's table and the comparison's count.
fn accuracy_report(state: &AccuracyState) -> Value {
    let measure = &state.measure;
    let rows: Vec<Value> = measure
        .measurement()
        .map(|m| {
            m.rows
                .iter()
                .map(|r| {
                    json!({
                        "arith": r.arith.to_string(), "ns_per_ray": ns_per_ray(r),
                        "differing": r.differing, "pixels": r.pixels,
                    })
                })
                .collect()
        })
        .unwrap_or_default();
    let fraction = match measure {
        MeasureState::Running {
            report: Some(r), ..
        } => Some(r.fraction),
        _ => None,
    };
    let stale = state.measured_elsewhere();
    let comparison = state.comparison_shown();
    json!({
        "measure": {
            "state": measure.label(), "fraction": fraction, "stale": stale,
            "size": measure.measurement().map(|m| [m.size.0, m.size.1]), "rows": rows,
        },
        "compare": {
            "on": state.compare_on,
            "state": state.compare.label(),
            "differing": comparison.map(|c| c.differing),
            "pixels": comparison.map(|c| c.pixels),
            "generation": comparison.map(|c| c.generation),
        },
    })
}

/// Named widgets' rectangles in window pixels: x0, y0, x1, y1.
fn widget_report(model: &Model) -> serde_json::Map<String, Value> {
    let ppp = model.pixels_per_point;
    model
        .widgets
        .rects
        .iter()
        .map(|(name, r)| {
            let physical = [r.min.x, r.min.y, r.max.x, r.max.y].map(|v| f64::from(v * ppp));
            ((*name).to_owned(), json!(physical))
        })
        .collect()
}

/// Everything a scene file's `[sun]`, `[effects]` and `[shading]` say.
fn lighting_report(model: &Model) -> Value {
    let lighting = model.settings.lighting();
    json!({
        "intensity": lighting.intensity, "ambient": lighting.ambient,
        "shadows": lighting.shadows, "fog": lighting.fog,
        "normals": format!("{:?}", lighting.normals).to_lowercase(),
        "ramp": format!("{:?}", lighting.ramp).to_lowercase(),
    })
}

fn decoding_report(decoding: Decoding) -> Value {
    json!({ "colour": decoding.colour.to_string(), "nodata": decoding.nodata.to_string() })
}
