//! Hard shadows: one shadow ray towards the sun, left out where the sun climbs more steeply
//! than any slope of the terrain, and walked only as far as the sun's strip bounds leave it
//! unsettled. The sun's shadow of a sample is recorded here too, hard or soft ([`Shadow`]):
//! both fill the one place the shader keeps for it.

use super::effect::{At, Effect};
use crate::arith::Scalar;
use crate::render::context::Context;
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

/// Why a shadow ray was not cast although the scene has shadows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowSkip {
    /// The surface faces away from the sun: it is dark whatever a shadow ray says.
    FacingAway,
    /// The sun stands higher than the steepest slope anywhere: nothing can cast a shadow.
    NoShadowPossible,
    /// The shadow ray starts above the highest terrain and rises.
    AboveTerrain,
    /// Soft shadows: every direction towards the sun's disc climbs more steeply than the
    /// terrain can rise around the point (see [`crate::render::effects`]).
    HorizonClear,
}

/// What became of a pixel's shadow.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shadow {
    /// No primary hit, or the scene has no shadows: nothing to decide.
    #[default]
    NotAsked,
    /// Left out where it cannot change the pixel, for this reason.
    Skipped(ShadowSkip),
    /// Cast towards the sun.
    Cast {
        /// The shadow ray found the surface: the pixel is in shadow.
        shadowed: bool,
    },
    /// Soft shadows: directions towards the sun's disc, some cast, the others provably clear.
    Soft(SoftShadow),
}

/// A pixel's shadow as cast: what became of it, the shadow ray's queries, and whether a
/// decision on it was made exactly after intervals left it unsettled (see
/// [`Sample::redone`](crate::render::Sample::redone)).
pub type Cast = (Shadow, Counters, bool);

impl Shadow {
    /// The share of the sun seen: none in a shadow, the disc's share seen of a soft one, all
    /// otherwise (where no shadow ray was asked, facing away leaves the point dark anyway).
    #[inline(always)]
    pub fn sun_seen(&self) -> f64 {
        match self {
            Shadow::Cast { shadowed: true } => 0.0,
            Shadow::Soft(soft) => soft.visible(),
            _ => 1.0,
        }
    }
}

/// A soft shadow: how many of the directions towards the sun's disc are clear.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SoftShadow {
    /// Directions that reach the sun.
    pub clear: u16,
    /// Directions asked.
    pub of: u16,
    /// Directions traced (the others climbed above the terrain's bound, or the cone was
    /// settled as blocked).
    pub cast: u16,
    /// A ray looked for the cone blocked whole (the cone test of soft shadows).
    pub probed: bool,
    /// The cone is blocked whole: no direction reaches the sun.
    pub blocked: bool,
}

impl SoftShadow {
    /// The share of the sun's disc seen.
    pub fn visible(&self) -> f64 {
        f64::from(self.clear) / f64::from(self.of.max(1))
    }
}
