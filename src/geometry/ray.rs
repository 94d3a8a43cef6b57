//! A ray `o + t*d`, validated once so the core never sees NaN or a zero direction.

use thiserror::Error;

/// Why a ray was refused.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum RayError {
    #[error("ray {what} component {axis} is {value}; every component must be finite")]
    NotFinite {
        what: &'static str,
        axis: char,
        value: f64,
    },
    #[error("ray direction is (0, 0, 0); it must have a non-zero component")]
    ZeroDirection,
}

/// A ray with finite origin and a finite, non-zero direction (not normalised: the core keeps
/// `d` exactly as given so exact mode answers for these very numbers).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    origin: [f64; 3],
    dir: [f64; 3],
}

impl Ray {
    pub fn new(origin: [f64; 3], dir: [f64; 3]) -> Result<Ray, RayError> {
        for (what, v) in [("origin", origin), ("direction", dir)] {
            for (axis, value) in ['x', 'y', 'z'].into_iter().zip(v) {
                if !value.is_finite() {
                    return Err(RayError::NotFinite { what, axis, value });
                }
            }
        }
        if dir.iter().all(|&c| c == 0.0) {
            return Err(RayError::ZeroDirection);
        }
        Ok(Ray { origin, dir })
    }
    /// A ray whose components the caller has already shown finite, with a non-zero direction.
    pub(crate) fn new_checked_by_caller(origin: [f64; 3], dir: [f64; 3]) -> Ray {
        debug_assert!(Ray::new(origin, dir).is_ok());
        Ray { origin, dir }
    }
    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }
    pub fn dir(&self) -> [f64; 3] {
        self.dir
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_nan_infinity_and_zero_direction() {
        assert!(matches!(
            Ray::new([f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0]),
            Err(RayError::NotFinite { axis: 'x', .. })
        ));
        assert!(matches!(
            Ray::new([0.0; 3], [0.0, f64::INFINITY, 0.0]),
            Err(RayError::NotFinite { axis: 'y', .. })
        ));
        assert_eq!(
            Ray::new([0.0; 3], [0.0, -0.0, 0.0]),
            Err(RayError::ZeroDirection)
        );
    }
}
