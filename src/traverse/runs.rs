//! Run-based traversal (Henning & Stephenson 2004): the projected path is walked one row of
//! cells (a run) at a time, run lengths coming from the intercept recurrence.
//!
//! In the octant frame the path is `v = a*u + b` with slope `a` in `(0, 1]`. A run's
//! intercept `beta` is the path's height above the row's bottom at the right edge of the
//! run's first cell, in `(0, a]`; `beta == a` means the path entered the row exactly through
//! a lattice point. With `short = floor(1/a)`, `long = ceil(1/a)` and the threshold
//! `v = 1 - a*short`, the run advances `len = short` columns if `beta > v`, else `long`, and
//! the next intercept is `beta + a*len - 1`. The first run may be truncated (the path starts
//! inside a row); its length comes from one division.
//!
//! Cells reported per run are the closed supercover: besides the cells the path crosses, the
//! cells it touches only at a lattice point, so in exact arithmetic the walk visits exactly
//! the cells the segment touches, in order of first contact.

use super::degenerate::{is_point, walk_level, walk_point};
use super::frame::{Follower, Frame, Span};
use crate::arith::scalar::{min, Scalar};
use std::ops::ControlFlow;

/// Walks the clipped path run by run, handing each run to `follower` until it breaks.
pub fn walk<S: Scalar>(f: &Frame<S>, follower: &mut impl Follower<S>) -> ControlFlow<()> {
    if is_point(f) {
        return walk_point(f, follower);
    }
    let a = f.dv.clone() / f.du.clone();
    if a.is_zero() {
        return walk_level(f, true, follower);
    }
    let (end_col, end_row) = (f.ue.floor_i64(), f.ve.floor_i64());
    // The clipped path starts inside the grid, so exactly these are no lower than its first
    // row and column; an enclosure too wide to tell (already unsettled) may floor far below,
    // and a walk from there would count rows for ever.
    let mut row = f.vs.floor_i64().max(f.rows.0);
    let mut col = f.us.floor_i64().max(f.cols.0);
    let one = S::one();

    // The row below is touched only at the start, when the path starts on its top edge.
    if f.vs.is_integer() {
        let below = Span {
            row: row - 1,
            rows: 1,
            cols: (f.us.ceil_i64() - 1, col),
            t_lo: f.t0.clone(),
            t_hi: f.t0.clone(),
        };
        f.emit(below, follower)?;
    }

    // Run lengths and the threshold between them.
    let inverse = one.clone() / a.clone();
    let (short, long) = (inverse.floor_i64(), inverse.ceil_i64());
    let threshold = one.clone() - a.clone() * S::from_i64(short);

    // The first intercept may exceed `a`: the first run is truncated.
    let beta =
        (f.vs.clone() - S::from_i64(row)) + a.clone() * (S::from_i64(col + 1) - f.us.clone());
    let beta = beta.align_to(&a);
    let mut steps = if beta >= one {
        0
    } else {
        ((one.clone() - beta.clone()) / a.clone()).ceil_i64()
    };
    // The division may round: settle on the least step count that reaches the row's top.
    let exit_after = |k: i64| beta.clone() + a.clone() * S::from_i64(k) - one.clone();
    if exit_after(steps).is_negative() {
        // (Saturated for slopes so small the path never reaches the top: it ends first.)
        steps = steps.saturating_add(1);
    } else if steps > 0 && !exit_after(steps - 1).is_negative() {
        steps -= 1;
    }
    let exit = exit_after(steps);
    let (mut len, mut next_beta) = if exit.nearly_equal(&S::zero()) {
        (steps.saturating_add(1), a.clone())
    } else {
        (steps, exit)
    };

    let mut lo = f.us.ceil_i64() - 1;
    let mut t_lo = f.t0.clone();
    loop {
        let last_row = row >= end_row || row >= f.rows.1;
        let t_hi = if last_row {
            f.t1.clone()
        } else {
            min(f.t1.clone(), f.t_at_v(row + 1))
        };
        let span = Span {
            row,
            rows: 1,
            cols: (lo, col.saturating_add(len).min(end_col)),
            t_lo,
            t_hi: t_hi.clone(),
        };
        f.emit(span, follower)?;
        if last_row {
            return ControlFlow::Continue(());
        }
        // Step to the next run: the recurrence.
        row += 1;
        col = col.saturating_add(len);
        let beta = next_beta;
        let through_corner = beta.nearly_equal(&a);
        lo = col - i64::from(through_corner);
        len = if beta > threshold { short } else { long };
        next_beta = beta + a.clone() * S::from_i64(len) - one.clone();
        t_lo = t_hi;
    }
}
