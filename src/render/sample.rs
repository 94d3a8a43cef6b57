//! A sample and what became of each of its rays: the primary ray's hit, the sun's shadow, and
//! each registered effect's outcome. The effects make these; the tallies and statistics count
//! them.

use super::effects::{EffectTime, Outcomes, Shadow};
use crate::geometry::Face;
use crate::traverse::Counters;

/// One traced sample, recorded on its own (see [`Tally`](crate::render::Tally)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    /// 0x00RRGGBB.
    pub rgb: u32,
    /// What the primary ray hit: the terrain or the base, if anything.
    pub hit: Option<Face>,
    /// What became of the shadow ray.
    pub shadow: Shadow,
    /// The primary ray's queries.
    pub primary: Counters,
    /// The shadow rays' queries (towards the sun, or its disc), or those of an effect that
    /// showed in place of the terrain (see [`BeforeHit`](super::effects::BeforeHit)).
    pub secondary: Counters,
    /// What each registered effect did (see [`crate::render::effects`]).
    pub effects: Outcomes,
    /// Intervals left a decision unsettled, and exact mode made it again exactly: it traced
    /// the pixel again in rationals, or cast only its shadow ray again, or decided one of the
    /// shadow ray's triangle tests on its own.
    pub redone: bool,
    /// The time its effects took.
    pub time: EffectTime,
}
