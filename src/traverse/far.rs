//! Rays from far off, in the arithmetics without rounding: a ray whose origin lies far outside
//! the terrain's box is clipped to the box exactly, in rationals, before any walk, and walked
//! from a start on the ray just outside the box. Walked from its own origin, its enclosures
//! and the `f64` walk near it would carry the rounding of the origin's magnitude (from an
//! origin at 1e17 every `t` is off by up to 16, a dozen cells), beyond what their bounds
//! cover; from a start next to the box their roundings are those of the box's size. The
//! start lies exactly on the ray, before the box, so the walk answers for the same ray: its
//! `t` is the far ray's less the start's.

use crate::arith::scalar::exact_from_f64;
use crate::arith::{unsettled, Exact, Scalar};
use crate::geometry::clip_to_box;
use crate::heightfield::Terrain;
use num_rational::BigRational;
use num_traits::{One, Signed};

/// An origin is far when it lies this many times the box's longest side (plus one) outside
/// the terrain's box on some axis.
const FAR_SIDES: f64 = 64.0;

/// Where the walk of a ray `o + t*d` starts (see [`far_start`]).
pub(super) enum FarStart<S> {
    /// At its origin: it is not far, or the arithmetic rounds.
    Given,
    /// Nowhere: it misses the box, or intervals cannot tell where it meets it (they are
    /// marked unsettled).
    Misses,
    /// At `origin`, the point of the ray at `t` (exactly), just outside the box.
    Moved { origin: [S; 3], t: BigRational },
}

/// Where the walk of `o + t*d` starts: for a far origin in an arithmetic without rounding,
/// one unit (of the largest direction component) before the ray's exact entry into the box.
#[inline(always)]
pub(super) fn far_start<S: Scalar>(terrain: &Terrain, o: &[S; 3], d: &[S; 3]) -> FarStart<S> {
    if !S::EXACT || !is_far(terrain, o) {
        return FarStart::Given;
    }
    moved_start(terrain, o, d)
}

/// Whether origin `o` lies far outside the terrain's box: the one check an ordinary ray of
/// an arithmetic without rounding makes (an origin beyond `f64`'s range is far).
#[inline(always)]
fn is_far<S: Scalar>(terrain: &Terrain, o: &[S; 3]) -> bool {
    let (lo, hi) = terrain.bounds();
    let side = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(hi[2] - lo[2]) + 1.0;
    let room = FAR_SIDES * side;
    (0..3).any(|k| {
        let x = o[k].to_f64();
        // (Written so that NaN is far.)
        !(x >= lo[k] - room && x <= hi[k] + room)
    })
}

/// [`far_start`] for a far origin, worked out in rationals.
// (Out of line: far rays are rare.)
#[inline(never)]
fn moved_start<S: Scalar>(terrain: &Terrain, o: &[S; 3], d: &[S; 3]) -> FarStart<S> {
    let exact = |x: &S| {
        x.to_exact().map(Exact).or_else(|| {
            let (x, radius) = x.f64_enclosure()?;
            (radius == 0.0).then(|| Exact(exact_from_f64(x)))
        })
    };
    let (Some(o), Some(d)) = (exact_all(o, exact), exact_all(d, exact)) else {
        // An origin known only within an enclosure: rationals know it exactly.
        unsettled();
        return FarStart::Misses;
    };
    let (lo, hi) = terrain.bounds();
    let Some(clipped) = clip_to_box(&o, &d, &lo.map(Exact::from_f64), &hi.map(Exact::from_f64))
    else {
        return FarStart::Misses;
    };
    let largest = d
        .iter()
        .map(|c| c.0.abs())
        .max()
        .unwrap_or_else(BigRational::one);
    let t = clipped.t0.0 - largest.recip();
    if !t.is_positive() {
        // (Not far after all: the check's `f64`s rounded.)
        return FarStart::Given;
    }
    let point = [0, 1, 2].map(|k| S::from_exact(&(&o[k].0 + &d[k].0 * &t)));
    match point {
        [Some(x), Some(y), Some(z)] => FarStart::Moved {
            origin: [x, y, z],
            t,
        },
        _ => {
            // The start lies beyond the range of the intervals' ends.
            unsettled();
            FarStart::Misses
        }
    }
}

/// Every component of `v` converted by `exact`, if each converts.
fn exact_all<S>(v: &[S; 3], exact: impl Fn(&S) -> Option<Exact>) -> Option<[Exact; 3]> {
    let [x, y, z] = [&v[0], &v[1], &v[2]].map(exact);
    Some([x?, y?, z?])
}
