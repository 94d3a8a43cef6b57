//! Numbers echoed in messages: in full where that is short, in scientific notation where the
//! magnitude is huge or tiny, so that `fov_y_deg = 1e300` is reported as `1e300`, not as 301
//! digits. Both forms are the shortest that read back as the same number.

use std::fmt;

/// A number written compactly: `Compact(1e300)` shows as `1e300`, `Compact(45.5)` as `45.5`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compact<T>(pub T);

/// Magnitudes written in full: from a ten-thousandth up to a quadrillion.
const PLAIN: std::ops::Range<f64> = 1e-4..1e15;

impl<T: Copy + Into<f64> + fmt::Display + fmt::LowerExp> fmt::Display for Compact<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let value: f64 = self.0.into();
        if value == 0.0 || !value.is_finite() || PLAIN.contains(&value.abs()) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Compact;

    #[test]
    fn huge_and_tiny_magnitudes_are_written_in_scientific_notation() {
        let shown = |v: f64| Compact(v).to_string();
        assert_eq!(shown(1e300), "1e300");
        assert_eq!(shown(-1.5e300), "-1.5e300");
        assert_eq!(shown(2.5e-300), "2.5e-300");
        assert_eq!(shown(f64::MAX), "1.7976931348623157e308");
        assert_eq!(shown(45.0), "45");
        assert_eq!(shown(-0.53), "-0.53");
        assert_eq!(shown(123456789.25), "123456789.25");
        assert_eq!(shown(0.0), "0");
        assert_eq!(shown(f64::NAN), "NaN");
        assert_eq!(shown(f64::NEG_INFINITY), "-inf");
        // An f32 in its own shortest digits, not its f64 widening's.
        assert_eq!(Compact(1e30f32).to_string(), "1e30");
        // Whatever the form, it reads back as the same number.
        for v in [1e300, 3.0e-5, 1e15, 999999999999999.9, 1e-4, 7.25e-310] {
            assert_eq!(shown(v).parse::<f64>(), Ok(v), "{v:e}");
        }
    }
}
