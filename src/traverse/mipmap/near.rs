//! The near walk: the first cells of a path walked one by one, with no level above the cells,
//! where the path starts next to where it may touch (a camera ray from its wedge's
//! clearance). Over a few cells a climb up the mipmap costs more than it skips.
//!
//! It hands each cell to the same tests as the block walk at level 0 ([`Search::cell_may_hit`],
//! [`Search::triangles`]), each crossing worked out from its grid line as the block walk's
//! [`exit_point`](super::exit_point) does, so it reaches the same answer. Where the block walk would hand a part to the run walk instead (a part
//! leaving through a lattice point, a path ending on a grid line, a start on one, a point
//! outside the grid), the near walk stops before that part and the block walk takes the
//! rest of the path from there.

use super::path::on_a_grid_line;
use crate::arith::scalar::Scalar;
use crate::traverse::cell_log::CellLog;
use crate::traverse::frame::Frame;
use crate::traverse::frame::Point;
use crate::traverse::options::WalkOptions;
use crate::traverse::search::Search;

/// How many cells the near walk takes before the block walk takes over: about as far as
/// a camera ray's wedge clearance or a shadow ray's start leaves to the first cells it may
/// touch (16 or more cost more than the climbs they save).
pub(in crate::traverse) const NEAR_CELLS: u32 = 8;

/// Whether a walk of `f` with `options` starts with the near walk: a hierarchical method's
/// first-hit ray from a clearance (`cleared`), in `f64`. (Occlusion rays from the surface
/// gain nothing from it: their first cells are mostly tested whole, and their walks are
/// short already.)
pub(in crate::traverse) fn starts_near<S: Scalar>(
    options: &WalkOptions,
    cleared: bool,
    f: &Frame<S>,
) -> bool {
    options.near
        && S::as_f64s::<0>(&[]).is_some()
        && options.method.is_hierarchical()
        && cleared
        && super::has_blocks(f)
}

/// Where the near walk left the path.
pub(in crate::traverse) enum Near<S> {
    /// The search has its answer, or the path ended.
    Done,
    /// The rest of the path, from this point on, is for the block walk.
    From(Point<S>),
}

/// Walks the first `cells` cells of `f` one by one; see the module's docs. The path must
/// cross blocks ([`super::has_blocks`]), in `f64` ([`starts_near`]): the walk reads the
/// frame's numbers as `f64`, each crossing `t` from its grid line as [`Frame::t_at_u`] does.
#[inline(always)]
pub(in crate::traverse) fn near_walk<S: Scalar, C: CellLog>(
    f: &Frame<S>,
    search: &mut Search<'_, S, C>,
    cells: u32,
) -> Near<S> {
    let start = Point::start(f);
    if on_a_grid_line(&start.u, &start.v) {
        return Near::From(start);
    }
    let [ou, ov, iu, iv, t_end] = [&f.ou, &f.ov, &f.inv_du, &f.inv_dv, &f.t1].map(S::to_f64);
    let t_at = |k: i64, o: f64, inverse: f64| (k as f64 - o) * inverse;
    let (mut cu, mut cv) = start.cell;
    let mut t = start.t.to_f64();
    let (mut tu, mut tv) = (t_at(cu + 1, ou, iu), t_at(cv + 1, ov, iv));
    // The last grid line crossed: `u` (else `v`); none before the first cell.
    let mut crossed_u = None;
    let resume = |t: f64, cu: i64, cv: i64, crossed_u: Option<bool>| {
        let along = |o: &S, d: &S| o.clone() + d.clone() * S::from_f64(t);
        let (u, v) = match crossed_u {
            None => return Near::From(Point::start(f)),
            Some(true) => (S::from_i64(cu), along(&f.ov, &f.dv)),
            Some(false) => (along(&f.ou, &f.du), S::from_i64(cv)),
        };
        Near::From(Point {
            t: S::from_f64(t),
            u,
            v,
            cell: (cu, cv),
            on_u: crossed_u == Some(true),
            on_v: crossed_u == Some(false),
        })
    };
    for _ in 0..cells {
        let t_lo = S::from_f64(t);
        if search.stop_before(&t_lo).is_break() {
            return Near::Done;
        }
        if cu < f.cols.0 || cu > f.cols.1 || cv < f.rows.0 || cv > f.rows.1 {
            return resume(t, cu, cv, crossed_u);
        }
        // Where the block walk would see a lattice point or the path's end on a face, it
        // takes over (with room beyond its own tolerance, see `Scalar::nearly_equal`).
        let exit = tu.min(tv);
        let near = |a: f64, b: f64| (a - b).abs() <= 4e-9 * a.abs().max(b.abs()).max(1.0);
        if near(tu, tv)
            || near(exit, t_end)
            || t.partial_cmp(&exit) != Some(std::cmp::Ordering::Less)
        {
            return resume(t, cu, cv, crossed_u);
        }
        let ends_inside = t_end < exit;
        let t_hi = S::from_f64(if ends_inside { t_end } else { exit });
        let (i, j) = f.cell(cu, cv);
        let may_hit = search.cell_may_hit(i, j, &t_lo, &t_hi);
        search.reached(i, j);
        if may_hit && search.triangles(i, j).is_break() {
            return Near::Done;
        }
        if ends_inside {
            return Near::Done;
        }
        t = exit;
        if tu < tv {
            (cu, crossed_u) = (cu + 1, Some(true));
            tu = t_at(cu + 1, ou, iu);
        } else {
            (cv, crossed_u) = (cv + 1, Some(false));
            tv = t_at(cv + 1, ov, iv);
        }
    }
    resume(t, cu, cv, crossed_u)
}

impl<S: Scalar> Frame<S> {
    /// The same path from `at` on (a point of the path).
    pub(in crate::traverse) fn resume(&mut self, at: Point<S>) {
        (self.t0, self.us, self.vs) = (at.t, at.u, at.v);
    }
}
