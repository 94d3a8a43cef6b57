//! Exact answers from an `f64` walk alone: the walk skips only what the exact ray clears
//! (with the room of [`Bounds`]), and where it cannot skip, the triangles of every cell the
//! exact ray may be in are tested in the exact arithmetic. No exact walk follows it.
//!
//! Why no cell is missed: the `f64` walk's parts tile the segment in `t`. Over a part it
//! skipped, the exact ray touches nothing. Over a part in cell `c` it could not skip, the
//! exact path is within `pos` of the walk's path (per axis, at the same `t`), so in `c` or in
//! a neighbour within `pos` of it, and only while the walk's path is that near the
//! neighbour's face: for that stretch of `t` the neighbour gets the same room test as any
//! cell, and its triangles if it may be hit. A hit at `t` lies in the part whose `t` range
//! holds `t`, so once the walk is past the first hit found, nothing earlier remains.
//!
//! Each method walks in `f64` as it does in any arithmetic, with one change that keeps every
//! point within `pos`: a point is worked out from the grid line it lies on, never accumulated
//! step by step (whose rounding grows along the path). The mipmap walks its blocks; the DDA is
//! the same walk without a level above the cells; the run walk goes row by row ([`runs`]).
//!
//! Recording cells, the walk notes the cells it reaches at the cell level along its own path
//! (passed or tested) and every neighbour it considers for the exact path: each lies within
//! rounding of the exact path, though not always on it, nor in the exact walk's order.
//!
//! Which of two triangles hit at the same `t` is the answer depends on the order the cells
//! are visited in, which a neighbour tested out of the exact walk's order could change: such a
//! tie is left to the caller ([`Search::tied`]).

mod runs;

use super::approximation::{Approximation, Bounds};
use super::cell_log::CellLog;
use super::frame::{run_sample, BlockRun, Follower, Part};
use super::mipmap::descend;
use super::mipmap::run_levels::descend_runs;
use crate::arith::scalar::Scalar;
use crate::traverse::frame::{Frame, Span};
use crate::traverse::search::{Found, Search};
use std::ops::ControlFlow;

/// Searches the exact ray near `ray` for its answer, walking only in `f64` with `walk` (a
/// method's [`Walk::certify`](super::walks::Walk::certify)); breaks when the answer is known. The path must cross blocks ([`super::mipmap::has_blocks`]: a path
/// along a row or a point is left to the exact walk). `None`, before any walk, where the
/// bounds do not hold (see [`Bounds::new`]).
pub fn certify<S: Scalar, C: CellLog>(
    ray: &Approximation,
    search: &mut Search<'_, S, C>,
    walk: impl FnOnce(&Approximation, &mut Certifying<'_, '_, S, C>) -> ControlFlow<()>,
) -> Option<ControlFlow<()>> {
    let mut certifying = Certifying {
        bounds: Bounds::new(ray, search.terrain)?,
        search,
        found_before: f64::INFINITY,
        recent: [(i64::MIN, i64::MIN); RECENT],
        oldest: 0,
    };
    Some(walk(ray, &mut certifying))
}

impl<S: Scalar, C: CellLog> Certifying<'_, '_, S, C> {
    /// The block walk in `f64` (the hierarchical run walk if `runs`), from the ray's first
    /// level.
    pub(in crate::traverse) fn blocks(
        &mut self,
        ray: &Approximation,
        runs: bool,
    ) -> ControlFlow<()> {
        let top = self.search.terrain.mipmap().top();
        let level = ray.first_level(self.search.query, top);
        if runs {
            descend_runs(&ray.frame, top, level, self)
        } else {
            descend(&ray.frame, top, level, self)
        }
    }

    /// Cell by cell: the block walk with no level above the cells.
    pub(in crate::traverse) fn cells(&mut self, ray: &Approximation) -> ControlFlow<()> {
        descend(&ray.frame, 0, 0, self)
    }

    /// The run walk in `f64` ([`runs`]).
    pub(in crate::traverse) fn runs(&mut self, ray: &Approximation) -> ControlFlow<()> {
        runs::walk(&ray.frame, self)
    }
}

/// How many of the cells tested last are remembered, so as not to test them again (a
/// neighbour of one part is often the next part's cell).
const RECENT: usize = 4;

/// Follows an `f64` walk, testing the triangles of the cells the exact ray may touch.
pub(in crate::traverse) struct Certifying<'s, 'a, S, C> {
    bounds: Bounds,
    search: &'s mut Search<'a, S, C>,
    /// A `t` the first hit found so far certainly lies before (infinite while none is).
    found_before: f64,
    /// The frame cells whose triangles were tested last, in a ring.
    recent: [(i64, i64); RECENT],
    /// The ring's slot the next tested cell goes in.
    oldest: usize,
}

/// Whether a window of `t` holds any (not where an end is NaN).
fn nonempty((lo, hi): (f64, f64)) -> bool {
    lo <= hi
}

/// A `t` that the hit certainly lies before.
fn before<S: Scalar>(found: &Found<S>) -> f64 {
    match found.t.f64_enclosure() {
        Some((t, radius)) => {
            let upper = t + radius;
            upper + 1e-9 * (upper.abs() + 1.0)
        }
        None => f64::INFINITY,
    }
}

impl<S: Scalar, C: CellLog> Follower<f64> for Certifying<'_, '_, S, C> {
    fn stop_before(&mut self, t: &f64) -> ControlFlow<()> {
        self.past_hit(*t)
    }
    // (Inlined by hand, as the search's: the block walk asks at every step.)
    #[inline(always)]
    fn may_hit(&mut self, k: u32, block: (usize, usize), t_lo: &f64, t_hi: &f64) -> bool {
        let (terrain, counters) = (self.search.terrain, &mut self.search.counters);
        self.bounds
            .may_hit(terrain, k, block, (*t_lo, *t_hi), counters)
    }
    fn run_may_hit(&mut self, f: &Frame<f64>, run: &BlockRun, t_lo: &f64, t_hi: &f64) -> bool {
        let terrain = self.search.terrain;
        let highest = terrain
            .field()
            .height_of(run_sample(terrain, f, run, false));
        let counter = &mut self.search.counters.run;
        self.bounds.may_reach(highest, (*t_lo, *t_hi), counter)
    }
    fn cell(&mut self, _cell: (usize, usize), part: Part<'_, f64>) -> ControlFlow<()> {
        self.candidates(part.frame, part.uv, (part.at.t, *part.end_t()))
    }
    fn span(&mut self, _f: &Frame<f64>, _span: Span<f64>) -> ControlFlow<()> {
        unreachable!("the certifying walks hand over cells, never spans")
    }
    fn passed(&mut self, cell: (usize, usize)) {
        self.search.cells.reached(cell);
    }
    fn moves_away(&self) -> bool {
        self.bounds.moves_away()
    }
    /// The exact path may still be in the grid's last cells after the walk's path left them.
    fn left_grid(&mut self, part: Part<'_, f64>) -> ControlFlow<()> {
        self.candidates(part.frame, part.uv, (part.at.t, *part.end_t()))
    }
}

impl<S: Scalar, C: CellLog> Certifying<'_, '_, S, C> {
    /// Breaks when the first hit found lies before `t`: nothing from `t` on can come first.
    fn past_hit(&self, t: f64) -> ControlFlow<()> {
        if self.found_before < t {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }

    /// Tests the triangles of every cell the exact path may be in while the walk's path
    /// crosses frame cell `(cu, cv)` over the `t` of `span` (and may touch there): the part's
    /// own cell, which the walk found may be hit, and its neighbours the exact path may stray
    /// into. A part outside the grid has only neighbours.
    fn candidates(
        &mut self,
        f: &Frame<f64>,
        (cu, cv): (i64, i64),
        span: (f64, f64),
    ) -> ControlFlow<()> {
        // How long after the walk's path crossed a face (or before it reaches one) the exact
        // path may still be on the face's other side: twice its distance, as a `t`, with room
        // for the rounding of the crossing's `t`.
        let reach = 2.0 * self.bounds.pos;
        let slack = 2.0 * self.bounds.dt;
        let (wu, wv) = (
            reach * f.inv_du.abs() + slack,
            reach * f.inv_dv.abs() + slack,
        );
        // The `t` over which the exact path may be in the column before, this one and the
        // one after, within the part (empty unless `lo <= hi`). The same for rows.
        let cols = [
            (span.0, span.1.min(f.t_at_u(cu) + wu)),
            span,
            (span.0.max(f.t_at_u(cu + 1) - wu), span.1),
        ];
        let rows = [
            (span.0, span.1.min(f.t_at_v(cv) + wv)),
            span,
            (span.0.max(f.t_at_v(cv + 1) - wv), span.1),
        ];
        // The part's own cell first: a hit there ends the search in most neighbours.
        self.candidate(f, (cu, cv), span, true)?;
        for (a, col) in cols.into_iter().enumerate() {
            if !nonempty(col) {
                continue;
            }
            for (b, row) in rows.into_iter().enumerate() {
                let window = (col.0.max(row.0), col.1.min(row.1));
                // (Most neighbours' windows are empty: asked here, not in a call.)
                if (a, b) != (1, 1) && nonempty(window) {
                    let uv = (cu + a as i64 - 1, cv + b as i64 - 1);
                    self.candidate(f, uv, window, false)?;
                }
            }
        }
        ControlFlow::Continue(())
    }

    /// Tests the triangles of frame cell `uv` if the exact path may touch it over the `t` of
    /// `window`; `own`: the part's own cell, which the walk found may be hit.
    fn candidate(
        &mut self,
        f: &Frame<f64>,
        uv: (i64, i64),
        window: (f64, f64),
        own: bool,
    ) -> ControlFlow<()> {
        let inside = (f.cols.0..=f.cols.1).contains(&uv.0) && (f.rows.0..=f.rows.1).contains(&uv.1);
        // (Past the first hit found, nothing in the cell can come first.)
        if !inside || !nonempty(window) || window.0 > self.found_before || self.recent.contains(&uv)
        {
            return ControlFlow::Continue(());
        }
        let cell = f.cell(uv.0, uv.1);
        self.search.cells.reached(cell);
        let (terrain, counters) = (self.search.terrain, &mut self.search.counters);
        if own || self.bounds.cell_may_hit(terrain, cell, window, counters) {
            self.test(cell, uv)?;
        }
        ControlFlow::Continue(())
    }

    /// Tests the triangles of cell `(i, j)`, frame cell `uv`.
    fn test(&mut self, (i, j): (usize, usize), uv: (i64, i64)) -> ControlFlow<()> {
        self.recent[self.oldest] = uv;
        self.oldest = (self.oldest + 1) % RECENT;
        let flow = self.search.triangles(i, j);
        self.found_before = self.search.found.as_ref().map_or(f64::INFINITY, before);
        flow
    }
}
