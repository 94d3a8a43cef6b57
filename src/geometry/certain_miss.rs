//! Triangle misses and hits certain in `f64`, for rays traced in an arithmetic without
//! rounding.
//!
//! Most triangles a walk tests are misses, and a miss is plain in the edge functions of the
//! watertight test ([`super::RaySpace`]): two of them have opposite signs. This filter computes
//! them in `f64` with a bound on their error, from a ray within a known radius of the exact
//! one; where two signs are certain and opposite, the exact test would find them so too, and
//! the miss is the exact answer. Where all three are certain and alike, the exact ray's line
//! crosses the triangle inside it, and the exact test hits it where the line meets the
//! triangle's plane if that lies ahead: an enclosure of that `t`, from the plane solve in
//! floats with a running error bound ([`Near`]), is the answer then. Every other case is left
//! to the exact test.
//!
//! The bound. The exact ray-space image of a vertex `p` is `x' = (p_x - o_x) - s (p_z - o_z)`
//! with `s = d_x / d_z`, `|s| <= 1` (z is the direction's largest component). The filter's
//! origin is within `r` of `o` on each axis and each of its operations rounds by at most
//! `eps` relative, so with `m` the largest magnitude of `p - o` over the cell,
//! `|x' - X'| <= 2r + 7 eps m` (a few more `eps` for the products of small terms): the
//! filter takes `e = 2.01 r + 16 eps m`. An edge function `c0 b1 - c1 b0` of coordinates each
//! off by at most `e` is off by at most `e (|c0| + |b1| + |c1| + |b0|) + 2 e^2`, and its own
//! two products and difference round by at most `3 eps (|c0 b1| + |c1 b0|)`. Every computed
//! image coordinate is at most `M = 2 m (1 + 4 eps)` in magnitude (two terms of at most `m`,
//! `|s| <= 1`, three roundings), so one bound serves all six edge functions of a cell:
//! `4 e M + 2 e^2 + 6.01 eps M^2`.

use super::{plane_crossing, triangle_corners, RaySpace};
use crate::arith::Interval;
use std::ops::{Add, Mul, Sub};

/// The `f64` stand-in of one ray.
pub struct CertainMiss {
    space: RaySpace<f64>,
    dir: [f64; 3],
    /// How far the exact origin may be from `space`'s, on any axis.
    radius: f64,
}

/// The four corners of one cell in the filter's ray space, with a bound on the error of every
/// edge function of them.
pub struct CellImages {
    images: [[f64; 3]; 4],
    bound: f64,
}

impl CertainMiss {
    /// For the exact ray `o + t*d` with `o` within `radius` of `origin` on each axis and `d`
    /// given exactly.
    pub fn new(origin: [f64; 3], radius: f64, dir: [f64; 3]) -> Self {
        CertainMiss {
            space: RaySpace::new(origin, dir, dir),
            dir,
            radius,
        }
    }

    /// An enclosure `(lo, hi)` of the `t` where the exact ray meets the plane of triangle `k`
    /// of cell `(i, j)` (corner heights `[z00, z10, z01, z11]`), where it certainly lies ahead
    /// of the origin (`t > 0`).
    pub fn plane_t(&self, (i, j): (usize, usize), k: u8, heights: [f64; 4]) -> Option<(f64, f64)> {
        let [ox, oy, oz] = *self.space.origin();
        let near = |x: f64| Near::within(x, self.radius);
        let (above, closing) = plane_crossing(
            k,
            heights.map(Near::exact),
            (Near::exact(i as f64), Near::exact(j as f64)),
            [near(ox), near(oy), near(oz)],
            self.dir.map(Near::exact),
        );
        let (above, closing) = (above.enclosure()?, closing.enclosure()?);
        // (Asked without a comparison, which would flag the ray where it cannot tell.)
        let (c_lo, c_hi) = closing.ends();
        if c_lo <= 0.0 && c_hi >= 0.0 {
            return None;
        }
        let (lo, hi) = (above / closing).ends();
        (lo > 0.0 && hi.is_finite()).then_some((lo, hi))
    }

    /// Cell `(i, j)` with corner heights `[z00, z10, z01, z11]`.
    pub fn cell(&self, i: usize, j: usize, heights: [f64; 4]) -> CellImages {
        let (x0, y0) = (i as f64, j as f64);
        let [z00, z10, z01, z11] = heights;
        let corners = [
            [x0, y0, z00],
            [x0 + 1.0, y0, z10],
            [x0, y0 + 1.0, z01],
            [x0 + 1.0, y0 + 1.0, z11],
        ];
        let origin = self.space.origin();
        let largest = corners
            .iter()
            .flat_map(|p| (0..3).map(move |k| (p[k] - origin[k]).abs()))
            .fold(0.0, f64::max);
        let e = 2.01 * self.radius + 16.0 * f64::EPSILON * largest;
        let m = 2.0 * largest * (1.0 + 4.0 * f64::EPSILON);
        // (Widened for the rounding of the bound's own few operations.)
        let bound = (4.0 * e * m + 2.0 * e * e + 6.01 * f64::EPSILON * m * m) * (1.0 + 1e-9);
        // (In straight code: an array's `map` goes out of line here, a call per corner.)
        let image = |n: usize| self.space.vertex(corners[n]);
        CellImages {
            images: [image(0), image(1), image(2), image(3)],
            bound: bound + 1e-300,
        }
    }
}

/// What the filter settles of one triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Certain {
    /// The exact ray misses it.
    Miss,
    /// The exact ray's line crosses it inside (not on an edge, and not in its plane).
    Crossing,
    /// Left to the exact test.
    Open,
}

impl CellImages {
    /// What is certain of triangle `k` (0 or 1, corners as in [`super::CellTriangles`]).
    pub fn triangle(&self, k: u8) -> Certain {
        let [a, b, c] = triangle_corners(k);
        let [a, b, c] = [a, b, c].map(|n| &self.images[n]);
        let first = self.sign(c[0], b[1], c[1], b[0]);
        let second = self.sign(a[0], c[1], a[1], c[0]);
        let opposite = |x: Option<bool>, y: Option<bool>| x.is_some() && y.is_some() && x != y;
        // (Two edge functions of opposite signs already tell a miss.)
        if opposite(first, second) {
            return Certain::Miss;
        }
        let third = self.sign(b[0], a[1], b[1], a[0]);
        if opposite(first, third) || opposite(second, third) {
            Certain::Miss
        } else if first.is_some() && first == second && second == third {
            Certain::Crossing
        } else {
            Certain::Open
        }
    }

    /// The sign of `p*q - r*s` (`true`: positive) where it is certain.
    fn sign(&self, p: f64, q: f64, r: f64, s: f64) -> Option<bool> {
        let value = p * q - r * s;
        // (NaN compares false both ways: uncertain.)
        if value > self.bound {
            Some(true)
        } else if value < -self.bound {
            Some(false)
        } else {
            None
        }
    }
}

/// An `f64` computed from inputs near exact values, with a bound on its distance from the
/// exact result: the plain float operations and a running bound, a few times cheaper than
/// intervals, whose every end rounds outwards with an error-free transformation.
///
/// The bound. A sum or product rounded to nearest is off by at most `u |r|` (`u` = 2^-53) of
/// its result `r`, plus, for a product, 2^-1074 where it underflows; the operands' own errors
/// add `ea + eb` to a sum and `|a| eb + |b| ea + ea eb` to a product. The bound is itself
/// computed in floats from non-negative terms, each rounding at most `u` relative: over the
/// few dozen operations of a plane solve that is far below the `2^-40` by which
/// [`Near::enclosure`] widens it.
#[derive(Clone, Copy, Debug)]
struct Near {
    value: f64,
    error: f64,
}

const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

impl Near {
    fn exact(value: f64) -> Near {
        Near { value, error: 0.0 }
    }

    /// A value known only to lie within `radius` of `value`.
    fn within(value: f64, radius: f64) -> Near {
        Near {
            value,
            error: radius,
        }
    }

    /// Bounds that certainly contain the exact value (`None` where a float overflowed).
    fn enclosure(self) -> Option<Interval> {
        let error = self.error * (1.0 + 1.0 / (1u64 << 40) as f64);
        Interval::between(
            (self.value - error).next_down(),
            (self.value + error).next_up(),
        )
    }
}

impl Add for Near {
    type Output = Near;
    fn add(self, rhs: Near) -> Near {
        let value = self.value + rhs.value;
        Near {
            value,
            error: self.error + rhs.error + UNIT_ROUNDOFF * value.abs(),
        }
    }
}

impl Sub for Near {
    type Output = Near;
    fn sub(self, rhs: Near) -> Near {
        self + Near {
            value: -rhs.value,
            error: rhs.error,
        }
    }
}

impl Mul for Near {
    type Output = Near;
    fn mul(self, rhs: Near) -> Near {
        let value = self.value * rhs.value;
        let operands =
            self.value.abs() * rhs.error + rhs.value.abs() * self.error + self.error * rhs.error;
        Near {
            value,
            error: operands + UNIT_ROUNDOFF * value.abs() + f64::MIN_POSITIVE,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::scalar::exact_from_f64;
    use crate::arith::Exact;
    use crate::geometry::strategies::component;
    use crate::geometry::CellTriangles;
    use num_rational::BigRational;
    use proptest::prelude::*;
    use proptest::test_runner::RngSeed;

    /// Where the exact test hits triangle `k` of cell `(i, j)`, for the ray from `origin`
    /// moved by `offset` (exactly) along `dir`.
    fn exact_hit(
        origin: [f64; 3],
        offset: [BigRational; 3],
        dir: [f64; 3],
        (i, j): (usize, usize),
        heights: [f64; 4],
        k: u8,
    ) -> Option<BigRational> {
        let o = [0, 1, 2].map(|n| Exact(exact_from_f64(origin[n]) + offset[n].clone()));
        let space = RaySpace::new(o, dir.map(|x| Exact(exact_from_f64(x))), dir);
        let cell = CellTriangles::new(&space, i, j, heights.map(|z| Exact(exact_from_f64(z))));
        cell.intersect(&space, k).map(|hit| hit.t_first.0)
    }

    /// Coordinates that stress the bound: on grid lines and vertices, just off them, and
    /// arbitrary.
    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            (0i32..6).prop_map(f64::from),
            (0i32..24).prop_map(|n| f64::from(n) / 4.0),
            (0i32..6, 1u8..4).prop_map(|(n, k)| (0..k).fold(f64::from(n), |x, _| x.next_up())),
            -2.0f64..8.0,
        ]
    }

    fn height() -> impl Strategy<Value = f64> {
        prop_oneof![
            (0i32..4).prop_map(f64::from),
            (0u16..1000).prop_map(|s| f64::from(s) * 0.0625),
            0.0f64..4.0,
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 6000, rng_seed: RngSeed::Fixed(11), ..ProptestConfig::default() })]

        /// What the filter settles is the exact test's answer, for the exact origin anywhere
        /// within the radius: a certain miss is a miss, and a certain crossing ahead of the
        /// origin a hit at a `t` inside the enclosure.
        #[test]
        fn certain_answers_are_exact_answers(
            origin in [coordinate(), coordinate(), coordinate()],
            dir in [component(), component(), component()],
            heights in [height(), height(), height(), height()],
            (i, j) in (0usize..5, 0usize..5),
            radius in prop_oneof![Just(0.0), Just(1e-12), Just(1e-6), Just(0.25)],
            fractions in [-8i64..=8, -8i64..=8, -8i64..=8],
        ) {
            prop_assume!(dir.iter().any(|&x| x != 0.0));
            let filter = CertainMiss::new(origin, radius, dir);
            let images = filter.cell(i, j, heights);
            let offset = fractions.map(|n| exact_from_f64(radius) * BigRational::new(n.into(), 8.into()));
            for k in 0..2 {
                let exact = exact_hit(origin, offset.clone(), dir, (i, j), heights, k);
                if images.triangle(k) == Certain::Miss {
                    prop_assert!(exact.is_none(), "triangle {} of ({}, {}) is hit", k, i, j);
                }
                let crossing = (images.triangle(k) == Certain::Crossing).then(|| filter.plane_t((i, j), k, heights));
                if let Some((lo, hi)) = crossing.flatten() {
                    let t = exact.unwrap_or_else(|| panic!("triangle {k} of ({i}, {j}) is missed"));
                    prop_assert!(
                        exact_from_f64(lo) <= t && t <= exact_from_f64(hi),
                        "t {} outside [{}, {}]", t, lo, hi
                    );
                }
            }
        }
    }

    /// The filter is worth its cost: it settles nearly every miss of rays that pass a cell
    /// at some distance (the usual case of a walk), and none of its hits.
    #[test]
    fn it_settles_most_misses() {
        let (mut misses, mut settled) = (0, 0);
        for n in 0..2000u32 {
            let f = |a: u32, m: u32| f64::from((n * a + 7) % m) / f64::from(m);
            let origin = [
                2.0 + 4.0 * f(37, 101),
                2.0 + 4.0 * f(53, 97),
                5.0 + f(11, 89),
            ];
            let dir = [f(13, 83) - 0.5, f(29, 79) - 0.5, -0.2 - f(17, 73)];
            let heights = [f(3, 71), f(5, 67), f(7, 61), f(19, 59)];
            let filter = CertainMiss::new(origin, 1e-9, dir);
            let images = filter.cell(3, 3, heights);
            for k in 0..2 {
                let zero = [0, 1, 2].map(|_| BigRational::from_integer(0.into()));
                if exact_hit(origin, zero, dir, (3, 3), heights, k).is_none() {
                    misses += 1;
                    settled += usize::from(images.triangle(k) == Certain::Miss);
                } else {
                    assert_ne!(
                        images.triangle(k),
                        Certain::Miss,
                        "ray {n} hits triangle {k}"
                    );
                }
            }
        }
        assert!(misses > 1000, "{misses} misses");
        assert!(
            settled * 100 >= misses * 95,
            "{settled} of {misses} misses settled"
        );
    }
}
