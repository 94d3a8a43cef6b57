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

use super::degenerate::is_point;
use super::frame::Frame;
use super::runs;
use super::scalar::{max, Scalar};
use super::search::Search;
use std::ops::ControlFlow;

/// A point on the path: its ray parameter and frame coordinates.
#[derive(Clone)]
struct Point<S> {
    t: S,
    u: S,
    v: S,
}

/// Walks the path block by block, handing the cells of blocks that may be hit to `search`.
pub fn walk<S: Scalar>(f: &Frame<S>, search: &mut Search<'_, S>) -> ControlFlow<()> {
    // A point or a path along a row has nothing to skip over that the run walk's single run
    // test would not skip as well.
    if is_point(f) || f.dv.is_zero() {
        return runs::walk(f, &mut |span| search.span(span));
    }
    let top = search.terrain.mipmap().top();
    let mut at = Point {
        t: f.t0.clone(),
        u: f.us.clone(),
        v: f.vs.clone(),
    };
    let mut k = top;
    let mut first_part = true;
    loop {
        search.stop_before(&at.t)?;
        // (Rounding, or an interval that cannot tell, may put a point on the grid's near
        // edge just outside it.)
        let (cu, cv) = (
            at.u.floor_i64().max(f.cols.0),
            at.v.floor_i64().max(f.rows.0),
        );
        if cu > f.cols.1 || cv > f.rows.1 {
            return ControlFlow::Continue(());
        }
        // Frame blocks are aligned like the grid's: mirroring maps multiples of 2^k to
        // multiples of 2^k.
        let (i, j) = f.cell(cu, cv);
        let exit = exit_point(f, &at, ((cu >> k) + 1) << k, ((cv >> k) + 1) << k);
        let ends_inside = exit.t >= f.t1;
        let t_hi = if ends_inside { &f.t1 } else { &exit.t };
        if k > 0 {
            let highest = search.terrain.mipmap().get(k, i >> k, j >> k);
            if search.block_may_hit(&at.t, t_hi, highest) {
                k -= 1;
                continue;
            }
        } else if search.cell_may_hit(i, j, &at.t, t_hi) {
            // Only the cell's own triangles, unless the path touches other cells at an end
            // of this part that no other part covers: the ray's start (no part before it),
            // a lattice point it leaves through, or the segment's end. Cells touched where
            // this part begins were covered by the part before, or lie in a skipped block.
            let corner_exit = exit.u.is_integer() && exit.v.is_integer();
            if first_part || corner_exit || ends_inside {
                let mut part = f.clone();
                (part.t0, part.us, part.vs) = (at.t.clone(), at.u.clone(), at.v.clone());
                if !ends_inside {
                    (part.t1, part.ue, part.ve) = (exit.t.clone(), exit.u.clone(), exit.v.clone());
                }
                runs::walk(&part, &mut |span| search.span(span))?;
            } else {
                search.reached(i, j);
                search.triangles(i, j)?;
            }
        }
        if ends_inside {
            return ControlFlow::Continue(());
        }
        at = exit;
        first_part = false;
        k = (k + 1).min(top);
    }
}

/// Where the path leaves the block whose far faces are `u = eu` and `v = ev`: on the face it
/// crosses first (both at a corner), with that coordinate exact. The other coordinate and `t`
/// are kept from falling behind `from` by rounding, so every step moves forward.
fn exit_point<S: Scalar>(f: &Frame<S>, from: &Point<S>, eu: i64, ev: i64) -> Point<S> {
    let (tu, tv) = (f.t_at_u(eu), f.t_at_v(ev));
    let at = |o: &S, d: &S, t: &S, least: &S| max(o.clone() + d.clone() * t.clone(), least.clone());
    let (t, u, v) = if tu < tv {
        let v = at(&f.ov, &f.dv, &tu, &from.v);
        (tu, S::from_i64(eu), v)
    } else if tv < tu {
        let u = at(&f.ou, &f.du, &tv, &from.u);
        (tv, u, S::from_i64(ev))
    } else {
        (tu, S::from_i64(eu), S::from_i64(ev))
    };
    Point {
        t: max(t, from.t.clone()),
        u,
        v,
    }
}
