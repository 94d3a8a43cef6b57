//! How Embree answers the hard-case sets of `bench accuracy`, beside heightray in the same
//! arithmetic: both take the ray in `f32`, and both are held to heightray's exact answers for
//! the ray as given.

use super::EmbreeScene;
use crate::bench::hard_cases;
use crate::bench::textbook::differ_by;
use crate::{trace, Arith, Method, TraceOptions};

/// A relative error in `t` that rounding the ray and the samples to `f32` can make on these
/// rays (which are at most a few hundred cells long): answers further off found another
/// part of the surface, or none.
pub const F32_TOLERANCE: f64 = 1e-4;

/// One hard-case set: how many answers of each tracer in `f32` differ from the exact ones (a
/// hit against a miss, or `t` off by more than [`F32_TOLERANCE`]).
#[derive(Clone, Debug)]
pub struct F32Row {
    pub set: String,
    pub rays: u64,
    pub heightray: u64,
    pub embree: u64,
}

/// The hard-case sets ([`hard_cases`], `per_set` rays each) traced by heightray's mipmap walk
/// in `f32` and by Embree, against the mipmap walk in exact arithmetic.
pub fn hard_cases_in_f32(per_set: usize) -> anyhow::Result<Vec<F32Row>> {
    let (f32_options, exact) = (
        TraceOptions::new(Method::Mipmap, Arith::F32),
        TraceOptions::new(Method::Mipmap, Arith::Exact),
    );
    let mut rows = Vec::new();
    for set in hard_cases(per_set)? {
        let embree = EmbreeScene::build(&set.terrain)?;
        let t = |ray, options| trace(&set.terrain, ray, options).hit.map(|hit| hit.t);
        let differ = |a, b| u64::from(differ_by(a, b, F32_TOLERANCE));
        let (mut heightray, mut theirs) = (0, 0);
        for ray in &set.rays {
            let reference = t(ray, &exact);
            heightray += differ(t(ray, &f32_options), reference);
            theirs += differ(embree.intersect(ray).map(|hit| hit.t), reference);
        }
        rows.push(F32Row {
            set: set.name,
            rays: set.rays.len() as u64,
            heightray,
            embree: theirs,
        });
    }
    Ok(rows)
}
