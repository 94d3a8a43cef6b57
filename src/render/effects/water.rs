//! Water: a flat surface at a level, wherever the terrain lies below it (a camera ray meets
//! the plane `z = level` over the map before the terrain), coloured by the water's own colour
//! lit as a flat surface, and mirroring what lies along the reflected ray by Schlick's
//! approximation of Fresnel's reflectance. A reflected ray that climbs more steeply than the
//! terrain can rise around its start sees the sky without a walk; the others are traced as
//! camera rays are, in the frame's arithmetic.

use super::horizon::{climbs_above, slope_bound, Sector};
use super::water_surface::{schlick, Water};
use crate::arith::Scalar;
use crate::geometry::Ray;
use crate::render::context::Context;
use crate::render::sample::{Reflection, WaterPixel};
use crate::traverse::Counters;
use glam::{DVec2, DVec3};

/// Water's reflection: the ray mirrored at the water's surface, traced as camera rays are.
pub struct WaterReflection<'w>(pub &'w Water);

impl WaterReflection<'_> {
    /// The water `t` along `ray` (grid coordinates), its reflection traced in `S`.
    pub fn cast<S: Scalar>(&self, cx: &Context<'_>, ray: &Ray, t: f64) -> WaterPixel {
        let water = self.0;
        let (o, d) = (DVec3::from(ray.origin()), DVec3::from(ray.dir()));
        let start = DVec3::new(o.x + t * d.x, o.y + t * d.y, water.level);
        let view = cx.world_dir(d.into()).normalize();
        let mirrored = DVec3::new(view.x, view.y, -view.z);
        let (reflected, reflection, counters, redone) =
            reflected::<S>(cx, start, mirrored, cx.grid_dir(mirrored));
        // Lit as any flat surface facing up, without a shadow ray.
        let sun_height = cx.lighting.sun[2].max(0.0);
        let light = cx.lighting.ambient + cx.lighting.intensity * sun_height;
        let body = DVec3::from(water.colour) * light;
        let colour = body.lerp(reflected, schlick(-view.z));
        WaterPixel {
            rgb: cx.fogged_rgb(ray, t, colour),
            reflection,
            counters,
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
