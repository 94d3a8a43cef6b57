//! A sample and what became of each of its rays: the primary ray's hit, the shadow, the sky
//! light, the reflection. The effects make these; the tallies and statistics count them.

use super::effects::EffectTime;
use crate::geometry::Face;
use crate::traverse::Counters;
use glam::DVec3;

/// One traced sample, recorded on its own (see [`Tally`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    /// 0x00RRGGBB.
    pub rgb: u32,
    /// What the primary ray hit: the terrain or the base, if anything.
    pub hit: Option<Face>,
    /// What became of the shadow ray.
    pub shadow: Shadow,
    /// The primary ray's queries.
    pub primary: Counters,
    /// The shadow rays' queries (towards the sun, or its disc), or the reflected ray's.
    pub secondary: Counters,
    /// The sky-light rays.
    pub sky: SkyRays,
    /// What became of the reflection of water the pixel shows.
    pub reflection: Reflection,
    /// Intervals left a decision unsettled, and exact mode made it again exactly: it traced
    /// the pixel again in rationals, or cast only its shadow ray again, or decided one of the
    /// shadow ray's triangle tests on its own.
    pub redone: bool,
    /// The time its effects took.
    pub time: EffectTime,
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
/// [`Sample::redone`]).
pub type Cast = (Shadow, Counters, bool);

/// A point's sky-light rays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SkyRays {
    /// Directions asked.
    pub of: u16,
    /// Directions that reach the sky.
    pub open: u16,
    /// Directions traced (the others climbed above the terrain's bound).
    pub cast: u16,
    /// The traced rays' queries.
    pub counters: Counters,
    /// A triangle test intervals could not settle was decided exactly.
    pub redone: bool,
}

impl SkyRays {
    /// The cosine-weighted share of the hemisphere open to the sky (the sky-view factor).
    pub fn open_share(&self) -> f64 {
        f64::from(self.open) / f64::from(self.of.max(1))
    }

    /// Directions left out because they provably reach the sky.
    pub fn culled(&self) -> u16 {
        self.of - self.cast
    }
}

/// A soft shadow: how many of the directions towards the sun's disc are clear.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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

/// What became of a pixel's reflection.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Reflection {
    /// The pixel shows no water.
    #[default]
    NotWater,
    /// The reflected ray climbs above the terrain's bound: it sees the sky, without a walk.
    Clear,
    /// The reflected ray was traced.
    Cast {
        /// It met the terrain (else the sky).
        hit: bool,
    },
}

/// A water pixel as shaded: its colour, its reflection, the reflected ray's queries, and
/// whether one of its decisions was made exactly after intervals left it unsettled.
pub struct WaterPixel {
    /// Its linear colour, through the fog.
    pub rgb: DVec3,
    /// What became of the reflected ray.
    pub reflection: Reflection,
    /// Its queries.
    pub counters: Counters,
    /// Exact mode decided one of its tests again exactly.
    pub redone: bool,
}
