//! The whole surface a ray meets: the terrain, walked by the method, and the base under it
//! (see [`Base`]), tested once beside the walk in the same arithmetic.
//!
//! Why testing the base beside the walk is exact: the walk answers the terrain alone, and
//! every cut it makes (clearances, bounds, certain misses) is proven for the terrain alone;
//! the base's first touch is computed on its own, and the answer is the earlier of the two,
//! the terrain's on a tie. A shadow ray is occluded if either is touched after its start
//! (within its reach: whatever proves the terrain clear beyond it proves the base clear too,
//! as a wall never rises above the terrain's edge and the floor lies below every sample).

use super::answer::ScalarTrace;
use super::engine::trace_terrain;
use super::options::{Query, WalkOptions};
use super::search::Found;
use crate::arith::{Exact, Scalar};
use crate::geometry::Ray;
use crate::geometry::{base_hit, Base, BaseQuery, Face};
use crate::heightfield::Terrain;
use num_rational::BigRational;

/// The answer for the ray `o + t*d` given in the traversal's arithmetic, over the terrain and
/// the base the options carry (see [`trace_terrain`] for the terrain's part).
// (Always inlined: out of line, its answer, a few hundred bytes, is copied once more on its
// way back to the ray's caller.)
#[inline(always)]
pub(super) fn trace_scalar<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    walk_options: WalkOptions,
) -> ScalarTrace<S> {
    let mut answer = trace_terrain(terrain, o, d, dir_f64, walk_options);
    let Some(base) = walk_options.base else {
        return answer;
    };
    let shadow = walk_options.query == Query::Shadow;
    if shadow && answer.hit.is_some() {
        return answer;
    }
    let query = BaseQuery {
        after_start: shadow,
        before: answer.hit.as_ref().map(|found| found.t.clone()),
    };
    let Some(hit) = base_hit(terrain, &base, o, d, &query) else {
        return answer;
    };
    if let Some(reach) = walk_options.reach.filter(|_| shadow) {
        if hit.t > S::from_f64(reach) {
            return answer;
        }
    }
    let point = [0, 1].map(|k| (o[k].clone() + d[k].clone() * hit.t.clone()).to_f64());
    answer.hit = Some(Found {
        cell: cell_under(terrain, point),
        t: hit.t,
        triangle: 0,
        face: hit.face,
    });
    answer
}

/// The cell a point of the footprint lies over (on its edge, the cell inside).
fn cell_under(terrain: &Terrain, [x, y]: [f64; 2]) -> (usize, usize) {
    let field = terrain.field();
    let index = |v: f64, samples: usize| (v.floor().max(0.0) as usize).min(samples - 2);
    (index(x, field.width()), index(y, field.height()))
}

/// The exact `t` at which `ray` first touches `face` of `base` (from its start on, or after
/// it for a shadow ray), its nearest `f64` and the point there to the nearest `f64`s: `None`
/// where the first touch of the base is another face's.
pub(super) fn base_t_exact(
    terrain: &Terrain,
    base: &Base,
    ray: &Ray,
    face: Face,
    after_start: bool,
) -> Option<(BigRational, f64, [f64; 3])> {
    let (o, d) = (
        ray.origin().map(Exact::from_f64),
        ray.dir().map(Exact::from_f64),
    );
    let query = BaseQuery {
        after_start,
        before: None,
    };
    let hit = base_hit(terrain, base, &o, &d, &query)?;
    if hit.face != face {
        return None;
    }
    let point = [0, 1, 2].map(|k| (o[k].clone() + d[k].clone() * hit.t.clone()).to_f64());
    let t = hit.t.to_f64();
    Some((hit.t.0, t, point))
}
