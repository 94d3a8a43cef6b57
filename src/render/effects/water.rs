//! Water: a flat surface at a level, wherever the terrain lies below it (a camera ray meets
//! the plane `z = level` over the map before the terrain), coloured by the water's own colour
//! lit as a flat surface, and mirroring what lies along the reflected ray by Schlick's
//! approximation of Fresnel's reflectance. A reflected ray that climbs more steeply than the
//! terrain can rise around its start sees the sky without a walk; the others are traced as
//! camera rays are, in the frame's arithmetic.

use super::effect::{Around, BeforeHit, Counted, Sampled, Shown};
use super::horizon::{climbs_above, slope_bound, Sector};
use super::water_surface::{schlick, Water};
use crate::arith::Scalar;
use crate::geometry::Ray;
use crate::render::context::Context;
use crate::traverse::{Counters, Found};
use derive_more::AddAssign;
use glam::{DVec2, DVec3};
use serde::Serialize;

/// Water's reflection: the ray mirrored at the water's surface, traced as camera rays are.
pub struct WaterReflection;

impl WaterReflection {
    /// The `water` `t` along `ray` (grid coordinates), its reflection traced in `S`.
    pub fn cast<S: Scalar>(
        &self,
        cx: &Context<'_>,
        water: &Water,
        ray: &Ray,
        t: f64,
    ) -> Shown<Reflection> {
        let (o, d) = (DVec3::from(ray.origin()), DVec3::from(ray.dir()));
        let start = DVec3::new(o.x + t * d.x, o.y + t * d.y, water.level);
        let view = cx.world_dir(d.into()).normalize();
        let mirrored = DVec3::new(view.x, view.y, -view.z);
        let (reflected, reflection, queries, redone) =
            reflected::<S>(cx, start, mirrored, cx.grid_dir(mirrored));
        // Lit as any flat surface facing up, without a shadow ray.
        let sun_height = cx.lighting.sun[2].max(0.0);
        let light = cx.lighting.ambient + cx.lighting.intensity * sun_height;
        let body = DVec3::from(water.colour) * light;
        let colour = body.lerp(reflected, schlick(-view.z));
        Shown {
            colour: cx.fogged_rgb(ray, t, colour),
            outcome: reflection,
            queries,
            redone,
        }
    }
}

/// What the water at `start` mirrors towards `world` (`grid` in grid coordinates): the
/// sky, or the terrain lit by the sun without a shadow ray.
fn reflected<S: Scalar>(
    cx: &Context<'_>,
    start: DVec3,
    world: DVec3,
    grid: DVec3,
) -> (DVec3, Reflection, Counters, bool) {
    let sky = cx.sky(world.into());
    let across = DVec2::new(grid.x, grid.y);
    if cx.culling.horizon_clear {
        let clear = across.length() == 0.0
            || climbs_above(
                grid,
                slope_bound(cx.terrain, start, Some(Sector::around(across, 1e-3))),
            );
        if clear {
            return (sky, Reflection::Clear, Counters::default(), false);
        }
    }
    let Ok(ray) = Ray::new(start.into(), grid.into()) else {
        return (sky, Reflection::Clear, Counters::default(), false);
    };
    let traced = cx.tracer().trace::<S>(&ray, None);
    let redone = traced.decided_exactly;
    let Some(found) = traced.hit else {
        return (
            sky,
            Reflection::Cast { hit: false },
            traced.counters,
            redone,
        );
    };
    let p = start + grid * found.t.to_f64();
    let facing = cx
        .facing(found.face, found.cell, found.triangle, p)
        .max(0.0);
    let light = cx.lighting.ambient + cx.lighting.intensity * facing;
    let colour = cx.albedo(found.face, p) * light;
    (
        colour,
        Reflection::Cast { hit: true },
        traced.counters,
        redone,
    )
}

/// What became of a pixel's reflection.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Reflection {
    /// The pixel shows no water.
    #[default]
    NotWater,
    /// The reflected ray climbs above the terrain's bound: it sees the sky, without a walk.
    Clear,
    /// The reflected ray was traced.
    Cast {
        /// It met the terrain (else the sky).
        hit: bool,
    },
}

/// Water of a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, AddAssign, Serialize)]
pub struct WaterStats {
    /// Pixels showing water.
    pub points: u64,
    /// Reflected rays traced.
    pub rays: u64,
    /// Reflected rays that met the terrain.
    pub hits: u64,
    /// Reflected rays left out: they climb above the terrain's bound and see the sky.
    pub culled_horizon_clear: u64,
}

impl Counted for WaterReflection {
    const NAME: &'static str = "water";
    const LABEL: &'static str = "water";
    const WORD: &'static str = "water";
    type Outcome = Reflection;
    type Stats = WaterStats;

    fn count(reflection: &Reflection, water: &mut WaterStats) {
        match *reflection {
            Reflection::NotWater => return,
            Reflection::Clear => water.culled_horizon_clear += 1,
            Reflection::Cast { hit } => {
                water.rays += 1;
                water.hits += u64::from(hit);
            }
        }
        water.points += 1;
    }

    fn rays(water: &WaterStats) -> u64 {
        water.rays
    }

    fn culled(water: &WaterStats, _: &Around<'_>) -> Option<f64> {
        (water.points > 0).then(|| water.culled_horizon_clear as f64 / water.points as f64)
    }
}

impl Sampled for WaterReflection {
    fn asked(cx: &Context<'_>) -> bool {
        cx.lighting.effects.water.is_some()
    }
}

impl BeforeHit for WaterReflection {
    /// The water, where the camera ray meets its level over the map before the terrain.
    #[inline(always)]
    fn before_hit<S: Scalar>(
        cx: &Context<'_>,
        ray: &Ray,
        found: Option<&Found<S>>,
    ) -> Option<Shown<Reflection>> {
        let water = cx.lighting.effects.water.as_ref()?;
        let terrain_t = found.map(|found| found.t.to_f64());
        let t = water.crossing(ray.origin(), ray.dir(), terrain_t, cx.terrain.field())?;
        Some(WaterReflection.cast::<S>(cx, water, ray, t))
    }
}
