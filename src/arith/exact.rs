//! Exact arithmetic: rationals without rounding, on the exact values of the `f64` inputs.

use super::scalar::{exact_from_f64, Scalar};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// An exact rational number. Every operation is exact; division by zero is never performed
/// by the traversal (it tests for zero first).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Exact(pub BigRational);

fn saturating_i64(n: &BigInt) -> i64 {
    n.to_i64()
        .unwrap_or(if n.is_negative() { i64::MIN } else { i64::MAX })
}

macro_rules! exact_binop {
    ($trait:ident, $method:ident) => {
        impl $trait for Exact {
            type Output = Exact;
            fn $method(self, rhs: Exact) -> Exact {
                Exact(self.0.$method(rhs.0))
            }
        }
    };
}
exact_binop!(Add, add);
exact_binop!(Sub, sub);
exact_binop!(Mul, mul);
exact_binop!(Div, div);

impl Neg for Exact {
    type Output = Exact;
    fn neg(self) -> Exact {
        Exact(-self.0)
    }
}

impl Scalar for Exact {
    const EXACT: bool = true;
    fn from_f64(x: f64) -> Self {
        Exact(exact_from_f64(x))
    }
    fn from_i64(n: i64) -> Self {
        Exact(BigRational::from_integer(n.into()))
    }
    fn to_f64(&self) -> f64 {
        self.0.to_f64().unwrap_or(f64::NAN)
    }
    fn rounding_error(_magnitude: f64) -> f64 {
        0.0
    }
    fn floor_i64(&self) -> i64 {
        saturating_i64(&self.0.floor().to_integer())
    }
    fn ceil_i64(&self) -> i64 {
        saturating_i64(&self.0.ceil().to_integer())
    }
    fn is_zero(&self) -> bool {
        self.0.is_zero()
    }
    fn is_negative(&self) -> bool {
        self.0.is_negative()
    }
    fn is_integer(&self) -> bool {
        self.0.is_integer()
    }
    fn det2(a: &Self, b: &Self, c: &Self, d: &Self) -> Self {
        Exact(&a.0 * &b.0 - &c.0 * &d.0)
    }
    fn to_exact(&self) -> Option<BigRational> {
        Some(self.0.clone())
    }
    fn from_exact(q: &BigRational) -> Option<Self> {
        Some(Exact(q.clone()))
    }
    fn f64_enclosure(&self) -> Option<(f64, f64)> {
        let x = self.to_f64();
        if !x.is_finite() {
            return None;
        }
        let off = (&self.0 - exact_from_f64(x)).abs();
        if off.is_zero() {
            return Some((x, 0.0));
        }
        // (The conversion of the offset may round down by half a unit, and then once more.)
        let radius = off.to_f64()?.next_up().next_up();
        radius.is_finite().then_some((x, radius))
    }
}
