//! The small number trait every traversal is generic over, and its float implementations.
//!
//! One traversal, four arithmetics: `f32`, `f64`, bounded rationals and exact rationals all
//! implement [`Scalar`]. The trait is deliberately small: field operations, comparisons,
//! floor/ceil to cell indices, and one exact-sign primitive ([`Scalar::det2`]) on which the
//! watertight triangle test rests.

use super::dyadic::Dyadic;
use num_rational::BigRational;
use num_traits::Signed;
use std::cmp::Ordering;
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A number the traversal can compute with.
pub trait Scalar:
    Clone
    + Debug
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Whether this arithmetic decides exactly (intervals that flag what they cannot settle,
    /// rationals): the `f64` shortcuts that only such arithmetics use are compiled out of the
    /// others.
    const EXACT: bool = false;

    /// Whether this arithmetic encloses exact values (intervals) and may leave a decision
    /// unsettled ([`settled`](super::settled)), for exact arithmetic to make again.
    const ENCLOSES: bool = false;

    /// Converts an input (a ray component or a height), rounding as this arithmetic must.
    fn from_f64(x: f64) -> Self;
    /// Converts a grid coordinate (exact in every arithmetic for the sizes we accept).
    fn from_i64(n: i64) -> Self;
    /// The nearest `f64` (for reporting).
    fn to_f64(&self) -> f64;
    /// Greatest integer not above `self`, saturating at the `i64` range.
    fn floor_i64(&self) -> i64;
    /// Least integer not below `self`, saturating at the `i64` range.
    fn ceil_i64(&self) -> i64;
    /// Whether the value is zero.
    fn is_zero(&self) -> bool;
    /// Whether the value is below zero.
    fn is_negative(&self) -> bool;

    /// `a*b - c*d`, with a sign that is exact even where the value is rounded.
    ///
    /// The returned value is zero when the exact sign is zero and never has the wrong sign, so
    /// callers may test signs on the value. This is what makes the triangle test watertight.
    fn det2(a: &Self, b: &Self, c: &Self, d: &Self) -> Self;

    /// Whether two computed values are equal as far as this arithmetic can tell: exactly for
    /// exact arithmetic, within accumulated rounding for floats. Walks use it to decide that a
    /// path crosses a lattice point and visit both cells touching it only there; visiting one
    /// too many is harmless, one too few leaves a hole.
    fn nearly_equal(&self, other: &Self) -> bool {
        self == other
    }

    /// A value raised by what floating-point rounding may have taken off it (itself in the
    /// other arithmetics, whose rounding a walk tolerates in its own way).
    fn past_rounding(self) -> Self {
        self
    }

    /// Rounds an intercept onto the denominator of `slope`, so that a recurrence adding
    /// multiples of the slope stays exact. Only bounded rationals round; others return `self`.
    fn align_to(self, _slope: &Self) -> Self {
        self
    }

    /// The size of one rounding of a value of about `magnitude` in this arithmetic (zero when
    /// exact): what separates a computed point from the surface it was computed on.
    fn rounding_error(magnitude: f64) -> f64;

    /// For the arithmetics without rounding (intervals, exact): an `f64` and a radius within
    /// which the exact value lies (zero when it is that `f64` exactly), so that an `f64` walk
    /// may clear the way for them (see `mipmap::clear_way`). `None` for the rounding
    /// arithmetics, which need no such help.
    fn f64_enclosure(&self) -> Option<(f64, f64)> {
        None
    }

    /// A value known only to lie in `[lo, hi]`, in the arithmetics that can hold one
    /// (intervals); `None` in the others.
    fn from_enclosure(_lo: f64, _hi: f64) -> Option<Self> {
        None
    }

    /// The values themselves where this arithmetic is `f64` (for kernels written for `f64`
    /// lanes); `None` in the others.
    fn as_f64s<const N: usize>(_values: &[Self; N]) -> Option<&[f64; N]> {
        None
    }

    /// The exact value as a fraction, for arithmetics that have one.
    fn to_exact(&self) -> Option<BigRational> {
        None
    }

    /// The fraction `q` in the arithmetics without rounding: itself in rationals, enclosed
    /// in intervals (`None` where an end leaves the `f64` range); `None` in the others.
    fn from_exact(_q: &BigRational) -> Option<Self> {
        None
    }

    /// The smaller of two values (the first on ties). Enclosing arithmetics need not decide
    /// which it is.
    fn lesser(self, other: Self) -> Self {
        if other < self {
            other
        } else {
            self
        }
    }
    /// The larger of two values (the first on ties).
    fn greater(self, other: Self) -> Self {
        if other > self {
            other
        } else {
            self
        }
    }

    /// `o + d*t` on a ray given in `f64` (where a hit found at `t` lies).
    fn along(o: f64, d: f64, t: &Self) -> Self {
        Self::from_f64(o) + Self::from_f64(d) * t.clone()
    }

    /// Zero.
    fn zero() -> Self {
        Self::from_i64(0)
    }
    /// One.
    fn one() -> Self {
        Self::from_i64(1)
    }
    /// Whether `self` is an integer (a grid line or lattice coordinate).
    fn is_integer(&self) -> bool {
        Self::from_i64(self.floor_i64()) == *self
    }
}

/// Smaller of two values (the first on ties).
pub fn min<S: Scalar>(a: S, b: S) -> S {
    a.lesser(b)
}

/// Larger of two values (the first on ties).
pub fn max<S: Scalar>(a: S, b: S) -> S {
    a.greater(b)
}

/// The exact value of a finite `f64` as a fraction (non-finite values give zero; callers
/// validate their inputs first).
pub fn exact_from_f64(x: f64) -> BigRational {
    Dyadic::from_f64(x).over(&Dyadic::from_i64(1))
}

/// Exact sign of `a*b - c*d` for `f64` inputs.
fn exact_det2_sign(a: f64, b: f64, c: f64, d: f64) -> Ordering {
    let value = exact_from_f64(a) * exact_from_f64(b) - exact_from_f64(c) * exact_from_f64(d);
    if value.is_positive() {
        Ordering::Greater
    } else if value.is_negative() {
        Ordering::Less
    } else {
        Ordering::Equal
    }
}

/// Forces the sign of a rounded value to the exact sign (zero stays zero).
fn with_sign(value: f64, sign: Ordering) -> f64 {
    match sign {
        Ordering::Equal => 0.0,
        Ordering::Greater if value > 0.0 => value,
        Ordering::Less if value < 0.0 => value,
        // The rounded value has the wrong sign or is zero: it is tiny, keep only its sign.
        Ordering::Greater => f64::MIN_POSITIVE,
        Ordering::Less => -f64::MIN_POSITIVE,
    }
}

/// The band around zero in which the rounded `f64` value of `a*b - c*d`, `p - q` with
/// `p = fl(ab)` and `q = fl(cd)`, may have the wrong sign: `DET2_RELATIVE * (|p| + |q|) +
/// DET2_ABSOLUTE` (a lane kernel computing the same steps asks exactly where this does).
pub const DET2_RELATIVE: f64 = 3.4e-16;
/// See [`DET2_RELATIVE`].
pub const DET2_ABSOLUTE: f64 = 1e-300;

/// `a*b - c*d` in `f64` with the exact sign: rounded where the error bound allows, decided
/// exactly inside it (rare).
#[inline]
fn det2_f64(a: &f64, b: &f64, c: &f64, d: &f64) -> f64 {
    let (p, q) = (a * b, c * d);
    let value = p - q;
    // Error of fl(fl(ab) - fl(cd)) is below 3u(|ab| + |cd|) with u = 2^-53; outside that
    // band the sign is certain.
    let bound = DET2_RELATIVE * (p.abs() + q.abs()) + DET2_ABSOLUTE;
    if value.abs() > bound {
        value
    } else {
        det2_in_doubt(value, [*a, *b, *c, *d])
    }
}

/// `value` with the exact sign of `a*b - c*d`, decided in rationals: out of line, so that the
/// rounded case inlines into the triangle test.
#[cold]
#[inline(never)]
fn det2_in_doubt(value: f64, [a, b, c, d]: [f64; 4]) -> f64 {
    with_sign(value, exact_det2_sign(a, b, c, d))
}

/// `a*b - c*d` in `f32` with the exact sign.
fn det2_f32(a: &f32, b: &f32, c: &f32, d: &f32) -> f32 {
    // Products of two f32 are exact in f64, and the f64 difference of two exact values has
    // the exact sign: the double-precision fallback of Woop et al., always taken.
    let value = f64::from(*a) * f64::from(*b) - f64::from(*c) * f64::from(*d);
    let rounded = value as f32;
    if rounded == 0.0 && value != 0.0 {
        // Underflow to zero would lose the sign.
        f32::MIN_POSITIVE.copysign(value as f32)
    } else {
        rounded
    }
}

/// The floating-point arithmetics: the same operations, their own epsilon, tolerance for
/// lattice crossings (room for a recurrence's drift over a million steps) and exact-sign
/// determinant.
macro_rules! float_scalar {
    ($float:ty, $tolerance:expr, $det2:path, $as_f64s:expr) => {
        impl Scalar for $float {
            fn from_f64(x: f64) -> Self {
                x as $float
            }
            fn from_i64(n: i64) -> Self {
                n as $float
            }
            fn rounding_error(magnitude: f64) -> f64 {
                magnitude * f64::from(<$float>::EPSILON) / 2.0
            }
            fn nearly_equal(&self, other: &Self) -> bool {
                // Infinities (a parameter step overflowing for a subnormal direction) are
                // near nothing but themselves: a finite difference means both are finite.
                // (`greater`, not `max`: a NaN fails the last comparison anyway, and `max`'s
                // handling of NaN costs instructions at every block step.)
                let difference = (self - other).abs();
                let scale = self.abs().greater(other.abs()).greater(1.0);
                self == other
                    || (difference < <$float>::INFINITY && difference <= $tolerance * scale)
            }
            fn to_f64(&self) -> f64 {
                f64::from(*self)
            }
            // Without SSE4.1, `floor` and `ceil` are library calls; a truncating conversion
            // and one comparison give the same saturated integers (NaN gives 0).
            #[inline]
            fn floor_i64(&self) -> i64 {
                let n = *self as i64;
                n.saturating_sub(i64::from((n as $float) > *self))
            }
            #[inline]
            fn ceil_i64(&self) -> i64 {
                let n = *self as i64;
                n.saturating_add(i64::from((n as $float) < *self))
            }
            fn is_zero(&self) -> bool {
                *self == 0.0
            }
            fn is_negative(&self) -> bool {
                *self < 0.0
            }
            #[inline]
            fn det2(a: &Self, b: &Self, c: &Self, d: &Self) -> Self {
                $det2(a, b, c, d)
            }
            fn past_rounding(self) -> Self {
                self + 8.0 * <$float>::EPSILON * self.abs()
            }
            #[inline(always)]
            fn as_f64s<const N: usize>(values: &[Self; N]) -> Option<&[f64; N]> {
                $as_f64s(values)
            }
        }
    };
}

/// How close (relative) two `f64` values must be to count as equal in
/// [`Scalar::nearly_equal`].
pub const F64_TOLERANCE: f64 = 1e-9;

float_scalar!(f64, F64_TOLERANCE, det2_f64, Some);
float_scalar!(f32, 1e-4, det2_f32, |_| None);

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    #[test]
    fn exact_from_f64_is_exact() {
        assert_eq!(exact_from_f64(0.5), BigRational::new(1.into(), 2.into()));
        assert_eq!(exact_from_f64(-3.0), BigRational::from_integer((-3).into()));
        let tenth = exact_from_f64(0.1);
        // 0.1 is 3602879701896397 / 2^55.
        assert_eq!(
            tenth,
            BigRational::new(3602879701896397u64.into(), BigInt::from(1u8) << 55)
        );
        assert_eq!(
            exact_from_f64(5e-324),
            BigRational::new(1.into(), BigInt::from(1u8) << 1074)
        );
    }

    #[test]
    fn f64_det2_sign_is_exact_where_rounding_cancels() {
        // (1 + 2^-52)^2 - (1 + 2^-51) = 2^-104 exactly, but rounds to 0 in f64.
        let a = 1.0 + f64::EPSILON;
        let c = 1.0 + 2.0 * f64::EPSILON;
        assert!(f64::det2(&a, &a, &c, &1.0) > 0.0);
        assert_eq!(f64::det2(&3.0, &4.0, &6.0, &2.0), 0.0);
        assert_eq!(f64::det2(&3.0, &4.0, &5.0, &2.0), 2.0);
    }

    #[test]
    fn f32_det2_sign_is_exact() {
        let a = 1.0f32 + f32::EPSILON;
        let c = 1.0f32 + 2.0 * f32::EPSILON;
        assert!(f32::det2(&a, &a, &c, &1.0) > 0.0);
        assert_eq!(f32::det2(&3.0, &4.0, &6.0, &2.0), 0.0);
    }
}
