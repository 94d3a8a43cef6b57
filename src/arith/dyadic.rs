//! Exact sums and products of `f64` values kept as an integer times a power of two: no gcd on
//! the way, one reduction at the end. The exact `t` of a hit is a handful of them, so this is
//! where exact mode spends its last step cheaply.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};
use std::ops::{Add, Mul, Neg, Sub};

/// `m * 2^e`, exactly.
#[derive(Clone, Debug)]
pub struct Dyadic {
    m: BigInt,
    e: i64,
}

impl Dyadic {
    /// The exact value of a finite `f64` (callers validate their inputs; non-finite is 0).
    pub fn from_f64(x: f64) -> Dyadic {
        if !x.is_finite() || x == 0.0 {
            return Dyadic::from_i64(0);
        }
        let bits = x.to_bits();
        let exponent = ((bits >> 52) & 0x7ff) as i64;
        let fraction = bits & ((1u64 << 52) - 1);
        // Normal numbers carry an implicit leading 1; subnormals have the minimum exponent.
        let (mantissa, e) = if exponent == 0 {
            (fraction, -1074)
        } else {
            (fraction | (1u64 << 52), exponent - 1075)
        };
        let m = BigInt::from(mantissa);
        Dyadic {
            m: if bits >> 63 == 1 { -m } else { m },
            e,
        }
    }

    pub fn from_i64(n: i64) -> Dyadic {
        Dyadic {
            m: BigInt::from(n),
            e: 0,
        }
    }

    pub fn is_zero(&self) -> bool {
        self.m.is_zero()
    }

    pub fn is_negative(&self) -> bool {
        self.m.is_negative()
    }

    /// `self / den` as a reduced fraction (`den` non-zero).
    pub fn over(&self, den: &Dyadic) -> BigRational {
        let (n, d) = self.scaled_pair(den);
        BigRational::new(n, d)
    }

    /// The `f64` nearest to `self / den` (`den` non-zero), without reducing the fraction.
    pub fn over_to_f64(&self, den: &Dyadic) -> f64 {
        let (n, d) = self.scaled_pair(den);
        let (n, d) = if d.is_negative() { (-n, -d) } else { (n, d) };
        BigRational::new_raw(n, d).to_f64().unwrap_or(f64::NAN)
    }

    /// The mantissa for the exponent `e` (at most `self.e`).
    fn mantissa_at(self, e: i64) -> BigInt {
        self.m << (self.e - e) as usize
    }

    /// Integers `n`, `d` with `n / d == self / den`.
    fn scaled_pair(&self, den: &Dyadic) -> (BigInt, BigInt) {
        let shift = self.e - den.e;
        if shift >= 0 {
            (self.m.clone() << shift as usize, den.m.clone())
        } else {
            (self.m.clone(), den.m.clone() << (-shift) as usize)
        }
    }
}

impl Add for Dyadic {
    type Output = Dyadic;
    fn add(self, rhs: Dyadic) -> Dyadic {
        let e = self.e.min(rhs.e);
        Dyadic {
            m: self.mantissa_at(e) + rhs.mantissa_at(e),
            e,
        }
    }
}

impl Sub for Dyadic {
    type Output = Dyadic;
    fn sub(self, rhs: Dyadic) -> Dyadic {
        self + -rhs
    }
}

impl Neg for Dyadic {
    type Output = Dyadic;
    fn neg(self) -> Dyadic {
        Dyadic {
            m: -self.m,
            e: self.e,
        }
    }
}

impl Mul for Dyadic {
    type Output = Dyadic;
    fn mul(self, rhs: Dyadic) -> Dyadic {
        Dyadic {
            m: self.m * rhs.m,
            e: self.e + rhs.e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::scalar::exact_from_f64;

    #[test]
    fn f64_values_are_read_exactly() {
        let one = Dyadic::from_i64(1);
        let ratio =
            |n: i64, shift: usize| BigRational::new(BigInt::from(n), BigInt::from(1) << shift);
        // 0.1 is 3602879701896397 / 2^55; the least subnormal is 2^-1074.
        assert_eq!(
            Dyadic::from_f64(0.1).over(&one),
            ratio(3602879701896397, 55)
        );
        assert_eq!(Dyadic::from_f64(-3.75).over(&one), ratio(-15, 2));
        assert_eq!(Dyadic::from_f64(5e-324).over(&one), ratio(1, 1074));
        assert_eq!(
            Dyadic::from_f64(2f64.powi(60)).over(&one),
            BigRational::from_integer(BigInt::from(1) << 60)
        );
        assert!(Dyadic::from_f64(-0.0).is_zero() && Dyadic::from_f64(f64::NAN).is_zero());
    }

    /// Against `BigRational` arithmetic on the same values.
    #[test]
    fn sums_products_and_quotients_are_exact() {
        let values = [
            0.1,
            -3.75,
            1e-300,
            5e-324,
            123456789.125,
            -0.0,
            2f64.powi(60),
        ];
        for &a in &values {
            for &b in &values {
                let (x, y) = (exact_from_f64(a), exact_from_f64(b));
                let (p, q) = (Dyadic::from_f64(a), Dyadic::from_f64(b));
                let sum = (p.clone() + q.clone()) * Dyadic::from_f64(3.0) - q.clone();
                let want = (x.clone() + y.clone()) * exact_from_f64(3.0) - y.clone();
                assert_eq!(sum.over(&Dyadic::from_i64(1)), want, "{a} {b}");
                if b != 0.0 {
                    assert_eq!(p.over(&q), x.clone() / y.clone(), "{a} / {b}");
                    let nearest = (x / y).to_f64().unwrap();
                    assert_eq!(p.over_to_f64(&q), nearest, "{a} / {b}");
                }
            }
        }
    }
}
