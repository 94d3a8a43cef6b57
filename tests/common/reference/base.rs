//! The reference for the base under a terrain, from the contract alone: the floor is the
//! closed rectangle `z = f` over `[0, W-1] x [0, H-1]`; on each edge line a wall piece stands
//! over each edge segment `[k, k+1]` whose edge cell is not a hole, the closed trapezoid
//! between `z = f` and the segment of the terrain's edge. The first hit is the least `t`
//! over triangles, walls and floor; ties go to the terrain, then to the walls (west `x = 0`,
//! east `x = W-1`, south `y = 0`, north `y = H-1`), then to the floor.

use super::numbers::{q, qi, ExactField, ExactRay, Interval, Q};
use super::{solve, ExactHit};
use heightray::{Face, Heightfield, Ray, Side};
use num_traits::Zero;

/// What the contract says a ray hits first over the terrain and its base.
#[derive(Clone, Debug, PartialEq)]
pub enum SurfaceHit {
    Terrain(ExactHit),
    Base { t: Q, face: Face },
}

impl SurfaceHit {
    pub fn t(&self) -> &Q {
        match self {
            SurfaceHit::Terrain(hit) => &hit.t,
            SurfaceHit::Base { t, .. } => t,
        }
    }
}

/// A convex polygon in the plane `p[axis] = at`, as half-spaces `a . p + b >= 0`.
struct Polygon {
    axis: usize,
    at: Q,
    halves: Vec<([Q; 3], Q)>,
}

impl Polygon {
    /// The least `t >= 0` at which the ray touches the polygon.
    fn first_touch(&self, ray: &ExactRay) -> Option<Q> {
        let (o, d) = (&ray.o[self.axis], &ray.d[self.axis]);
        let mut inside = Interval::nonnegative();
        if d.is_zero() {
            if *o != self.at {
                return None;
            }
        } else if !inside.keep(&(o - &self.at), d) || !inside.keep(&(&self.at - o), &-d) {
            // (The plane, as a slab of width zero.)
            return None;
        }
        for (a, b) in &self.halves {
            let g0 = (0..3).fold(b.clone(), |s, k| s + &a[k] * &ray.o[k]);
            let g1 = (0..3).fold(Q::zero(), |s, k| s + &a[k] * &ray.d[k]);
            if !inside.keep(&g0, &g1) {
                return None;
            }
        }
        Some(inside.lo)
    }
}

fn unit(axis: usize, sign: i64) -> [Q; 3] {
    let mut a = [qi(0), qi(0), qi(0)];
    a[axis] = qi(sign);
    a
}

/// The wall pieces of `side`.
fn walls(field: &ExactField, floor: &Q, side: Side) -> Vec<Polygon> {
    let (w, h) = (field.w - 1, field.h - 1);
    let (axis, at, length) = match side {
        Side::West => (0, 0, h),
        Side::East => (0, w, h),
        Side::South => (1, 0, w),
        Side::North => (1, h, w),
    };
    let along = 1 - axis;
    let inner = if at == 0 { 0 } else { at - 1 };
    (0..length)
        .filter_map(|k| {
            let (cell, p0, p1) = if axis == 0 {
                ([inner, k], (at, k), (at, k + 1))
            } else {
                ([k, inner], (k, at), (k + 1, at))
            };
            if field.is_hole(cell) {
                return None;
            }
            let (z0, z1) = (field.z(p0.0, p0.1), field.z(p1.0, p1.1));
            // z <= z0 + (z1 - z0) (u - k)
            let mut a = [qi(0), qi(0), qi(-1)];
            a[along] = z1 - z0;
            let b = z0 - (z1 - z0) * qi(k as i64);
            Some(Polygon {
                axis,
                at: qi(at as i64),
                halves: vec![
                    (unit(along, 1), qi(-(k as i64))),
                    (unit(along, -1), qi(k as i64 + 1)),
                    (unit(2, 1), -floor.clone()),
                    (a, b),
                ],
            })
        })
        .collect()
}

/// The first hit of `ray` over the terrain of `field` and a base with its floor at `floor`
/// (walls if `with_walls`).
pub fn solve_with_base(
    field: &Heightfield,
    ray: &Ray,
    floor: f64,
    with_walls: bool,
) -> Option<SurfaceHit> {
    let terrain = solve(field, ray).hit.map(SurfaceHit::Terrain);
    let exact = ExactField::new(field);
    let exact_ray = ExactRay::new(ray);
    let f = q(floor);
    let mut faces: Vec<(Face, Vec<Polygon>)> = Vec::new();
    if with_walls {
        for side in Side::ALL {
            faces.push((Face::Wall(side), walls(&exact, &f, side)));
        }
    }
    let (w, h) = ((exact.w - 1) as i64, (exact.h - 1) as i64);
    let rectangle = Polygon {
        axis: 2,
        at: f.clone(),
        halves: vec![
            (unit(0, 1), qi(0)),
            (unit(0, -1), qi(w)),
            (unit(1, 1), qi(0)),
            (unit(1, -1), qi(h)),
        ],
    };
    faces.push((Face::Floor, vec![rectangle]));
    // In order of precedence: a later face wins only strictly earlier.
    let mut best = terrain;
    for (face, polygons) in faces {
        let Some(t) = polygons
            .iter()
            .filter_map(|p| p.first_touch(&exact_ray))
            .min()
        else {
            continue;
        };
        if best.as_ref().is_none_or(|b| t < *b.t()) {
            best = Some(SurfaceHit::Base { t, face });
        }
    }
    best
}
