//! The effects a scene calls for, validated, and their limits.

use super::water_surface::Water;

/// The most rays towards the sun's disc, or the sky, and samples per pixel a scene may ask.
pub const MOST_RAYS: u32 = 1024;

/// The widest sun a scene may ask, in degrees (the real one is about 0.53).
pub const WIDEST_SUN_DEG: f64 = 20.0;

/// The effects a scene calls for, validated (all off by default).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effects {
    /// The sun's angular diameter in degrees: 0 casts today's hard shadows.
    pub sun_angle_deg: f64,
    /// Directions towards the sun's disc per pixel, shared out among its samples (soft
    /// shadows only).
    pub sun_rays: u32,
    /// Light from the sky dome instead of the constant ambient term.
    pub sky_light: bool,
    /// Sky-light rays per pixel, shared out among its samples (see [`per_sample`](super::pixel::per_sample)).
    pub sky_rays: u32,
    /// How far a sky-light ray looks for terrain in its way, horizontally, in world units
    /// (cells along y): the light of a sky hidden only by far ridges is kept, as a terrain
    /// picture's ambient shading does.
    pub sky_distance: f64,
    /// Camera rays per pixel (at most; see `adaptive`).
    pub samples: u32,
    /// A pixel stops taking samples once they agree (see [`super::pixel`]).
    pub adaptive: bool,
    /// A water surface and its reflections.
    pub water: Option<Water>,
}

impl Default for Effects {
    fn default() -> Self {
        Effects {
            sun_angle_deg: 0.0,
            sun_rays: DEFAULT_RAYS,
            sky_light: false,
            sky_rays: DEFAULT_RAYS,
            sky_distance: DEFAULT_SKY_DISTANCE,
            samples: 1,
            adaptive: false,
            water: None,
        }
    }
}

/// Rays towards the sun's disc or the sky when the scene does not say.
pub const DEFAULT_RAYS: u32 = 16;

/// How far sky-light rays look when the scene does not say, in world units: the valleys and
/// gullies that shade a terrain picture are narrower; the distant ridges beyond darken a
/// whole slope alike.
pub const DEFAULT_SKY_DISTANCE: f64 = 64.0;

impl Effects {
    /// Whether any effect beyond today's frame is asked for.
    pub fn any(&self) -> bool {
        self.sun_angle_deg > 0.0 || self.sky_light || self.samples > 1 || self.water.is_some()
    }
}
