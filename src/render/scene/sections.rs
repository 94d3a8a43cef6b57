//! The `[sun]`, `[effects]` and `[render]` sections of a scene file, as written.

use super::triple;
use serde::Deserialize;

/// A scene file's `[sun]` section.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SunSection {
    /// Towards the sun; normalised on load.
    #[serde(default = "default_sun", deserialize_with = "triple::three")]
    pub direction: [f64; 3],
    /// Instead of `direction`: the sun's compass bearing (0 north, 90 east) and its
    /// elevation above the horizon, in degrees.
    #[serde(default)]
    pub azimuth_deg: Option<f64>,
    /// With `azimuth_deg`: degrees above the horizon.
    #[serde(default)]
    pub elevation_deg: Option<f64>,
    /// Instead of `direction`: where the sun stands at this time over the map's centre, or
    /// over `lat` and `lon`: an instant (`2026-12-21T08:00:00Z`) or a local time
    /// (`2026-06-21T09:30`) in `zone`.
    #[serde(default)]
    pub time: Option<String>,
    /// The IANA time zone of a local `time` (default: the zone at the place).
    #[serde(default)]
    pub zone: Option<String>,
    /// Latitude in degrees for `time`.
    #[serde(default)]
    pub lat: Option<f64>,
    /// Longitude in degrees for `time`.
    #[serde(default)]
    pub lon: Option<f64>,
    /// Direct light at full facing (default 1).
    #[serde(default = "one")]
    pub intensity: f64,
    /// Light everywhere, facing the sun or not (default 0.25).
    #[serde(default = "default_ambient")]
    pub ambient: f64,
    /// The sun's angular diameter in degrees (default 0: hard shadows).
    #[serde(default)]
    pub angle_deg: f64,
    /// Directions towards the sun's disc per point, for soft shadows (default 16).
    #[serde(default)]
    pub rays: Option<u32>,
}

/// A scene file's `[effects]` section.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct EffectsSection {
    /// Cast shadow rays towards the sun (default off).
    #[serde(default)]
    pub shadows: bool,
    /// Fog density per unit of distance; 0 is off.
    #[serde(default)]
    pub fog: f64,
    /// Light from the sky dome instead of the constant ambient term (default off).
    #[serde(default)]
    pub sky_light: bool,
    /// Sky-light rays per pixel, shared out among its samples (default 16).
    #[serde(default)]
    pub sky_rays: Option<u32>,
    /// How far sky-light rays look for terrain, in world units (default 64).
    #[serde(default)]
    pub sky_distance: Option<f64>,
}

/// A scene file's `[render]` section, as written (parsed when the scene is validated).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RenderSection {
    /// Traversal method, as `--method` takes it (default `auto`).
    #[serde(default = "default_method")]
    pub method: String,
    /// Arithmetic, as `--arith` takes it (default `f64`).
    #[serde(default = "default_arith")]
    pub arith: String,
    /// Camera rays per pixel (default 1).
    #[serde(default = "one_sample")]
    pub samples: u32,
    /// Stop a pixel's samples once they agree (default off).
    #[serde(default)]
    pub adaptive: bool,
}

impl Default for SunSection {
    fn default() -> Self {
        SunSection {
            direction: default_sun(),
            azimuth_deg: None,
            elevation_deg: None,
            time: None,
            zone: None,
            lat: None,
            lon: None,
            intensity: 1.0,
            ambient: default_ambient(),
            angle_deg: 0.0,
            rays: None,
        }
    }
}

impl Default for RenderSection {
    fn default() -> Self {
        RenderSection {
            method: default_method(),
            arith: default_arith(),
            samples: 1,
            adaptive: false,
        }
    }
}

fn default_sun() -> [f64; 3] {
    [0.4, 0.3, 0.8]
}
pub(super) fn one() -> f64 {
    1.0
}
fn one_sample() -> u32 {
    1
}
fn default_ambient() -> f64 {
    0.25
}
fn default_method() -> String {
    "auto".into()
}
fn default_arith() -> String {
    "f64".into()
}
