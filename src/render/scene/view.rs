//! A scene file's `[camera]` section, and the camera of a scene without one: the whole map,
//! framed as the viewer first shows it.

use super::orbit::Orbit;
use super::triple::{maybe_three, three};
use super::SceneError;
use crate::render::camera::Camera;
use crate::render::framing;
use crate::{Heightfield, Terrain};
use serde::Deserialize;
use std::path::Path;

/// The image size of a scene without a `[camera]` section, nor a size given.
pub const DEFAULT_SIZE: (u32, u32) = (1280, 720);

/// A scene file's `[camera]` section: `eye` and `target`, or `orbit`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CameraSection {
    /// Where the camera is (with `target`).
    #[serde(default, deserialize_with = "maybe_three")]
    pub eye: Option<[f64; 3]>,
    /// What it looks at (with `eye`).
    #[serde(default, deserialize_with = "maybe_three")]
    pub target: Option<[f64; 3]>,
    /// An orbit around a target instead of `eye` and `target`.
    pub orbit: Option<Orbit>,
    /// The direction that is up in the image (default +z).
    #[serde(default = "default_up", deserialize_with = "three")]
    pub up: [f64; 3],
    /// Vertical field of view in degrees (default 45).
    #[serde(default = "default_fov")]
    pub fov_y_deg: f64,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

fn default_up() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}
fn default_fov() -> f64 {
    45.0
}

/// The camera of a `[camera]` section at `size` if given, or framing the whole of `field`
/// (which framing builds the terrain of, and hands back); `path` names the scene in errors.
pub fn camera(
    section: Option<&CameraSection>,
    size: Option<(u32, u32)>,
    field: Heightfield,
    path: &Path,
) -> Result<(Heightfield, Camera), SceneError> {
    let camera_error = |source| SceneError::Camera {
        path: path.to_owned(),
        source,
    };
    let Some(section) = section else {
        let terrain = Terrain::new(field);
        let camera = framing::framed_camera(&terrain, size.unwrap_or(DEFAULT_SIZE));
        return Ok((terrain.into_field(), camera.map_err(camera_error)?));
    };
    let size = size.unwrap_or((section.width, section.height));
    let built = match (section.eye, section.target, section.orbit) {
        (Some(eye), Some(target), None) => {
            Camera::look_at(eye, target, section.up, section.fov_y_deg, size)
        }
        (None, None, Some(o)) => Camera::orbit(
            o.target,
            o.yaw_deg,
            o.pitch_deg,
            o.distance,
            section.fov_y_deg,
            size,
        ),
        _ => {
            return Err(SceneError::Invalid {
                path: path.to_owned(),
                message: "[camera] needs either both eye and target, or \
                          orbit = {target, yaw_deg, pitch_deg, distance}"
                    .into(),
            })
        }
    };
    Ok((field, built.map_err(camera_error)?))
}
