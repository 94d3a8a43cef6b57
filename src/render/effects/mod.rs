//! Effects beyond one ray per pixel, each only where it can change a pixel: several samples
//! per pixel ([`pixel`]), soft shadows from the sun's disc ([`SoftShadows`]), light from the
//! sky ([`SkyLight`]) and water ([`WaterReflection`]). A ray that climbs more steeply than
//! the terrain can rise around its start ([`slope_bound`]) is clear without a walk; the
//! others are ordinary shadow rays, traced in the frame's arithmetic (exactly from the exact
//! surface point in exact mode).
//!
//! Each effect lives in one file and is asked as pbrt asks its lights: the shader calls every
//! effect of the list below in its stage, and each says what it did; the statistics, the
//! `--stats` JSON, the viewer's Effects panel and `bench effects` go through the same list.
//!
//! To add an effect: write `effects/<name>.rs` holding
//! - its type, what it does ([`Effect::cast`], or directly in its stage's hook), its
//!   per-sample outcome (`Copy + Default + PartialEq`, the default meaning "not asked") and
//!   its counters, a struct that derives `AddAssign` and `Serialize`;
//! - `impl` [`Counted`] (its name in the statistics, its labels, how one outcome is counted,
//!   the rays it cast and the share it left out) and [`Sampled`] (whether the scene asks for
//!   it);
//! - `impl` its stage: [`AtHit`] (it changes the [`Light`] at a hit, the sun's share seen or
//!   the ambient light, and its outcome keeps its rays' queries) or [`BeforeHit`] (it shows
//!   in place of the terrain along the camera ray, as water does);
//!
//! then register it with one line in the list below, `name: file::Type,` in its stage (the
//! list declares the file's module; the shader asks a stage's effects in the list's order).
//! The sample's record ([`Outcomes`]), the frame's counters ([`EffectStats`]) and times
//! ([`EffectTime`]), their `--stats` JSON, the viewer's Effects panel and the columns of
//! `bench effects` follow from the list. An effect reads its settings from the scene's
//! [`Effects`]; a setting the scene file does not have yet is a field there and a key of the
//! file's `[effects]` section. (`sun` holds the disc that casts the sun's shadow in place of
//! hard shadows' one ray: the shader's own place, so only counted here.)
//!
//! To add a counter to an effect: add a field to its counters' struct and count it in its
//! [`Counted::count`]; the derives sum it and report it under the field's name.

mod effect;
mod horizon;
pub mod pixel;
mod probe;
mod registry;
pub(crate) mod sampling;
mod settings;
mod sun_cone;
mod sun_disc;
mod sun_shadow;
mod time;
mod water_surface;

use pixel::SampleStats;
use registry::registry;

pub use effect::{Around, At, AtHit, BeforeHit, Counted, Effect, Light, Sampled, Shown, Summary};
pub use horizon::{climbs_above, slope_bound};
pub use settings::{Effects, DEFAULT_RAYS, DEFAULT_SKY_DISTANCE, MOST_RAYS, WIDEST_SUN_DEG};
pub use sky::{open_sky_mean, SkyLight, SkyRays, SkyStats};
pub use soft_shadow::{SoftShadows, SoftStats};
pub(super) use sun_disc::SunDisc;
pub use sun_shadow::{Cast, Shadow, ShadowSkip, SoftShadow, SunShadow};
pub use time::{nanos_since, TimeShares};
pub use water::{Reflection, WaterReflection, WaterStats};
pub use water_surface::{schlick, Water, NORMAL_REFLECTANCE};

registry! {
    sun {
        soft_shadow: soft_shadow::SoftShadows,
    }
    before_hit {
        water: water::WaterReflection,
    }
    at_hit {
        sky_light: sky::SkyLight,
    }
}
