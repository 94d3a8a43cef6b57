//! The two paths both walkers share: a path that is a single point (a vertical ray, or a
//! segment clipped to length zero in the plane) and a path parallel to the rows.

use super::frame::{Follower, Frame, Span};
use crate::arith::scalar::{max, min, Scalar};
use std::ops::ControlFlow;

/// Whether the path is a single point: a vertical ray, or one clipped to length zero. Its
/// cells are all touched at once and are walked row by row, like a point.
pub fn is_point<S: Scalar>(f: &Frame<S>) -> bool {
    f.du.is_zero() || f.t0 == f.t1
}

/// Cells touching the point `(us, vs)`: up to two rows of up to two cells, row by row.
pub fn walk_point<S: Scalar>(f: &Frame<S>, follower: &mut impl Follower<S>) -> ControlFlow<()> {
    let cols = (f.us.ceil_i64() - 1, f.us.floor_i64());
    for row in f.vs.ceil_i64() - 1..=f.vs.floor_i64() {
        let span = Span {
            row,
            rows: 1,
            cols,
            t_lo: f.t0.clone(),
            t_hi: f.t1.clone(),
        };
        f.emit(span, follower)?;
    }
    ControlFlow::Continue(())
}

/// A path along a row (`dv == 0`); on a grid line it touches the rows on both sides, walked
/// together column by column. `whole_run`: one span for the whole path (runs), else one span
/// per column (cell by cell).
pub fn walk_level<S: Scalar>(
    f: &Frame<S>,
    whole_run: bool,
    follower: &mut impl Follower<S>,
) -> ControlFlow<()> {
    let on_line = f.vs.is_integer();
    let (row, rows) = if on_line {
        (f.vs.floor_i64() - 1, 2)
    } else {
        (f.vs.floor_i64(), 1)
    };
    let (first, last) = (f.us.ceil_i64() - 1, f.ue.floor_i64());
    if whole_run {
        let span = Span {
            row,
            rows,
            cols: (first, last),
            t_lo: f.t0.clone(),
            t_hi: f.t1.clone(),
        };
        return f.emit(span, follower);
    }
    for col in first.max(f.cols.0)..=last.min(f.cols.1) {
        let span = Span {
            row,
            rows,
            cols: (col, col),
            t_lo: max(f.t0.clone(), f.t_at_u(col)),
            t_hi: min(f.t1.clone(), f.t_at_u(col + 1)),
        };
        f.emit(span, follower)?;
    }
    ControlFlow::Continue(())
}
