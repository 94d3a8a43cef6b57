//! The sky-view factor as the Relief Visualization Toolbox defines it (Zakšek, Oštir & Kokalj
//! 2011): `SVF = 1 - (1/n) * sum over n compass directions of sin(max(gamma_k, 0))`, where
//! `gamma_k` is the elevation angle of the highest terrain within a radius `R` along
//! direction `k` (directions from north, clockwise, `360/n` degrees apart). An open plane
//! sees the whole sky (1); a pit or a narrow valley less. The horizon is the triangulated
//! surface's own, found exactly along each direction ([`Horizon::rise`]).

use super::horizon::Horizon;
use thiserror::Error;

/// RVT's default number of directions.
pub const DEFAULT_DIRECTIONS: u32 = 16;

/// RVT's default radius, in cells.
pub const DEFAULT_RADIUS_CELLS: f64 = 10.0;

/// Why a sky-view measure cannot be used.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SkyViewError {
    /// Directions outside 1 to 360.
    #[error("the sky-view factor takes 1 to 360 directions, got {0}")]
    Directions(u32),
    /// A radius that is not a positive number.
    #[error("the sky-view radius must be a positive number of cells, got {0}")]
    Radius(f64),
}

/// How the sky-view factor is measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyView {
    /// Compass directions searched for the horizon.
    pub directions: u32,
    /// How far the horizon is searched, in world units (cells along y; cells on a plain
    /// image).
    pub radius: f64,
}

impl Default for SkyView {
    fn default() -> Self {
        SkyView {
            directions: DEFAULT_DIRECTIONS,
            radius: DEFAULT_RADIUS_CELLS,
        }
    }
}

impl SkyView {
    /// The measure with `directions` and `radius`, or why they cannot be used.
    pub fn new(directions: u32, radius: f64) -> Result<SkyView, SkyViewError> {
        if !(1..=360).contains(&directions) {
            return Err(SkyViewError::Directions(directions));
        }
        if !(radius.is_finite() && radius > 0.0) {
            return Err(SkyViewError::Radius(radius));
        }
        Ok(SkyView { directions, radius })
    }

    /// The sky-view factor at grid point `at` of the surface; `None` off the surface.
    pub fn at(&self, horizon: &Horizon<'_>, at: [f64; 2]) -> Option<f64> {
        let z0 = horizon.surface_z(at)?;
        let n = self.directions;
        let blocked: f64 = (0..n)
            .map(|k| {
                let bearing = std::f64::consts::TAU * f64::from(k) / f64::from(n);
                let toward = [bearing.sin(), bearing.cos()];
                let rise = horizon.rise(at, z0, toward, self.radius).unwrap_or(0.0);
                // sin(atan(r)), for the horizon's angle clamped to the horizontal.
                let r = rise.max(0.0);
                r / (1.0 + r * r).sqrt()
            })
            .sum();
        Some(1.0 - blocked / f64::from(n))
    }
}
