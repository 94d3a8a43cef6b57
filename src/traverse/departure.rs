//! Where occlusion rays from one start set out: the start raised above what rounding may have
//! moved it below, the triangle it lies on and, in exact arithmetic, the start given exactly.
//! None of it depends on a ray's direction, and a hit casts many rays (a sky-lit point up to
//! 16, a soft shadow several, besides the sun's), so it is worked out once per start
//! ([`Departure::new`]) and each ray adds only what its direction decides
//! ([`Departure::own_triangle`]).

use super::exact_plane::crosses_plane;
use super::exact_start::PlanePoint;
use super::search::Found;
use crate::arith::{settled, Scalar};
use crate::geometry::{gradient, plane_height, triangle_corners, Base, Face, Ray, Side};
use crate::heightfield::Terrain;
use glam::DVec3;

/// Where an occlusion ray ([`Tracer::occluded`](super::Tracer::occluded)) starts.
#[derive(Debug)]
pub enum Start<'r, S> {
    /// At a point given in the traversal's arithmetic.
    Point(&'r [S; 3]),
    /// On the surface, where `ray` hit it (`hit`): in arithmetics without rounding exactly
    /// there, on the hit triangle's plane; in the others raised by what rounding may have
    /// moved the point below the surface. The ray leaves its own triangle untested where it
    /// leaves the triangle's plane at once.
    Hit {
        /// The ray that hit.
        ray: &'r Ray,
        /// Its hit, in the traversal's arithmetic.
        hit: &'r Found<S>,
    },
    /// At `point` near the hit of `ray` (on a curved surface the hit triangle stands for),
    /// raised like [`Start::Hit`]; the hit triangle is not tested.
    Near {
        /// The ray that hit.
        ray: &'r Ray,
        /// Its hit, in the traversal's arithmetic.
        hit: &'r Found<S>,
        /// Where the occlusion ray starts, before raising.
        point: [f64; 3],
    },
}

// (By hand: it holds references alone, so it is `Copy` whatever `S` is.)
impl<S> Clone for Start<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S> Copy for Start<'_, S> {}

/// How a start's rays treat the triangle it lies on (the hit's).
#[derive(Clone, Copy, Debug)]
enum Own {
    /// There is none: a point, or the base.
    None,
    /// Left untested whatever the direction ([`Start::Near`]).
    Always,
    /// Left untested by the rays that leave its plane at once ([`Start::Hit`]); the plane's
    /// upward normal `(-gx, -gy, 1)`.
    Leaving(DVec3),
}

/// What every occlusion ray from one [`Start`] shares, whatever its direction.
#[derive(Clone, Debug)]
pub struct Departure<'r, S> {
    /// The start it was worked out from (intervals cast an unsettled ray again from it).
    pub(super) from: Start<'r, S>,
    /// The ray's origin, raised above rounding.
    pub(super) origin: [S; 3],
    own: Own,
    /// Working it out left no decision unsettled (in intervals; always in the others).
    pub(super) settled: bool,
}

impl<'r, S: Scalar> Departure<'r, S> {
    /// The departure from `from` over `terrain` (and `base`, part of the surface where
    /// given). In intervals a decision they cannot settle is not passed on to the caller but
    /// kept with it, for each ray to be cast again exactly as if it had met it itself.
    #[inline]
    pub fn new(terrain: &Terrain, base: Option<Base>, from: &Start<'r, S>) -> Self {
        if !S::ENCLOSES {
            return Self::worked_out(terrain, base, from);
        }
        let (departure, is_settled) = settled(|| Self::worked_out(terrain, base, from));
        Departure {
            settled: is_settled,
            ..departure
        }
    }

    #[inline(always)]
    fn worked_out(terrain: &Terrain, base: Option<Base>, from: &Start<'r, S>) -> Self {
        let (origin, own) = match *from {
            Start::Point(o) => (o.clone(), Own::None),
            Start::Hit { ray, hit } if hit.face != Face::Terrain => {
                let [x, y, z] = base_point(terrain, base, hit, ray);
                let origin = [x, y, z + S::from_f64(lift(terrain, ray, hit))];
                (origin, Own::None)
            }
            Start::Hit { ray, hit } => {
                let heights = terrain.corner_heights(hit.cell.0, hit.cell.1);
                let [x, y, z] = plane_point(heights, hit, ray);
                let origin = [x, y, z + S::from_f64(lift(terrain, ray, hit))];
                let (gx, gy) = gradient(hit.triangle, heights);
                (origin, Own::Leaving(DVec3::new(-gx, -gy, 1.0)))
            }
            Start::Near { ray, hit, point } => {
                let [x, y, z] = point;
                let origin = [x, y, z + lift(terrain, ray, hit)].map(S::from_f64);
                (origin, Own::Always)
            }
        };
        Departure {
            from: *from,
            origin,
            own,
            settled: true,
        }
    }

    /// In exact arithmetic, the start of a ray from a hit on the terrain given exactly (see
    /// [`WalkOptions::exact_start`](super::options::WalkOptions)).
    pub(super) fn exact_start(&self) -> Option<PlanePoint> {
        match self.from {
            Start::Hit { ray, hit } if S::EXACT && hit.face == Face::Terrain => Some(PlanePoint {
                ray: *ray,
                cell: hit.cell,
                triangle: hit.triangle,
            }),
            _ => None,
        }
    }

    /// The triangle `(cell, k)` a ray in direction `dir` leaves untested: the one it starts
    /// on, where it touches it only at its start.
    #[inline(always)]
    pub(super) fn own_triangle(
        &self,
        terrain: &Terrain,
        dir: [f64; 3],
    ) -> Option<((usize, usize), u8)> {
        let hit = match self.from {
            Start::Hit { hit, .. } | Start::Near { hit, .. } => hit,
            Start::Point(_) => return None,
        };
        let own = (hit.cell, hit.triangle);
        match self.own {
            Own::None => None,
            Own::Always => Some(own),
            Own::Leaving(n) => leaves_at_once::<S>(terrain, own, n, dir).then_some(own),
        }
    }
}

/// Whether a ray in direction `dir` leaves the plane of triangle `own` (of upward normal `n`)
/// at once, so that it touches the triangle it starts on only at its start (in floats decided
/// with room to spare for rounding: when in doubt the triangle is tested like any other).
fn leaves_at_once<S: Scalar>(
    terrain: &Terrain,
    (cell, k): ((usize, usize), u8),
    n: DVec3,
    dir: [f64; 3],
) -> bool {
    let s = DVec3::from(dir);
    let terms = [n.x * s.x, n.y * s.y, n.z * s.z];
    let sum: f64 = terms.iter().sum();
    if sum.abs() > 1e-9 * terms.iter().map(|t| t.abs()).sum::<f64>() {
        return true;
    }
    // Without rounding the ray starts on the plane itself, and leaves it at once unless it
    // runs in it: asked exactly (intervals cannot tell the two apart in the tests).
    S::EXACT && crosses_plane(terrain, cell, k, dir)
}

/// How far to raise a start on the surface above what rounding may have moved it below (zero
/// in exact arithmetic): the surface is a height field, so up is always outside. The point is
/// `o + t*d`, each component within a few roundings of `|o| + |t*d|`; off by that across an
/// edge, the surface may be higher by the steepest slope times it.
fn lift<S: Scalar>(terrain: &Terrain, ray: &Ray, hit: &Found<S>) -> f64 {
    let t = hit.t.to_f64().abs();
    let (ray_o, ray_d) = (ray.origin(), ray.dir());
    let largest = (0..3).fold(0.0f64, |m, k| m.max(ray_o[k].abs() + t * ray_d[k].abs()));
    64.0 * S::rounding_error(largest) * (1.0 + terrain.max_slope())
}

/// The hit point as a ray from the flat triangle starts at, in arithmetic `S`, the hit cell's
/// corners at `heights`.
#[inline(always)]
fn plane_point<S: Scalar>(heights: [f64; 4], found: &Found<S>, ray: &Ray) -> [S; 3] {
    let (ray_o, ray_d) = (ray.origin(), ray.dir());
    let [x, y] = [0, 1].map(|k| S::along(ray_o[k], ray_d[k], &found.t));
    // Rounding arithmetics take the height on the hit triangle's plane: exact on flat ground.
    // Without rounding the ray's own point is on the plane, and enclosing it takes a fifth of
    // the work of enclosing the plane's height over the enclosures of x and y; on a flat
    // triangle the point's height is the triangle's, exactly: intervals must know it then, or
    // the run and cell tests of a ray from a terrace's top, the highest sample of the runs and
    // cells around it, cannot be settled where intervals walk (a path along a grid row, which
    // the `f64` walk leaves to them), and each such ray is cast again in rationals, at a
    // millisecond a ray.
    let z = if S::EXACT {
        let [a, b, c] = triangle_corners(found.triangle).map(|k| heights[k]);
        match a == b && b == c {
            true => S::from_f64(a),
            false => S::along(ray_o[2], ray_d[2], &found.t),
        }
    } else {
        let heights = heights.map(S::from_f64);
        plane_height(found.triangle, found.cell, heights, x.clone(), y.clone())
    };
    [x, y, z]
}

/// The point where a ray hit the base, in arithmetic `S`, on the face's plane exactly.
fn base_point<S: Scalar>(
    terrain: &Terrain,
    base: Option<Base>,
    found: &Found<S>,
    ray: &Ray,
) -> [S; 3] {
    let (ray_o, ray_d) = (ray.origin(), ray.dir());
    let mut point = [0, 1, 2].map(|k| S::along(ray_o[k], ray_d[k], &found.t));
    let field = terrain.field();
    let (w, h) = (field.width() as i64 - 1, field.height() as i64 - 1);
    match (found.face, base) {
        (Face::Floor, Some(base)) => point[2] = S::from_f64(base.floor()),
        (Face::Wall(Side::West), _) => point[0] = S::zero(),
        (Face::Wall(Side::East), _) => point[0] = S::from_i64(w),
        (Face::Wall(Side::South), _) => point[1] = S::zero(),
        (Face::Wall(Side::North), _) => point[1] = S::from_i64(h),
        _ => {}
    }
    point
}
