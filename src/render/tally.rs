//! Where a sample's rays are counted as they are cast: straight into the statistics of the
//! frame and the pixel being traced ([`Counting`]), or into a record of the one sample
//! ([`Sample`]) where it may be traced again before it counts (exact mode, see
//! [`Numbers::REDOES`](crate::arith::Numbers::REDOES)) or is shown alone (the viewer's probe).
//! A frame's pixels then carry no counters of their own: only their colour and heat-map
//! queries leave the shader.

use super::effects::{AtHit, BeforeHit, EffectTime, Kept, Record, Shadow, ShadowSkip, SoftShadows};
use super::sample::Sample;
use super::stats::{FrameStats, PixelStats};
use crate::geometry::Face;
use crate::traverse::Counters;

/// Counts what a sample's rays asked, as they are cast; each effect's outcome goes through
/// [`Record`].
pub trait Tally: Record {
    /// The sample is traced again from the start: forget what it counted so far. Counts in a
    /// frame cannot be taken back, so by default nothing is forgotten: only numbers that
    /// never trace a sample twice count straight into a frame (see
    /// [`Numbers::REDOES`](crate::arith::Numbers::REDOES)).
    fn restart(&mut self) {}
    /// Its primary ray: the queries, and what it hit, if anything.
    fn primary(&mut self, counters: &Counters, hit: Option<Face>);
    /// What became of its shadow, and the shadow rays' queries (a scene with shadows only).
    fn shadow(&mut self, shadow: Shadow, counters: &Counters);
    /// A decision on it was made again exactly ([`Sample::redone`]); noted once per sample.
    fn redone(&mut self);
    /// The time its effects took (a frame with effects only).
    fn time(&mut self, time: &EffectTime);
}

/// Counts straight into the statistics of a frame (or a band of it) and of one pixel.
pub struct Counting<'a> {
    /// The frame's totals.
    pub frame: &'a mut FrameStats,
    /// The pixel's queries (its `samples` are the caller's to set).
    pub pixel: PixelStats,
}

impl<'a> Counting<'a> {
    /// Counting a new pixel into `frame`.
    #[inline(always)]
    pub fn new(frame: &'a mut FrameStats) -> Self {
        Counting {
            frame,
            pixel: PixelStats::default(),
        }
    }
}

impl Record for Counting<'_> {
    #[inline(always)]
    fn before_hit<E: BeforeHit + Kept>(&mut self, outcome: &E::Outcome, queries: &Counters) {
        self.frame.before_hit::<E>(outcome, queries);
        self.pixel.add_queries(queries);
    }
    #[inline(always)]
    fn at_hit<E: AtHit + Kept>(&mut self, outcome: &E::Outcome) {
        self.frame.at_hit::<E>(outcome);
        self.pixel.add_queries(&E::queries(outcome));
    }
}

impl Tally for Counting<'_> {
    #[inline(always)]
    fn primary(&mut self, counters: &Counters, hit: Option<Face>) {
        self.frame.primary(counters, hit);
        self.pixel.add_queries(counters);
    }
    #[inline(always)]
    fn shadow(&mut self, shadow: Shadow, counters: &Counters) {
        self.frame.shadow(shadow, counters);
        self.pixel.add_queries(counters);
    }
    #[inline(always)]
    fn redone(&mut self) {
        self.frame.redone();
    }
    #[inline(always)]
    fn time(&mut self, time: &EffectTime) {
        self.frame.time += *time;
    }
}

impl Record for FrameStats {
    #[inline(always)]
    fn before_hit<E: BeforeHit + Kept>(&mut self, outcome: &E::Outcome, queries: &Counters) {
        // (In place of the shadow ray: its queries count with the shadow rays', as secondary.)
        self.shadow += *queries;
        self.effects.count::<E>(outcome);
    }
    #[inline(always)]
    fn at_hit<E: AtHit + Kept>(&mut self, outcome: &E::Outcome) {
        self.effects.count::<E>(outcome);
    }
}

impl Tally for FrameStats {
    #[inline(always)]
    fn primary(&mut self, counters: &Counters, hit: Option<Face>) {
        self.primary_rays += 1;
        self.primary_hits += u64::from(hit.is_some());
        self.base_hits += u64::from(hit.is_some_and(|face| face != Face::Terrain));
        self.primary += *counters;
    }
    #[inline(always)]
    fn shadow(&mut self, shadow: Shadow, counters: &Counters) {
        self.shadow += *counters;
        match shadow {
            Shadow::NotAsked => {}
            Shadow::Cast { shadowed } => {
                self.shadow_rays += 1;
                self.shadowed += u64::from(shadowed);
            }
            Shadow::Skipped(ShadowSkip::FacingAway) => self.skipped.facing_away += 1,
            Shadow::Skipped(ShadowSkip::NoShadowPossible) => self.skipped.no_shadow_possible += 1,
            Shadow::Skipped(ShadowSkip::AboveTerrain) => self.skipped.above_terrain += 1,
            Shadow::Skipped(ShadowSkip::HorizonClear) => self.skipped.horizon_clear += 1,
            Shadow::Soft(soft) => self.effects.count::<SoftShadows>(&soft),
        }
    }
    #[inline(always)]
    fn redone(&mut self) {
        self.redone += 1;
    }
    #[inline(always)]
    fn time(&mut self, time: &EffectTime) {
        self.time += *time;
    }
}

impl Record for Sample {
    fn before_hit<E: BeforeHit + Kept>(&mut self, outcome: &E::Outcome, queries: &Counters) {
        *E::outcome_mut(&mut self.effects) = *outcome;
        self.secondary = *queries;
    }
    fn at_hit<E: AtHit + Kept>(&mut self, outcome: &E::Outcome) {
        *E::outcome_mut(&mut self.effects) = *outcome;
    }
}

impl Tally for Sample {
    fn restart(&mut self) {
        *self = Sample::default();
    }
    fn primary(&mut self, counters: &Counters, hit: Option<Face>) {
        (self.primary, self.hit) = (*counters, hit);
    }
    fn shadow(&mut self, shadow: Shadow, counters: &Counters) {
        (self.shadow, self.secondary) = (shadow, *counters);
    }
    fn redone(&mut self) {
        self.redone = true;
    }
    fn time(&mut self, time: &EffectTime) {
        self.time += *time;
    }
}

impl Sample {
    /// Counts this sample, as recorded, into `tally`.
    pub fn count_into(&self, tally: &mut impl Tally) {
        tally.primary(&self.primary, self.hit);
        if self.shadow != Shadow::NotAsked {
            tally.shadow(self.shadow, &self.secondary);
        }
        self.effects.record_into(&self.secondary, tally);
        if self.redone {
            tally.redone();
        }
        if self.time != EffectTime::default() {
            tally.time(&self.time);
        }
    }
}
