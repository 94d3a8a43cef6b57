//! The `f64` ray near a ray in an arithmetic without rounding, which exact mode's `f64`
//! walks follow in its place.

use crate::arith::Scalar;

/// Origin, radius per axis and direction of an `f64` ray near an exact one (see [`f64_ray`]).
pub(super) type F64Ray = ([f64; 3], [f64; 3], [f64; 3]);

/// An `f64` ray near one in an arithmetic without rounding: its origin, how far the exact
/// origin may be from it per axis, and its direction, which must be the exact one. `None`
/// for the rounding arithmetics, and where the direction is not an `f64` exactly.
pub(super) fn f64_ray<S: Scalar>(o: &[S; 3], d: &[S; 3]) -> Option<F64Ray> {
    if !S::EXACT {
        return None;
    }
    let exact = |c: &S| c.f64_enclosure().filter(|&(_, r)| r == 0.0).map(|(x, _)| x);
    let dir = [exact(&d[0])?, exact(&d[1])?, exact(&d[2])?];
    // (Component by component: an array's `map` goes out of line here.)
    let (x, rx) = o[0].f64_enclosure()?;
    let (y, ry) = o[1].f64_enclosure()?;
    let (z, rz) = o[2].f64_enclosure()?;
    Some(([x, y, z], [rx, ry, rz], dir))
}
