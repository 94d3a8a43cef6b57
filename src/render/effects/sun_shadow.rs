//! Hard shadows: one shadow ray towards the sun, left out where the sun climbs more steeply
//! than any slope of the terrain, and walked only as far as the sun's strip bounds leave it
//! unsettled.

use super::effect::{At, Effect};
use crate::arith::Scalar;
use crate::render::context::Context;
use crate::render::sample::{Cast, Shadow, ShadowSkip};
use crate::traverse::Counters;

/// The sun's shadow as a point: one ray towards it.
pub struct SunShadow;

impl Effect for SunShadow {
    type Outcome = Cast;

    fn cast<S: Scalar>(&self, cx: &Context<'_>, at: &At<'_, S>) -> Cast {
        let skip = |why| (Shadow::Skipped(why), Counters::default(), false);
        let sun = cx.grid_sun();
        // The sun climbs strictly steeper than any triangle (with room for the rounding of
        // max_slope), compared squared: no square root per shadow ray.
        let steepest = cx.terrain.max_slope() * (1.0 + 1e-9);
        let climbs_steeper = sun[2] > 0.0
            && sun[2] * sun[2] > steepest * steepest * (sun[0] * sun[0] + sun[1] * sun[1]);
        if cx.culling.no_shadow_possible && climbs_steeper {
            return skip(ShadowSkip::NoShadowPossible);
        }
        let occlusion = cx.occluded_beyond(at.start(cx), (sun, sun));
        match occlusion.occluded {
            Some(shadowed) => (
                Shadow::Cast { shadowed },
                occlusion.counters,
                occlusion.exactly,
            ),
            None => (
                Shadow::Skipped(ShadowSkip::AboveTerrain),
                Counters::default(),
                occlusion.exactly,
            ),
        }
    }
}
