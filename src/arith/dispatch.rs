//! The one way from an [`Arith`] to code generic over [`Scalar`]: [`with_numbers`] picks the
//! arithmetic's [`Numbers`] once (for a frame's band, or one ray), with the arithmetic's
//! thread-local state (the rational bound) set around the code, and each [`Numbers`] runs
//! code per ray its own way: exact arithmetic in intervals first, and again in rationals
//! only where they left a decision unsettled.

use super::{settled, with_bound, Arith, Exact, Interval, Rational, RationalEvents, Scalar};
use std::marker::PhantomData;

/// Code to run in whichever arithmetic an [`Arith`] names (see [`run`], [`Numbers::run`]).
pub trait Generic {
    /// What the code answers.
    type Output;
    /// Runs the code in arithmetic `S`.
    fn run<S: Scalar>(&self) -> Self::Output;
}

/// What [`Numbers::run`] answered, and how.
#[derive(Clone, Debug)]
pub struct Ran<O> {
    /// The code's answer.
    pub output: O,
    /// Exact arithmetic: intervals left a decision unsettled and the code ran again in
    /// rationals.
    pub redone: bool,
}

/// How an arithmetic runs [`Generic`] code, one call (a ray, a pixel) at a time.
pub trait Numbers {
    /// Whether [`Numbers::run`] may run code twice (exact arithmetic, again in rationals
    /// after intervals), so that what the first run recorded must be taken back.
    const REDOES: bool = false;
    /// Runs `code` in this arithmetic.
    fn run<G: Generic>(code: &G) -> Ran<G::Output>;
}

/// An arithmetic of one [`Scalar`] type: `f32`, `f64`, or bounded rationals (their bound set
/// by [`with_numbers`]).
pub struct Plain<S>(PhantomData<S>);

impl<S: Scalar> Numbers for Plain<S> {
    #[inline(always)]
    fn run<G: Generic>(code: &G) -> Ran<G::Output> {
        Ran {
            output: code.run::<S>(),
            redone: false,
        }
    }
}

/// Exact arithmetic: [`Interval`]s and, where they leave a decision unsettled
/// ([`settled`]), again [`Exact`] rationals. Settled decisions are the exact ones, so the
/// answer is exact either way.
pub struct Settling;

impl Numbers for Settling {
    const REDOES: bool = true;
    #[inline(always)]
    fn run<G: Generic>(code: &G) -> Ran<G::Output> {
        match settled(|| code.run::<Interval>()) {
            (output, true) => Ran {
                output,
                redone: false,
            },
            (_, false) => Ran {
                output: code.run::<Exact>(),
                redone: true,
            },
        }
    }
}

/// Code that runs with an arithmetic's [`Numbers`] (see [`with_numbers`]).
pub trait WithNumbers {
    /// What the code answers.
    type Output;
    /// Runs the code with `N`.
    fn with<N: Numbers>(self) -> Self::Output;
}

/// Runs `code` with the [`Numbers`] `arith` names, the bound of bounded rationals set around
/// it; returns its answer and the rounding events of bounded rationals it caused.
#[inline]
pub fn with_numbers<C: WithNumbers>(arith: Arith, code: C) -> (C::Output, RationalEvents) {
    let plain = |output| (output, RationalEvents::default());
    match arith {
        Arith::F32 => plain(code.with::<Plain<f32>>()),
        Arith::F64 => plain(code.with::<Plain<f64>>()),
        Arith::Rational { bound } => with_bound(bound, || code.with::<Plain<Rational>>()),
        Arith::Exact => plain(code.with::<Settling>()),
    }
}

/// Runs `code` once in the arithmetic `arith` names (see [`with_numbers`]).
pub fn run<G: Generic>(arith: Arith, code: &G) -> (Ran<G::Output>, RationalEvents) {
    /// One call of the code.
    struct Once<'g, G>(&'g G);
    impl<G: Generic> WithNumbers for Once<'_, G> {
        type Output = Ran<G::Output>;
        fn with<N: Numbers>(self) -> Self::Output {
            N::run(self.0)
        }
    }
    with_numbers(arith, Once(code))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::unsettled;

    /// One third in the arithmetic run, and whether it encloses; in intervals it declares
    /// itself unsettled.
    struct Third {
        give_up_in_intervals: bool,
    }

    impl Generic for Third {
        type Output = (f64, bool);
        fn run<S: Scalar>(&self) -> (f64, bool) {
            if S::ENCLOSES && self.give_up_in_intervals {
                unsettled();
            }
            let third = S::from_i64(1) / S::from_i64(3);
            (third.to_f64(), S::ENCLOSES)
        }
    }

    #[test]
    fn each_arith_runs_its_own_numbers() {
        let code = Third {
            give_up_in_intervals: false,
        };
        let (f32_third, _) = run(Arith::F32, &code).0.output;
        assert_eq!(f32_third, f64::from(1.0f32 / 3.0));
        assert_eq!(run(Arith::F64, &code).0.output, (1.0 / 3.0, false));
        // Settled in intervals: answered there, not run again.
        let (exact, _) = run(Arith::Exact, &code);
        assert_eq!((exact.output.1, exact.redone), (true, false));
    }

    #[test]
    fn bounded_rationals_run_under_their_bound_and_count_its_roundings() {
        // 1/3 is within every bound from 3: no rounding; under bound 2 it becomes 1/2 (the
        // nearest fraction with a denominator of at most 2), one rounding.
        let code = Third {
            give_up_in_intervals: false,
        };
        let (within, events) = run(Arith::Rational { bound: 3 }, &code);
        assert_eq!((within.output.0, events.rounded), (1.0 / 3.0, 0));
        let (rounded, events) = run(Arith::Rational { bound: 2 }, &code);
        assert_eq!((rounded.output.0, events.rounded), (0.5, 1));
    }

    #[test]
    fn exact_runs_again_in_rationals_where_intervals_leave_a_decision_unsettled() {
        let code = Third {
            give_up_in_intervals: true,
        };
        let (ran, _) = run(Arith::Exact, &code);
        assert_eq!(ran.output, (1.0 / 3.0, false));
        assert!(ran.redone);
    }
}
