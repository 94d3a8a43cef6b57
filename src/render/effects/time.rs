//! What the effects cost in time: each effect's part of a sample timed as it runs (only in a
//! frame with effects, so a plain frame reads no clock per pixel), and the thread time of
//! the whole frame, timed per band or row, to take shares of. Times are in nanoseconds of
//! thread time, summed over threads.

use derive_more::AddAssign;
use serde_json::{json, Value};
use std::time::Instant;

/// Thread time a frame spent, in all and per effect.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign)]
pub struct EffectTime {
    /// Tracing and shading the frame's pixels, everything included.
    pub traced: u64,
    /// Soft shadows: the directions towards the sun's disc, their culling and rays.
    pub soft: u64,
    /// Sky light: its culling and rays.
    pub sky: u64,
    /// Water: the reflected rays and the water's shading.
    pub water: u64,
    /// The samples each pixel took after its first, with their effects' rays.
    pub later_samples: u64,
}

/// Nanoseconds since `start`.
pub fn nanos_since(start: Instant) -> u64 {
    u64::try_from(start.elapsed().as_nanos()).unwrap_or(u64::MAX)
}

impl EffectTime {
    /// The share of the traced time each part took (0 to 1): camera rays, hard shadows and
    /// shading (what is left), soft shadows, sky light, water; and, across those, the samples
    /// after each pixel's first. `None` before anything was timed.
    pub fn shares(&self) -> Option<TimeShares> {
        if self.traced == 0 {
            return None;
        }
        let share = |nanos: u64| (nanos as f64 / self.traced as f64).min(1.0);
        let effects = self.soft + self.sky + self.water;
        Some(TimeShares {
            camera: share(self.traced.saturating_sub(effects)),
            soft: share(self.soft),
            sky: share(self.sky),
            water: share(self.water),
            later_samples: share(self.later_samples),
        })
    }

    /// The times as JSON, in milliseconds of thread time.
    pub fn to_json(&self) -> Value {
        let ms = |nanos: u64| nanos as f64 / 1e6;
        json!({
            "traced": ms(self.traced), "soft_shadow": ms(self.soft), "sky_light": ms(self.sky),
            "water": ms(self.water), "later_samples": ms(self.later_samples),
        })
    }
}

/// [`EffectTime::shares`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeShares {
    /// Camera rays, hard shadows and shading.
    pub camera: f64,
    /// Soft shadows.
    pub soft: f64,
    /// Sky light.
    pub sky: f64,
    /// Water.
    pub water: f64,
    /// Samples after each pixel's first, their effects included.
    pub later_samples: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Shares of a hand-made record: what the effects leave of the traced time is the camera's.
    #[test]
    fn shares_split_the_traced_time() {
        let time = EffectTime {
            traced: 1000,
            soft: 100,
            sky: 500,
            water: 0,
            later_samples: 750,
        };
        let shares = time.shares().expect("timed");
        assert_eq!(shares.camera, 0.4);
        assert_eq!((shares.soft, shares.sky, shares.water), (0.1, 0.5, 0.0));
        assert_eq!(shares.later_samples, 0.75);
        assert_eq!(EffectTime::default().shares(), None);
    }
}
