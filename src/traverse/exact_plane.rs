//! A hit's triangle plane met exactly: the `t` of a ray there as a fraction of dyadic
//! numbers, and the point, so that exact mode's answers need no rational walk.

use crate::arith::dyadic::Dyadic;
use crate::geometry::{plane_crossing, Ray};
use crate::heightfield::Terrain;
use num_rational::BigRational;

/// The `t` where the ray meets the plane of triangle `k` of `cell`, exactly; `None` if it
/// runs parallel.
pub fn plane_t_exact(
    terrain: &Terrain,
    ray: &Ray,
    cell: (usize, usize),
    k: u8,
) -> Option<BigRational> {
    let (above, closing) = exact_t(terrain, ray, [cell.0, cell.1], k)?;
    Some(above.over(&closing))
}

/// Whether a ray of direction `dir` crosses the plane of triangle `k` of `cell` (does not
/// run parallel to it), decided exactly.
pub fn crosses_plane(terrain: &Terrain, cell: (usize, usize), k: u8, dir: [f64; 3]) -> bool {
    let zero = || Dyadic::from_i64(0);
    let (_, closing) = plane_crossing(
        k,
        terrain.corner_heights(cell.0, cell.1).map(Dyadic::from_f64),
        (zero(), zero()),
        [zero(), zero(), zero()],
        dir.map(Dyadic::from_f64),
    );
    !closing.is_zero()
}

/// Where the ray meets the plane of triangle `k` of `cell`, exactly, as `t = above / closing`;
/// `None` if it runs parallel.
pub(super) fn exact_t(
    terrain: &Terrain,
    ray: &Ray,
    [i, j]: [usize; 2],
    k: u8,
) -> Option<(Dyadic, Dyadic)> {
    let (above, closing) = plane_crossing(
        k,
        terrain.corner_heights(i, j).map(Dyadic::from_f64),
        (Dyadic::from_i64(i as i64), Dyadic::from_i64(j as i64)),
        ray.origin().map(Dyadic::from_f64),
        ray.dir().map(Dyadic::from_f64),
    );
    (!closing.is_zero()).then_some((above, closing))
}

/// The point `o + d * above/closing` of `ray`: each coordinate's numerator over `closing`,
/// exactly.
pub(super) fn point_over(ray: &Ray, above: &Dyadic, closing: &Dyadic) -> [Dyadic; 3] {
    let (o, d) = (ray.origin(), ray.dir());
    [0, 1, 2]
        .map(|k| Dyadic::from_f64(o[k]) * closing.clone() + Dyadic::from_f64(d[k]) * above.clone())
}
