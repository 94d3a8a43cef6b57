//! Where a sample's rays are counted as they are cast: straight into the statistics of the
//! frame and the pixel being traced ([`Counting`]), or into a record of the one sample
//! ([`Sample`]) where it may be traced again before it counts (exact mode, see
//! [`Numbers::REDOES`](crate::arith::Numbers::REDOES)) or is shown alone (the viewer's probe).
//! A frame's pixels then carry no counters of their own: only their colour and heat-map
//! queries leave the shader.

use super::effects::EffectTime;
use super::sample::{Reflection, Sample, Shadow, ShadowSkip, SkyRays};
use super::stats::{FrameStats, PixelStats};
use crate::geometry::Face;
use crate::traverse::Counters;

/// Counts what a sample's rays asked, as they are cast.
pub trait Tally {
    /// The sample is traced again from the start: forget what it counted so far. Counts in a
    /// frame cannot be taken back, so by default nothing is forgotten: only numbers that
    /// never trace a sample twice count straight into a frame (see
    /// [`Numbers::REDOES`](crate::arith::Numbers::REDOES)).
    fn restart(&mut self) {}
    /// Its primary ray: the queries, and what it hit, if anything.
    fn primary(&mut self, counters: &Counters, hit: Option<Face>);
    /// What became of its shadow, and the shadow rays' queries (a scene with shadows only).
    fn shadow(&mut self, shadow: Shadow, counters: &Counters);
    /// Its sky-light rays (a scene with sky light only).
    fn sky(&mut self, sky: &SkyRays);
    /// What became of the reflection of the water it shows, and the reflected ray's queries.
    fn water(&mut self, reflection: Reflection, counters: &Counters);
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
    fn sky(&mut self, sky: &SkyRays) {
        self.frame.sky(sky);
        self.pixel.add_queries(&sky.counters);
    }
    #[inline(always)]
    fn water(&mut self, reflection: Reflection, counters: &Counters) {
        self.frame.water(reflection, counters);
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
            Shadow::Soft(soft) => self.effects.add_soft(&soft),
        }
    }
    #[inline(always)]
    fn sky(&mut self, sky: &SkyRays) {
        self.effects.add_sky(sky);
    }
    #[inline(always)]
    fn water(&mut self, reflection: Reflection, counters: &Counters) {
        // (The reflected ray's queries count with the shadow rays', as secondary rays.)
        self.shadow += *counters;
        self.effects.add_reflection(reflection);
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
    fn sky(&mut self, sky: &SkyRays) {
        self.sky = *sky;
    }
    fn water(&mut self, reflection: Reflection, counters: &Counters) {
        (self.reflection, self.secondary) = (reflection, *counters);
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
        if self.sky.of > 0 {
            tally.sky(&self.sky);
        }
        if self.reflection != Reflection::NotWater {
            tally.water(self.reflection, &self.secondary);
        }
        if self.redone {
            tally.redone();
        }
        if self.time != EffectTime::default() {
            tally.time(&self.time);
        }
    }
}
