//! How Embree answers the hard-case sets of `bench accuracy`, beside heightray in the same
//! arithmetic: both take the ray in `f32`, and both are held to heightray's exact answers for
//! the ray as given.

use super::{EmbreeScene, Geometry};
use crate::bench::textbook::{hard_cases_against_exact, mipmap_in, HardCaseRow};
use crate::Arith;

/// A relative error in `t` that rounding the ray and the samples to `f32` can make on these
/// rays (which are at most a few hundred cells long): answers further off found another
/// part of the surface, or none.
pub const F32_TOLERANCE: f64 = 1e-4;

/// The hard-case sets answered by heightray's mipmap walk in `f32` and by Embree, against
/// exact (answers differ by more than [`F32_TOLERANCE`] in `t`).
pub fn hard_cases_in_f32(per_set: usize) -> anyhow::Result<Vec<HardCaseRow>> {
    hard_cases_against_exact(per_set, F32_TOLERANCE, |set| {
        let embree = EmbreeScene::build(&set.terrain, Geometry::Triangles)?;
        Ok([
            mipmap_in(set, Arith::F32),
            Box::new(move |ray| embree.intersect(ray).map(|hit| hit.t)),
        ])
    })
}
