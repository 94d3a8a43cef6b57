//! The fast path of exact arithmetic: `f64` intervals that always contain the exact value.
//!
//! Every operation rounds its lower end down and its upper end up. Operations on points (exact
//! values) do it exactly, with error-free transformations (TwoSum, and the residual of products
//! and quotients), so that an exact result stays a point and ties between exact values settle.
//! Ends of wider intervals take the cheaper way: sums still by TwoSum, products and quotients
//! one float outwards unless their operands show them exact (the residual would be most of
//! exact mode's time). A comparison whose answer the intervals cannot settle raises a per-thread
//! flag; exact mode then answers the ray again with [`super::Exact`] rationals. Every decision
//! made without the flag is the exact decision, so a ray traced without raising it gets the
//! exact answer (and counters) at interval speed.

use super::rounding::{above, below, product, product_end, quotient, quotient_end, sum};
use super::scalar::{exact_from_f64, Scalar};
use num_rational::BigRational;
use num_traits::ToPrimitive;
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

/// Marks the code running under [`settled`] as unsettled: a decision it had to make, intervals
/// could not.
pub fn unsettled() {
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

    /// Every value from `lo` to `hi`: an input known only that well (`None` unless
    /// `lo <= hi`, both finite).
    pub fn between(lo: f64, hi: f64) -> Option<Interval> {
        (lo.is_finite() && hi.is_finite() && lo <= hi).then_some(Interval { lo, hi })
    }

    /// The ends `(lo, hi)`.
    pub fn ends(&self) -> (f64, f64) {
        (self.lo, self.hi)
    }

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

impl Add for Interval {
    type Output = Interval;
    fn add(self, rhs: Interval) -> Interval {
        if self.is_point() && rhs.is_point() {
            let (lo, hi) = sum(self.lo, rhs.lo);
            return Interval::checked(lo, hi);
        }
        // (TwoSum is cheap, and keeps ends that are exact sums exact.)
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
            Interval::checked(product_end(x, y, below), product_end(z, w, above))
        };
        match (a.lo >= 0.0, a.hi <= 0.0, b.lo >= 0.0, b.hi <= 0.0) {
            (true, _, true, _) => return ends((a.lo, b.lo), (a.hi, b.hi)),
            (true, _, _, true) => return ends((a.hi, b.lo), (a.lo, b.hi)),
            (_, true, true, _) => return ends((a.lo, b.hi), (a.hi, b.lo)),
            (_, true, _, true) => return ends((a.hi, b.hi), (a.lo, b.lo)),
            _ => {}
        }
        let pairs = [(a.lo, b.lo), (a.lo, b.hi), (a.hi, b.lo), (a.hi, b.hi)];
        let lo = pairs
            .iter()
            .map(|&(x, y)| product_end(x, y, below))
            .fold(f64::INFINITY, f64::min);
        let hi = pairs
            .iter()
            .map(|&(x, y)| product_end(x, y, above))
            .fold(f64::NEG_INFINITY, f64::max);
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
        if self.is_point() && rhs.is_point() {
            let (lo, hi) = quotient(self.lo, rhs.lo);
            return Interval::checked(lo, hi);
        }
        // The divisor has one sign: `a / b` falls with `b` where `a` is positive.
        let (a, b) = if rhs.lo > 0.0 {
            (self, rhs)
        } else {
            (-self, -rhs)
        };
        let lo = quotient_end(a.lo, if a.lo >= 0.0 { b.hi } else { b.lo }, below);
        let hi = quotient_end(a.hi, if a.hi >= 0.0 { b.lo } else { b.hi }, above);
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
    const EXACT: bool = true;
    const ENCLOSES: bool = true;
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
    fn from_enclosure(lo: f64, hi: f64) -> Option<Self> {
        Interval::between(lo, hi)
    }
    fn from_exact(q: &BigRational) -> Option<Self> {
        let x = q.to_f64()?;
        let below_q = |x: f64| exact_from_f64(x) <= *q;
        // The nearest `f64`, then the floats on either side of `q` (the conversion is within
        // a unit of it; stepping is bounded all the same).
        let (mut lo, mut hi) = (x, x);
        for _ in 0..4 {
            if !below_q(lo) {
                lo = lo.next_down();
            }
            if exact_from_f64(hi) < *q {
                hi = hi.next_up();
            }
        }
        (below_q(lo) && exact_from_f64(hi) >= *q)
            .then(|| Interval::between(lo, hi))
            .flatten()
    }
    fn along(o: f64, d: f64, t: &Interval) -> Interval {
        if d == 0.0 {
            return Interval::point(o);
        }
        if t.is_point() {
            return Interval::point(o) + Interval::point(d) * *t;
        }
        // `t` is not a point, so no end is exact: each end one float outwards after each of
        // its two roundings, a fraction of the work of the general product and sum (every
        // shadow ray starts at such a point).
        let (first, last) = if d >= 0.0 { (t.lo, t.hi) } else { (t.hi, t.lo) };
        Interval::checked(below(o + below(d * first)), above(o + above(d * last)))
    }
    fn f64_enclosure(&self) -> Option<(f64, f64)> {
        if self.is_point() {
            return Some((self.lo, 0.0));
        }
        let mid = self.lo + (self.hi - self.lo) / 2.0;
        // (Each difference is rounded to nearest: its neighbour above is no less.)
        let radius = (self.hi - mid).max(mid - self.lo).next_up();
        radius.is_finite().then_some((mid, radius))
    }
    fn rounding_error(_magnitude: f64) -> f64 {
        // It encloses the exact value: no lift needed, as in exact arithmetic.
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::rounding::TINY;
    use proptest::prelude::*;
    use proptest::test_runner::RngSeed;

    /// Inputs that stress the end rounding: ties and short significands (grid coordinates,
    /// halves, powers of two), neighbours of each other, tiny, subnormal and huge values, and
    /// arbitrary ones.
    fn value() -> impl Strategy<Value = f64> {
        let special = prop::sample::select(vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            2.0,
            0.5,
            3.0,
            -3.0,
            0.1,
            1.0 / 3.0,
            1e-300,
            -1e-300,
            1e-290,
            5e-324,
            -5e-324,
            2.2e-308,
            1e300,
            -1e300,
            1e200,
            134_217_729.0,
            0.75,
            1.75,
        ]);
        prop_oneof![
            special,
            (-64i32..64).prop_map(f64::from),
            (-64i32..64).prop_map(|n| f64::from(n) / 4.0),
            -1e6f64..1e6,
            (-1.0f64..1.0, -300i32..300).prop_map(|(m, e)| m * 2f64.powi(e)),
            (-1e6f64..1e6, 0u8..3).prop_map(|(x, k)| (0..k).fold(x, |x, _| x.next_up())),
        ]
    }

    /// A point, or an interval between two values (or a value and its neighbour).
    fn interval() -> impl Strategy<Value = Interval> {
        prop_oneof![
            value().prop_map(Interval::point),
            (value(), value()).prop_map(|(a, b)| Interval {
                lo: a.min(b),
                hi: a.max(b)
            }),
            value().prop_map(|a| Interval {
                lo: a,
                hi: a.next_up()
            }),
        ]
    }

    fn exact(x: f64) -> BigRational {
        exact_from_f64(x)
    }

    /// `r` (untouched when the operation could not be trusted) contains every `exact` value;
    /// a point result is the one exact value.
    fn check(r: Interval, values: &[BigRational], what: &str) -> Result<(), TestCaseError> {
        if r.lo == f64::NEG_INFINITY && r.hi == f64::INFINITY {
            return Ok(());
        }
        prop_assert!(r.lo <= r.hi, "{what}: {r:?}");
        for v in values {
            prop_assert!(
                exact(r.lo) <= *v && *v <= exact(r.hi),
                "{what}: {r:?} misses {v}"
            );
        }
        if r.is_point() {
            prop_assert!(
                values.iter().all(|v| *v == exact(r.lo)),
                "{what}: {r:?} not exact"
            );
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 20000, rng_seed: RngSeed::Fixed(6), ..ProptestConfig::default() })]

        #[test]
        fn operations_enclose_the_exact_results(a in interval(), b in interval()) {
            let ends = |x: Interval| [exact(x.lo), exact(x.hi)];
            let (ea, eb) = (ends(a), ends(b));
            let pairs = || ea.iter().flat_map(|x| eb.iter().map(move |y| (x, y)));
            let ((sum, product), _) = settled(|| (a + b, a * b));
            check(sum, &pairs().map(|(x, y)| x + y).collect::<Vec<_>>(), "sum")?;
            check(product, &pairs().map(|(x, y)| x * y).collect::<Vec<_>>(), "product")?;
            if b.lo > 0.0 || b.hi < 0.0 {
                let (quotient, _) = settled(|| a / b);
                check(quotient, &pairs().map(|(x, y)| x / y).collect::<Vec<_>>(), "quotient")?;
            }
        }

        /// The point `o + d*t` on a ray given in `f64` (a shadow ray's start).
        #[test]
        fn points_along_a_ray_enclose_the_exact_points(o in value(), d in value(), t in interval()) {
            let (point, _) = settled(|| Interval::along(o, d, &t));
            let exact_at = |t: f64| exact(o) + exact(d) * exact(t);
            check(point, &[exact_at(t.lo), exact_at(t.hi)], "along")?;
        }

        #[test]
        fn exact_results_of_points_stay_points(x in value(), y in value()) {
            let (a, b) = (Interval::point(x), Interval::point(y));
            let ((sum, product), _) = settled(|| (a + b, a * b));
            let exact_sum = exact(x) + exact(y);
            let exact_product = exact(x) * exact(y);
            prop_assert_eq!(sum.is_point(), exact(x + y) == exact_sum, "{} + {}", x, y);
            // (Near underflow exact results may be left a little wide.)
            let fits = (x * y).is_finite() && exact(x * y) == exact_product;
            prop_assert!(!product.is_point() || fits, "{} * {}", x, y);
            if (x * y).abs() >= TINY || x == 0.0 || y == 0.0 {
                prop_assert_eq!(product.is_point(), fits, "{} * {}", x, y);
            }
            if y != 0.0 {
                let (quotient, _) = settled(|| a / b);
                let fits = (x / y).is_finite() && exact(x / y) == exact(x) / exact(y);
                prop_assert!(!quotient.is_point() || fits, "{} / {}", x, y);
                if ((x / y).abs() >= TINY && x.abs() >= TINY) || x == 0.0 {
                    prop_assert_eq!(quotient.is_point(), fits, "{} / {}", x, y);
                }
            }
        }

        /// Ends one float outwards at most: wider intervals would leave more rays unsettled.
        #[test]
        fn inexact_ends_move_one_float(x in -1e6f64..1e6, y in -1e6f64..1e6) {
            let a = Interval { lo: x, hi: x.next_up() };
            let b = Interval::point(y);
            let (p, _) = settled(|| a * b);
            let (lo, hi) = ((x * y).min(x.next_up() * y), (x * y).max(x.next_up() * y));
            prop_assert!(p.lo >= lo.next_down() && p.hi <= hi.next_up(), "{:?} {}", p, y);
        }
    }

    #[test]
    fn short_products_and_power_of_two_quotients_stay_exact_at_the_ends() {
        let a = Interval { lo: 1.5, hi: 2.25 };
        let p = a * Interval::point(3.0);
        assert_eq!((p.lo, p.hi), (4.5, 6.75));
        let q = a / Interval::point(-4.0);
        assert_eq!((q.lo, q.hi), (-0.5625, -0.375));
        // A hit at `t = 0` stays exactly zero.
        let zero = Interval::point(0.0) / Interval { lo: 2.0, hi: 3.0 };
        assert_eq!((zero.lo, zero.hi), (0.0, 0.0));
        // Underflow is never exact.
        let tiny = Interval {
            lo: 1e-200,
            hi: 2e-200,
        } * Interval::point(1e-200);
        assert!(tiny.lo <= 0.0 && tiny.hi > 0.0);
    }

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
