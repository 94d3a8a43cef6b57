//! Hierarchical traversal over the max-mipmap (Tevs, Ihrke & Seidel 2008), with the run walk
//! at the bottom.
//!
//! The path is followed block by block: the largest aligned block around the current point
//! whose highest sample lies below the ray over the block's part of the path is skipped whole,
//! from the point to where the path leaves the block. A block the ray may touch is split into
//! its quarter-size children, down to single cells; the path across a cell that may be hit is
//! handed to the run walk ([`super::runs`]), which reports the cells it touches in order (the
//! closed supercover, lattice-point touches included) to the same search as every other method.
//!
//! Why skipping is exact: the surface is continuous, so over the closed block its height never
//! exceeds the block's highest sample; a ray strictly above that over the block's part of the
//! path touches no cell there, not even one meeting the block at a face or corner. Exit points
//! are snapped onto the block face they lie on, so the next block is found without rounding in
//! that coordinate, and a walk in a rounding arithmetic cannot step back into a skipped block.
//!
//! In arithmetics without rounding the walk is made in `f64`, skipping only blocks the ray
//! clears with room for every rounding it made and for the exact ray's distance from it
//! ([`Approximation`](super::approximation::Approximation)). Where it cannot skip, the
//! triangles of the cells the exact ray may be in are tested exactly
//! ([`certify`](super::certified::certify)); where two triangles are hit at the same `t`,
//! which the order of the cells decides, the `f64` walk only clears the way ([`clear_way`])
//! and an exact walk follows the stretches between the blocks it skipped.

pub(super) mod near;
mod path;
pub(super) mod run_levels;
pub(super) mod stretches;

use path::{cell_in_grid, ends_inside, exit_point};
use run_levels::descend_runs;

use super::degenerate::is_point;
use super::frame::{Follower, Frame, Levels, Part, Point};
use super::runs;
use crate::arith::scalar::Scalar;
use std::ops::ControlFlow;

/// Walks the path block by block, handing the cells of blocks that may be hit to
/// `follower`. `levels.start`: the level to start at where the caller knows better than the
/// default: 0 where the path starts next to the surface (on it, or just before a cell an `f64`
/// walk found may be hit), where every block around the start would fail its test, or the
/// level a ray's clearance names.
pub fn walk<S: Scalar>(
    f: &Frame<S>,
    follower: &mut impl Follower<S>,
    levels: Levels,
) -> ControlFlow<()> {
    if !has_blocks(f) {
        return runs::walk(f, follower);
    }
    descend(f, levels.top, levels.first(), follower)
}

/// The hierarchical run walk ([`descend_runs`]), started as [`walk`] starts the block walk.
// (Out of line: inlined beside the block walk into the trace, it would slow the block walk.)
#[inline(never)]
pub fn walk_runs<S: Scalar>(
    f: &Frame<S>,
    follower: &mut impl Follower<S>,
    levels: Levels,
) -> ControlFlow<()> {
    if !has_blocks(f) {
        return runs::walk(f, follower);
    }
    descend_runs(f, levels.top, levels.first(), follower)
}

/// Whether the path crosses blocks: a point or a path along a row has nothing to skip over
/// that the run walk's single run test would not skip as well, and a path that starts on the
/// grid's far edge (a float segment lengthened by its rounding past a corner it touches) has
/// no block ahead, only the cells behind its start.
pub fn has_blocks<S: Scalar>(f: &Frame<S>) -> bool {
    let beyond = f.us.floor_i64() > f.cols.1 || f.vs.floor_i64() > f.rows.1;
    !(is_point(f) || f.dv.is_zero() || beyond)
}

/// The block walk from level `k`, down to cells and up again (at most to `top`).
pub(super) fn descend<S: Scalar>(
    f: &Frame<S>,
    top: u32,
    mut k: u32,
    follower: &mut impl Follower<S>,
) -> ControlFlow<()> {
    let mut at = Point::start(f);
    let mut first_part = true;
    // A ray moving away moved on to a new block: whether it may move up a level there.
    let mut try_climb = false;
    loop {
        follower.stop_before(&at.t)?;
        let (cu, cv) = match cell_in_grid(f, &at, follower) {
            Ok(cell) => cell,
            Err(left) => return left,
        };
        // Frame blocks are aligned like the grid's: mirroring maps multiples of 2^k to
        // multiples of 2^k.
        let (i, j) = f.cell(cu, cv);
        // A ray moving away is nearest the samples its test compares where it is now, so the
        // parent block's test is the one it would fail or pass after moving up, asked before
        // the exit from the parent is worked out: a ray that grazes the surface does not move
        // up only to come down again.
        let mut known_clear = false;
        if std::mem::take(&mut try_climb) && k < top {
            let parent = (i >> (k + 1), j >> (k + 1));
            if !follower.may_hit(k + 1, parent, &at.t, &at.t) {
                (k, known_clear) = (k + 1, true);
            }
        }
        let (eu, ev) = (((cu >> k) + 1) << k, ((cv >> k) + 1) << k);
        let exit = exit_point(f, &at, eu, ev);
        let ends_inside = ends_inside(f, &exit);
        let t_hi = if ends_inside { &f.t1 } else { &exit.t };
        let may_hit = !known_clear && follower.may_hit(k, (i >> k, j >> k), &at.t, t_hi);
        if k > 0 && may_hit {
            k -= 1;
            continue;
        }
        if k == 0 && may_hit {
            let part = Part::crossing(f, (cu, cv), (&at, &exit), ends_inside, first_part);
            follower.cell((i, j), part)?;
        } else if k == 0 {
            follower.passed((i, j));
        }
        if ends_inside {
            return ControlFlow::Continue(());
        }
        // Up a level only into a new parent block, or where the ray moves away: otherwise
        // its nearest point in the parent it is still in has not moved since the parent
        // failed its test.
        let parent = (1i64 << (k + 1)) - 1;
        let new_parent = (exit.on_u && eu & parent == 0) || (exit.on_v && ev & parent == 0);
        if follower.moves_away() {
            try_climb = true;
        } else if k < top && new_parent {
            k += 1;
        }
        at = exit;
        first_part = false;
    }
}
