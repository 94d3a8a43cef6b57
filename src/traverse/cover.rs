//! The cells a walk covers: every cell of the whole clipped ray, in the walk's order, with no
//! culling and no stop at a hit (what the exact-reference tests and the accuracy bench compare).

use super::far::{far_start, FarStart};
use super::frame::{clip, Frame};
use super::walks::{choose, Covering, Walk, WithWalk};
use super::Method;
use crate::arith::{Arith, Generic, Scalar};
use crate::geometry::Ray;
use crate::heightfield::Terrain;

/// Every cell the walk of `method` covers for the whole clipped ray, in order, with no culling
/// and no stop at a hit: in exact arithmetic, exactly the cells the projected segment touches.
pub fn covered_cells(
    terrain: &Terrain,
    ray: &Ray,
    method: Method,
    arith: Arith,
) -> Vec<[usize; 2]> {
    let cover = Cover {
        terrain,
        ray,
        method,
    };
    crate::arith::run(arith, &cover).0.output
}

/// The cells a walk covers, in whichever arithmetic [`run`](crate::arith::run) picks.
struct Cover<'a> {
    terrain: &'a Terrain,
    ray: &'a Ray,
    method: Method,
}

impl Generic for Cover<'_> {
    type Output = Vec<[usize; 2]>;
    fn run<S: Scalar>(&self) -> Self::Output {
        let ray = self.ray;
        let (mut o, d) = (ray.origin().map(S::from_f64), ray.dir().map(S::from_f64));
        match far_start(self.terrain, &o, &d) {
            FarStart::Given => {}
            FarStart::Misses => return Vec::new(),
            FarStart::Moved { origin, .. } => o = origin,
        }
        let Some(frame) = clip(self.terrain, &o, &d, ray.dir()) else {
            return Vec::new();
        };
        choose(self.method, CoverWith(&frame)).cells
    }
}

/// Lists the cells of a path in whichever walk [`choose`] picks.
struct CoverWith<'f, S>(&'f Frame<S>);

impl<S: Scalar> WithWalk for CoverWith<'_, S> {
    type Output = Covering;
    fn with<W: Walk>(self) -> Covering {
        let mut covering = Covering::default();
        // The walk ends by itself: nothing breaks it.
        let _ = W::cover(self.0, &mut covering);
        covering
    }
}
