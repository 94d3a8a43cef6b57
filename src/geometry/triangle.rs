//! The watertight ray/triangle test of Woop, Benthin & Wald (2013), over any [`Scalar`].
//!
//! Why it is watertight: each vertex is moved into ray space (the ray becomes the +z axis)
//! once per vertex, by the same operations whichever triangle it belongs to, so neighbouring
//! triangles see bit-identical 2D vertices. The edge functions are 2D orientations of those
//! vertices against the origin, and [`Scalar::det2`] gives their sign exactly. So the hit
//! decision is an exact predicate on one consistent planar mesh: a ray through a shared edge
//! or vertex is inside (edges count) of at least one triangle around it, never none. In exact
//! arithmetic the test is the exact definition itself (the surface contract, [`super`]): closed
//! triangles, and a ray
//! lying in a triangle's plane hits where it first touches the triangle.

use crate::arith::scalar::{max, min, Scalar};
use std::ops::{Add, Mul, Sub};

/// A ray prepared for many triangle tests: the axis permutation and shear of Woop et al.
#[derive(Clone, Debug)]
pub struct RaySpace<S> {
    pub(super) axes: [usize; 3],
    pub(super) shear: [S; 3],
    origin: [S; 3],
    dir: [S; 3],
}

/// Where a ray touches a triangle: `t_first` is the first touch (the hit); `t_last` differs
/// only when the ray lies in the triangle's plane and runs across it (`None`: unbounded).
#[derive(Clone, Debug, PartialEq)]
pub struct TriangleHit<S> {
    /// The first touch: the hit.
    pub t_first: S,
    /// The last touch: `t_first` but for a ray in the triangle's plane (`None`: unbounded).
    pub t_last: Option<S>,
}

/// The axes of ray space `[x, y, z]`: the direction's largest component becomes z, and the
/// order stays cyclic, so orientations keep their sign.
// (`#[inline]`, so that `RaySpace::new`, which prepares every walk's ray, inlines whole.)
#[inline]
pub fn ray_space_axes(dir: [f64; 3]) -> [usize; 3] {
    let kz = (0..3)
        .max_by(|&a, &b| dir[a].abs().total_cmp(&dir[b].abs()))
        .unwrap_or(2);
    [(kz + 1) % 3, (kz + 2) % 3, kz]
}

/// The corners of triangle `k` (0 or 1) of a cell, counter-clockwise seen from +z, as indices
/// into its corners `[P00, P10, P01, P11]` (the surface contract, [`crate::geometry`]).
pub fn triangle_corners(k: u8) -> [usize; 3] {
    if k == 0 {
        [0, 1, 3]
    } else {
        [0, 3, 2]
    }
}

impl<S: Scalar> RaySpace<S> {
    /// `dir_f64` picks the axes the same way in every arithmetic.
    pub fn new(origin: [S; 3], dir: [S; 3], dir_f64: [f64; 3]) -> Self {
        let [kx, ky, kz] = ray_space_axes(dir_f64);
        // Shear so the direction becomes (0, 0, 1).
        let dz = dir[kz].clone();
        let shear = [
            dir[kx].clone() / dz.clone(),
            dir[ky].clone() / dz.clone(),
            S::one() / dz,
        ];
        RaySpace {
            axes: [kx, ky, kz],
            shear,
            origin,
            dir,
        }
    }

    /// The ray's origin.
    pub fn origin(&self) -> &[S; 3] {
        &self.origin
    }

    /// A vertex in ray space.
    #[inline]
    pub fn vertex(&self, p: [S; 3]) -> [S; 3] {
        let [kx, ky, kz] = self.axes;
        let rel = |k: usize| p[k].clone() - self.origin[k].clone();
        let (x, y, z) = (rel(kx), rel(ky), rel(kz));
        [
            x - self.shear[0].clone() * z.clone(),
            y - self.shear[1].clone() * z.clone(),
            self.shear[2].clone() * z,
        ]
    }

    /// Intersects the triangle with vertices `p` (counter-clockwise seen from +z) whose ray-space
    /// images are `q`. Hits at `t >= 0` only.
    pub fn intersect(&self, p: [&[S; 3]; 3], q: [&[S; 3]; 3]) -> Option<TriangleHit<S>> {
        let [a, b, c] = q;
        // Compute edge functions, signs exact (the third only where the first two leave the
        // answer open, so none more is asked of an arithmetic that may not settle it).
        let u = S::det2(&c[0], &b[1], &c[1], &b[0]);
        let v = S::det2(&a[0], &c[1], &a[1], &c[0]);
        let w = || S::det2(&b[0], &a[1], &b[1], &a[0]);
        let heights = [&a[2], &b[2], &c[2]];
        self.decide([u, v], w, heights, || self.intersect_coplanar(p))
    }

    /// The test from a triangle's edge functions `u`, `v` and `w` (in ray space, against the
    /// corners `c`-`b`, `a`-`c`, `b`-`a`) and its corners' ray-space heights; `coplanar`
    /// answers for a ray in the triangle's plane (all three zero).
    #[inline(always)]
    pub(super) fn decide(
        &self,
        [u, v]: [S; 2],
        w: impl FnOnce() -> S,
        [az, bz, cz]: [&S; 3],
        coplanar: impl FnOnce() -> Option<TriangleHit<S>>,
    ) -> Option<TriangleHit<S>> {
        // Two of opposite signs already tell a miss.
        let zero = S::zero();
        if (u < zero && v > zero) || (u > zero && v < zero) {
            return None;
        }
        let w = w();
        let any_negative = u < zero || v < zero || w < zero;
        let any_positive = u > zero || v > zero || w > zero;
        if any_negative && any_positive {
            return None;
        }
        if !any_negative && !any_positive {
            return coplanar();
        }
        // Interpolate the hit distance; det and t_scaled share a sign when t >= 0.
        let det = u.clone() + v.clone() + w.clone();
        let t_scaled = u * az.clone() + v * bz.clone() + w * cz.clone();
        if t_scaled.is_negative() != det.is_negative() && !t_scaled.is_zero() {
            return None;
        }
        let t = t_scaled / det;
        Some(TriangleHit {
            t_first: t.clone(),
            t_last: Some(t),
        })
    }

    /// The ray lies in the triangle's plane: clip its xy path to the triangle's three edge
    /// half-planes (the triangle projects onto xy without degenerating).
    fn intersect_coplanar(&self, p: [&[S; 3]; 3]) -> Option<TriangleHit<S>> {
        let (o, d) = (&self.origin, &self.dir);
        let mut lo = S::zero();
        let mut hi: Option<S> = None;
        for k in 0..3 {
            let (from, to) = (p[k], p[(k + 1) % 3]);
            let (ex, ey) = (
                to[0].clone() - from[0].clone(),
                to[1].clone() - from[1].clone(),
            );
            // Inside the edge where g0 + g1*t >= 0.
            let g0 = ex.clone() * (o[1].clone() - from[1].clone())
                - ey.clone() * (o[0].clone() - from[0].clone());
            let g1 = ex * d[1].clone() - ey * d[0].clone();
            if g1.is_zero() {
                if g0.is_negative() {
                    return None;
                }
                continue;
            }
            let crossing = -g0 / g1.clone();
            if g1.is_negative() {
                hi = Some(match hi {
                    Some(h) => min(h, crossing),
                    None => crossing,
                });
            } else {
                lo = max(lo, crossing);
            }
        }
        if hi.as_ref().is_some_and(|h| *h < lo) {
            return None;
        }
        Some(TriangleHit {
            t_first: lo,
            t_last: hi,
        })
    }
}

/// The two triangles of cell `(i, j)`: `T0 = (P00, P10, P11)` and `T1 = (P00, P11, P01)`.
pub struct CellTriangles<S> {
    corners: [[S; 3]; 4],
    images: [[S; 3]; 4],
}

impl<S: Scalar> CellTriangles<S> {
    /// `heights` are `[z00, z10, z01, z11]` of the cell's corners.
    pub fn new(ray: &RaySpace<S>, i: usize, j: usize, heights: [S; 4]) -> Self {
        let (x0, y0) = (S::from_i64(i as i64), S::from_i64(j as i64));
        let (x1, y1) = (S::from_i64(i as i64 + 1), S::from_i64(j as i64 + 1));
        let [z00, z10, z01, z11] = heights;
        let corners = [
            [x0.clone(), y0.clone(), z00],
            [x1.clone(), y0, z10],
            [x0, y1.clone(), z01],
            [x1, y1, z11],
        ];
        // (Written out: `array::map` over generic values is not reliably unrolled.)
        let images = [
            ray.vertex(corners[0].clone()),
            ray.vertex(corners[1].clone()),
            ray.vertex(corners[2].clone()),
            ray.vertex(corners[3].clone()),
        ];
        CellTriangles { corners, images }
    }

    /// Intersects triangle `k` (0 or 1).
    pub fn intersect(&self, ray: &RaySpace<S>, k: u8) -> Option<TriangleHit<S>> {
        // Corner indices: 0 = P00, 1 = P10, 2 = P01, 3 = P11; both counter-clockwise.
        let [a, b, c] = triangle_corners(k);
        ray.intersect(
            [&self.corners[a], &self.corners[b], &self.corners[c]],
            [&self.images[a], &self.images[b], &self.images[c]],
        )
    }
}

/// The gradient `(dz/dx, dz/dy)` of triangle `k` of a cell with corner heights
/// `[z00, z10, z01, z11]`: over `T0` the plane is `z = z00 + (z10-z00)(x-i) + (z11-z10)(y-j)`,
/// over `T1` `z = z00 + (z11-z01)(x-i) + (z01-z00)(y-j)` (the surface contract,
/// [`crate::geometry`]).
pub fn gradient<S: Clone + Sub<Output = S>>(k: u8, [z00, z10, z01, z11]: [S; 4]) -> (S, S) {
    if k == 0 {
        (z10.clone() - z00, z11 - z10)
    } else {
        (z11 - z01.clone(), z01 - z00)
    }
}

/// Where the line `o + t*d` meets the plane of triangle `k` of the cell whose corner `P00` is
/// at `corner` with corner heights `[z00, z10, z01, z11]`: `t = above / closing`, returned as
/// `(above, closing)` (`closing` is zero where the line runs parallel to the plane).
pub fn plane_crossing<T>(k: u8, heights: [T; 4], corner: (T, T), o: [T; 3], d: [T; 3]) -> (T, T)
where
    T: Clone + Add<Output = T> + Sub<Output = T> + Mul<Output = T>,
{
    let z00 = heights[0].clone();
    let (gx, gy) = gradient(k, heights);
    let ([ox, oy, oz], [dx, dy, dz]) = (o, d);
    // oz + t*dz = z00 + gx*(ox + t*dx - x0) + gy*(oy + t*dy - y0), solved for t.
    let above = oz - z00 - gx.clone() * (ox - corner.0) - gy.clone() * (oy - corner.1);
    let closing = gx * dx + gy * dy - dz;
    (above, closing)
}

/// The height of triangle `k`'s plane over `(x, y)`, for the cell `(i, j)` with corner heights
/// `heights`: exact for a flat triangle in every arithmetic.
pub fn plane_height<S: Scalar>(k: u8, (i, j): (usize, usize), heights: [S; 4], x: S, y: S) -> S {
    let z00 = heights[0].clone();
    let (gx, gy) = gradient(k, heights);
    z00 + gx * (x - S::from_i64(i as i64)) + gy * (y - S::from_i64(j as i64))
}
