//! The answer for one ray in the arithmetic it was traced in, as the walks leave it.

use super::counters::Counters;
use super::search::Found;

/// The answer for one ray, in the arithmetic it was traced in.
#[derive(Clone, Debug)]
pub struct ScalarTrace<S> {
    /// The hit, if any, with `t` in the traversal's arithmetic.
    pub hit: Option<Found<S>>,
    /// The queries the ray made.
    pub counters: Counters,
    /// Cells covered, in order (when asked for).
    pub cells: Vec<[usize; 2]>,
    /// A triangle test intervals could not settle was decided exactly, from a start on the
    /// surface given exactly (see [`Start::Hit`](crate::traverse::Start::Hit)).
    pub decided_exactly: bool,
}

impl<S> ScalarTrace<S> {
    /// No hit, after the queries counted.
    pub(super) fn missed(counters: Counters) -> Self {
        ScalarTrace {
            hit: None,
            counters,
            cells: Vec::new(),
            decided_exactly: false,
        }
    }
}
