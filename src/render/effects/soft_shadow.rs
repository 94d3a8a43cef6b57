//! Soft shadows: the sun as a disc of the scene's angular diameter. A point whose whole cone
//! towards the disc provably clears the terrain is settled by the rules hard shadows use
//! (generalised to the cone's lowest direction) or by the mipmap's bound of how steeply the
//! terrain rises around it, where it has [`BOUNDED_FROM`] directions or more (with fewer, the
//! bounds cost more than the rays); elsewhere each direction of a stratified set over the disc is a
//! shadow ray, unless it alone climbs above that bound. A cone whose first direction traced
//! is blocked may be settled as blocked whole ([`sun_cone`](super::sun_cone)) by one more ray.

use super::effect::{At, Effect};
use super::horizon::{climbs_above, slope_bound};
use super::sampling::{point, seed_of};
use super::sun_cone::{self, Cone};
use crate::arith::Scalar;
use crate::geometry::Ray;
use crate::render::context::Context;
use crate::render::sample::{Cast, Shadow, ShadowSkip, SoftShadow};
use crate::traverse::{Counters, Found};
use glam::DVec3;

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
