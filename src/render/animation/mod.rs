//! Camera paths (a scene file's `[animation]`): keyframes the camera passes through, smoothly
//! (`spline`), an orbit turning around its target, or a track to follow (`track`). Frame `k` shows the path at time
//! `k / fps`; the eye never goes below the surface (it is lifted above it as the viewer keeps
//! its own eye, by the same clearance).

mod spline;
mod track;
mod view;

use track::Track;
pub(crate) use track::{gpx_points, read_text, NotGpx};
pub use track::{TextError, TrackError, TrackFileError, TrackSection};
pub use view::View;

use super::camera::{Camera, CameraError};
use super::framing;
use super::scene::Orbit;
use crate::{Heightfield, Terrain};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Frames a path may have: a day at 60 frames a second, far beyond any flythrough, and small
/// enough that a frame number always fits the file names' digits.
pub const MOST_FRAMES: u64 = 60 * 60 * 60 * 24;

/// Why an `[animation]` section makes no camera path; each names the key at fault.
#[derive(Debug, Error)]
pub enum AnimationError {
    /// Frames a second out of range.
    #[error("[animation] fps must be above 0 and at most 1000, got {0}")]
    Fps(f64),
    /// A track without a map to place it on.
    #[error("[animation.track] needs the scene's map")]
    NoMap,
    /// The track cannot be flown.
    #[error(transparent)]
    Track(#[from] TrackError),
    /// A track with keys or an orbit.
    #[error(
        "[animation] takes one of [[animation.key]] entries, orbit_deg_per_s or \
         [animation.track]"
    )]
    TrackAndMore,
    /// An orbit speed without a `[camera]` orbit.
    #[error(
        "[animation] orbit_deg_per_s turns the [camera] orbit: give [camera] orbit = {{ \
         target, yaw_deg, pitch_deg, distance }}"
    )]
    NoOrbit,
    /// An orbit speed out of range.
    #[error("[animation] orbit_deg_per_s must be non-zero and at most 3600 either way, got {0}")]
    OrbitSpeed(f64),
    /// No path at all.
    #[error(
        "[animation] needs [[animation.key]] entries (time_s, and eye and target or orbit), \
         orbit_deg_per_s or [animation.track]"
    )]
    NoPath,
    /// Keys and an orbit speed.
    #[error("[animation] takes either [[animation.key]] entries or orbit_deg_per_s, not both")]
    KeysAndOrbit,
    /// A duration for keys or a track.
    #[error("[animation] duration_s is for an orbit; keys end at the last key's time_s")]
    Duration,
    /// Too long a path, or one of no duration.
    #[error(
        "[animation] a path of {duration} s at {fps} frames a second is more than \
         {MOST_FRAMES} frames or not a duration"
    )]
    Frames {
        /// Seconds.
        duration: f64,
        /// Frames a second.
        fps: f64,
    },
    /// A key out of range or out of order.
    #[error("[[animation.key]] {number} (time_s = {time_s}): {problem}")]
    Key {
        /// The key's number, from 1.
        number: usize,
        /// Its time.
        time_s: f64,
        /// What is wrong with it.
        problem: KeyProblem,
    },
}

/// What is wrong with an `[[animation.key]]`.
#[derive(Clone, Copy, Debug, Error, PartialEq, Eq)]
pub enum KeyProblem {
    /// A negative or infinite time.
    #[error("time_s must be a finite number of seconds >= 0")]
    Time,
    /// Not later than the key before.
    #[error("keys must be in order of time, each later than the one before")]
    Order,
    /// Neither eye and target nor orbit.
    #[error("needs either both eye and target, or orbit")]
    View,
    /// A view that is not finite, or a field of view out of range.
    #[error("eye and target must be finite, fov_y_deg between 0 and 180")]
    Values,
}

/// A scene file's `[animation]` section: `fps` and either keys or an orbit.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AnimationSection {
    /// Frames per second.
    pub fps: f64,
    /// `[[animation.key]]`: the views the camera passes through, in order of time.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub key: Vec<KeySection>,
    /// Instead of keys: the `[camera]` orbit turns by this many degrees a second.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orbit_deg_per_s: Option<f64>,
    /// With `orbit_deg_per_s`: how long the path lasts (default: one whole turn).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration_s: Option<f64>,
    /// Instead of keys or an orbit: a GPX or GeoJSON track to fly along.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub track: Option<TrackSection>,
}

/// One `[[animation.key]]`: a view at a time.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct KeySection {
    /// When the camera is here, in seconds from the start.
    pub time_s: f64,
    /// Where the camera is (with `target`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eye: Option<[f64; 3]>,
    /// What it looks at (with `eye`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<[f64; 3]>,
    /// Instead of `eye` and `target`: an orbit around a target.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orbit: Option<Orbit>,
    /// Vertical field of view in degrees (default the `[camera]`'s, else 45).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fov_y_deg: Option<f64>,
}

/// How the camera moves.
#[derive(Clone, Debug, PartialEq)]
enum Path {
    /// Through views at times (increasing).
    Keys { times: Vec<f64>, views: Vec<View> },
    /// Along a track on the map.
    Track { track: Track, fov_y_deg: f64 },
    /// Around an orbit's target, its yaw turning at a rate.
    Orbit {
        orbit: Orbit,
        deg_per_s: f64,
        fov_y_deg: f64,
    },
}

/// A validated camera path.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    fps: f64,
    /// Frames 0 to `frames - 1`.
    frames: u64,
    path: Path,
    /// The image's up direction.
    up: [f64; 3],
}

impl Animation {
    /// Validates a section; `orbit` is the `[camera]` orbit (which `orbit_deg_per_s` turns),
    /// `fov_y_deg` and `up` the `[camera]`'s; `map` the scene's folder and map, which a track
    /// is read from and placed on. Errors name the key at fault.
    pub fn new(
        section: &AnimationSection,
        orbit: Option<Orbit>,
        fov_y_deg: f64,
        up: [f64; 3],
        map: Option<(&std::path::Path, &Heightfield)>,
    ) -> Result<Animation, AnimationError> {
        let fps = section.fps;
        if !(fps.is_finite() && fps > 0.0 && fps <= 1000.0) {
            return Err(AnimationError::Fps(fps));
        }
        let (path, duration) = match (&section.key[..], section.orbit_deg_per_s) {
            ([], None) if section.track.is_some() => {
                let (Some(track), Some((base, field))) = (&section.track, map) else {
                    return Err(AnimationError::NoMap);
                };
                let track = Track::load(track, base, field)?;
                let duration = track.duration();
                (Path::Track { track, fov_y_deg }, duration)
            }
            (_, _) if section.track.is_some() => return Err(AnimationError::TrackAndMore),
            ([], Some(deg_per_s)) => {
                let orbit = orbit.ok_or(AnimationError::NoOrbit)?;
                if !(deg_per_s.is_finite() && deg_per_s != 0.0 && deg_per_s.abs() <= 3600.0) {
                    return Err(AnimationError::OrbitSpeed(deg_per_s));
                }
                let turn = 360.0 / deg_per_s.abs();
                let path = Path::Orbit {
                    orbit,
                    deg_per_s,
                    fov_y_deg,
                };
                (path, section.duration_s.unwrap_or(turn))
            }
            ([_, ..], None) => keys(&section.key, fov_y_deg)?,
            ([], None) => return Err(AnimationError::NoPath),
            ([_, ..], Some(_)) => return Err(AnimationError::KeysAndOrbit),
        };
        if section.duration_s.is_some() && !matches!(path, Path::Orbit { .. }) {
            return Err(AnimationError::Duration);
        }
        let frames = frames_for(duration, fps).ok_or(AnimationError::Frames { duration, fps })?;
        Ok(Animation {
            fps,
            frames,
            path,
            up,
        })
    }

    /// Frames per second.
    pub fn fps(&self) -> f64 {
        self.fps
    }

    /// How many frames the path has (frame 0 at its start, the last at or before its end).
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// The view at `time_s` seconds, as the path gives it (the eye not yet kept above the
    /// ground; see [`Animation::camera`]).
    pub fn view_at(&self, time_s: f64) -> View {
        match &self.path {
            Path::Keys { times, views } => {
                let eyes: Vec<DVec3> = views.iter().map(|v| v.eye).collect();
                let targets: Vec<DVec3> = views.iter().map(|v| v.target).collect();
                View {
                    eye: spline::at(times, &eyes, time_s),
                    target: spline::at(times, &targets, time_s),
                    fov_y_deg: fov_at(times, views, time_s),
                }
            }
            Path::Track { track, fov_y_deg } => track.view_at(time_s, *fov_y_deg),
            Path::Orbit {
                orbit,
                deg_per_s,
                fov_y_deg,
            } => {
                let yaw = orbit.yaw_deg + deg_per_s * time_s;
                let offset = framing::eye_direction(yaw, orbit.pitch_deg) * orbit.distance;
                let target = DVec3::from(orbit.target);
                View {
                    eye: target + offset,
                    target,
                    fov_y_deg: *fov_y_deg,
                }
            }
        }
    }

    /// The camera of frame `frame` at `size` over `terrain` (world coordinates): the path's
    /// view with its eye lifted to [`framing::EYE_CLEARANCE`] of the map's scale above the
    /// surface where it would be lower, seeded as that frame.
    pub fn camera(
        &self,
        frame: u64,
        terrain: &Terrain,
        size: (u32, u32),
    ) -> Result<Camera, CameraError> {
        let view = self.view_at(frame as f64 / self.fps);
        let eye = above_ground(view.eye, terrain);
        let camera = Camera::look_at(
            eye.into(),
            view.target.into(),
            self.up,
            view.fov_y_deg,
            size,
        )?;
        Ok(camera.for_frame(frame))
    }
}

/// `eye`, lifted where it is less than the viewer's clearance above the surface below it.
pub fn above_ground(eye: DVec3, terrain: &Terrain) -> DVec3 {
    let floor = framing::surface_z(terrain, eye.x, eye.y)
        + framing::EYE_CLEARANCE * framing::scale(terrain);
    DVec3::new(eye.x, eye.y, eye.z.max(floor))
}

/// The frames of a path lasting `duration` seconds: one at every whole multiple of `1 / fps`
/// from 0 up to the end.
fn frames_for(duration: f64, fps: f64) -> Option<u64> {
    let last = (duration * fps + 1e-9).floor();
    (duration.is_finite() && duration >= 0.0 && last < MOST_FRAMES as f64).then(|| last as u64 + 1)
}

/// The keys' times and views, checked: times increasing from 0 or later, each key a view.
fn keys(keys: &[KeySection], fov_y_deg: f64) -> Result<(Path, f64), AnimationError> {
    let mut times = Vec::with_capacity(keys.len());
    let mut views = Vec::with_capacity(keys.len());
    for (n, key) in keys.iter().enumerate() {
        let at = |problem| AnimationError::Key {
            number: n + 1,
            time_s: key.time_s,
            problem,
        };
        if !(key.time_s.is_finite() && key.time_s >= 0.0) {
            return Err(at(KeyProblem::Time));
        }
        if times.last().is_some_and(|&before| key.time_s <= before) {
            return Err(at(KeyProblem::Order));
        }
        let (eye, target) = match (key.eye, key.target, key.orbit) {
            (Some(eye), Some(target), None) => (DVec3::from(eye), DVec3::from(target)),
            (None, None, Some(o)) => {
                let target = DVec3::from(o.target);
                (
                    target + framing::eye_direction(o.yaw_deg, o.pitch_deg) * o.distance,
                    target,
                )
            }
            _ => return Err(at(KeyProblem::View)),
        };
        let fov = key.fov_y_deg.unwrap_or(fov_y_deg);
        if !(eye.is_finite() && target.is_finite() && fov > 0.0 && fov < 180.0) {
            return Err(at(KeyProblem::Values));
        }
        times.push(key.time_s);
        views.push(View {
            eye,
            target,
            fov_y_deg: fov,
        });
    }
    let duration = times.last().copied().unwrap_or(0.0);
    Ok((Path::Keys { times, views }, duration))
}

/// The field of view at `time`, eased between keys (smoothstep): it starts and ends each
/// change at rest, as a zoom lens is turned.
fn fov_at(times: &[f64], views: &[View], time: f64) -> f64 {
    let i = times.partition_point(|&t| t <= time);
    match (i.checked_sub(1), views.get(i)) {
        (Some(a), Some(b)) => {
            let u = (time - times[a]) / (times[i] - times[a]);
            let ease = u * u * (3.0 - 2.0 * u);
            views[a].fov_y_deg + (b.fov_y_deg - views[a].fov_y_deg) * ease
        }
        (None, Some(first)) => first.fov_y_deg,
        (_, None) => views.last().map_or(45.0, |v| v.fov_y_deg),
    }
}
