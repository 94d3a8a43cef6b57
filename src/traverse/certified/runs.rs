//! The run walk in `f64` for exact answers: row by row, as [`crate::traverse::runs`] walks,
//! but each run's end worked out from the grid line the path leaves the row through (one
//! multiplication per run). The recurrence adds to the intercept at every run, and its
//! rounding grows along the path; this walk's points are each within [`Bounds`]' `pos` of the
//! exact path.
//!
//! A run the exact ray clears with room is passed whole, as the run test passes it in any
//! arithmetic. In a run it may touch, each cell gets the room test, and where that fails, its
//! triangles and those of the neighbours the exact path may stray into are tested exactly.
//!
//! [`Bounds`]: crate::traverse::approximation::Bounds

use super::Certifying;
use crate::arith::scalar::Scalar;
use crate::traverse::cell_log::CellLog;
use crate::traverse::frame::Frame;
use crate::traverse::span_cells::run_highest;
use std::ops::ControlFlow;

/// Walks the path run by run; breaks when the answer is known.
pub(super) fn walk<S: Scalar, C: CellLog>(
    f: &Frame<f64>,
    certifying: &mut Certifying<'_, '_, S, C>,
) -> ControlFlow<()> {
    // (The segment grown to cover the exact one may start, or lie wholly, a rounding outside
    // the grid: that bit belongs to the first row and column.)
    let mut row = (f.vs.floor() as i64).max(f.rows.0);
    let (mut t_lo, mut u_lo) = (f.t0, f.us);
    loop {
        certifying.past_hit(t_lo)?;
        let first = (u_lo.floor() as i64).max(f.cols.0);
        if row > f.rows.1 || first > f.cols.1 {
            return left_grid(f, certifying, (first, row), t_lo);
        }
        let ends = f.ve <= (row + 1) as f64;
        let (t_hi, u_hi) = if ends {
            (f.t1, f.ue)
        } else {
            // (Kept from falling behind by rounding, so that every run moves forward.)
            let t = f.t_at_v(row + 1).max(t_lo);
            (t, (f.ou + f.du * t).max(u_lo))
        };
        // The path leaves the grid through its side in this row if it goes past the last
        // column: the run ends there.
        let leaves = u_hi >= (f.cols.1 + 1) as f64 && !(ends && u_hi == (f.cols.1 + 1) as f64);
        let last = (u_hi.floor() as i64).clamp(first, f.cols.1);
        let t_end = if leaves {
            f.t_at_u(f.cols.1 + 1).clamp(t_lo, t_hi)
        } else {
            t_hi
        };
        run(f, certifying, row, (first, last), (t_lo, t_end))?;
        if leaves {
            return left_grid(f, certifying, (f.cols.1 + 1, row), t_end);
        }
        if ends {
            return ControlFlow::Continue(());
        }
        (row, t_lo, u_lo) = (row + 1, t_hi, u_hi);
    }
}

/// The run of frame row `row` over columns `cols`, while the walk's `t` runs over `window`.
fn run<S: Scalar, C: CellLog>(
    f: &Frame<f64>,
    certifying: &mut Certifying<'_, '_, S, C>,
    row: i64,
    (first, last): (i64, i64),
    (t_lo, t_hi): (f64, f64),
) -> ControlFlow<()> {
    let terrain = certifying.search.terrain;
    let highest = run_highest(terrain, f, (first, last), (row, row));
    let counter = &mut certifying.search.counters.run;
    if !certifying.bounds.may_reach(highest, (t_lo, t_hi), counter) {
        if C::RECORDS {
            (first..=last).for_each(|cu| certifying.search.cells.reached(f.cell(cu, row)));
        }
        return ControlFlow::Continue(());
    }
    // The cell's part of the run: between the column's grid lines, the run's ends at the
    // run's first and last cells (so the parts tile the run whatever the rounding). Each
    // grid line's `t` is worked out once, for the cells on both sides of it.
    let mut line = t_lo;
    for cu in first..=last {
        let from = if cu == first { t_lo } else { line.max(t_lo) };
        let to = if cu == last {
            t_hi
        } else {
            line = f.t_at_u(cu + 1);
            line.min(t_hi)
        };
        certifying.past_hit(from)?;
        let counters = &mut certifying.search.counters;
        let cell = f.cell(cu, row);
        if certifying
            .bounds
            .may_hit(terrain, 0, cell, (from, to), counters)
        {
            certifying.candidates(f, (cu, row), (from, to))?;
        } else {
            certifying.search.cells.reached(cell);
        }
    }
    ControlFlow::Continue(())
}

/// The walk's path left the grid at `t` (into frame cell `uv`, outside it) before its end,
/// the segment having been grown to cover the exact one: the exact path may still be in the
/// grid's last cells.
fn left_grid<S: Scalar, C: CellLog>(
    f: &Frame<f64>,
    certifying: &mut Certifying<'_, '_, S, C>,
    uv: (i64, i64),
    t: f64,
) -> ControlFlow<()> {
    certifying.candidates(f, uv, (t, f.t1.max(t)))
}
