//! Recording a flythrough: K (or *Add view*) adds the current view as a key two seconds after
//! the last; the Flythrough section lists the keys to retime or delete, and *Play* previews the
//! path at a low render scale, as `render --frames` will fly it. *Save scene* writes the keys as
//! the scene's `[animation]`.

use super::orbit::Orbit;
use super::state::{Action, Flythrough, Model, Playing};
use super::worker::RenderedFrame;
use crate::render::animation::above_ground;
use crate::Terrain;
use egui::{DragValue, Ui};
use std::time::Instant;

/// The render scale the path is previewed at: about a ninth of the rays, so it plays smoothly.
const PREVIEW_SCALE: f32 = 0.35;

/// The longest a preview waits for a view to be rendered before it moves on.
const LONGEST_WAIT_S: f64 = 0.5;

/// The Flythrough section: frames per second, the keys (time, delete), Add view (adding
/// `orbit`) and Play, which it asks for.
pub fn flythrough_ui(ui: &mut Ui, fly: &mut Flythrough, orbit: Orbit) -> Option<Action> {
    ui.horizontal(|ui| {
        ui.label("frames per second");
        ui.add(DragValue::new(&mut fly.fps).range(1.0..=240.0).speed(0.5));
    });
    let mut removed = None;
    let (mut earliest, count) = (0.0, fly.keys.len());
    for (n, key) in fly.keys.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.label(format!("key {}", n + 1));
            // Each key stays after the one before it: the path's keys are in order of time.
            let least = if n == 0 { 0.0 } else { earliest + 0.05 };
            ui.add(
                DragValue::new(&mut key.time_s)
                    .range(least..=3600.0)
                    .speed(0.05)
                    .suffix(" s"),
            );
            if ui.small_button("delete").clicked() {
                removed = Some(n);
            }
        });
        earliest = key.time_s;
    }
    if let Some(n) = removed {
        fly.keys.remove(n);
    }
    if count == 0 {
        ui.weak("no keys yet: move the camera, then add its view");
    }
    ui.horizontal(|ui| {
        if ui.button("Add view (K)").clicked() {
            fly.add(orbit);
        }
        let playing = fly.playing();
        let label = if playing { "Stop" } else { "Play" };
        let clicked = ui.button(label).clicked();
        let action = if playing {
            Action::StopFlythrough
        } else {
            Action::PlayFlythrough
        };
        clicked.then_some(action)
    })
    .inner
}

/// Starts previewing the keys.
pub fn play(model: &mut Model) {
    if let Err(refused) = model.flythrough.animation() {
        model.error = Some(refused.to_string());
        return;
    }
    model.flythrough.playing = Some(Playing {
        start: Instant::now(),
        moved: Instant::now(),
        generation: None,
        render_scale: model.settings.render_scale,
        orbit: model.orbit,
    });
    model.settings.render_scale = PREVIEW_SCALE;
}

/// Ends the preview, restoring the render scale and the view it started from.
pub fn stop(model: &mut Model) {
    if let Some(playing) = model.flythrough.playing.take() {
        model.settings.render_scale = playing.render_scale;
        model.orbit = playing.orbit;
    }
}

/// Moves the camera along the path while a preview plays, ending it after the last key. The
/// camera moves on once the view it shows is rendered (or after [`LONGEST_WAIT_S`]), to where
/// the path is by then: the preview keeps time, showing as many whole frames as the machine
/// renders.
///
/// It moves `orbit` over `terrain`; `latest` is the frame on screen. At the path's end it asks
/// for the preview to stop.
pub fn play_ui(
    ui: &Ui,
    fly: &mut Flythrough,
    orbit: &mut Orbit,
    terrain: &Terrain,
    latest: Option<&RenderedFrame>,
) -> Option<Action> {
    let playing = fly.playing?;
    ui.ctx().request_repaint();
    let rendered =
        latest.is_some_and(|l| Some(l.generation) > playing.generation && l.frame.complete());
    if !rendered && playing.moved.elapsed().as_secs_f64() < LONGEST_WAIT_S {
        return None;
    }
    let Ok(path) = fly.animation() else {
        return Some(Action::StopFlythrough);
    };
    let time_s = playing.start.elapsed().as_secs_f64();
    if time_s > (path.frames() - 1) as f64 / path.fps() + 0.5 {
        return Some(Action::StopFlythrough);
    }
    let view = path.view_at(time_s);
    let eye = above_ground(view.eye, terrain);
    *orbit = Orbit::from_eye(eye.into(), view.target.into(), view.fov_y_deg, orbit.scale);
    if let Some(playing) = &mut fly.playing {
        playing.moved = Instant::now();
        playing.generation = latest.map(|l| l.generation);
    }
    None
}
