//! A shadow ray's start given exactly, so that a triangle test intervals cannot settle is
//! decided exactly on its own: one test in integers, where casting the whole ray again in
//! rationals costs about sixty times as much.

use super::exact_plane::{exact_t, point_over};
use crate::arith::dyadic::Dyadic;
use crate::geometry::Ray;
use crate::geometry::{ray_space_axes, triangle_corners};
use crate::heightfield::Terrain;

/// Where `ray` meets the plane of triangle `triangle` of `cell`: a hit point, given by what
/// makes it exactly rather than by its coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanePoint {
    /// The ray that hit.
    pub ray: Ray,
    /// The cell `(i, j)` it hit.
    pub cell: (usize, usize),
    /// The triangle it hit, 0 or 1.
    pub triangle: u8,
}

/// A point as numerators over one denominator: `n / den`, exactly.
struct Homogeneous {
    n: [Dyadic; 3],
    den: Dyadic,
}

impl PlanePoint {
    /// The point, exactly; `None` where the ray runs parallel to the plane.
    fn homogeneous(&self, terrain: &Terrain) -> Option<Homogeneous> {
        let (cell, k) = ([self.cell.0, self.cell.1], self.triangle);
        let (above, closing) = exact_t(terrain, &self.ray, cell, k)?;
        Some(Homogeneous {
            n: point_over(&self.ray, &above, &closing),
            den: closing,
        })
    }

    /// Whether the ray of direction `dir` from this point touches triangle `k` of `cell` after
    /// its start, decided exactly, and if so the `f64` nearest to where (`Some(None)`: it does
    /// not); `None` where this cannot decide: the point cannot be made exact, or the ray lies
    /// in the triangle's plane.
    ///
    /// The watertight test of [`crate::geometry::RaySpace`] on the same ray space, every
    /// quantity multiplied by a power of `s = den * d_z` (the start's denominator and the
    /// direction's ray-space z): edge functions by `s^2`, which keeps their signs, and the
    /// hit's `t` is the scaled numerator over the scaled denominator times `s`.
    pub fn touches_after_start(
        &self,
        terrain: &Terrain,
        dir: [f64; 3],
        (i, j): (usize, usize),
        k: u8,
    ) -> Option<Option<f64>> {
        let start = self.homogeneous(terrain)?;
        let [kx, ky, kz] = ray_space_axes(dir);
        let d = dir.map(Dyadic::from_f64);
        let heights = terrain.corner_heights(i, j);
        // Corner `c` of `[P00, P10, P01, P11]` in ray space, times `s`.
        let image = |c: usize| {
            let p = [
                Dyadic::from_i64((i + (c & 1)) as i64),
                Dyadic::from_i64((j + (c >> 1)) as i64),
                Dyadic::from_f64(heights[c]),
            ];
            let rel = |a: usize| p[a].clone() * start.den.clone() - start.n[a].clone();
            let z = rel(kz);
            [
                rel(kx) * d[kz].clone() - d[kx].clone() * z.clone(),
                rel(ky) * d[kz].clone() - d[ky].clone() * z.clone(),
                z,
            ]
        };
        let [a, b, c] = triangle_corners(k).map(image);
        let det2 = |p: &Dyadic, q: &Dyadic, r: &Dyadic, s: &Dyadic| {
            p.clone() * q.clone() - r.clone() * s.clone()
        };
        let u = det2(&c[0], &b[1], &c[1], &b[0]);
        let v = det2(&a[0], &c[1], &a[1], &c[0]);
        let w = det2(&b[0], &a[1], &b[1], &a[0]);
        let signs = [&u, &v, &w].map(sign);
        if signs.iter().all(|&s| s == 0) {
            return None;
        }
        if signs.contains(&1) && signs.contains(&-1) {
            return Some(None);
        }
        let det = u.clone() + v.clone() + w.clone();
        let t_scaled = u * a[2].clone() + v * b[2].clone() + w * c[2].clone();
        let s = start.den.clone() * d[kz].clone();
        let after_start = sign(&t_scaled) * sign(&det) * sign(&s) > 0;
        Some(after_start.then(|| t_scaled.over_to_f64(&(det * s))))
    }
}

fn sign(x: &Dyadic) -> i8 {
    if x.is_zero() {
        0
    } else if x.is_negative() {
        -1
    } else {
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::scalar::exact_from_f64;
    use crate::arith::{Exact, Scalar};
    use crate::geometry::strategies::component;
    use crate::geometry::{plane_crossing, CellTriangles, RaySpace};
    use crate::heightfield::Heightfield;
    use num_rational::BigRational;
    use num_traits::Zero;
    use proptest::prelude::*;
    use proptest::test_runner::RngSeed;

    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            (-1i32..7).prop_map(f64::from),
            (-4i32..28).prop_map(|n| f64::from(n) / 4.0),
            -1.0f64..7.0,
        ]
    }

    /// A 7x7 field of hills, flats and steps, in heights `z_scale / 255` apart (not dyadic).
    fn terrain() -> Terrain {
        let sample = |i: usize, j: usize| [0, 0, 40, 255, 128, 128, 7][(i * 3 + j * 5) % 7];
        Terrain::new(Heightfield::from_fn(7, 7, 255, 5.0, sample).unwrap())
    }

    /// The answer of the `BigRational` test of triangle `k` of `cell` for the ray from where
    /// `ray` meets the plane of triangle `start.1` of `start.0` (all in rationals): `None`
    /// where that ray lies in the triangle's plane and touches it (which ours leaves to
    /// rationals).
    fn reference(
        terrain: &Terrain,
        ray: &Ray,
        start: ((usize, usize), u8),
        dir: [f64; 3],
        (i, j): (usize, usize),
        k: u8,
    ) -> Option<Option<f64>> {
        let exact = |x: f64| Exact(exact_from_f64(x));
        let heights = |(i, j): (usize, usize)| terrain.corner_heights(i, j).map(exact);
        let corner =
            |(i, j): (usize, usize)| (Exact::from_i64(i as i64), Exact::from_i64(j as i64));
        let (o, d) = (ray.origin().map(exact), ray.dir().map(exact));
        let (above, closing) = plane_crossing(
            start.1,
            heights(start.0),
            corner(start.0),
            o.clone(),
            d.clone(),
        );
        assert!(!closing.is_zero(), "the ray runs parallel to its plane");
        let t = above / closing;
        let p = [0, 1, 2].map(|n| o[n].clone() + d[n].clone() * t.clone());
        let s = dir.map(exact);
        let (_, parallel) =
            plane_crossing(k, heights((i, j)), corner((i, j)), p.clone(), s.clone());
        let space = RaySpace::new(p, s, dir);
        let hit = CellTriangles::new(&space, i, j, heights((i, j))).intersect(&space, k);
        if parallel.is_zero() && hit.is_some() {
            return None;
        }
        Some(hit.and_then(|hit| {
            let after = hit
                .t_last
                .as_ref()
                .is_none_or(|t| t.0 > BigRational::zero());
            after.then(|| hit.t_first.to_f64())
        }))
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 3000, rng_seed: RngSeed::Fixed(12), ..ProptestConfig::default() })]

        /// The test in integers answers as the test in rationals, for rays from hit points on
        /// and around lattice points, edges and flats, towards the triangles around them.
        #[test]
        fn answers_as_the_rational_test(
            (x, y, z) in (coordinate(), coordinate(), 2i32..12),
            dir in [component(), component(), component()],
            sun in [component(), component(), component()],
            (i, j, k) in (0usize..6, 0usize..6, 0u8..2),
            (di, dj, k2) in (-1i64..=1, -1i64..=1, 0u8..2),
        ) {
            let ray = Ray::new([x, y, f64::from(z)], dir);
            prop_assume!(ray.is_ok() && sun.iter().any(|&x| x != 0.0));
            let ray = ray.unwrap();
            let terrain = terrain();
            let start = PlanePoint { ray, cell: (i, j), triangle: k };
            prop_assume!(start.homogeneous(&terrain).is_some());
            let cell = ((i as i64 + di).clamp(0, 5) as usize, (j as i64 + dj).clamp(0, 5) as usize);
            let ours = start.touches_after_start(&terrain, sun, cell, k2);
            let theirs = reference(&terrain, &ray, ((i, j), k), sun, cell, k2);
            match (ours, theirs) {
                // (Ours leaves every ray in the triangle's plane to rationals.)
                (None, theirs) => prop_assert!(theirs.is_none() || theirs == Some(None)),
                (ours, theirs) => prop_assert_eq!(ours, theirs),
            }
        }
    }
}
