//! Soft shadows: the sun as a disc of the scene's angular diameter. A point whose whole cone
//! towards the disc provably clears the terrain is settled by the rules hard shadows use
//! (generalised to the cone's lowest direction) or by the mipmap's bound of how steeply the
//! terrain rises around it, where it has [`BOUNDED_FROM`] directions or more (with fewer, the
//! bounds cost more than the rays); elsewhere each direction of a stratified set over the disc is a
//! shadow ray, unless it alone climbs above that bound. A cone whose first direction traced
//! is blocked may be settled as blocked whole ([`sun_cone`](super::sun_cone)) by one more ray.
//!
//! Its outcome fills the sun's shadow of a sample ([`Shadow::Soft`]) in place of the hard
//! shadow's one ray; points its rules settle whole count with the hard shadows' skips
//! ([`crate::render::FrameStats::skipped`]).

use super::effect::{Around, At, Counted, Effect};
use super::horizon::{climbs_above, slope_bound};
use super::pixel::per_sample;
use super::sampling::{point, seed_of};
use super::sun_cone::{self, Cone};
use super::sun_shadow::{Cast, Shadow, ShadowSkip, SoftShadow};
use crate::arith::Scalar;
use crate::geometry::Ray;
use crate::render::context::Context;
use crate::traverse::{Counters, Found};
use derive_more::AddAssign;
use glam::DVec3;
use serde::Serialize;

/// The purpose a soft shadow's samples are seeded with (see [`seed_of`]).
const PURPOSE: u64 = 0x5011_d15c;

/// Directions a point needs before its cone is bounded: the march along the cone and the
/// slope bound each cost about as much as a ray or two, and a point with one direction
/// renders faster casting it than bounding it first (measured).
const BOUNDED_FROM: u32 = 4;

/// The sun as a disc: shadow rays over it, those that provably clear the terrain or are
/// provably blocked left out.
pub struct SoftShadows;

impl Effect for SoftShadows {
    type Outcome = Cast;

    fn cast<S: Scalar>(&self, cx: &Context<'_>, at: &At<'_, S>) -> Cast {
        let (found, ray) = (at.found, at.ray);
        let skip = |why| (Shadow::Skipped(why), Counters::default(), false);
        // The disc is drawn around the sun's direction in grid coordinates, where the rays and
        // the bounds are; on non-square cells it is stretched with the cells.
        let disc = cx.sun_disc();
        let (axis, rises) = (disc.axis, disc.lowest > 0.0);
        let steepest = cx.terrain.max_slope() * (1.0 + 1e-9);
        if cx.culling.no_shadow_possible && rises && disc.lowest_tan > steepest {
            return skip(ShadowSkip::NoShadowPossible);
        }
        let shared = at.start(cx);
        let start = shared.point;
        let (_, z_max) = cx.terrain.z_range();
        if cx.culling.above_terrain && rises && start.z > z_max {
            return skip(ShadowSkip::AboveTerrain);
        }
        // The kept bounds clear the whole disc with one look-up.
        if rises && cx.disc_clear(shared, axis.into(), disc.lowest_tan) {
            return skip(ShadowSkip::HorizonClear);
        }
        let whole_cone = disc.cone.map(|cone| cone.moved_to(start));
        let rays = cx.lighting.effects.sun_rays;
        let bounded = cx.culling.horizon_clear && rays >= BOUNDED_FROM;
        if bounded && whole_cone.is_some_and(|c| sun_cone::clear(cx.terrain, &c)) {
            return skip(ShadowSkip::HorizonClear);
        }
        let bound = if bounded {
            slope_bound(cx.terrain, start, disc.sector)
        } else {
            f64::INFINITY
        };
        if rises && disc.lowest_tan > bound {
            return skip(ShadowSkip::HorizonClear);
        }
        let seed = seed_of(ray.origin(), ray.dir(), PURPOSE);
        let mut soft = SoftShadow {
            clear: 0,
            of: rays as u16,
            cast: 0,
            probed: false,
            blocked: false,
        };
        let (mut counters, mut exactly) = (Counters::default(), false);
        for index in 0..rays {
            // A cone whose first direction traced is blocked may be blocked whole.
            if cx.culling.cone_blocked && soft.cast == 1 && soft.clear == 0 && !soft.probed {
                soft.probed = true;
                if whole_cone.is_some_and(|whole| cone_blocked(cx, &whole, found, &mut counters)) {
                    soft.blocked = true;
                    break;
                }
            }
            let (u, v) = point(index, seed);
            let dir = disc.directions.at(u, v);
            if climbs_above(dir, bound) {
                soft.clear += 1;
                continue;
            }
            let answer = cx.occluded_beyond(shared, (axis.into(), dir.into()));
            // (Not traced: it starts above the terrain and rises.)
            let Some(occluded) = answer.occluded else {
                soft.clear += 1;
                continue;
            };
            soft.cast += 1;
            soft.clear += u16::from(!occluded);
            counters += answer.counters;
            exactly |= answer.exactly;
        }
        (Shadow::Soft(soft), counters, exactly)
    }
}

/// Whether every direction of `cone` from the hit `found` is provably blocked, looking
/// with one ray traced in `f64` (its queries added to `counters`).
fn cone_blocked<S: Scalar>(
    cx: &Context<'_>,
    cone: &Cone,
    found: &Found<S>,
    counters: &mut Counters,
) -> bool {
    let tracer = cx.tracer();
    let first_touch = |from: DVec3, dir: DVec3| {
        let ray = Ray::new(from.into(), dir.into()).ok()?;
        let traced = tracer.trace::<f64>(&ray, None);
        *counters += traced.counters;
        Some(traced.hit?.t * dir.truncate().length())
    };
    sun_cone::blocked(cx.terrain, cone, (found.cell, found.triangle), first_touch)
}

/// Soft shadows of a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign, Serialize)]
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
    pub points_blocked: u64,
    /// Directions not traced: they climbed above the terrain's bound, or the cone was
    /// settled as blocked.
    pub culled: u64,
    /// Directions that reached the sun.
    pub clear: u64,
}

impl Counted for SoftShadows {
    const NAME: &'static str = "soft_shadow";
    const LABEL: &'static str = "soft shadow";
    const WORD: &'static str = "soft";
    type Outcome = SoftShadow;
    type Stats = SoftStats;

    fn count(soft: &SoftShadow, stats: &mut SoftStats) {
        stats.points += 1;
        stats.directions += u64::from(soft.of);
        stats.rays += u64::from(soft.cast);
        stats.probes += u64::from(soft.probed);
        stats.points_blocked += u64::from(soft.blocked);
        stats.culled += u64::from(soft.of - soft.cast);
        stats.clear += u64::from(soft.clear);
    }

    fn rays(stats: &SoftStats) -> u64 {
        stats.rays + stats.probes
    }

    /// A cone settled whole would have taken a ray per direction; rays that looked for a
    /// blocked cone count as cast.
    fn culled(stats: &SoftStats, frame: &Around<'_>) -> Option<f64> {
        let per_point = u64::from(per_sample(frame.asked).sun_rays);
        let possible = frame.settled * per_point + stats.directions;
        (frame.asked.sun_angle_deg > 0.0 && frame.shadow_rays == 0 && possible > 0)
            .then(|| 1.0 - (stats.rays + stats.probes) as f64 / possible as f64)
    }
}
