//! The 3D view: an egui widget over the rendered terrain that turns drags, the wheel and
//! double-clicks into camera moves (so panels and the orbit never fight over the pointer),
//! probes the hovered pixel, and draws the overlays (legend, messages, drop hint).

use super::compose::{self, HeatScale};
use super::model::Model;
use super::navigation;
use super::probe::Probe;
use super::settings::HeatMode;
use crate::render::PASS_BLOCKS;
use crate::TraceOptions;
use egui::{Align2, Color32, Id, Pos2, Rect, Sense, Ui, Vec2};
use std::time::Duration;

/// How long a notice stays up.
pub const NOTICE_TIME: Duration = Duration::from_secs(4);

/// Shows the view in the space left by the panels; returns its rectangle in points.
pub fn view_ui(ui: &mut Ui, model: &mut Model) -> Rect {
    let rect = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    camera_input(ui, &response, model, rect);
    if response.double_clicked() {
        if let Some(pos) = response.interact_pointer_pos() {
            retarget(ui, model, rect, pos);
        }
    }
    let dragging = response.dragged() || response.is_pointer_button_down_on();
    model.view_held = dragging;
    match response.hover_pos() {
        Some(pos) if model.show_probe && !dragging && !model.drop_hover => {
            if rested(ui, model, pos) {
                hover_probe(ui, model, rect, pos);
            } else {
                model.probe = None;
            }
        }
        _ => {
            model.probe = None;
            model.pointer_rest = None;
        }
    }
    if model.latest.is_none() {
        ui.painter().text(
            rect.center(),
            Align2::CENTER_CENTER,
            "rendering…",
            egui::FontId::proportional(18.0),
            Color32::GRAY,
        );
    }
    status_ui(ui, model, rect);
    super::legend::height_legend_ui(ui, rect, model);
    messages_ui(ui, model, rect);
    if model.drop_hover {
        drop_hint_ui(ui, rect);
    }
    if !model.panels_visible {
        let hint = corner_text(ui, rect, Align2::RIGHT_TOP, "H: show panel   F1: help");
        model.widget_rects.insert("show_panel_hint", hint);
    }
    if model.help_open {
        help_ui(ui, model);
    }
    rect
}

/// Orbit (left drag), pan (right or middle drag, or shift + left drag), zoom towards the point
/// under the pointer (wheel); then the framed view follows the view's shape and the camera
/// stays above the ground.
fn camera_input(ui: &Ui, response: &egui::Response, model: &mut Model, rect: Rect) {
    use egui::PointerButton::{Middle, Primary, Secondary};
    let delta = response.drag_delta();
    let shift = ui.input(|i| i.modifiers.shift);
    let delta_f64 = (f64::from(delta.x), f64::from(delta.y));
    if delta != Vec2::ZERO {
        if response.dragged_by(Primary) && !shift {
            model.orbit.rotate(delta_f64.0, delta_f64.1);
        } else if response.dragged_by(Secondary)
            || response.dragged_by(Middle)
            || response.dragged_by(Primary)
        {
            model
                .orbit
                .pan(delta_f64.0, delta_f64.1, f64::from(rect.height()));
        }
    }
    if response.hovered() {
        let steps: f32 = ui.input(|i| {
            i.events
                .iter()
                .map(|event| match event {
                    egui::Event::MouseWheel { unit, delta, .. } => match unit {
                        egui::MouseWheelUnit::Point => delta.y / 50.0,
                        egui::MouseWheelUnit::Line => delta.y,
                        egui::MouseWheelUnit::Page => delta.y * 10.0,
                    },
                    _ => 0.0,
                })
                .sum()
        });
        if let (true, Some(pos)) = (steps != 0.0, response.hover_pos()) {
            match terrain_under(ui, model, rect, pos) {
                Some(point) => model.orbit.zoom_towards(point, f64::from(steps)),
                // Over the sky: towards the target, not up into the air.
                None => model.orbit.zoom(f64::from(steps)),
            }
        }
    }
    let aspect = f64::from(rect.width()) / f64::from(rect.height());
    navigation::settle(model, aspect);
}

/// The terrain point under `pos` in the current camera (not the frame on screen, which may
/// lag behind it), if the pointer is over the terrain.
fn terrain_under(ui: &Ui, model: &Model, rect: Rect, pos: Pos2) -> Option<[f64; 3]> {
    let ppp = ui.ctx().pixels_per_point();
    let physical = compose::physical_rect(rect, ppp);
    let size = (physical.width.max(1), physical.height.max(1));
    let pixel = (
        (((pos.x - rect.min.x) * ppp).max(0.0) as u32).min(size.0 - 1),
        (((pos.y - rect.min.y) * ppp).max(0.0) as u32).min(size.1 - 1),
    );
    let terrain = &model.shown.terrain;
    let camera = model.orbit.camera(size).ok()?;
    let ray = camera
        .in_grid(terrain.world_from_grid())
        .ray(pixel.0, pixel.1);
    let options = TraceOptions::new(model.settings.method, crate::Arith::F64);
    let hit = crate::trace(terrain, &ray, &options).hit?;
    Some(terrain.world_point(hit.point))
}

/// The rendered pixel under a point of the view, in the frame on screen.
fn pixel_at(ui: &Ui, model: &Model, rect: Rect, pos: Pos2) -> Option<(u32, u32)> {
    let latest = model.latest.as_ref()?;
    let ppp = ui.ctx().pixels_per_point();
    let physical = compose::physical_rect(rect, ppp);
    let size = (latest.frame.width, latest.frame.height);
    if size.0 == 0 || size.1 == 0 {
        return None;
    }
    compose::frame_pixel(
        physical,
        size,
        f64::from(pos.x * ppp),
        f64::from(pos.y * ppp),
    )
}

/// Traces the pixel under `pos` and, where it meets the terrain, orbits around that point.
fn retarget(ui: &Ui, model: &mut Model, rect: Rect, pos: Pos2) {
    let (Some(pixel), Some(latest)) = (pixel_at(ui, model, rect, pos), model.latest.clone()) else {
        return;
    };
    let job = &latest.job;
    let camera = job.camera.in_grid(job.terrain.world_from_grid());
    let ray = camera.ray(pixel.0, pixel.1);
    let answer = crate::trace(
        &job.terrain,
        &ray,
        &TraceOptions::new(job.method, job.arith),
    );
    match answer.hit {
        Some(hit) => model.orbit.retarget(job.terrain.world_point(hit.point)),
        None => model.notify("Double-click on the terrain to orbit around that point"),
    }
}

/// How long the pointer rests before the probe shows: long enough that moving across the
/// view or letting go of a drag shows nothing.
const PROBE_REST: Duration = Duration::from_millis(500);

/// Whether the pointer has rested at `pos` for [`PROBE_REST`]; until then it asks for a
/// redraw at the moment it will have.
fn rested(ui: &Ui, model: &mut Model, pos: Pos2) -> bool {
    let since = match model.pointer_rest {
        Some((at, since)) if at.distance(pos) < 3.0 => since,
        _ => {
            let now = std::time::Instant::now();
            model.pointer_rest = Some((pos, now));
            now
        }
    };
    let waited = since.elapsed();
    if waited < PROBE_REST {
        ui.ctx().request_repaint_after(PROBE_REST - waited);
    }
    waited >= PROBE_REST
}

/// Re-traces the hovered pixel's ray when the pixel or the frame changed, and shows it.
fn hover_probe(ui: &Ui, model: &mut Model, rect: Rect, pos: Pos2) {
    let (Some(pixel), Some(latest)) = (pixel_at(ui, model, rect, pos), model.latest.clone()) else {
        model.probe = None;
        return;
    };
    let fresh = model
        .probe
        .as_ref()
        .is_some_and(|p| p.pixel == pixel && p.generation == latest.generation);
    if !fresh {
        let job = &latest.job;
        let renderer = job.renderer(job.arith);
        let ray = renderer.camera.ray(pixel.0, pixel.1);
        let probe = Probe::trace(&renderer.shader, job.arith, ray, pixel, latest.generation);
        model.probe = Some(probe);
    }
    if let Some(probe) = &model.probe {
        // Open towards the middle of the view so the box stays inside it.
        let right = pos.x > rect.center().x;
        let below = pos.y > rect.center().y;
        let pivot = Align2([
            if right {
                egui::Align::Max
            } else {
                egui::Align::Min
            },
            if below {
                egui::Align::Max
            } else {
                egui::Align::Min
            },
        ]);
        let offset = Vec2::new(
            if right { -18.0 } else { 18.0 },
            if below { -18.0 } else { 18.0 },
        );
        egui::Area::new(Id::new("hovered ray"))
            .order(egui::Order::Tooltip)
            .pivot(pivot)
            .fixed_pos(pos + offset)
            .interactable(false)
            .show(ui.ctx(), |ui| {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    super::probe_ui::probe_ui(
                        ui,
                        probe,
                        model.shown.terrain.field(),
                        latest
                            .frame
                            .stats
                            .get((pixel.1 * latest.frame.width + pixel.0) as usize),
                    )
                });
            });
    }
}

/// Pass progress and, in heat-map mode, the legend.
fn status_ui(ui: &mut Ui, model: &mut Model, rect: Rect) {
    let Some(latest) = model.latest.clone() else {
        return;
    };
    let frame = &latest.frame;
    if model.settings.heat != HeatMode::Off {
        let key = (latest.generation, frame.passes_done);
        let scale = match model.heat_scale {
            Some((g, p, scale)) if (g, p) == key && scale.mode == model.settings.heat => scale,
            _ => {
                let scale = HeatScale::of(frame, model.settings.heat);
                model.heat_scale = Some((key.0, key.1, scale));
                scale
            }
        };
        legend_ui(ui, rect, scale);
        // Chosen under another method: say why the view is one flat colour.
        if let Some(why) = model.settings.heat.unavailable(model.settings.method) {
            let text = format!("{why}: choose another heat map or method");
            let painter = ui.painter_at(rect);
            let galley = painter.layout(
                text,
                egui::FontId::proportional(15.0),
                Color32::WHITE,
                (rect.width() - 40.0).max(80.0),
            );
            let min = rect.center() - galley.size() / 2.0;
            let backdrop = Rect::from_min_size(min, galley.size()).expand(8.0);
            painter.rect_filled(backdrop, 4.0, Color32::from_black_alpha(170));
            painter.galley(min, galley, Color32::WHITE);
        }
    }
    if !frame.complete() {
        let text = format!(
            "refining: pass {}/{} ({} px blocks)",
            frame.passes_done,
            PASS_BLOCKS.len(),
            PASS_BLOCKS[frame
                .passes_done
                .saturating_sub(1)
                .min(PASS_BLOCKS.len() - 1)]
        );
        corner_text(ui, rect, Align2::LEFT_TOP, &text);
    }
}

/// A gradient bar from 0 to the scale's maximum.
fn legend_ui(ui: &Ui, rect: Rect, scale: HeatScale) {
    let painter = ui.painter_at(rect);
    let size = Vec2::new(220.0, 14.0);
    let origin = rect.left_bottom() + Vec2::new(16.0, -40.0);
    let bar = Rect::from_min_size(origin, size);
    let backdrop = bar
        .expand2(Vec2::new(10.0, 24.0))
        .translate(Vec2::new(0.0, -6.0));
    painter.rect_filled(backdrop, 4.0, Color32::from_black_alpha(170));
    let steps = 64;
    for k in 0..steps {
        let x0 = bar.left() + size.x * k as f32 / steps as f32;
        let x1 = bar.left() + size.x * (k + 1) as f32 / steps as f32;
        let rgb = compose::ramp(k as f32 / (steps - 1) as f32);
        let colour = Color32::from_rgb((rgb >> 16) as u8, (rgb >> 8) as u8, rgb as u8);
        painter.rect_filled(
            Rect::from_x_y_ranges(x0..=x1 + 0.5, bar.y_range()),
            0.0,
            colour,
        );
    }
    let font = egui::FontId::proportional(12.0);
    let label = format!("{} per pixel (primary + shadow)", scale.mode.label());
    painter.text(
        bar.left_top() - Vec2::new(0.0, 3.0),
        Align2::LEFT_BOTTOM,
        label,
        font.clone(),
        Color32::WHITE,
    );
    painter.text(
        bar.left_bottom() + Vec2::new(0.0, 2.0),
        Align2::LEFT_TOP,
        "0",
        font.clone(),
        Color32::WHITE,
    );
    painter.text(
        bar.right_bottom() + Vec2::new(0.0, 2.0),
        Align2::RIGHT_TOP,
        format!("≥ {}", scale.max),
        font,
        Color32::WHITE,
    );
}

/// The loading progress, the last error and short notices, at the top of the view and
/// inside it: long text wraps to the view's width, never over the panel.
fn messages_ui(ui: &mut Ui, model: &mut Model, rect: Rect) {
    let mut dismiss = false;
    let width = (rect.width() - 32.0).clamp(80.0, 640.0);
    // Below the corner's hint to bring the panel back, when it is there.
    let top = if model.panels_visible { 12.0 } else { 40.0 };
    egui::Area::new(Id::new("view messages"))
        .pivot(Align2::CENTER_TOP)
        .fixed_pos(Pos2::new(rect.center().x, rect.top() + top))
        .constrain_to(rect)
        .order(egui::Order::Foreground)
        .show(ui.ctx(), |ui| {
            ui.set_max_width(width);
            if let Some(progress) = &model.progress {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    ui.horizontal_wrapped(|ui| {
                        ui.spinner();
                        ui.label(format!(
                            "Loading {}: {}",
                            progress.label,
                            progress.stage.label()
                        ));
                    });
                    let seconds = progress.started.elapsed().as_secs_f32();
                    ui.add(
                        egui::ProgressBar::new(progress.stage.fraction())
                            .text(format!("{seconds:.1} s")),
                    );
                });
            }
            if let Some(error) = &model.error {
                let frame = egui::Frame::popup(ui.style())
                    .fill(Color32::from_rgb(110, 24, 24))
                    .show(ui, |ui| {
                        let text = egui::RichText::new(format!("⚠ {error}")).color(Color32::WHITE);
                        // A parser's message on several lines points at a column: monospace
                        // keeps its marker under the bad key.
                        let text = if error.contains('\n') {
                            text.monospace()
                        } else {
                            text
                        };
                        ui.label(text);
                        let button = ui.button("Dismiss");
                        model.widget_rects.insert("error_dismiss", button.rect);
                        dismiss = button.clicked();
                    });
                model
                    .widget_rects
                    .insert("error_message", frame.response.rect);
            }
            if let Some(notice) = &model.notice {
                if notice.at.elapsed() < NOTICE_TIME {
                    egui::Frame::popup(ui.style()).show(ui, |ui| ui.label(&notice.text));
                }
            }
        });
    if dismiss {
        model.error = None;
    }
    if model
        .notice
        .as_ref()
        .is_some_and(|n| n.at.elapsed() >= NOTICE_TIME)
    {
        model.notice = None;
    }
    if let Some(notice) = &model.notice {
        // Wake up once more to take the notice down.
        ui.ctx()
            .request_repaint_after(NOTICE_TIME.saturating_sub(notice.at.elapsed()));
    }
}

/// Shown while a file is dragged over the window.
fn drop_hint_ui(ui: &Ui, rect: Rect) {
    let painter = ui.ctx().layer_painter(egui::LayerId::new(
        egui::Order::Foreground,
        Id::new("drop hint"),
    ));
    painter.rect_filled(rect, 0.0, Color32::from_black_alpha(150));
    let inner = rect.shrink(24.0);
    painter.rect_stroke(
        inner,
        12.0,
        egui::Stroke::new(3.0, Color32::from_rgb(250, 200, 80)),
        egui::StrokeKind::Inside,
    );
    let lines = [
        "Drop a height map (PNG, PGM, TIFF, .hgt, .asc)",
        "or a scene (.toml) to open it",
    ];
    for (k, line) in lines.into_iter().enumerate() {
        let y = 30.0 * (k as f32 - 0.5);
        painter.text(
            rect.center() + Vec2::new(0.0, y),
            Align2::CENTER_CENTER,
            line,
            egui::FontId::proportional(22.0),
            Color32::WHITE,
        );
    }
}

/// Writes `text` in a corner of `rect`; returns where.
fn corner_text(ui: &Ui, rect: Rect, align: Align2, text: &str) -> Rect {
    let painter = ui.painter_at(rect);
    let galley = painter.layout_no_wrap(
        text.to_owned(),
        egui::FontId::proportional(13.0),
        Color32::WHITE,
    );
    let margin = Vec2::new(10.0, 8.0);
    let min = match align {
        Align2::RIGHT_TOP => rect.right_top() + Vec2::new(-margin.x - galley.size().x, margin.y),
        _ => rect.left_top() + margin,
    };
    let backdrop = Rect::from_min_size(min, galley.size()).expand(4.0);
    painter.rect_filled(backdrop, 3.0, Color32::from_black_alpha(120));
    painter.galley(min, galley, Color32::WHITE);
    backdrop
}

/// The F1 window: what the mouse and keys do.
fn help_ui(ui: &Ui, model: &mut Model) {
    let mut open = model.help_open;
    egui::Window::new("Help")
        .open(&mut open)
        .collapsible(false)
        .resizable(false)
        .anchor(Align2::LEFT_TOP, Vec2::new(16.0, 40.0))
        .show(ui.ctx(), |ui| {
            egui::Grid::new("help grid").num_columns(2).show(ui, |ui| {
                for (what, does) in HELP {
                    ui.strong(*what);
                    ui.label(*does);
                    ui.end_row();
                }
            });
        });
    model.help_open = open;
}

const HELP: &[(&str, &str)] = &[
    ("Left drag", "orbit around the target"),
    ("Right drag, Shift + left drag", "pan"),
    ("Wheel", "zoom towards the point under the cursor"),
    ("Arrow keys", "move over the map"),
    ("Q, E", "turn around the target"),
    ("+, -", "zoom in, out"),
    ("Page Up, Page Down", "look down more, less"),
    ("F", "frame the whole map from this direction"),
    (
        "Double-click",
        "orbit around the terrain point under the cursor",
    ),
    (
        "Rest the pointer",
        "with the probe on (Statistics): the pixel's ray, its hit and its queries",
    ),
    (
        "Drop a file",
        "open a height map (PNG, PGM, TIFF, .hgt, .asc) or a scene (.toml)",
    ),
    ("R", "reset the view (the whole map)"),
    ("S", "export the rendered image (PNG, no panels)"),
    (
        "K",
        "add the view to the flythrough (played and edited in its section)",
    ),
    (
        "H",
        "hide or show the panel (it hides itself in narrow windows)",
    ),
    ("F1", "this help"),
];
