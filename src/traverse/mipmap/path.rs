//! The path through the grid as the block walks see it: points where it leaves blocks, the
//! cell a point lies in, and a cell's part of the path.

use crate::arith::scalar::{max, Scalar};
use crate::traverse::frame::{Follower, Frame, Part, Point};
use std::ops::ControlFlow;

impl<S: Scalar> Point<S> {
    /// The start of the path, on no face.
    pub(super) fn start(f: &Frame<S>) -> Self {
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
pub(super) fn ends_inside<S: Scalar>(f: &Frame<S>, exit: &Point<S>) -> bool {
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
pub(super) fn cell_in_grid<S: Scalar>(
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
pub(super) fn on_a_grid_line<S: Scalar>(u: &S, v: &S) -> bool {
    u.is_integer() || v.is_integer()
}

impl<'a, S: Scalar> Part<'a, S> {
    /// The part of the path across frame cell `uv` from `at` to `exit` (to the path's end if
    /// `ends_inside`); `first_part`: no part of the walk came before it.
    #[inline(always)]
    pub(in crate::traverse) fn crossing(
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
    pub(in crate::traverse) fn path(&self) -> Frame<S> {
        let (at, exit) = (self.at, self.exit);
        let mut frame = self.frame.clone();
        (frame.t0, frame.us, frame.vs) = (at.t.clone(), at.u.clone(), at.v.clone());
        if !self.ends_inside {
            (frame.t1, frame.ue, frame.ve) = (exit.t.clone(), exit.u.clone(), exit.v.clone());
        }
        frame
    }

    /// The `t` where the part ends.
    pub(in crate::traverse) fn end_t(&self) -> &S {
        if self.ends_inside {
            &self.frame.t1
        } else {
            &self.exit.t
        }
    }
}

/// Where the path leaves the block whose far faces are `u = eu` and `v = ev`: on the face it
/// crosses first (both at a corner), with that coordinate exact. The other coordinate and `t`
/// are kept from falling behind `from` by rounding, so every step moves forward.
// (Inlined by hand: the run walk calls it too, and the block walk's loop needs it inline.)
#[inline(always)]
pub(super) fn exit_point<S: Scalar>(f: &Frame<S>, from: &Point<S>, eu: i64, ev: i64) -> Point<S> {
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
