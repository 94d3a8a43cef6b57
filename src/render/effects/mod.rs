//! Effects beyond one ray per pixel, each only where it can change a pixel: several samples
//! per pixel ([`pixel`]), soft shadows from the sun's disc ([`SoftShadows`]) and light from
//! the sky ([`SkyLight`]). A ray that climbs more steeply than the terrain can rise around its
//! start ([`slope_bound`]) is clear without a walk; the others are ordinary shadow rays, traced
//! in the frame's arithmetic (exactly from the exact surface point in exact mode).

mod effect;
mod horizon;
pub mod pixel;
pub(crate) mod sampling;
mod settings;
mod sky;
mod soft_shadow;
mod stats;
mod sun_cone;
mod sun_disc;
mod sun_shadow;
mod time;
mod water;
mod water_surface;

pub use effect::{At, Effect};
pub use horizon::{climbs_above, slope_bound};
pub use settings::{Effects, DEFAULT_RAYS, DEFAULT_SKY_DISTANCE, MOST_RAYS, WIDEST_SUN_DEG};
pub use sky::{open_sky_mean, SkyLight};
pub use soft_shadow::SoftShadows;
pub use stats::{EffectStats, SampleStats, SkyStats, SoftStats, WaterStats};
pub(super) use sun_disc::SunDisc;
pub use sun_shadow::SunShadow;
pub use time::{nanos_since, EffectTime, TimeShares};
pub use water::WaterReflection;
pub use water_surface::{schlick, Water, NORMAL_REFLECTANCE};
