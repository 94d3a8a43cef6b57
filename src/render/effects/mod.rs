//! Effects beyond one ray per pixel, each only where it can change a pixel: several samples
//! per pixel ([`pixel`]), soft shadows from the sun's disc ([`SoftShadow`]) and light from
//! the sky ([`SkyRays`]). A ray that climbs more steeply than the terrain can rise around its
//! start ([`slope_bound`]) is clear without a walk; the others are ordinary shadow rays, traced
//! in the frame's arithmetic (exactly from the exact surface point in exact mode).

mod accumulate;
mod horizon;
pub mod pixel;
pub(crate) mod sampling;
mod sky;
mod soft_shadow;
mod stats;
mod sun_cone;
mod time;
mod water;

pub use accumulate::{reach, Accumulation};
pub use horizon::{climbs_above, slope_bound};
pub use sky::{open_sky_mean, SkyRays};
pub use soft_shadow::SoftShadow;
pub use stats::{EffectStats, SampleStats, SkyStats, SoftStats, WaterStats};
pub use time::{nanos_since, EffectTime, TimeShares};
pub use water::{schlick, Reflection, Water, WaterPixel, NORMAL_REFLECTANCE};

use super::scene::{EffectsSection, RenderSection, SunSection};
use crate::compact::Compact;

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
    /// Sky-light rays per pixel, shared out among its samples (see [`pixel::per_sample`]).
    pub sky_rays: u32,
    /// How far a sky-light ray looks for terrain in its way, horizontally, in world units
    /// (cells along y): the light of a sky hidden only by far ridges is kept, as a terrain
    /// picture's ambient shading does.
    pub sky_distance: f64,
    /// Camera rays per pixel (at most; see `adaptive`).
    pub samples: u32,
    /// A pixel stops taking samples once they agree (see [`pixel`]).
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
    /// The effects of a scene file's sections, or which key is out of range.
    pub fn from_sections(
        sun: &SunSection,
        effects: &EffectsSection,
        render: &RenderSection,
    ) -> Result<Effects, String> {
        let angle = sun.angle_deg;
        if !(angle.is_finite() && (0.0..=WIDEST_SUN_DEG).contains(&angle)) {
            return Err(format!(
                "[sun] angle_deg must be a number from 0 to {WIDEST_SUN_DEG} (degrees; the \
                 real sun is 0.53), got {}",
                Compact(angle)
            ));
        }
        let count = |key: &str, value: Option<u32>| match value.unwrap_or(DEFAULT_RAYS) {
            n @ 1..=MOST_RAYS => Ok(n),
            n => Err(format!("{key} must be from 1 to {MOST_RAYS}, got {n}")),
        };
        let sky_distance = effects.sky_distance.unwrap_or(DEFAULT_SKY_DISTANCE);
        if sky_distance.is_nan() || sky_distance <= 0.0 {
            return Err(format!(
                "[effects] sky_distance must be a distance above 0 (world units; inf looks \
                 across the whole map), got {}",
                Compact(sky_distance)
            ));
        }
        Ok(Effects {
            sun_angle_deg: angle,
            sun_rays: count("[sun] rays", sun.rays)?,
            sky_light: effects.sky_light,
            sky_rays: count("[effects] sky_rays", effects.sky_rays)?,
            sky_distance,
            samples: count("[render] samples", Some(render.samples))?,
            adaptive: render.adaptive,
            water: None,
        })
    }

    /// Whether any effect beyond today's frame is asked for.
    pub fn any(&self) -> bool {
        self.sun_angle_deg > 0.0 || self.sky_light || self.samples > 1 || self.water.is_some()
    }
}
