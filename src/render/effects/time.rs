//! What the effects cost in time: each effect's part of a sample timed as it runs (only in a
//! frame with effects, so a plain frame reads no clock per pixel), and the thread time of
//! the whole frame, timed per band or row, to take shares of. Times are in nanoseconds of
//! thread time, summed over threads; the list of effects makes the record
//! ([`EffectTime`](super::EffectTime)), a field per effect.

use std::time::Instant;

/// Nanoseconds since `start`.
pub fn nanos_since(start: Instant) -> u64 {
    u64::try_from(start.elapsed().as_nanos()).unwrap_or(u64::MAX)
}

/// The share of the traced time each part took (0 to 1).
#[derive(Clone, Debug, PartialEq)]
pub struct TimeShares {
    /// Camera rays, hard shadows and shading: what the effects leave.
    pub camera: f64,
    /// Each effect's, by its label, in the list's order.
    pub effects: Vec<(&'static str, f64)>,
    /// Samples after each pixel's first, their effects included.
    pub later_samples: f64,
}

impl TimeShares {
    /// The shares of `traced` nanoseconds that the effects (`(label, nanos)`) and the samples
    /// after each pixel's first took; `None` before anything was timed.
    pub fn of(traced: u64, effects: &[(&'static str, u64)], later_samples: u64) -> Option<Self> {
        if traced == 0 {
            return None;
        }
        let share = |nanos: u64| (nanos as f64 / traced as f64).min(1.0);
        let all: u64 = effects.iter().map(|(_, nanos)| nanos).sum();
        Some(TimeShares {
            camera: share(traced.saturating_sub(all)),
            effects: effects
                .iter()
                .map(|&(l, nanos)| (l, share(nanos)))
                .collect(),
            later_samples: share(later_samples),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::EffectTime;

    /// Shares of a hand-made record: what the effects leave of the traced time is the camera's.
    #[test]
    fn shares_split_the_traced_time() {
        let time = EffectTime {
            traced: 1000,
            soft_shadow: 100,
            sky_light: 500,
            later_samples: 750,
            ..EffectTime::default()
        };
        let shares = time.shares().expect("timed");
        assert_eq!(shares.camera, 0.4);
        let share = |label| {
            shares
                .effects
                .iter()
                .find(|(l, _)| *l == label)
                .map(|s| s.1)
        };
        assert_eq!((share("soft shadow"), share("sky")), (Some(0.1), Some(0.5)));
        assert_eq!(shares.effects.iter().map(|s| s.1).sum::<f64>(), 0.6);
        assert_eq!(shares.later_samples, 0.75);
        assert_eq!(EffectTime::default().shares(), None);
    }
}
