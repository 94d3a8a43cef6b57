//! A flythrough's keys, and the preview playing them.

use crate::render::animation::{Animation, AnimationError, AnimationSection, KeySection};
use crate::render::Orbit as SceneOrbit;
use crate::viewer::orbit::Orbit;
use std::time::Instant;
use thiserror::Error;

/// Why the keys make no path, or no scene text.
#[derive(Debug, Error)]
pub enum KeysError {
    /// No keys yet.
    #[error("no keys: add a view first (K)")]
    NoKeys,
    /// The keys make no camera path.
    #[error(transparent)]
    Path(#[from] AnimationError),
    /// The keys would not write as TOML.
    #[error("cannot write the flythrough's keys: {0}")]
    Toml(#[from] toml::ser::Error),
}

/// Seconds between a new key and the one before it.
const KEY_SPACING_S: f64 = 2.0;

/// The keys recorded, and the preview under way.
#[derive(Clone, Debug)]
pub struct Flythrough {
    /// Keys in order of time.
    pub keys: Vec<Key>,
    /// Frames per second of the saved path.
    pub fps: f64,
    pub playing: Option<Playing>,
}

/// A view at a time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Key {
    pub time_s: f64,
    pub orbit: Orbit,
}

/// A preview: when it started and last moved, and what to restore when it ends.
#[derive(Clone, Copy, Debug)]
pub struct Playing {
    pub start: Instant,
    pub moved: Instant,
    /// The generation of the frame on screen when the camera last moved: a later one shows
    /// the new view.
    pub generation: Option<u64>,
    pub render_scale: f32,
    pub orbit: Orbit,
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
    pub fn scene_text(&self) -> Result<String, KeysError> {
        let Some(section) = self.section() else {
            return Ok(String::new());
        };
        #[derive(serde::Serialize)]
        struct File<'a> {
            animation: &'a AnimationSection,
        }
        let text = toml::to_string(&File {
            animation: &section,
        })?;
        Ok(format!("\n{text}"))
    }

    /// The keys as a path, or why they are none.
    pub fn animation(&self) -> Result<Animation, KeysError> {
        let section = self.section().ok_or(KeysError::NoKeys)?;
        Ok(Animation::new(&section, None, 45.0, [0.0, 0.0, 1.0], None)?)
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
        assert_eq!(Flythrough::default().scene_text().ok(), Some(String::new()));
    }
}
