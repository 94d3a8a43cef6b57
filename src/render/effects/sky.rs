//! Sky light: the sky dome in the scene's sky colours lights a point through the directions
//! its hemisphere leaves open within the sky distance, drawn with the cosine's density (a
//! stratified set per point), in place of the constant ambient term. A point with no terrain
//! above it within the distance needs no rays; where a point has more rays than sectors of
//! azimuth, a direction that climbs more steeply than the terrain within the distance can
//! rise in its sector is open without a walk.

use super::effect::{Around, At, AtHit, Counted, Effect, Light, Sampled};
use super::probe::blocked_under_surface;
use super::horizon::{climbs_above, level_within, sector_of, slope_bound_within, Sector};
use super::sampling::{point, seed_of, Hemisphere};
use crate::arith::Scalar;
use crate::geometry::{Face, Ray};
use crate::render::context::Context;
use crate::render::scene::Normals;
use crate::render::sky_gradient::{horizon, sky_colour, zenith};
use crate::traverse::Counters;
use derive_more::AddAssign;
use glam::DVec3;
use serde::Serialize;

/// Sectors of azimuth the terrain's rise around a point is bounded in.
const SECTORS: usize = 8;

/// The purpose a point's sky samples are seeded with (see [`seed_of`]).
const PURPOSE: u64 = 0x0051_7a11;

/// The mean sky colour a horizontal point sees under an open sky, cosine-weighted: the
/// gradient goes by `sqrt(sin(elevation))`, and under the cosine's density `sin(elevation)^2`
/// is uniform on `[0, 1]`, so the mean of its fourth root is 4/5.
pub fn open_sky_mean() -> DVec3 {
    horizon().lerp(zenith(), 0.8)
}

/// The sky's light at a hit: the scene's ambient term times the mean colour of the open
/// directions over the open sky's mean brightness (an open plane gets the ambient term in the
/// sky's tint), and the rays.
pub struct SkyLight;

impl SkyLight {
    /// The sky light (a colour, before the surface's own) where `ray` first meets the
    /// terrain, traced in `f64`, and its rays; `None` where the ray misses.
    pub fn at(cx: &Context<'_>, ray: &Ray) -> Option<(DVec3, SkyRays)> {
        let found = cx.tracer().trace::<f64>(ray, None).hit?;
        let (o, d) = (ray.origin(), ray.dir());
        let p = DVec3::from(found.point(&o, &d));
        Some(SkyLight.cast(cx, &At::new(&found, ray, p)))
    }
}

impl Effect for SkyLight {
    type Outcome = (DVec3, SkyRays);

    fn cast<S: Scalar>(&self, cx: &Context<'_>, at: &At<'_, S>) -> (DVec3, SkyRays) {
        let At { found, ray, p, .. } = *at;
        let hemisphere = Hemisphere::around(cx.normal(found.face, found.cell, found.triangle, p));
        let shared = at.start(cx);
        let start = shared.point;
        let distance = cx.lighting.effects.sky_distance;
        let scale = cx.terrain.world_from_grid().unwrap_or([1.0; 3]);
        let reach = cx.sky_reach();
        let rays = cx.lighting.effects.sky_rays;
        let culling = cx.culling.horizon_clear;
        // Nothing above the point within reach: every rising ray is open.
        let level = culling && level_within(cx.terrain, start, reach);
        // A sector's bound costs a few walks: worth it where its sector holds several rays.
        // (Where the sky's bounds are kept, they settle the far part of each ray instead.)
        let far = cx.sky.as_ref().filter(|_| cx.culling.far_bounds);
        // A ray the bounds leave unsettled is probed under the surface first, where it starts
        // on its flat triangle.
        let on_triangle = cx.lighting.normals == Normals::Flat && found.face == Face::Terrain;
        let probing = cx.culling.probes && on_triangle;
        let by_sector = culling && !level && rays > SECTORS as u32 && far.is_none();
        // Each sector's bound, found when a direction in it first asks.
        let mut bounds = [None; SECTORS];
        let mut bound = |dir: DVec3| {
            let k = sector_of(dir, SECTORS);
            *bounds[k].get_or_insert_with(|| {
                slope_bound_within(cx.terrain, start, Some(Sector::nth(k, SECTORS)), reach)
            })
        };
        let seed = seed_of(ray.origin(), ray.dir(), PURPOSE);
        let mut sky = SkyRays {
            of: rays as u16,
            ..SkyRays::default()
        };
        let mut light = DVec3::ZERO;
        for index in 0..rays {
            let (u, v) = point(index, seed);
            let dir = hemisphere.cosine(u, v);
            // (Traced and bounded in grid coordinates; coloured by the world direction.)
            let grid = cx.grid_dir(dir);
            let culled = grid.z > 0.0 && (level || (by_sector && climbs_above(grid, bound(grid))));
            // What the kept bounds leave the ray to walk: `Some(None)` where nothing.
            let part = far.filter(|_| !culled).map(|b| {
                b.unsettled(cx.terrain, start.into(), grid.into(), shared.room, shared.near)
            });
            let open = culled || part == Some(None) || {
                let part = part.flatten();
                // (The ray's `t` runs along the unit grid direction.)
                let (ax, ay) = (grid.x * scale[0], grid.y * scale[1]);
                // (Not `hypot`: its care for overflow, needless for a unit direction, costs
                // more than the rest of the ray's set-up.)
                let across = (ax * ax + ay * ay).sqrt();
                let t_max = (distance / across).is_finite().then(|| distance / across);
                let t_max = match part.and_then(|p| p.to) {
                    Some(t) => Some(t_max.map_or(t, |m| m.min(t))),
                    None => t_max,
                };
                let probed = |t_max: f64| {
                    blocked_under_surface(cx.terrain, start, shared.room, grid, t_max)
                };
                let ring_bound = part.is_some_and(|p| p.to.is_some());
                if probing && part.is_some() && !ring_bound && t_max.is_some_and(probed) {
                    sky.probed += 1;
                    continue;
                }
                let clear = part.map_or(0.0, |p| p.from);
                let mut answer = cx.occluded_between(shared, grid.into(), (clear, t_max));
                if part.is_some() && answer.occluded.is_some() {
                    answer.counters.bound.record(!ring_bound);
                }
                if answer.occluded.is_some() {
                    sky.cast += 1;
                    sky.counters += answer.counters;
                    sky.redone |= answer.exactly;
                }
                answer.occluded != Some(true)
            };
            if open {
                sky.open += 1;
                light += sky_colour(dir);
            }
        }
        let open_mean = open_sky_mean();
        let brightness = (open_mean.x + open_mean.y + open_mean.z) / 3.0;
        let ambient = light * (cx.lighting.ambient / (f64::from(rays) * brightness));
        (ambient, sky)
    }
}

/// A point's sky-light rays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SkyRays {
    /// Directions asked.
    pub of: u16,
    /// Directions that reach the sky.
    pub open: u16,
    /// Directions traced (the others climbed above the terrain's bound, or were probed).
    pub cast: u16,
    /// Directions found blocked by probes under the surface, not traced.
    pub probed: u16,
    /// The traced rays' queries.
    pub counters: Counters,
    /// A triangle test intervals could not settle was decided exactly.
    pub redone: bool,
}

impl SkyRays {
    /// The cosine-weighted share of the hemisphere open to the sky (the sky-view factor).
    pub fn open_share(&self) -> f64 {
        f64::from(self.open) / f64::from(self.of.max(1))
    }

    /// Directions left out because they provably reach the sky.
    pub fn culled(&self) -> u16 {
        self.of - self.cast - self.probed
    }
}

/// Sky light of a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign, Serialize)]
pub struct SkyStats {
    /// Points lit by the sky.
    pub points: u64,
    /// Directions asked.
    pub directions: u64,
    /// Directions traced.
    pub rays: u64,
    /// Directions left out: they climbed above the terrain's bound, so reach the sky.
    pub culled_horizon_clear: u64,
    /// Directions left out: probes found them under the surface, so blocked.
    pub probed_blocked: u64,
    /// Directions that reached the sky.
    pub open: u64,
    /// Points whose every direction climbed above the terrain's bound: no ray at all.
    pub points_without_rays: u64,
    /// The traced rays' queries.
    pub queries: Counters,
}

impl Counted for SkyLight {
    const NAME: &'static str = "sky_light";
    const LABEL: &'static str = "sky";
    const WORD: &'static str = "sky";
    type Outcome = SkyRays;
    type Stats = SkyStats;

    fn count(sky: &SkyRays, stats: &mut SkyStats) {
        if sky.of == 0 {
            return;
        }
        stats.points += 1;
        stats.directions += u64::from(sky.of);
        stats.rays += u64::from(sky.cast);
        stats.culled_horizon_clear += u64::from(sky.culled());
        stats.probed_blocked += u64::from(sky.probed);
        stats.open += u64::from(sky.open);
        stats.points_without_rays += u64::from(sky.cast == 0);
        stats.queries += sky.counters;
    }

    fn rays(stats: &SkyStats) -> u64 {
        stats.rays
    }

    fn culled(stats: &SkyStats, _: &Around<'_>) -> Option<f64> {
        (stats.directions > 0).then(|| 1.0 - stats.rays as f64 / stats.directions as f64)
    }
}

impl Sampled for SkyLight {
    fn asked(cx: &Context<'_>) -> bool {
        cx.lighting.effects.sky_light
    }
}

impl AtHit for SkyLight {
    /// The sky's light in place of the ambient term.
    #[inline(always)]
    fn at_hit<S: Scalar>(cx: &Context<'_>, at: &At<'_, S>, light: &mut Light) -> SkyRays {
        let (ambient, sky) = SkyLight.cast(cx, at);
        light.ambient = ambient;
        sky
    }

    fn queries(sky: &SkyRays) -> Counters {
        sky.counters
    }

    fn redone(sky: &SkyRays) -> bool {
        sky.redone
    }
}
