//! Water: a flat surface at a level, wherever the terrain lies below it (a camera ray meets
//! the plane `z = level` over the map before the terrain), coloured by the water's own colour
//! lit as a flat surface, and mirroring what lies along the reflected ray by Schlick's
//! approximation of Fresnel's reflectance. A reflected ray that climbs more steeply than the
//! terrain can rise around its start sees the sky without a walk; the others are traced as
//! camera rays are, in the frame's arithmetic.

use super::horizon::{climbs_above, slope_bound, Sector};
use crate::arith::Scalar;
use crate::geometry::Ray;
use crate::heightfield::Heightfield;
use crate::render::shade::Shader;
use crate::traverse::Counters;
use glam::{DVec2, DVec3};

/// A scene's water, validated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Water {
    /// The water's height (`z`, as the terrain's heights).
    pub level: f64,
    /// The water's own colour in linear light.
    pub colour: [f64; 3],
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

/// Water's reflectance at normal incidence: `((n - 1) / (n + 1))^2` for `n = 1.333`.
pub const NORMAL_REFLECTANCE: f64 = 0.0204;

/// Schlick's approximation of the share of light water reflects at an angle whose cosine to
/// the surface's normal is `cos`.
pub fn schlick(cos: f64) -> f64 {
    let r0 = NORMAL_REFLECTANCE;
    r0 + (1.0 - r0) * (1.0 - cos.clamp(0.0, 1.0)).powi(5)
}

impl Water {
    /// Where the ray `o + t d` (grid coordinates) meets the water: its `t`, if it crosses
    /// the level from above over a cell of `field` that is not a hole (no data holds no
    /// water), before the terrain's hit at `terrain_t` if any (a terrain hit at the level or
    /// above it is dry land).
    pub fn crossing(
        &self,
        o: [f64; 3],
        d: [f64; 3],
        terrain_t: Option<f64>,
        field: &Heightfield,
    ) -> Option<f64> {
        if !(d[2] < 0.0 && o[2] > self.level) {
            return None;
        }
        let t = (self.level - o[2]) / d[2];
        if terrain_t.is_some_and(|hit| hit <= t) {
            return None;
        }
        let (x, y) = (o[0] + t * d[0], o[1] + t * d[1]);
        let cells = (field.width() - 1, field.height() - 1);
        let over = |v: f64, cells: usize| (0.0..=cells as f64).contains(&v);
        if !(over(x, cells.0) && over(y, cells.1)) {
            return None;
        }
        // (The far edges belong to the last cells.)
        let cell = |v: f64, cells: usize| (v as usize).min(cells - 1);
        let (i, j) = (cell(x, cells.0), cell(y, cells.1));
        if field.is_hole_cell(i, j) {
            return None;
        }
        // A ray that came in under the surface through the map's side crosses the level
        // beneath dry land, where there is no water to see.
        let under_land = field.surface_z((i, j), (x - i as f64, y - j as f64)) >= self.level;
        (!under_land).then_some(t)
    }
}

/// A water pixel as shaded: its colour, its reflection, the reflected ray's queries, and
/// whether one of its decisions was made exactly after intervals left it unsettled.
pub struct WaterPixel {
    /// 0x00RRGGBB.
    pub rgb: u32,
    /// What became of the reflected ray.
    pub reflection: Reflection,
    /// Its queries.
    pub counters: Counters,
    /// Exact mode decided one of its tests again exactly.
    pub redone: bool,
}

impl Shader<'_> {
    /// The water `t` along `ray` (grid coordinates), its reflection traced in `S`.
    pub(in crate::render) fn water_pixel<S: Scalar>(
        &self,
        water: &Water,
        ray: &Ray,
        t: f64,
    ) -> WaterPixel {
        let (o, d) = (DVec3::from(ray.origin()), DVec3::from(ray.dir()));
        let start = DVec3::new(o.x + t * d.x, o.y + t * d.y, water.level);
        let view = self.world_dir(d.into()).normalize();
        let mirrored = DVec3::new(view.x, view.y, -view.z);
        let (reflected, reflection, counters, redone) =
            self.reflected::<S>(start, mirrored, self.grid_dir(mirrored));
        // Lit as any flat surface facing up, without a shadow ray.
        let sun_height = self.lighting.sun[2].max(0.0);
        let light = self.lighting.ambient + self.lighting.intensity * sun_height;
        let body = DVec3::from(water.colour) * light;
        let colour = body.lerp(reflected, schlick(-view.z));
        WaterPixel {
            rgb: self.fogged_rgb(ray, t, colour),
            reflection,
            counters,
            redone,
        }
    }

    /// What the water at `start` mirrors towards `world` (`grid` in grid coordinates): the
    /// sky, or the terrain lit by the sun without a shadow ray.
    fn reflected<S: Scalar>(
        &self,
        start: DVec3,
        world: DVec3,
        grid: DVec3,
    ) -> (DVec3, Reflection, Counters, bool) {
        let sky = self.sky(world.into());
        let across = DVec2::new(grid.x, grid.y);
        if self.culling.horizon_clear {
            let clear = across.length() == 0.0
                || climbs_above(
                    grid,
                    slope_bound(self.terrain, start, Some(Sector::around(across, 1e-3))),
                );
            if clear {
                return (sky, Reflection::Clear, Counters::default(), false);
            }
        }
        let Ok(ray) = Ray::new(start.into(), grid.into()) else {
            return (sky, Reflection::Clear, Counters::default(), false);
        };
        let traced = self.tracer().trace::<S>(&ray, None);
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
        let facing = self
            .facing(found.face, found.cell, found.triangle, p)
            .max(0.0);
        let light = self.lighting.ambient + self.lighting.intensity * facing;
        let colour = self.albedo(found.face, p) * light;
        (
            colour,
            Reflection::Cast { hit: true },
            traced.counters,
            redone,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schlick_is_the_normal_reflectance_head_on_and_total_at_grazing() {
        assert_eq!(schlick(1.0), NORMAL_REFLECTANCE);
        assert_eq!(schlick(0.0), 1.0);
        // Half way: r0 + (1 - r0) / 32.
        let half = NORMAL_REFLECTANCE + (1.0 - NORMAL_REFLECTANCE) / 32.0;
        assert!((schlick(0.5) - half).abs() < 1e-15);
    }

    #[test]
    fn rays_meet_the_water_only_from_above_over_the_map_before_dry_land() {
        let water = Water {
            level: 2.0,
            colour: [0.0; 3],
        };
        let down = [1.0, 0.0, -1.0];
        let field = |side| Heightfield::from_fn(side, side, 1, 1.0, |_, _| 0).unwrap();
        let (large, small) = (field(9), field(3));
        // From (0, 1, 5) down at 45 degrees: the level at t = 3, over x = 3.
        assert_eq!(
            water.crossing([0.0, 1.0, 5.0], down, None, &large),
            Some(3.0)
        );
        assert_eq!(
            water.crossing([0.0, 1.0, 5.0], down, Some(4.0), &large),
            Some(3.0)
        );
        // The terrain at the level or above it first: dry land.
        assert_eq!(
            water.crossing([0.0, 1.0, 5.0], down, Some(3.0), &large),
            None
        );
        // Off the map (x = 3 past a 3-sample map's x = 2), from below, and rising.
        assert_eq!(water.crossing([0.0, 1.0, 5.0], down, None, &small), None);
        assert_eq!(water.crossing([0.0, 1.0, 1.0], down, None, &large), None);
        assert_eq!(
            water.crossing([0.0, 1.0, 5.0], [1.0, 0.0, 1.0], None, &large),
            None
        );
        // Land 3 high everywhere: a ray in through the map's side at height 2.5 crosses the
        // level at x = 1 under the surface, with no terrain hit, and sees no water.
        let high = Heightfield::from_fn(9, 9, 1, 3.0, |_, _| 1).unwrap();
        let shallow = [1.0, 0.0, -0.125];
        assert_eq!(water.crossing([-3.0, 1.0, 2.5], shallow, None, &high), None);
        // The same ray over the flat map at height 0 meets the water there.
        assert_eq!(
            water.crossing([-3.0, 1.0, 2.5], shallow, None, &large),
            Some(4.0)
        );
    }
}
