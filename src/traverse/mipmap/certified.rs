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
//! Which of two triangles hit at the same `t` is the answer depends on the order the cells
//! are visited in, which a neighbour tested out of the exact walk's order could change: such a
//! tie is left to the caller ([`Search::tied`]).

use super::approximation::{Approximation, Bounds};
use super::{descend, Follower, Part};
use crate::traverse::scalar::Scalar;
use crate::traverse::search::{Found, Search};
use std::ops::ControlFlow;

/// Searches the exact ray near `ray` for its answer, walking only in `f64`; breaks when the
/// answer is known. The path must cross blocks ([`super::has_blocks`]).
pub fn certify<S: Scalar>(ray: &Approximation, search: &mut Search<'_, S>) -> ControlFlow<()> {
    let terrain = search.terrain;
    let top = terrain.mipmap().top();
    let first = ray.first_level(search.query, top);
    let mut certifying = Certifying {
        bounds: Bounds::new(ray, terrain),
        search,
        found_before: f64::INFINITY,
        recent: [(i64::MIN, i64::MIN); RECENT],
    };
    descend(&ray.frame, top, first, &mut certifying)
}

/// How many of the cells tested last are remembered, so as not to test them again (a
/// neighbour of one part is often the next part's cell).
const RECENT: usize = 4;

/// A cell and its neighbours, as the column and row one before it (0), its own (1) or after
/// it (2); itself first.
const NEIGHBOURHOOD: [(usize, usize); 9] = [
    (1, 1),
    (0, 0),
    (0, 1),
    (0, 2),
    (1, 0),
    (1, 2),
    (2, 0),
    (2, 1),
    (2, 2),
];

/// Follows an `f64` walk, testing the triangles of the cells the exact ray may touch.
struct Certifying<'s, 'a, S> {
    bounds: Bounds,
    search: &'s mut Search<'a, S>,
    /// A `t` the first hit found so far certainly lies before (infinite while none is).
    found_before: f64,
    /// The frame cells whose triangles were tested last, the latest first.
    recent: [(i64, i64); RECENT],
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

impl<S: Scalar> Follower<f64> for Certifying<'_, '_, S> {
    fn stop_before(&mut self, t: &f64) -> ControlFlow<()> {
        if self.found_before < *t {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
    // (Inlined by hand, as the search's.)
    #[inline(always)]
    fn may_hit(&mut self, k: u32, block: (usize, usize), t_lo: &f64, t_hi: &f64) -> bool {
        let (terrain, counters) = (self.search.terrain, &mut self.search.counters);
        self.bounds
            .may_hit(terrain, k, block, (*t_lo, *t_hi), counters)
    }
    fn cell(&mut self, _cell: (usize, usize), part: Part<'_, f64>) -> ControlFlow<()> {
        self.candidates(&part)
    }
    fn passed(&mut self, _cell: (usize, usize)) {}
    fn climbs(&self) -> bool {
        self.bounds.climbs()
    }
    /// The exact path may still be in the grid's last cells after the walk's path left them.
    fn left_grid(&mut self, part: Part<'_, f64>) -> ControlFlow<()> {
        self.candidates(&part)
    }
}

impl<S: Scalar> Certifying<'_, '_, S> {
    /// Tests the triangles of every cell the exact path may be in over `part` (and may touch
    /// there): the part's own cell, which the walk found may be hit, and its neighbours the
    /// exact path may stray into. A part outside the grid has only neighbours.
    fn candidates(&mut self, part: &Part<'_, f64>) -> ControlFlow<()> {
        let f = part.frame;
        let (cu, cv) = part.uv;
        let span = (part.at.t, *part.end_t());
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
        // one after, within the part; `None` where it cannot be there. The same for rows.
        let within = |lo: f64, hi: f64| {
            let (lo, hi) = (lo.max(span.0), hi.min(span.1));
            (lo <= hi).then_some((lo, hi))
        };
        let (all, inf) = (f64::NEG_INFINITY, f64::INFINITY);
        let cols = [
            within(all, f.t_at_u(cu) + wu),
            within(all, inf),
            within(f.t_at_u(cu + 1) - wu, inf),
        ];
        let rows = [
            within(all, f.t_at_v(cv) + wv),
            within(all, inf),
            within(f.t_at_v(cv + 1) - wv, inf),
        ];
        // The part's own cell first: a hit there ends the search in most neighbours.
        for (a, b) in NEIGHBOURHOOD {
            let (Some(col), Some(row)) = (cols[a], rows[b]) else {
                continue;
            };
            let (nu, nv) = (cu + a as i64 - 1, cv + b as i64 - 1);
            let inside = (f.cols.0..=f.cols.1).contains(&nu) && (f.rows.0..=f.rows.1).contains(&nv);
            let (lo, hi) = (col.0.max(row.0), col.1.min(row.1));
            // (Past the first hit found, nothing in the cell can come first.)
            if !inside || lo > hi || lo > self.found_before || self.recent.contains(&(nu, nv)) {
                continue;
            }
            let cell = f.cell(nu, nv);
            // (The walk tested the part's own cell.)
            let own = (a, b) == (1, 1);
            let (terrain, counters) = (self.search.terrain, &mut self.search.counters);
            if own || self.bounds.may_hit(terrain, 0, cell, (lo, hi), counters) {
                self.test(cell, (nu, nv))?;
            }
        }
        ControlFlow::Continue(())
    }

    /// Tests the triangles of cell `(i, j)`, frame cell `uv`.
    fn test(&mut self, (i, j): (usize, usize), uv: (i64, i64)) -> ControlFlow<()> {
        self.recent.rotate_right(1);
        self.recent[0] = uv;
        let flow = self.search.triangles(i, j);
        self.found_before = self.search.found.as_ref().map_or(f64::INFINITY, before);
        flow
    }
}
