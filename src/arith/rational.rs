//! Bounded rationals: `Ratio<i64>`-sized fractions whose denominators never exceed a chosen
//! bound.
//!
//! Every result is computed exactly in `i128` and then, if its reduced denominator exceeds the
//! bound (or its numerator would not fit an `i64`), rounded to the nearest fraction that fits
//! (best rational approximation, as by continued fractions). Values beyond the `i64` range
//! saturate. Both events are counted per thread, never panic, and are reported with each ray.
//!
//! The run recurrence stays exact in this arithmetic: the slope `a = p/q` is rounded once, the
//! intercept is rounded onto multiples of `1/(q*m)` with `m = floor(bound/q)`
//! ([`Scalar::align_to`]), and `beta + a*len - 1` then never leaves that denominator.

use super::scalar::Scalar;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::{BigRational, Ratio};
use num_traits::Signed;
use std::cell::Cell;
use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Default denominator bound when none is given: 2^16.
pub const DEFAULT_BOUND: u32 = 1 << 16;

thread_local! {
    static BOUND: Cell<i128> = const { Cell::new(DEFAULT_BOUND as i128) };
    static ROUNDED: Cell<u64> = const { Cell::new(0) };
    static SATURATED: Cell<u64> = const { Cell::new(0) };
}

/// How often bounded arithmetic had to give up exactness on this thread.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RationalEvents {
    /// Results rounded to a fraction within the bound.
    pub rounded: u64,
    /// Results outside the `i64` range, clamped (also division by zero).
    pub saturated: u64,
}

/// Runs `f` with the given denominator bound on this thread and returns what it produced with
/// the rounding events it caused.
pub fn with_bound<R>(bound: u32, f: impl FnOnce() -> R) -> (R, RationalEvents) {
    let previous = BOUND.with(|b| b.replace(i128::from(bound.max(1))));
    let before = (ROUNDED.with(Cell::get), SATURATED.with(Cell::get));
    let result = f();
    let events = RationalEvents {
        rounded: ROUNDED.with(Cell::get) - before.0,
        saturated: SATURATED.with(Cell::get) - before.1,
    };
    BOUND.with(|b| b.set(previous));
    (result, events)
}

fn count(cell: &'static std::thread::LocalKey<Cell<u64>>) {
    cell.with(|c| c.set(c.get() + 1));
}

/// A fraction `num/den` with `den > 0`, in lowest terms, `den` within the thread's bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rational {
    num: i64,
    den: i64,
}

impl Rational {
    /// Builds the fraction nearest to `num/den` (`den != 0`) that the bound allows.
    fn from_i128(num: i128, den: i128) -> Rational {
        let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
        let g = num.gcd(&den).max(1);
        let (num, den) = (num / g, den / g);
        let bound = BOUND.with(Cell::get);
        if den <= bound && num.abs() <= i128::from(i64::MAX) {
            return Rational {
                num: num as i64,
                den: den as i64,
            };
        }
        // Too large for any denominator: clamp.
        let limit = i128::from(i64::MAX);
        if num.abs() / den >= limit {
            count(&SATURATED);
            let num = if num < 0 { -limit } else { limit };
            return Rational {
                num: num as i64,
                den: 1,
            };
        }
        count(&ROUNDED);
        // Large values get a coarser denominator so that the numerator still fits an i64.
        let max_den = bound.min(limit / (num.abs() / den + 1)).max(1);
        let (p, q) = best_approximation(num.abs(), den, max_den);
        let p = if num < 0 { -p } else { p };
        Rational {
            num: p as i64,
            den: q as i64,
        }
    }

    /// The value as a `Ratio<i64>` (for inspection and reporting).
    pub fn ratio(&self) -> Ratio<i64> {
        Ratio::new_raw(self.num, self.den)
    }
}

/// Best approximation of `n/d` (both positive) by a fraction with denominator at most
/// `max_den`, by continued-fraction convergents and the last semiconvergent.
fn best_approximation(n: i128, d: i128, max_den: i128) -> (i128, i128) {
    let (mut p0, mut q0, mut p1, mut q1) = (0i128, 1i128, 1i128, 0i128);
    let (mut rn, mut rd) = (n, d);
    // Walk the convergents while their denominators stay within the bound.
    loop {
        let a = rn / rd;
        let q2 = q0 + a * q1;
        if q2 > max_den {
            break;
        }
        (p0, q0, p1, q1) = (p1, q1, p0 + a * p1, q2);
        (rn, rd) = (rd, rn - a * rd);
        if rd == 0 {
            return (p1, q1);
        }
    }
    // The last semiconvergent within the bound competes with the last convergent; ties go to
    // the convergent, which keeps rounding symmetric under negation.
    let k = (max_den - q0) / q1;
    let (pa, qa) = (p0 + k * p1, q0 + k * q1);
    // Compare |pa/qa - n/d| with |p1/q1 - n/d| after multiplying both by d*qa*q1.
    let error = |p: i128, q: i128| (BigInt::from(p) * d - BigInt::from(n) * q).abs();
    let (error_a, error_1) = (error(pa, qa) * q1, error(p1, q1) * qa);
    if error_a < error_1 {
        (pa, qa)
    } else {
        (p1, q1)
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Rational) -> Option<Ordering> {
        Some(
            (i128::from(self.num) * i128::from(other.den))
                .cmp(&(i128::from(other.num) * i128::from(self.den))),
        )
    }
}

impl Add for Rational {
    type Output = Rational;
    fn add(self, rhs: Rational) -> Rational {
        let (a, b, c, d) = widen(self, rhs);
        Rational::from_i128(a * d + c * b, b * d)
    }
}

impl Sub for Rational {
    type Output = Rational;
    fn sub(self, rhs: Rational) -> Rational {
        let (a, b, c, d) = widen(self, rhs);
        Rational::from_i128(a * d - c * b, b * d)
    }
}

impl Mul for Rational {
    type Output = Rational;
    fn mul(self, rhs: Rational) -> Rational {
        let (a, b, c, d) = widen(self, rhs);
        Rational::from_i128(a * c, b * d)
    }
}

impl Div for Rational {
    type Output = Rational;
    fn div(self, rhs: Rational) -> Rational {
        let (a, b, c, d) = widen(self, rhs);
        if c == 0 {
            count(&SATURATED);
            let limit = i64::MAX;
            return Rational {
                num: if a < 0 { -limit } else { limit },
                den: 1,
            };
        }
        Rational::from_i128(a * d, b * c)
    }
}

impl Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        // Numerators stay within ±i64::MAX, so negation cannot overflow.
        Rational {
            num: -self.num,
            den: self.den,
        }
    }
}

fn widen(x: Rational, y: Rational) -> (i128, i128, i128, i128) {
    (
        i128::from(x.num),
        i128::from(x.den),
        i128::from(y.num),
        i128::from(y.den),
    )
}

impl Scalar for Rational {
    fn from_f64(x: f64) -> Self {
        let limit = 2f64.powi(62);
        if x.is_nan() {
            count(&SATURATED);
            return Rational { num: 0, den: 1 };
        }
        if x.abs() >= limit {
            count(&SATURATED);
            let num = if x < 0.0 { -i64::MAX } else { i64::MAX };
            return Rational { num, den: 1 };
        }
        // x * 2^64 is exact (a power-of-two scaling) and below 2^126: an exact i128 fraction
        // up to bits below 2^-64, far finer than any bound.
        let scaled = (x * 2f64.powi(64)).round() as i128;
        Rational::from_i128(scaled, 1i128 << 64)
    }
    fn from_i64(n: i64) -> Self {
        Rational::from_i128(i128::from(n), 1)
    }
    fn to_f64(&self) -> f64 {
        self.num as f64 / self.den as f64
    }
    fn rounding_error(magnitude: f64) -> f64 {
        // Values are rounded to multiples of 1/bound (coarser for huge values, whose
        // numerators would not fit): mostly an absolute error.
        let bound = BOUND.with(Cell::get) as f64;
        (1.0 / bound).max(magnitude * bound / i64::MAX as f64)
    }
    fn floor_i64(&self) -> i64 {
        self.num.div_euclid(self.den)
    }
    fn ceil_i64(&self) -> i64 {
        -((-self.num).div_euclid(self.den))
    }
    fn is_zero(&self) -> bool {
        self.num == 0
    }
    fn is_negative(&self) -> bool {
        self.num < 0
    }
    fn is_integer(&self) -> bool {
        self.den == 1
    }
    fn det2(a: &Self, b: &Self, c: &Self, d: &Self) -> Self {
        let value = *a * *b - *c * *d;
        // Decide the sign exactly: a*b and c*d as exact fractions compared in 256 bits via
        // BigRational (operands are small, this stays cheap).
        let exact = |x: &Rational| BigRational::new(x.num.into(), x.den.into());
        let sign = (exact(a) * exact(b)).cmp(&(exact(c) * exact(d)));
        match (sign, value.num.cmp(&0)) {
            (Ordering::Equal, _) => Rational { num: 0, den: 1 },
            (s, v) if s == v => value,
            // Rounding lost or flipped the sign of a tiny value: keep the smallest one.
            (Ordering::Greater, _) => Rational {
                num: 1,
                den: BOUND.with(Cell::get) as i64,
            },
            (Ordering::Less, _) => Rational {
                num: -1,
                den: BOUND.with(Cell::get) as i64,
            },
        }
    }
    fn align_to(self, slope: &Self) -> Self {
        // Round self to the nearest multiple of 1/(q*m), q the slope's denominator and m as
        // large as the bound allows: adding multiples of the slope then never leaves that
        // denominator, and the resolution stays about 1/bound.
        let bound = BOUND.with(Cell::get);
        let q = i128::from(slope.den) * (bound / i128::from(slope.den)).max(1);
        let scaled = i128::from(self.num) * q;
        let den = i128::from(self.den);
        let numerator = (2 * scaled + den).div_euclid(2 * den);
        if numerator * den != scaled {
            count(&ROUNDED);
        }
        Rational::from_i128(numerator, q)
    }
    fn to_exact(&self) -> Option<BigRational> {
        None
    }
}
