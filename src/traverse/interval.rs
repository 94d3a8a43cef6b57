//! The fast path of exact arithmetic: `f64` intervals that always contain the exact value.
//!
//! Every operation rounds its lower end down and its upper end up, exactly, using error-free
//! transformations (TwoSum, and the FMA residual of products and quotients). A comparison
//! whose answer the intervals cannot settle raises a per-thread flag; exact mode then answers
//! the ray again with [`super::Exact`] rationals. Every decision made without the flag is the
//! exact decision, so a ray traced without raising it gets the exact answer (and counters) at
//! interval speed.

use super::scalar::Scalar;
use std::cell::Cell;
use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};

thread_local! {
    static UNSETTLED: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f` and tells whether any comparison in it could not be settled by intervals.
pub fn settled<R>(f: impl FnOnce() -> R) -> (R, bool) {
    let before = UNSETTLED.with(|u| u.replace(false));
    let result = f();
    let unsettled = UNSETTLED.with(|u| u.replace(before));
    (result, !unsettled)
}

fn unsettled() {
    if std::env::var_os("HR_DEBUG").is_some() && !UNSETTLED.with(|u| u.get()) {
        eprintln!("{}", std::backtrace::Backtrace::force_capture());
    }
    UNSETTLED.with(|u| u.set(true));
}

/// An interval `[lo, hi]` of `f64` containing the exact value.
#[derive(Clone, Copy, Debug)]
pub struct Interval {
    lo: f64,
    hi: f64,
}

impl Interval {
    const EVERYTHING: Interval = Interval {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };

    fn point(x: f64) -> Interval {
        Interval { lo: x, hi: x }
    }

    /// A result whose ends were rounded outwards; non-finite ends cannot be trusted.
    fn checked(lo: f64, hi: f64) -> Interval {
        if lo.is_finite() && hi.is_finite() {
            Interval { lo, hi }
        } else {
            unsettled();
            Interval::EVERYTHING
        }
    }

    fn is_point(&self) -> bool {
        self.lo == self.hi
    }
}

/// `a + b` rounded down and up: `s + e` is the exact sum (TwoSum).
fn sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (
        if e < 0.0 { s.next_down() } else { s },
        if e > 0.0 { s.next_up() } else { s },
    )
}

/// Products below this may lose bits of their FMA residual to underflow.
const TINY: f64 = 1e-280;

/// Operands above this could overflow when split for [`product_error`].
const HUGE: f64 = 1e290;

/// The rounding error `a*b - p` of the product `p = a*b`, exactly: one fused multiply-add
/// where the target has it, else Dekker's splitting (a library `fma` call is several times
/// slower than the dozen operations of the split).
#[inline]
fn product_error(a: f64, b: f64, p: f64) -> f64 {
    if cfg!(target_feature = "fma") || a.abs() > HUGE || b.abs() > HUGE {
        return a.mul_add(b, -p);
    }
    // Veltkamp's split into halves of 26 bits: products of halves are exact.
    let split = |x: f64| {
        let c = 134_217_729.0 * x; // 2^27 + 1
        let hi = c - (c - x);
        (hi, x - hi)
    };
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    ((ah * bh - p) + ah * bl + al * bh) + al * bl
}

/// `a * b` rounded down and up: `p + e` is the exact product.
#[inline]
fn product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    if p != 0.0 && p.abs() < TINY {
        return (p.next_down().min(0.0), p.next_up().max(0.0));
    }
    let e = product_error(a, b, p);
    (
        if e < 0.0 { p.next_down() } else { p },
        if e > 0.0 { p.next_up() } else { p },
    )
}

/// `a / b` (b non-zero) rounded down and up: the residual `a - q*b` gives the side of `q`.
fn quotient(a: f64, b: f64) -> (f64, f64) {
    let q = a / b;
    if q != 0.0 && q.abs() < TINY {
        return (q.next_down().min(0.0), q.next_up().max(0.0));
    }
    // `a - q*b`: `a - p` is exact (Sterbenz: `p` is within a factor 2 of `a`), so the
    // difference with the product's error has the residual's sign.
    let p = q * b;
    let r = (a - p) - product_error(q, b, p);
    let above = (r > 0.0) == (b > 0.0) && r != 0.0; // exact quotient above q
    let below = r != 0.0 && !above;
    (
        if below { q.next_down() } else { q },
        if above { q.next_up() } else { q },
    )
}

impl Add for Interval {
    type Output = Interval;
    fn add(self, rhs: Interval) -> Interval {
        Interval::checked(sum(self.lo, rhs.lo).0, sum(self.hi, rhs.hi).1)
    }
}

impl Sub for Interval {
    type Output = Interval;
    fn sub(self, rhs: Interval) -> Interval {
        self + -rhs
    }
}

impl Neg for Interval {
    type Output = Interval;
    fn neg(self) -> Interval {
        Interval {
            lo: -self.hi,
            hi: -self.lo,
        }
    }
}

impl Mul for Interval {
    type Output = Interval;
    fn mul(self, rhs: Interval) -> Interval {
        if self.is_point() && rhs.is_point() {
            let (lo, hi) = product(self.lo, rhs.lo);
            return Interval::checked(lo, hi);
        }
        // Where the signs are known, two end products bound it (the usual case).
        let (a, b) = (self, rhs);
        let ends = |(x, y): (f64, f64), (z, w): (f64, f64)| {
            Interval::checked(product(x, y).0, product(z, w).1)
        };
        match (a.lo >= 0.0, a.hi <= 0.0, b.lo >= 0.0, b.hi <= 0.0) {
            (true, _, true, _) => return ends((a.lo, b.lo), (a.hi, b.hi)),
            (true, _, _, true) => return ends((a.hi, b.lo), (a.lo, b.hi)),
            (_, true, true, _) => return ends((a.lo, b.hi), (a.hi, b.lo)),
            (_, true, _, true) => return ends((a.hi, b.hi), (a.lo, b.lo)),
            _ => {}
        }
        let ends = [
            product(self.lo, rhs.lo),
            product(self.lo, rhs.hi),
            product(self.hi, rhs.lo),
            product(self.hi, rhs.hi),
        ];
        let lo = ends.iter().map(|e| e.0).fold(f64::INFINITY, f64::min);
        let hi = ends.iter().map(|e| e.1).fold(f64::NEG_INFINITY, f64::max);
        Interval::checked(lo, hi)
    }
}

impl Div for Interval {
    type Output = Interval;
    fn div(self, rhs: Interval) -> Interval {
        if rhs.lo <= 0.0 && rhs.hi >= 0.0 {
            unsettled();
            return Interval::EVERYTHING;
        }
        let ends = [
            quotient(self.lo, rhs.lo),
            quotient(self.lo, rhs.hi),
            quotient(self.hi, rhs.lo),
            quotient(self.hi, rhs.hi),
        ];
        let lo = ends.iter().map(|e| e.0).fold(f64::INFINITY, f64::min);
        let hi = ends.iter().map(|e| e.1).fold(f64::NEG_INFINITY, f64::max);
        Interval::checked(lo, hi)
    }
}

impl PartialEq for Interval {
    fn eq(&self, other: &Interval) -> bool {
        self.partial_cmp(other) == Some(Ordering::Equal)
    }
}

impl PartialOrd for Interval {
    fn partial_cmp(&self, other: &Interval) -> Option<Ordering> {
        if self.hi < other.lo {
            Some(Ordering::Less)
        } else if self.lo > other.hi {
            Some(Ordering::Greater)
        } else if self.is_point() && other.is_point() {
            Some(Ordering::Equal)
        } else {
            unsettled();
            (self.lo + self.hi).partial_cmp(&(other.lo + other.hi))
        }
    }
}

impl Scalar for Interval {
    fn from_f64(x: f64) -> Self {
        Interval::point(x)
    }
    fn from_i64(n: i64) -> Self {
        let x = n as f64;
        // Grid coordinates are far below 2^53 and exact; saturated step counts may not be.
        if x.abs() < 9.0e15 {
            Interval::point(x)
        } else {
            Interval::checked(x.next_down(), x.next_up())
        }
    }
    fn to_f64(&self) -> f64 {
        self.lo + (self.hi - self.lo) / 2.0
    }
    fn floor_i64(&self) -> i64 {
        let (lo, hi) = (self.lo.floor(), self.hi.floor());
        if lo != hi {
            unsettled();
        }
        lo as i64
    }
    fn ceil_i64(&self) -> i64 {
        let (lo, hi) = (self.lo.ceil(), self.hi.ceil());
        if lo != hi {
            unsettled();
        }
        hi as i64
    }
    fn is_zero(&self) -> bool {
        *self == Interval::point(0.0)
    }
    fn is_negative(&self) -> bool {
        *self < Interval::point(0.0)
    }
    fn is_integer(&self) -> bool {
        if self.is_point() {
            return self.lo.fract() == 0.0;
        }
        // No integer inside: certainly not one.
        if self.lo.ceil() > self.hi {
            return false;
        }
        unsettled();
        false
    }
    fn det2(a: &Self, b: &Self, c: &Self, d: &Self) -> Self {
        let value = *a * *b - *c * *d;
        // The sign is decided (or flagged) where it is used; a straddling interval is only
        // trusted as a value in sums.
        value
    }
    fn lesser(self, other: Interval) -> Interval {
        // Encloses the smaller exact value without deciding which one it is.
        Interval {
            lo: self.lo.min(other.lo),
            hi: self.hi.min(other.hi),
        }
    }
    fn greater(self, other: Interval) -> Interval {
        Interval {
            lo: self.lo.max(other.lo),
            hi: self.hi.max(other.hi),
        }
    }
    fn exact_f64(&self) -> Option<f64> {
        self.is_point().then_some(self.lo)
    }
    fn rounding_error(_magnitude: f64) -> f64 {
        // It encloses the exact value: no lift needed, as in exact arithmetic.
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intervals_enclose_inexact_results_and_keep_exact_ones() {
        let third = Interval::point(1.0) / Interval::point(3.0);
        assert!(third.lo < third.hi && third.lo <= 1.0 / 3.0 && 1.0 / 3.0 <= third.hi);
        let exact = Interval::point(0.5) + Interval::point(0.25);
        assert!(exact.is_point() && exact.lo == 0.75);
        let ((), settled_ok) =
            settled(|| assert!(third * Interval::point(3.0) > Interval::point(0.9)));
        assert!(settled_ok);
        // 0.1 + 0.2 against 0.3: the exact sums differ, but the test of 3 * (1/3) == 1 cannot be
        // settled by intervals.
        let (_, unsettled_ok) = settled(|| third * Interval::point(3.0) == Interval::point(1.0));
        assert!(!unsettled_ok);
    }
}
