//! Cell-by-cell baseline: the grid DDA of Amanatides & Woo (1987), as Musgrave used it for
//! height fields. It steps to whichever grid line the path crosses next, accumulating the
//! crossing parameters; a crossing through a lattice point also visits the two cells that
//! touch the path only there, so in exact arithmetic it visits the same cells, in the same
//! order, as the run walk.

use super::degenerate::{is_point, walk_level, walk_point};
use super::frame::{Follower, Frame, Span};
use crate::arith::scalar::{min, Scalar};
use std::cmp::Ordering;
use std::ops::ControlFlow;

fn cell<S: Scalar>(cu: i64, cv: i64, t_lo: S, t_hi: S) -> Span<S> {
    Span {
        row: cv,
        rows: 1,
        cols: (cu, cu),
        t_lo,
        t_hi,
    }
}

/// Walks the clipped path cell by cell, handing each cell to `follower` until it breaks.
pub fn walk<S: Scalar>(f: &Frame<S>, follower: &mut impl Follower<S>) -> ControlFlow<()> {
    if is_point(f) {
        return walk_point(f, follower);
    }
    if f.dv.is_zero() {
        return walk_level(f, false, follower);
    }
    // (No lower than the grid's first column and row, as in the run walk.)
    let (mut cu, mut cv) = (
        f.us.floor_i64().max(f.cols.0),
        f.vs.floor_i64().max(f.rows.0),
    );
    let t0 = f.t0.clone();

    // Cells touched only at the start point: the row below, and the cell behind.
    if f.vs.is_integer() {
        for col in f.us.ceil_i64() - 1..=cu {
            f.emit(cell(col, cv - 1, t0.clone(), t0.clone()), follower)?;
        }
    }
    if f.us.is_integer() {
        f.emit(cell(cu - 1, cv, t0.clone(), t0.clone()), follower)?;
    }

    // Parameters of the next u and v grid line crossings, and their increments.
    let (step_u, step_v) = (f.inv_du.clone(), f.inv_dv.clone());
    let (mut next_u, mut next_v) = (f.t_at_u(cu + 1), f.t_at_v(cv + 1));
    let mut t_enter = t0;
    while cu <= f.cols.1 && cv <= f.rows.1 {
        let t_exit = min(f.t1.clone(), min(next_u.clone(), next_v.clone()));
        f.emit(cell(cu, cv, t_enter, t_exit), follower)?;
        let order = if next_u.nearly_equal(&next_v) {
            Ordering::Equal
        } else {
            next_u.partial_cmp(&next_v).unwrap_or(Ordering::Equal)
        };
        let t = if order == Ordering::Greater {
            next_v.clone()
        } else {
            next_u.clone()
        };
        // Leaving the grid ends the walk whatever t1 says (when the path leaves through the
        // box side the two are equal, which rounding arithmetic cannot always tell).
        let leaves_grid = match order {
            Ordering::Less => cu + 1 > f.cols.1,
            Ordering::Greater => cv + 1 > f.rows.1,
            Ordering::Equal => cu + 1 > f.cols.1 && cv + 1 > f.rows.1,
        };
        if leaves_grid || t > f.t1 {
            break;
        }
        match order {
            Ordering::Less => {
                cu += 1;
                next_u = next_u + step_u.clone();
            }
            Ordering::Greater => {
                cv += 1;
                next_v = next_v + step_v.clone();
            }
            Ordering::Equal => {
                // Through a lattice point: the two cells touching it only there come first.
                f.emit(cell(cu + 1, cv, t.clone(), t.clone()), follower)?;
                f.emit(cell(cu, cv + 1, t.clone(), t.clone()), follower)?;
                cu += 1;
                cv += 1;
                next_u = next_u + step_u.clone();
                next_v = next_v + step_v.clone();
            }
        }
        t_enter = t;
    }
    ControlFlow::Continue(())
}
