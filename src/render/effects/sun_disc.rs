//! The sun's disc as a frame's soft shadows see it: its axis and half-angle in the grid, the
//! lowest elevation of its directions, their azimuths, the cone the proofs of
//! [`sun_cone`](super::sun_cone) take and the basis its directions are drawn in. None of it
//! depends on the point shaded, and working it out takes a dozen calls of the trigonometric
//! functions (more than a shadow ray's own set-up), so a frame makes it once.

use super::horizon::Sector;
use super::sampling::ConeDirections;
use super::sun_cone::Cone;
use glam::{DVec2, DVec3};

/// The sun's disc, in the grid.
#[derive(Clone, Copy, Debug)]
pub struct SunDisc {
    /// The sun's direction (in the world) and the disc's angular diameter (degrees) it was
    /// made for.
    made_for: ([f64; 3], f64),
    /// The sun's direction in the grid, unit.
    pub axis: DVec3,
    /// The lowest elevation of its directions (radians, with room for rounding: no direction
    /// drawn is lower), and its tangent.
    pub lowest: f64,
    pub lowest_tan: f64,
    /// The cone of its directions from the origin ([`Cone::moved_to`] a start); `None` where
    /// the proofs cannot take it.
    pub cone: Option<Cone>,
    /// The azimuths of its directions, with room for rounding; `None` where they span a half
    /// turn or more (the cone holds the zenith, or nearly).
    pub sector: Option<Sector>,
    /// How its directions are drawn.
    pub directions: ConeDirections,
}

impl SunDisc {
    /// The disc of angular diameter `angle_deg` around the sun `sun` (in the world), `axis`
    /// in the grid.
    pub fn new(sun: [f64; 3], angle_deg: f64, axis: DVec3) -> SunDisc {
        let half = (angle_deg / 2.0).to_radians();
        let lowest = axis.z.clamp(-1.0, 1.0).asin() - half * (1.0 + 1e-9);
        SunDisc {
            made_for: (sun, angle_deg),
            axis,
            lowest,
            lowest_tan: lowest.tan(),
            cone: Cone::new(DVec3::ZERO, axis, half),
            sector: sun_sector(axis, half),
            directions: ConeDirections::around(axis, half),
        }
    }

    /// Whether this is the disc of angular diameter `angle_deg` around `sun`.
    pub fn is_for(&self, sun: [f64; 3], angle_deg: f64) -> bool {
        self.made_for == (sun, angle_deg)
    }
}

/// The azimuths of the directions within `half` (radians) of `axis`, with room for rounding;
/// `None` where they span a half turn or more (the cone holds the zenith, or nearly).
fn sun_sector(axis: DVec3, half: f64) -> Option<Sector> {
    let horizontal = DVec2::new(axis.x, axis.y);
    let across = half.sin() / horizontal.length();
    (across < 0.9).then(|| Sector::around(horizontal, across.asin() * (1.0 + 1e-6) + 1e-9))
}
