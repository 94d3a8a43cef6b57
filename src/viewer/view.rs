//! The 3D view: an egui widget over the rendered terrain that turns drags, the wheel and
//! double-clicks into camera moves (so panels and the orbit never fight over the pointer) and
//! probes the hovered pixel; what is drawn over it is in `annotations`.

use super::compose;
use super::navigation::Placing;
use super::probe::Probe;
use super::state::{Model, Notice};
use super::worker::RenderedFrame;
use crate::{Method, TraceOptions};
use egui::{Align2, Id, Pos2, Rect, Sense, Ui, Vec2};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// What the 3D view reads and edits.
pub struct ViewParts<'a> {
    /// The camera, moved by drags, the wheel and double-clicks.
    pub camera: Placing<'a>,
    /// The traversal method, which finds the point under the wheel.
    pub method: Method,
    /// The frame on screen.
    pub latest: Option<&'a Arc<RenderedFrame>>,
    /// The probe is on (Statistics).
    pub show_probe: bool,
    /// A file is being dragged over the window.
    pub drop_hover: bool,
    /// A mouse button is held on the view.
    pub held: &'a mut bool,
    pub probe: &'a mut Option<Probe>,
    /// Where the pointer came to rest over the view, and when.
    pub pointer_rest: &'a mut Option<(Pos2, Instant)>,
    pub notice: &'a mut Option<Notice>,
}

impl<'a> ViewParts<'a> {
    /// The model's parts the view reads and edits.
    pub fn of(model: &'a mut Model) -> ViewParts<'a> {
        ViewParts {
            camera: Placing {
                orbit: &mut model.orbit,
                framed: &mut model.framed,
                view_aspect: &mut model.view_aspect,
                home: model.home,
                terrain: &model.shown.terrain,
            },
            method: model.settings.method,
            latest: model.latest.as_ref(),
            show_probe: model.widgets.show_probe,
            drop_hover: model.drop_hover,
            held: &mut model.view_held,
            probe: &mut model.probe,
            pointer_rest: &mut model.pointer_rest,
            notice: &mut model.notice,
        }
    }
}

/// Shows the view in the space left by the panels; returns its rectangle in points.
pub fn view_ui(ui: &mut Ui, mut view: ViewParts<'_>) -> Rect {
    let rect = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    camera_input(ui, &response, &mut view, rect);
    if response.double_clicked() {
        if let Some(pos) = response.interact_pointer_pos() {
            retarget(ui, &mut view, rect, pos);
        }
    }
    let dragging = response.dragged() || response.is_pointer_button_down_on();
    *view.held = dragging;
    match response.hover_pos() {
        Some(pos) if view.show_probe && !dragging && !view.drop_hover => {
            if rested(ui, view.pointer_rest, pos) {
                hover_probe(ui, &mut view, rect, pos);
            } else {
                *view.probe = None;
            }
        }
        _ => {
            *view.probe = None;
            *view.pointer_rest = None;
        }
    }
    rect
}

/// Orbit (left drag), pan (right or middle drag, or shift + left drag), zoom towards the point
/// under the pointer (wheel); then the framed view follows the view's shape and the camera
/// stays above the ground.
fn camera_input(ui: &Ui, response: &egui::Response, view: &mut ViewParts<'_>, rect: Rect) {
    use egui::PointerButton::{Middle, Primary, Secondary};
    let delta = response.drag_delta();
    let shift = ui.input(|i| i.modifiers.shift);
    let delta_f64 = (f64::from(delta.x), f64::from(delta.y));
    if delta != Vec2::ZERO {
        if response.dragged_by(Primary) && !shift {
            view.camera.orbit.rotate(delta_f64.0, delta_f64.1);
        } else if response.dragged_by(Secondary)
            || response.dragged_by(Middle)
            || response.dragged_by(Primary)
        {
            view.camera
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
            match terrain_under(ui, view, rect, pos) {
                Some(point) => view.camera.orbit.zoom_towards(point, f64::from(steps)),
                // Over the sky: towards the target, not up into the air.
                None => view.camera.orbit.zoom(f64::from(steps)),
            }
        }
    }
    let aspect = f64::from(rect.width()) / f64::from(rect.height());
    view.camera.settle(aspect);
}

/// The terrain point under `pos` in the current camera (not the frame on screen, which may
/// lag behind it), if the pointer is over the terrain.
fn terrain_under(ui: &Ui, view: &ViewParts<'_>, rect: Rect, pos: Pos2) -> Option<[f64; 3]> {
    let ppp = ui.ctx().pixels_per_point();
    let physical = compose::physical_rect(rect, ppp);
    let size = (physical.width.max(1), physical.height.max(1));
    let pixel = (
        (((pos.x - rect.min.x) * ppp).max(0.0) as u32).min(size.0 - 1),
        (((pos.y - rect.min.y) * ppp).max(0.0) as u32).min(size.1 - 1),
    );
    let terrain = view.camera.terrain;
    let camera = view.camera.orbit.camera(size).ok()?;
    let ray = camera
        .in_grid(terrain.world_from_grid())
        .ray(pixel.0, pixel.1);
    let options = TraceOptions::new(view.method, crate::Arith::F64);
    let hit = crate::trace(terrain, &ray, &options).hit?;
    Some(terrain.world_point(hit.point))
}

/// The rendered pixel under a point of the view, in the frame on screen.
fn pixel_at(
    ui: &Ui,
    latest: Option<&Arc<RenderedFrame>>,
    rect: Rect,
    pos: Pos2,
) -> Option<(u32, u32)> {
    let latest = latest?;
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
fn retarget(ui: &Ui, view: &mut ViewParts<'_>, rect: Rect, pos: Pos2) {
    let (Some(pixel), Some(latest)) = (pixel_at(ui, view.latest, rect, pos), view.latest) else {
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
        Some(hit) => view
            .camera
            .orbit
            .retarget(job.terrain.world_point(hit.point)),
        None => {
            *view.notice = Some(Notice::now(
                "Double-click on the terrain to orbit around that point",
            ))
        }
    }
}

/// How long the pointer rests before the probe shows: long enough that moving across the
/// view or letting go of a drag shows nothing.
const PROBE_REST: Duration = Duration::from_millis(500);

/// Whether the pointer has rested at `pos` for [`PROBE_REST`]; until then it asks for a
/// redraw at the moment it will have.
fn rested(ui: &Ui, pointer_rest: &mut Option<(Pos2, Instant)>, pos: Pos2) -> bool {
    let since = match *pointer_rest {
        Some((at, since)) if at.distance(pos) < 3.0 => since,
        _ => {
            let now = Instant::now();
            *pointer_rest = Some((pos, now));
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
fn hover_probe(ui: &Ui, view: &mut ViewParts<'_>, rect: Rect, pos: Pos2) {
    let (Some(pixel), Some(latest)) = (pixel_at(ui, view.latest, rect, pos), view.latest) else {
        *view.probe = None;
        return;
    };
    let fresh = view
        .probe
        .as_ref()
        .is_some_and(|p| p.pixel == pixel && p.generation == latest.generation);
    if !fresh {
        let job = &latest.job;
        let renderer = job.renderer(job.arith);
        let ray = renderer.camera.ray(pixel.0, pixel.1);
        let probe = Probe::trace(&renderer.shader, job.arith, ray, pixel, latest.generation);
        *view.probe = Some(probe);
    }
    if let Some(probe) = view.probe.as_ref() {
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
                        view.camera.terrain.field(),
                        latest
                            .frame
                            .stats
                            .get((pixel.1 * latest.frame.width + pixel.0) as usize),
                    )
                });
            });
    }
}
