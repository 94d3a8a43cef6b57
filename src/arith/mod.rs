// (The summary line of this module's docs is its `pub mod` line in lib.rs; the empty line
// below starts the rest as a paragraph of its own.)
//!
//! The [`Scalar`](crate::arith::Scalar) trait and its kinds: `f32`, `f64`,
//! [`Interval`](crate::arith::Interval), bounded [`Rational`](crate::arith::Rational) and
//! [`Exact`](crate::arith::Exact), with the error-free dyadic sums and products exact mode
//! builds on, and the [`Arith`](crate::arith::Arith) a user picks. Nothing here knows about
//! rays or terrain: geometry and the traversals are generic over these numbers.

mod dispatch;
pub(crate) mod dyadic;
mod exact;
mod interval;
mod order;
mod rational;
mod rounding;
pub mod scalar;
mod simd;

pub use dispatch::{run, with_numbers, Generic, Numbers, Plain, Ran, Settling, WithNumbers};
pub use exact::Exact;
pub use interval::{settled, unsettled, Interval};
pub use order::{larger, smaller};
pub use rational::{with_bound, Rational, RationalEvents, DEFAULT_BOUND};
pub use scalar::Scalar;
pub use simd::{SimdPath, UnknownSimdPath, SIMD_VARIABLE};

use std::fmt;
use std::str::FromStr;

/// The arithmetic a traversal computes in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arith {
    /// Single-precision floats: inputs rounded to `f32`.
    F32,
    /// Double-precision floats.
    F64,
    /// Fractions with denominators at most `bound` (num-rational `Ratio<i64>` sized).
    Rational {
        /// The largest denominator.
        bound: u32,
    },
    /// No rounding at all: the surface contract's answer ([`crate::geometry`]) for the given
    /// `f64` inputs.
    Exact,
}

impl fmt::Display for Arith {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Arith::F32 => f.write_str("f32"),
            Arith::F64 => f.write_str("f64"),
            Arith::Rational { bound } => write!(f, "rational:{bound}"),
            Arith::Exact => f.write_str("exact"),
        }
    }
}

/// A name that is not an arithmetic's.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown arithmetic '{0}': use f32, f64, rational, rational:BOUND (1..=2^30) or exact")]
pub struct UnknownArith(pub String);

impl FromStr for Arith {
    type Err = UnknownArith;
    /// `f32`, `f64`, `exact`, `rational` (bound 2^16) or `rational:BOUND`.
    fn from_str(s: &str) -> Result<Self, UnknownArith> {
        match s {
            "f32" => Ok(Arith::F32),
            "f64" => Ok(Arith::F64),
            "exact" => Ok(Arith::Exact),
            "rational" => Ok(Arith::Rational {
                bound: DEFAULT_BOUND,
            }),
            _ => {
                let bound = s
                    .strip_prefix("rational:")
                    .and_then(|b| b.parse::<u32>().ok())
                    .filter(|&b| (1..=1 << 30).contains(&b));
                bound
                    .map(|bound| Arith::Rational { bound })
                    .ok_or_else(|| UnknownArith(s.to_owned()))
            }
        }
    }
}
