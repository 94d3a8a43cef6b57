//! The last sun's sweep of a terrain, kept for the frames that follow with the same sun.

use super::{SunSweep, SweepStart, Verdict};
use crate::heightfield::Terrain;
use std::sync::RwLock;

/// The sweep for the last sun asked for (`None` inside where that sun has none).
#[derive(Debug, Default)]
pub struct SweepCache(RwLock<Option<([f64; 3], Option<SunSweep>)>>);

impl Clone for SweepCache {
    /// A clone starts empty: the sweep is rebuilt on first use.
    fn clone(&self) -> Self {
        SweepCache::default()
    }
}

impl SweepCache {
    /// The verdict of the sweep of `terrain` for a sun in direction `dir` on the shadow ray
    /// from `start`, sweeping first if the last sun was another; `Verdict::Unknown` where
    /// that sun has no sweep.
    pub fn verdict(&self, terrain: &Terrain, dir: [f64; 3], start: &SweepStart) -> Verdict {
        let answer = |kept: &Option<([f64; 3], Option<SunSweep>)>| match kept {
            Some((swept, sweep)) if *swept == dir => Some(
                sweep
                    .as_ref()
                    .map_or(Verdict::Unknown, |sweep| sweep.verdict(terrain, start)),
            ),
            _ => None,
        };
        // (A poisoned lock only means another thread panicked mid-sweep: sweep again.)
        if let Some(verdict) = answer(&self.0.read().unwrap_or_else(|e| e.into_inner())) {
            return verdict;
        }
        let mut kept = self.0.write().unwrap_or_else(|e| e.into_inner());
        if answer(&kept).is_none() {
            *kept = Some((dir, SunSweep::build(terrain, dir)));
        }
        answer(&kept).unwrap_or(Verdict::Unknown)
    }

    /// Drops the kept sweep, so the next shadow ray sweeps again.
    pub fn forget(&self) {
        *self.0.write().unwrap_or_else(|e| e.into_inner()) = None;
    }

    /// Bytes of the kept sweep's table.
    pub fn bytes(&self) -> usize {
        let kept = self.0.read().unwrap_or_else(|e| e.into_inner());
        kept.as_ref()
            .and_then(|(_, sweep)| sweep.as_ref())
            .map_or(0, SunSweep::bytes)
    }
}
