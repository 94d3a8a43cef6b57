//! The open zenith: one occlusion ray straight up from each point; a point with terrain above
//! it gets half the ambient light. Asked in frames of several samples without sky light.

use super::effect::{Around, At, AtHit, Counted, Light, Sampled};
use crate::arith::Scalar;
use crate::render::context::Context;
use crate::traverse::Counters;
use derive_more::AddAssign;
use serde::Serialize;

/// The zenith's ray.
pub struct Zenith;

/// What became of a point's ray up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Up {
    /// The ray was asked.
    pub asked: bool,
    /// It met the terrain.
    pub blocked: bool,
    /// Its queries.
    pub queries: Counters,
    /// Exact mode decided one of its tests again exactly.
    pub redone: bool,
}

/// The zenith's rays of a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign, Serialize)]
pub struct ZenithStats {
    /// Points asked.
    pub points: u64,
    /// Rays up that met the terrain.
    pub blocked: u64,
    /// Their queries.
    pub queries: Counters,
}

impl Counted for Zenith {
    const NAME: &'static str = "zenith";
    const LABEL: &'static str = "zenith";
    const WORD: &'static str = "zenith";
    type Outcome = Up;
    type Stats = ZenithStats;

    fn count(up: &Up, stats: &mut ZenithStats) {
        stats.points += u64::from(up.asked);
        stats.blocked += u64::from(up.blocked);
        stats.queries += up.queries;
    }

    fn rays(stats: &ZenithStats) -> u64 {
        stats.points
    }

    fn culled(_: &ZenithStats, _: &Around<'_>) -> Option<f64> {
        None
    }
}

impl Sampled for Zenith {
    fn asked(cx: &Context<'_>) -> bool {
        cx.lighting.effects.samples > 1 && !cx.lighting.effects.sky_light
    }
}

impl AtHit for Zenith {
    fn at_hit<S: Scalar>(cx: &Context<'_>, at: &At<'_, S>, light: &mut Light) -> Up {
        let answer = cx.occluded(at.start(cx), [0.0, 0.0, 1.0], None);
        let blocked = answer.occluded == Some(true);
        if blocked {
            light.ambient *= 0.5;
        }
        Up {
            asked: true,
            blocked,
            queries: answer.counters,
            redone: answer.exactly,
        }
    }

    fn queries(up: &Up) -> Counters {
        up.queries
    }

    fn redone(up: &Up) -> bool {
        up.redone
    }
}
