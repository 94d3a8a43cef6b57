//! A ray `o + t*d`, validated once so the core never sees NaN or a zero direction.

use thiserror::Error;

/// Why a ray was refused.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum RayError {
    /// A component is NaN or infinite.
    #[error("ray {what} component {axis} is {value}; every component must be finite")]
    NotFinite {
        /// `origin` or `direction`.
        what: &'static str,
        /// `x`, `y` or `z`.
        axis: char,
        /// The component as given.
        value: f64,
    },
    /// The direction is zero.
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
    /// The ray from `origin` along `dir`, if every component is finite and `dir` is not zero.
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
    /// The origin `o`.
    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }
    /// The direction `d`, as given.
    pub fn dir(&self) -> [f64; 3] {
        self.dir
    }

    /// The same line with its direction scaled by `2^-k` so that its largest component lies in
    /// `[1, 2)`, and `k`: `t` along it is `2^-k` times `t` along this ray. A power of two
    /// scales without rounding, so the line is exactly the same; only a direction far from
    /// unit length is rescaled (`k` is 0 otherwise), one whose hit parameter or products
    /// would leave an arithmetic's range (a direction of 1e-310 puts the terrain at `t` near
    /// 1e312, past `f64`'s largest; one of 1e100 is infinite in `f32`).
    ///
    /// Scaled down, no component may lose bits below the subnormals (the line would move):
    /// a direction spanning more than `f64`'s normal range is scaled only as far as its
    /// lowest bit allows.
    pub fn at_unit_scale(&self) -> (Ray, i32) {
        let largest = self.dir.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let nonzero = self.dir.iter().filter(|c| **c != 0.0);
        let k = nonzero.fold(exponent(largest), |k, &c| k.min(lowest_bit(c) + 1074));
        if k.abs() <= UNSCALED_EXPONENT {
            return (*self, 0);
        }
        let dir = self.dir.map(|c| times_power_of_two(c, -k));
        (Ray::new_checked_by_caller(self.origin, dir), k)
    }
}

/// Directions whose largest component lies within `2^±32` are traced as given.
const UNSCALED_EXPONENT: i32 = 32;

/// `floor(log2 |x|)` for a finite nonzero `x`, from its bits (once per ray: `log2` is a
/// library call).
fn exponent(x: f64) -> i32 {
    let biased = ((x.to_bits() >> 52) & 0x7ff) as i32;
    if biased == 0 {
        // Subnormal: scaled into the normal range, exactly.
        exponent(x * 2f64.powi(64)) - 64
    } else {
        biased - 1023
    }
}

/// The exponent of the lowest set bit of a finite nonzero `x`: `x` is an odd integer times 2
/// to its power.
fn lowest_bit(x: f64) -> i32 {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let fraction = bits & ((1u64 << 52) - 1);
    let (mantissa, e) = if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1u64 << 52), biased - 1075)
    };
    e + mantissa.trailing_zeros() as i32
}

/// `x * 2^k`, in two steps so that neither factor overflows (`k` may reach about ±1100 for a
/// subnormal direction); exact unless the result leaves the `f64` range.
pub fn times_power_of_two(x: f64, k: i32) -> f64 {
    let half = k / 2;
    x * 2f64.powi(half) * 2f64.powi(k - half)
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

    #[test]
    fn directions_far_from_unit_length_are_rescaled_exactly() {
        let scaled = |dir| Ray::new([1.0; 3], dir).unwrap().at_unit_scale();
        let (ray, k) = scaled([3.0, -1.0, 0.5]);
        assert_eq!((ray.dir(), k), ([3.0, -1.0, 0.5], 0));
        for (x, k) in [
            (1.0, 0),
            (1.5, 0),
            (0.75, -1),
            (5e-324, -1074),
            (3e-320, -1062),
        ] {
            assert_eq!(exponent(x), k, "{x:e}");
            assert_eq!(exponent(-x), k, "{x:e}");
        }
        assert_eq!(exponent(f64::MAX), 1023);
        let (ray, k) = scaled([1e-320, 0.0, -3e-320]);
        assert!((1.0..2.0).contains(&ray.dir()[2].abs()), "{:?}", ray.dir());
        // Back at the old scale, every component is what it was.
        assert_eq!(
            ray.dir().map(|c| times_power_of_two(c, k)),
            [1e-320, 0.0, -3e-320]
        );
        // A direction spanning more than the normal range is scaled only as far as its lowest
        // bit allows: 1.25 and 0.75 + 2^-52 stay exact.
        let wide = [1.25, -0.7500000000000002, -1e308];
        let (ray, k) = scaled(wide);
        assert_eq!(k, 1022);
        assert_eq!(ray.dir().map(|c| times_power_of_two(c, k)), wide);
        assert_eq!(
            (lowest_bit(1.25), lowest_bit(-0.75), lowest_bit(5e-324)),
            (-2, -2, -1074)
        );
        let (ray, k) = scaled([1e300, -7e299, 1.0]);
        assert_eq!(ray.dir()[0].abs().log2().floor(), 0.0);
        assert_eq!(
            ray.dir().map(|c| times_power_of_two(c, k)),
            [1e300, -7e299, 1.0]
        );
        assert_eq!(ray.origin(), [1.0; 3]);
    }
}
