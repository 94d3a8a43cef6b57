//! Recording a flythrough: K (or *Add view*) adds the current view as a key two seconds after
//! the last; the Flythrough section lists the keys to retime or delete, and *Play* previews the
//! path at a low render scale, as `render --frames` will fly it. *Save scene* writes the keys as
//! the scene's `[animation]`.

use super::model::Model;
use super::orbit::Orbit;
use crate::render::animation::{above_ground, Animation, AnimationSection, KeySection};
use crate::render::Orbit as SceneOrbit;
use egui::{DragValue, Ui};
use std::time::Instant;

/// Seconds between a new key and the one before it.
const KEY_SPACING_S: f64 = 2.0;

/// The render scale the path is previewed at: about a ninth of the rays, so it plays smoothly.
const PREVIEW_SCALE: f32 = 0.35;

/// The longest a preview waits for a view to be rendered before it moves on.
const LONGEST_WAIT_S: f64 = 0.5;

/// The keys recorded, and the preview under way.
#[derive(Clone, Debug)]
pub struct Flythrough {
    /// Keys in order of time.
    pub keys: Vec<Key>,
    /// Frames per second of the saved path.
    pub fps: f64,
    playing: Option<Playing>,
}

/// A view at a time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Key {
    pub time_s: f64,
    pub orbit: Orbit,
}

/// A preview: when it started and last moved, and what to restore when it ends.
#[derive(Clone, Copy, Debug)]
struct Playing {
    start: Instant,
    moved: Instant,
    /// The generation of the frame on screen when the camera last moved: a later one shows
    /// the new view.
    generation: Option<u64>,
    render_scale: f32,
    orbit: Orbit,
}

impl Default for Flythrough {
    fn default() -> Self {
        Flythrough {
            keys: Vec::new(),
            fps: 30.0,
            playing: None,
        }
    }
}

impl Flythrough {
    /// Adds `orbit` as a key after the last.
    pub fn add(&mut self, orbit: Orbit) {
        let time_s = self.keys.last().map_or(0.0, |k| k.time_s + KEY_SPACING_S);
        self.keys.push(Key { time_s, orbit });
    }

    /// The keys of a scene file's `[animation]` (an orbit's turning is not a list of keys: it
    /// gives none); `fov_y_deg` for keys without their own, `scale` the map's.
    pub fn from_section(section: &AnimationSection, fov_y_deg: f64, scale: f64) -> Flythrough {
        let key = |k: &KeySection| {
            let fov = k.fov_y_deg.unwrap_or(fov_y_deg);
            let orbit = match (k.eye, k.target, k.orbit) {
                (Some(eye), Some(target), _) => Orbit::from_eye(eye, target, fov, scale),
                (_, _, Some(o)) => Orbit {
                    target: o.target,
                    yaw_deg: o.yaw_deg,
                    pitch_deg: o.pitch_deg,
                    distance: o.distance,
                    fov_y_deg: fov,
                    scale,
                },
                // (Scene::from_file refused any other form.)
                _ => return None,
            };
            Some(Key {
                time_s: k.time_s,
                orbit,
            })
        };
        Flythrough {
            keys: section.key.iter().filter_map(key).collect(),
            fps: section.fps,
            playing: None,
        }
    }

    /// Whether a preview is playing.
    pub fn playing(&self) -> bool {
        self.playing.is_some()
    }

    /// The `[animation]` section of the keys (`None` without keys).
    pub fn section(&self) -> Option<AnimationSection> {
        let key = |k: &Key| KeySection {
            time_s: k.time_s,
            eye: None,
            target: None,
            orbit: Some(SceneOrbit {
                target: k.orbit.target,
                yaw_deg: k.orbit.yaw_deg,
                pitch_deg: k.orbit.pitch_deg,
                distance: k.orbit.distance,
            }),
            fov_y_deg: Some(k.orbit.fov_y_deg),
        };
        (!self.keys.is_empty()).then(|| AnimationSection {
            fps: self.fps,
            key: self.keys.iter().map(key).collect(),
            orbit_deg_per_s: None,
            duration_s: None,
            track: None,
        })
    }

    /// The scene file's `[animation]` text for the keys (empty without keys).
    pub fn scene_text(&self) -> Result<String, String> {
        let Some(section) = self.section() else {
            return Ok(String::new());
        };
        #[derive(serde::Serialize)]
        struct File<'a> {
            animation: &'a AnimationSection,
        }
        toml::to_string(&File {
            animation: &section,
        })
        .map(|text| format!("\n{text}"))
        .map_err(|e| format!("cannot write the flythrough's keys: {e}"))
    }

    /// The keys as a path, or why they are none.
    fn animation(&self) -> Result<Animation, String> {
        let section = self.section().ok_or("no keys: add a view first (K)")?;
        Animation::new(&section, None, 45.0, [0.0, 0.0, 1.0], None)
    }
}

/// The Flythrough section: frames per second, the keys (time, delete), Add view and Play.
pub fn flythrough_ui(ui: &mut Ui, model: &mut Model) {
    let fly = &mut model.flythrough;
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
            let orbit = model.orbit;
            model.flythrough.add(orbit);
        }
        let playing = model.flythrough.playing();
        let label = if playing { "Stop" } else { "Play" };
        if ui.button(label).clicked() {
            if playing {
                stop(model);
            } else {
                play(model);
            }
        }
    });
}

/// Starts previewing the keys.
pub fn play(model: &mut Model) {
    if let Err(message) = model.flythrough.animation() {
        model.error = Some(message);
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
pub fn play_ui(ui: &Ui, model: &mut Model) {
    let Some(playing) = model.flythrough.playing else {
        return;
    };
    ui.ctx().request_repaint();
    let latest = model.latest.as_ref();
    let rendered =
        latest.is_some_and(|l| Some(l.generation) > playing.generation && l.frame.complete());
    if !rendered && playing.moved.elapsed().as_secs_f64() < LONGEST_WAIT_S {
        return;
    }
    let Ok(path) = model.flythrough.animation() else {
        return stop(model);
    };
    let time_s = playing.start.elapsed().as_secs_f64();
    if time_s > (path.frames() - 1) as f64 / path.fps() + 0.5 {
        return stop(model);
    }
    let view = path.view_at(time_s);
    let eye = above_ground(view.eye, &model.shown.terrain);
    let scale = model.orbit.scale;
    model.orbit = Orbit::from_eye(eye.into(), view.target.into(), view.fov_y_deg, scale);
    let generation = model.latest.as_ref().map(|l| l.generation);
    if let Some(playing) = &mut model.flythrough.playing {
        playing.moved = Instant::now();
        playing.generation = generation;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saved_keys_read_back_as_the_same_path() {
        let orbit = |yaw_deg: f64, fov_y_deg: f64| Orbit {
            target: [10.0, 20.5, 3.25],
            yaw_deg,
            pitch_deg: 30.0,
            distance: 150.0,
            fov_y_deg,
            scale: 100.0,
        };
        let mut fly = Flythrough {
            fps: 24.0,
            ..Flythrough::default()
        };
        fly.add(orbit(-130.0, 45.0));
        fly.add(orbit(-100.0, 60.0));
        fly.keys[1].time_s = 3.5;
        let text = fly.scene_text().unwrap();
        #[derive(serde::Deserialize)]
        struct File {
            animation: AnimationSection,
        }
        let read: File = toml::from_str(&text).unwrap();
        let again = Flythrough::from_section(&read.animation, 45.0, 100.0);
        assert_eq!(again.keys, fly.keys);
        assert_eq!(again.fps, 24.0);
        // The keys two seconds apart when added, then as retimed.
        let path = again.animation().unwrap();
        assert_eq!(path.frames(), 3 * 24 + 12 + 1);
        assert_eq!(Flythrough::default().scene_text(), Ok(String::new()));
    }
}
