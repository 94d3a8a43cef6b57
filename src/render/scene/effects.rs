//! The effects of a scene file's sections, validated.

use super::{EffectsSection, RenderSection, SunSection};
use crate::compact::Compact;
use crate::render::effects::{
    Effects, DEFAULT_RAYS, DEFAULT_SKY_DISTANCE, MOST_RAYS, WIDEST_SUN_DEG,
};
use thiserror::Error;

/// Which effects key is out of range.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum EffectsError {
    /// The sun's angular diameter.
    #[error(
        "[sun] angle_deg must be a number from 0 to {WIDEST_SUN_DEG} (degrees; the real sun \
         is 0.53), got {}",
        Compact(*.0)
    )]
    SunAngle(f64),
    /// A count of rays or samples.
    #[error("{key} must be from 1 to {MOST_RAYS}, got {value}")]
    Count {
        /// The key.
        key: &'static str,
        /// Its value.
        value: u32,
    },
    /// How far sky rays look.
    #[error(
        "[effects] sky_distance must be a distance above 0 (world units; inf looks across \
         the whole map), got {}",
        Compact(*.0)
    )]
    SkyDistance(f64),
}

/// The effects of a scene file's sections, or which key is out of range.
pub(super) fn effects_of(
    sun: &SunSection,
    effects: &EffectsSection,
    render: &RenderSection,
) -> Result<Effects, EffectsError> {
    let angle = sun.angle_deg;
    if !(angle.is_finite() && (0.0..=WIDEST_SUN_DEG).contains(&angle)) {
        return Err(EffectsError::SunAngle(angle));
    }
    let count = |key: &'static str, value: Option<u32>| match value.unwrap_or(DEFAULT_RAYS) {
        n @ 1..=MOST_RAYS => Ok(n),
        value => Err(EffectsError::Count { key, value }),
    };
    let sky_distance = effects.sky_distance.unwrap_or(DEFAULT_SKY_DISTANCE);
    if sky_distance.is_nan() || sky_distance <= 0.0 {
        return Err(EffectsError::SkyDistance(sky_distance));
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
