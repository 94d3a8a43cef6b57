//! What the effects cost in a frame: rays cast and left out, per effect and reason, and the
//! samples each pixel took.

use crate::render::sample::{Reflection, SkyRays, SoftShadow};
use crate::traverse::Counters;
use derive_more::with_trait::AddAssign;
use serde_json::{json, Value};

/// Soft shadows of a frame (points the shadow rules settled whole are counted with the hard
/// shadows' skips, [`crate::render::FrameStats::skipped`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign)]
pub struct SoftStats {
    /// Points that needed directions towards the sun's disc (a penumbra or not proven).
    pub points: u64,
    /// Directions asked at those points.
    pub directions: u64,
    /// Directions traced as shadow rays.
    pub rays: u64,
    /// Rays that looked for a cone blocked whole (beside the directions).
    pub probes: u64,
    /// Points whose cone was settled as blocked whole.
    pub blocked: u64,
    /// Directions that reached the sun.
    pub clear: u64,
}

/// Sky light of a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign)]
pub struct SkyStats {
    /// Points lit by the sky.
    pub points: u64,
    /// Directions asked.
    pub directions: u64,
    /// Directions traced.
    pub rays: u64,
    /// Directions that reached the sky.
    pub open: u64,
    /// Points whose every direction climbed above the terrain's bound: no ray at all.
    pub points_clear: u64,
    /// The traced rays' queries.
    pub queries: Counters,
}

/// Water of a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign)]
pub struct WaterStats {
    /// Pixels showing water.
    pub points: u64,
    /// Reflected rays traced.
    pub rays: u64,
    /// Reflected rays that met the terrain.
    pub hits: u64,
    /// Reflected rays left out: they climb above the terrain's bound and see the sky.
    pub culled: u64,
}

/// Samples per pixel: how many pixels took how many camera rays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SampleStats {
    /// Pixels finished.
    pub pixels: u64,
    /// Pixels by samples taken: entry `k` counts those that took `2^k` to `2^(k+1) - 1`.
    pub histogram: [u64; 11],
}

/// The effects' rays of a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign)]
pub struct EffectStats {
    /// Soft shadows.
    pub soft: SoftStats,
    /// Sky light.
    pub sky: SkyStats,
    /// Samples per pixel.
    pub samples: SampleStats,
    /// Water.
    pub water: WaterStats,
}

impl EffectStats {
    /// Counts one shaded point's soft shadow.
    pub fn add_soft(&mut self, soft: &SoftShadow) {
        self.soft.points += 1;
        self.soft.directions += u64::from(soft.of);
        self.soft.rays += u64::from(soft.cast);
        self.soft.probes += u64::from(soft.probed);
        self.soft.blocked += u64::from(soft.blocked);
        self.soft.clear += u64::from(soft.clear);
    }

    /// Counts one shaded point's sky light.
    pub fn add_sky(&mut self, sky: &SkyRays) {
        if sky.of == 0 {
            return;
        }
        self.sky.points += 1;
        self.sky.directions += u64::from(sky.of);
        self.sky.rays += u64::from(sky.cast);
        self.sky.open += u64::from(sky.open);
        self.sky.points_clear += u64::from(sky.cast == 0);
        self.sky.queries += sky.counters;
    }

    /// Counts one camera ray's reflection.
    pub fn add_reflection(&mut self, reflection: Reflection) {
        let water = &mut self.water;
        match reflection {
            Reflection::NotWater => return,
            Reflection::Clear => water.culled += 1,
            Reflection::Cast { hit } => {
                water.rays += 1;
                water.hits += u64::from(hit);
            }
        }
        water.points += 1;
    }

    /// Counts one finished pixel that took `samples` camera rays.
    pub fn add_pixel(&mut self, samples: u32) {
        self.samples.pixels += 1;
        let bucket = (31 - samples.max(1).leading_zeros()) as usize;
        self.samples.histogram[bucket.min(10)] += 1;
    }

    /// The effects as JSON; `camera_rays` is the frame's primary rays (for samples per pixel).
    pub fn to_json(&self, camera_rays: u64) -> Value {
        let (soft, sky, samples) = (&self.soft, &self.sky, &self.samples);
        json!({
            "soft_shadow": {
                "points": soft.points, "directions": soft.directions, "rays": soft.rays,
                "probes": soft.probes, "points_blocked": soft.blocked,
                "culled": soft.directions - soft.rays, "clear": soft.clear,
            },
            "sky_light": {
                "points": sky.points, "directions": sky.directions, "rays": sky.rays,
                "culled_horizon_clear": sky.directions - sky.rays, "open": sky.open,
                "points_without_rays": sky.points_clear, "queries": sky.queries,
            },
            "water": {
                "points": self.water.points, "rays": self.water.rays,
                "culled_horizon_clear": self.water.culled, "hits": self.water.hits,
            },
            "samples_per_pixel": {
                "mean": camera_rays as f64 / samples.pixels.max(1) as f64,
                "pixels_by_power_of_two": samples.histogram,
            },
        })
    }
}

impl AddAssign for SampleStats {
    fn add_assign(&mut self, rhs: SampleStats) {
        self.pixels += rhs.pixels;
        for (a, b) in self.histogram.iter_mut().zip(rhs.histogram) {
            *a += b;
        }
    }
}
