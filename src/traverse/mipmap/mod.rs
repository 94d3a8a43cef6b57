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

mod near;
mod run_levels;
mod stretches;

pub(super) use near::{near_walk, starts_near, Near, NEAR_CELLS};

pub(super) use run_levels::{descend_runs, run_sample, BlockRun};
pub use stretches::clear_way;

use super::cell_log::CellLog;
use super::degenerate::is_point;
use super::frame::{Frame, Span};
use super::runs;
use super::search::{Follower, Search};
use crate::arith::scalar::{max, Scalar};
use std::ops::ControlFlow;

/// A point on the path: its ray parameter and frame coordinates, the frame cell they floor
/// to, and whether it lies on the `u` or `v` face of the block it leaves (the start lies on
/// neither).
// (The cell is kept with the point, so that the tests of a descent do not work its two
// floors out again.)
#[derive(Clone)]
pub(super) struct Point<S> {
    pub t: S,
    u: S,
    v: S,
    cell: (i64, i64),
    on_u: bool,
    on_v: bool,
}

/// A cell's part of the path.
pub(super) struct Part<'a, S> {
    pub frame: &'a Frame<S>,
    /// The cell in frame indices.
    pub uv: (i64, i64),
    pub at: &'a Point<S>,
    exit: &'a Point<S>,
    ends_inside: bool,
    alone: bool,
}

/// Walks the path block by block, handing the cells of blocks that may be hit to `search`.
/// `level`: the level to start at where the caller knows better than the default: 0 where the
/// path starts next to the surface (on it, or just before a cell an `f64` walk found may be
/// hit), where every block around the start would fail its test, or the level a ray's
/// clearance names.
pub fn walk<S: Scalar, C: CellLog>(
    f: &Frame<S>,
    search: &mut Search<'_, S, C>,
    level: Option<u32>,
) -> ControlFlow<()> {
    walk_with(f, search, level, |f, top, k, search| {
        descend(f, top, k, search)
    })
}

/// The hierarchical run walk ([`descend_runs`]), started as [`walk`] starts the block walk.
// (Out of line: inlined beside the block walk into the trace, it would slow the block walk.)
#[inline(never)]
pub fn walk_runs<S: Scalar, C: CellLog>(
    f: &Frame<S>,
    search: &mut Search<'_, S, C>,
    level: Option<u32>,
) -> ControlFlow<()> {
    walk_with(f, search, level, |f, top, k, search| {
        descend_runs(f, top, k, search)
    })
}

/// Starts a hierarchical walk (`descend` from its start level), or the run walk where the
/// path crosses no blocks.
#[inline(always)]
fn walk_with<'a, S: Scalar, C: CellLog>(
    f: &Frame<S>,
    search: &mut Search<'a, S, C>,
    level: Option<u32>,
    descend: impl FnOnce(&Frame<S>, u32, u32, &mut Search<'a, S, C>) -> ControlFlow<()>,
) -> ControlFlow<()> {
    if !has_blocks(f) {
        return runs::walk(f, search);
    }
    let top = search.terrain.mipmap().top();
    descend(f, top, start_level(top, level), search)
}

/// The level a walk starts at: [`first_level`], or lower where the caller knows better.
pub(super) fn start_level(top: u32, level: Option<u32>) -> u32 {
    let first = first_level(top);
    level.map_or(first, |k| k.min(first))
}

/// Blocks an eighth of the grid wide: the two levels above them seldom pass a test (the ray
/// is inside the box, so the top block always fails), and climbing is cheap.
fn first_level(top: u32) -> u32 {
    top.saturating_sub(3)
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

impl<S: Scalar> Point<S> {
    /// The start of the path, on no face.
    fn start(f: &Frame<S>) -> Self {
        Point {
            t: f.t0.clone(),
            u: f.us.clone(),
            v: f.vs.clone(),
            cell: (f.us.floor_i64(), f.vs.floor_i64()),
            on_u: false,
            on_v: false,
        }
    }
}

/// Whether the path ends before `exit`, the point where it leaves a block. The path is
/// monotone in u and v: it ends in the block if its end lies before the face it leaves
/// through. (Compared on that face's coordinate, exact on both sides when the path ends on the
/// same face of the grid, where comparing `t` could not tell the two apart in intervals.)
#[inline(always)]
fn ends_inside<S: Scalar>(f: &Frame<S>, exit: &Point<S>) -> bool {
    if exit.on_u {
        f.ue <= exit.u
    } else {
        f.ve <= exit.v
    }
}

/// The frame cell of `at`, or, where the path has left the grid there, what the follower
/// makes of that. (Rounding, or an interval that cannot tell, may put a point on the grid's
/// near edge just outside it: it is in the first row or column.)
#[inline(always)]
fn cell_in_grid<S: Scalar>(
    f: &Frame<S>,
    at: &Point<S>,
    follower: &mut impl Follower<S>,
) -> Result<(i64, i64), ControlFlow<()>> {
    let (cu, cv) = (at.cell.0.max(f.cols.0), at.cell.1.max(f.rows.0));
    if cu > f.cols.1 || cv > f.rows.1 {
        return Err(follower.left_grid(Part {
            frame: f,
            uv: (cu, cv),
            at,
            exit: at,
            ends_inside: true,
            alone: false,
        }));
    }
    Ok((cu, cv))
}

/// Whether a point lies on a grid line: else it touches one cell only.
fn on_a_grid_line<S: Scalar>(u: &S, v: &S) -> bool {
    u.is_integer() || v.is_integer()
}

impl<'a, S: Scalar> Part<'a, S> {
    /// The part of the path across frame cell `uv` from `at` to `exit` (to the path's end if
    /// `ends_inside`); `first_part`: no part of the walk came before it.
    #[inline(always)]
    fn crossing(
        frame: &'a Frame<S>,
        uv: (i64, i64),
        (at, exit): (&'a Point<S>, &'a Point<S>),
        ends_inside: bool,
        first_part: bool,
    ) -> Self {
        // Cells touched where this part begins were covered by the part before, or lie in a
        // skipped block; others are touched at the ray's start (no part before it, and the
        // start on a grid line as the run walk tells it: a shadow ray's start mostly lies off
        // them, and is tested alone), at a lattice point it leaves through, or at the
        // segment's end.
        let touched_at_start = first_part && on_a_grid_line(&at.u, &at.v);
        let alone = !(touched_at_start || (exit.on_u && exit.on_v) || ends_inside);
        Part {
            frame,
            uv,
            at,
            exit,
            ends_inside,
            alone,
        }
    }

    /// The part as a path of its own, for the run walk across it.
    pub(super) fn path(&self) -> Frame<S> {
        let (at, exit) = (self.at, self.exit);
        let mut frame = self.frame.clone();
        (frame.t0, frame.us, frame.vs) = (at.t.clone(), at.u.clone(), at.v.clone());
        if !self.ends_inside {
            (frame.t1, frame.ue, frame.ve) = (exit.t.clone(), exit.u.clone(), exit.v.clone());
        }
        frame
    }

    /// The `t` where the part ends.
    pub(super) fn end_t(&self) -> &S {
        if self.ends_inside {
            &self.frame.t1
        } else {
            &self.exit.t
        }
    }
}

impl<S: Scalar, C: CellLog> Follower<S> for Search<'_, S, C> {
    fn stop_before(&mut self, t: &S) -> ControlFlow<()> {
        Search::stop_before(self, t)
    }
    // Inlined by hand: a call costs a fifth of the walk's time, and whether the compiler
    // inlines it by itself depends on unrelated code elsewhere in the crate.
    #[inline(always)]
    fn may_hit(&mut self, k: u32, (bi, bj): (usize, usize), t_lo: &S, t_hi: &S) -> bool {
        if k == 0 {
            self.cell_may_hit(bi, bj, t_lo, t_hi)
        } else {
            let may_hit = self.block_may_hit(k, (bi, bj), t_lo, t_hi);
            if may_hit {
                self.terrain.fetch_below(k, bi, bj);
            }
            may_hit
        }
    }
    fn run_may_hit(&mut self, f: &Frame<S>, run: &BlockRun, t_lo: &S, t_hi: &S) -> bool {
        self.blocks_run_may_hit(f, run, t_lo, t_hi)
    }
    // (Inlined by hand too: the run walk calls it as well, and out of line it would slow the
    // block walk.)
    #[inline(always)]
    fn cell(&mut self, (i, j): (usize, usize), part: Part<'_, S>) -> ControlFlow<()> {
        if part.alone {
            self.reached(i, j);
            return self.triangles(i, j);
        }
        runs::walk(&part.path(), self)
    }
    #[inline(always)]
    fn span(&mut self, f: &Frame<S>, span: Span<S>) -> ControlFlow<()> {
        Search::span(self, f, span)
    }
    fn passed(&mut self, (i, j): (usize, usize)) {
        self.reached(i, j);
    }
    fn moves_away(&self) -> bool {
        self.moves_away
    }
}

/// Where the path leaves the block whose far faces are `u = eu` and `v = ev`: on the face it
/// crosses first (both at a corner), with that coordinate exact. The other coordinate and `t`
/// are kept from falling behind `from` by rounding, so every step moves forward.
// (Inlined by hand: the run walk calls it too, and the block walk's loop needs it inline.)
#[inline(always)]
fn exit_point<S: Scalar>(f: &Frame<S>, from: &Point<S>, eu: i64, ev: i64) -> Point<S> {
    let (tu, tv) = (f.t_at_u(eu), f.t_at_v(ev));
    let at = |o: &S, d: &S, t: &S, least: &S| max(o.clone() + d.clone() * t.clone(), least.clone());
    // A path through a lattice point as far as the arithmetic can tell leaves through the
    // corner: the cells meeting there are then all tested (a float walk that picked one face
    // could leave a hole at the vertex).
    let (t, u, v, cell, on_u, on_v) = if tu.nearly_equal(&tv) {
        (tu, S::from_i64(eu), S::from_i64(ev), (eu, ev), true, true)
    } else if tu < tv {
        let v = at(&f.ov, &f.dv, &tu, &from.v);
        let cv = v.floor_i64();
        (tu, S::from_i64(eu), v, (eu, cv), true, false)
    } else {
        let u = at(&f.ou, &f.du, &tv, &from.u);
        let cu = u.floor_i64();
        (tv, u, S::from_i64(ev), (cu, ev), false, true)
    };
    Point {
        t: max(t, from.t.clone()),
        u,
        v,
        cell,
        on_u,
        on_v,
    }
}
