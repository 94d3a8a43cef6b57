//! From a ray to a colour: the primary ray, the shadow ray only where it can change the pixel,
//! Lambert shading with an elevation ramp, sky and fog.

use super::gamma;
use super::normals;
use super::ramp::HeightSpan;
use super::scene::{Lighting, Normals};
use crate::geometry::{gradient, plane_height, triangle_corners};
use crate::heightfield::Terrain;
use crate::traverse::{
    crosses_plane, plane_t_exact, settled, trace_scalar, Clearance, Counters, Exact, Found,
    Interval, Method, PlanePoint, Query, Scalar, WalkOptions,
};
use crate::Ray;
use glam::DVec3;
use std::convert::Infallible as Never;

/// Why a shadow ray was not cast although the scene has shadows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowSkip {
    /// The surface faces away from the sun: it is dark whatever a shadow ray says.
    FacingAway,
    /// The sun stands higher than the steepest slope anywhere: nothing can cast a shadow.
    NoShadowPossible,
    /// The shadow ray starts above the highest terrain and rises.
    AboveTerrain,
}

/// What became of a pixel's shadow.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shadow {
    /// No primary hit, or the scene has no shadows: nothing to decide.
    NotAsked,
    /// Left out where it cannot change the pixel, for this reason.
    Skipped(ShadowSkip),
    /// Cast towards the sun.
    Cast {
        /// The shadow ray found the surface: the pixel is in shadow.
        shadowed: bool,
    },
}

/// A pixel's shadow as cast: what became of it, the shadow ray's queries, and whether a
/// decision on it was made exactly after intervals left it unsettled (see [`Sample::redone`]).
type Cast = (Shadow, Counters, bool);

/// One traced pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// 0x00RRGGBB.
    pub rgb: u32,
    /// The primary ray hit the terrain.
    pub hit: bool,
    /// What became of the shadow ray.
    pub shadow: Shadow,
    /// The primary ray's queries.
    pub primary: Counters,
    /// The shadow ray's queries.
    pub secondary: Counters,
    /// Intervals left a decision unsettled, and exact mode made it again exactly: it traced
    /// the pixel again in rationals, or cast only its shadow ray again, or decided one of the
    /// shadow ray's triangle tests on its own.
    pub redone: bool,
}

/// Which shadow rays to leave out where they cannot change the pixel (all on by default;
/// switching one off must not change the image, only the work).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Culling {
    /// Leave out shadow rays of surfaces facing away from the sun ([`ShadowSkip::FacingAway`]).
    pub facing_away: bool,
    /// Leave out every shadow ray when the sun climbs steeper than any slope
    /// ([`ShadowSkip::NoShadowPossible`]).
    pub no_shadow_possible: bool,
    /// Leave out shadow rays that start above the terrain and rise
    /// ([`ShadowSkip::AboveTerrain`]).
    pub above_terrain: bool,
}

impl Default for Culling {
    fn default() -> Self {
        Culling {
            facing_away: true,
            no_shadow_possible: true,
            above_terrain: true,
        }
    }
}

/// Everything a pixel needs besides its ray.
pub struct Shader<'a> {
    /// The terrain traced.
    pub terrain: &'a Terrain,
    /// Sun, shading and effects.
    pub lighting: Lighting,
    /// The traversal method of primary and shadow rays.
    pub method: Method,
    /// Which shadow rays to leave out.
    pub culling: Culling,
}

impl Shader<'_> {
    /// Traces and shades one primary ray exactly: in intervals, and again in rationals if
    /// they left a decision unsettled. A shadow ray's triangle test they cannot settle is
    /// decided exactly on its own, from the exact hit point (the primary ray's settled answer
    /// is the exact one, and its exact `t` is one plane solve); a shadow ray that still has a
    /// decision unsettled (one running in a triangle's plane) is cast again alone in
    /// rationals: a whole pixel in rationals costs about a millisecond.
    /// `beam`: see [`WalkOptions::beam`].
    pub fn sample_exact(&self, ray: &Ray, beam: Option<Clearance>) -> Sample {
        let cast = |found: &Found<Interval>, p, facing| match settled(|| {
            self.shadow::<Interval>(found, ray, p, facing)
        }) {
            (cast, true) => Ok(cast),
            (_, false) => self.shadow_in_rationals(found, ray, p, facing),
        };
        match settled(|| self.sample_with::<Interval, ()>(ray, beam, cast)) {
            (Ok(sample), true) => sample,
            _ => Sample {
                redone: true,
                ..self.sample::<Exact>(ray, beam)
            },
        }
    }

    /// The shadow ray of a hit found in intervals, cast again in rationals from the exact hit
    /// point (`p` is the point shaded). `Err` where the primary ray runs in the hit triangle's
    /// plane, whose exact hit only the walk tells.
    fn shadow_in_rationals(
        &self,
        found: &Found<Interval>,
        ray: &Ray,
        p: DVec3,
        facing: f64,
    ) -> Result<Cast, ()> {
        let t = plane_t_exact(self.terrain, ray, found.cell, found.triangle).ok_or(())?;
        let exact = Found {
            t: Exact(t),
            cell: found.cell,
            triangle: found.triangle,
        };
        let (shadow, counters, _) = self.shadow::<Exact>(&exact, ray, p, facing);
        Ok((shadow, counters, true))
    }

    /// Traces and shades one primary ray in arithmetic `S`, behind a beam that cleared the
    /// way if given (see [`WalkOptions::beam`]).
    pub fn sample<S: Scalar>(&self, ray: &Ray, beam: Option<Clearance>) -> Sample {
        let cast =
            |found: &Found<S>, p, facing| Ok::<_, Never>(self.shadow::<S>(found, ray, p, facing));
        let Ok(sample) = self.sample_with(ray, beam, cast);
        sample
    }

    /// [`Shader::sample`], with the shadow ray of a hit cast by `cast` (given the hit, the point
    /// shaded and how the surface faces the sun there), which also tells whether it was cast
    /// again in rationals, or fails.
    fn sample_with<S: Scalar, E>(
        &self,
        ray: &Ray,
        beam: Option<Clearance>,
        cast: impl FnOnce(&Found<S>, DVec3, f64) -> Result<Cast, E>,
    ) -> Result<Sample, E> {
        let (o, d) = (ray.origin().map(S::from_f64), ray.dir().map(S::from_f64));
        let walk = WalkOptions {
            beam,
            ..WalkOptions::new(self.method, Query::FirstHit)
        };
        let primary = trace_scalar(self.terrain, &o, &d, ray.dir(), walk);
        let Some(found) = primary.hit else {
            return Ok(Sample {
                rgb: self.sky_rgb(ray),
                hit: false,
                shadow: Shadow::NotAsked,
                primary: primary.counters,
                secondary: Counters::default(),
                redone: false,
            });
        };
        // Shading needs the point only in `f64`. Arithmetics that round shade the point they
        // computed; for the others, `t` to the nearest `f64` is as good and much cheaper than
        // the point in intervals, which only a shadow ray needs.
        let t = found.t.to_f64();
        let p = if S::EXACT {
            DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * t
        } else {
            DVec3::from(found.point(&o, &d).map(|c| c.to_f64()))
        };
        let facing = self.facing(found.cell, found.triangle, p);
        let (shadow, secondary, redone) = cast(&found, p, facing)?;
        Ok(Sample {
            rgb: self.surface_rgb(ray, p, t, facing, shadow),
            hit: true,
            shadow,
            primary: primary.counters,
            secondary,
            redone,
        })
    }

    /// How the surface at `p` on triangle `triangle` of `cell` faces the sun: the cosine of
    /// the angle between the shading normal and the sun (not positive where it faces away).
    // (This, `normal` and `surface_rgb` inlined by hand: every arithmetic's `sample_with`
    // calls them once per pixel.)
    #[inline(always)]
    pub fn facing(&self, cell: (usize, usize), triangle: u8, p: DVec3) -> f64 {
        self.normal(cell, triangle, p)
            .dot(DVec3::from(self.lighting.sun))
    }

    /// The colour of the surface at `p`, `t` along `ray`, facing the sun as [`Shader::facing`]
    /// says, in shadow or not as `shadow` says.
    #[inline(always)]
    pub fn surface_rgb(&self, ray: &Ray, p: DVec3, t: f64, facing: f64, shadow: Shadow) -> u32 {
        let lit = match shadow {
            Shadow::Cast { shadowed: true } => 0.0,
            _ => facing.max(0.0),
        };
        let light = self.lighting.ambient + self.lighting.intensity * lit;
        let mut colour = self.lighting.ramp.colour(p.z, HeightSpan::of(self.terrain)) * light;
        if self.lighting.fog > 0.0 {
            let distance = t * self.world_dir(ray.dir()).length();
            let clear = (-self.lighting.fog * distance).exp();
            colour = colour * clear + horizon() * (1.0 - clear);
        }
        pack(colour)
    }

    /// The colour of a ray that misses the terrain.
    pub fn sky_rgb(&self, ray: &Ray) -> u32 {
        pack(self.sky(self.world_dir(ray.dir()).into()))
    }

    /// Decides whether a shadow ray of the hit `found`, shaded at `p`, can change the pixel,
    /// and casts it if so.
    fn shadow<S: Scalar>(&self, found: &Found<S>, ray: &Ray, p: DVec3, facing: f64) -> Cast {
        let skip = |why| (Shadow::Skipped(why), Counters::default(), false);
        if !self.lighting.shadows {
            return (Shadow::NotAsked, Counters::default(), false);
        }
        if self.culling.facing_away && facing <= 0.0 {
            return skip(ShadowSkip::FacingAway);
        }
        let sun = self.grid_sun();
        // The sun climbs strictly steeper than any triangle (with room for the rounding of
        // max_slope), compared squared: no square root per shadow ray.
        let steepest = self.terrain.max_slope() * (1.0 + 1e-9);
        let climbs_steeper = sun[2] > 0.0
            && sun[2] * sun[2] > steepest * steepest * (sun[0] * sun[0] + sun[1] * sun[1]);
        if self.culling.no_shadow_possible && climbs_steeper {
            return skip(ShadowSkip::NoShadowPossible);
        }
        // Lift the start above the surface by what rounding may have moved it below (zero in
        // exact arithmetic): the surface is a height field, so up is always outside. The point
        // is `o + t*d`, each component within a few roundings of `|o| + |t*d|`; off by that
        // across an edge, the surface may be higher by the steepest slope times it.
        let t = found.t.to_f64().abs();
        let (ray_o, ray_d) = (ray.origin(), ray.dir());
        let largest = (0..3).fold(0.0f64, |m, k| m.max(ray_o[k].abs() + t * ray_d[k].abs()));
        let lift = 64.0 * S::rounding_error(largest) * (1.0 + self.terrain.max_slope());
        let smooth = self.lighting.normals == Normals::Smooth;
        let origin = if smooth {
            // Smooth shading: from the curved surface the shading describes, which its own
            // flat triangle may cross (see `normals`); the ray is then an ordinary one from
            // that point, traced exactly in exact arithmetics.
            let start = normals::shadow_origin(self.terrain, found.cell, found.triangle, p);
            [start.x, start.y, start.z + lift].map(S::from_f64)
        } else {
            let [x, y, z] = self.plane_point(found, ray);
            [x, y, z + S::from_f64(lift)]
        };
        let (_, z_max) = self.terrain.z_range();
        if self.culling.above_terrain && sun[2] > 0.0 && origin[2] > S::from_f64(z_max) {
            return skip(ShadowSkip::AboveTerrain);
        }
        // A smoothly shaded ray skips its own triangle, which stands for the curved surface it
        // starts on.
        let walk = WalkOptions {
            start_triangle: (smooth || self.leaves_at_once(found))
                .then_some((found.cell, found.triangle)),
            exact_start: (S::EXACT && !smooth).then_some(PlanePoint {
                ray: *ray,
                cell: found.cell,
                triangle: found.triangle,
            }),
            ..WalkOptions::new(self.method, Query::Shadow)
        };
        let answer = trace_scalar(self.terrain, &origin, &sun.map(S::from_f64), sun, walk);
        (
            Shadow::Cast {
                shadowed: answer.hit.is_some(),
            },
            answer.counters,
            answer.decided_exactly,
        )
    }

    /// The hit point as a shadow ray from the flat triangle starts at, in arithmetic `S`.
    fn plane_point<S: Scalar>(&self, found: &Found<S>, ray: &Ray) -> [S; 3] {
        let (ray_o, ray_d) = (ray.origin(), ray.dir());
        let [x, y] = [0, 1].map(|k| S::along(ray_o[k], ray_d[k], &found.t));
        // Rounding arithmetics take the height on the hit triangle's plane: exact on flat
        // ground. Without rounding the ray's own point is on the plane, and enclosing it takes
        // a fifth of the work of enclosing the plane's height over the enclosures of x and y;
        // on a flat triangle the point's height is the triangle's, exactly: intervals must
        // know it then, or the run and cell tests of a ray from a terrace's top, the highest
        // sample of the runs and cells around it, cannot be settled where intervals walk (a
        // path along a grid row, which the `f64` walk leaves to them), and each such ray is
        // cast again in rationals, at a millisecond a ray.
        let z = if S::EXACT {
            match self.flat_height(found) {
                Some(height) => S::from_f64(height),
                None => S::along(ray_o[2], ray_d[2], &found.t),
            }
        } else {
            let (i, j) = found.cell;
            let heights = self.terrain.corner_heights(i, j).map(S::from_f64);
            plane_height(found.triangle, found.cell, heights, x.clone(), y.clone())
        };
        [x, y, z]
    }

    /// Whether a ray towards the sun leaves the hit triangle's plane at once, so that it
    /// touches the triangle it starts on only at its start (in floats decided with room to
    /// spare for rounding: when in doubt the triangle is tested like any other).
    fn leaves_at_once<S: Scalar>(&self, found: &Found<S>) -> bool {
        let n = self.geometric_normal(found.cell, found.triangle);
        let s = DVec3::from(self.grid_sun());
        let terms = [n.x * s.x, n.y * s.y, n.z * s.z];
        let sum: f64 = terms.iter().sum();
        if sum.abs() > 1e-9 * terms.iter().map(|t| t.abs()).sum::<f64>() {
            return true;
        }
        // Without rounding the ray starts on the plane itself, and leaves it at once unless it
        // runs in it: asked exactly (intervals cannot tell the two apart in the tests).
        S::EXACT && crosses_plane(self.terrain, found.cell, found.triangle, self.grid_sun())
    }

    /// The height of the hit triangle if it is flat (its three corners at one height).
    fn flat_height<S: Scalar>(&self, found: &Found<S>) -> Option<f64> {
        let heights = self.terrain.corner_heights(found.cell.0, found.cell.1);
        let [a, b, c] = triangle_corners(found.triangle).map(|k| heights[k]);
        (a == b && b == c).then_some(a)
    }

    /// The (unnormalised) normal of the hit triangle's plane: `(-gx, -gy, 1)`.
    fn geometric_normal(&self, (i, j): (usize, usize), triangle: u8) -> DVec3 {
        let heights = self.terrain.corner_heights(i, j);
        let (gx, gy) = gradient(triangle, heights);
        DVec3::new(-gx, -gy, 1.0)
    }

    /// The shading normal at `p` on triangle `triangle` of cell `(i, j)`, in world
    /// coordinates (where cells may be non-square).
    #[inline(always)]
    fn normal(&self, cell: (usize, usize), triangle: u8, p: DVec3) -> DVec3 {
        let normal = match self.lighting.normals {
            Normals::Flat => self.geometric_normal(cell, triangle).normalize_or(DVec3::Z),
            Normals::Smooth => normals::smooth_normal(self.terrain, cell, triangle, p),
        };
        // A normal maps by the inverse transpose of the points' map: divided per axis.
        match self.terrain.world_from_grid() {
            Some(scale) => (normal / DVec3::from(scale)).normalize_or(DVec3::Z),
            None => normal,
        }
    }

    /// The direction towards the sun in grid coordinates, where shadow rays are traced.
    fn grid_sun(&self) -> [f64; 3] {
        let sun = self.lighting.sun;
        match self.terrain.world_from_grid() {
            Some(scale) => std::array::from_fn(|k| sun[k] / scale[k]),
            None => sun,
        }
    }

    /// A ray direction in grid coordinates as a direction in the world.
    fn world_dir(&self, dir: [f64; 3]) -> DVec3 {
        match self.terrain.world_from_grid() {
            Some(scale) => DVec3::from(dir) * DVec3::from(scale),
            None => DVec3::from(dir),
        }
    }

    /// Sky gradient for rays that miss.
    fn sky(&self, dir: [f64; 3]) -> DVec3 {
        let d = DVec3::from(dir).normalize_or(DVec3::Z);
        horizon().lerp(DVec3::new(0.28, 0.46, 0.82), d.z.clamp(0.0, 1.0).sqrt())
    }
}

fn horizon() -> DVec3 {
    DVec3::new(0.78, 0.85, 0.93)
}

/// Linear colour to 0x00RRGGBB with a display gamma of 2.2.
fn pack(c: DVec3) -> u32 {
    let channel = |v: f64| u32::from(gamma::byte(v));
    (channel(c.x) << 16) | (channel(c.y) << 8) | channel(c.z)
}
