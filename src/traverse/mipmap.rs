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

/// A point on the path: its ray parameter and frame coordinates, and whether it lies on the
/// `u` or `v` face of the block it leaves (the start lies on neither).
#[derive(Clone)]
struct Point<S> {
    t: S,
    u: S,
    v: S,
    on_u: bool,
    on_v: bool,
}

/// Walks the path block by block, handing the cells of blocks that may be hit to `search`.
pub fn walk<S: Scalar>(f: &Frame<S>, search: &mut Search<'_, S>) -> ControlFlow<()> {
    // A point or a path along a row has nothing to skip over that the run walk's single run
    // test would not skip as well.
    // A path that starts on the grid's far edge (a float segment lengthened by its rounding
    // past a corner it touches) has no block ahead: only the cells behind its start.
    let beyond = f.us.floor_i64() > f.cols.1 || f.vs.floor_i64() > f.rows.1;
    if is_point(f) || f.dv.is_zero() || beyond {
        return runs::walk(f, &mut |span| search.span(span));
    }
    let top = search.terrain.mipmap().top();
    let mut at = Point {
        t: f.t0.clone(),
        u: f.us.clone(),
        v: f.vs.clone(),
        on_u: false,
        on_v: false,
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
        let (eu, ev) = (((cu >> k) + 1) << k, ((cv >> k) + 1) << k);
        let exit = exit_point(f, &at, eu, ev);
        // The path is monotone in u and v: it ends in this block if its end lies before the
        // face it leaves through. (Compared on that face's coordinate, exact on both sides
        // when the path ends on the same face of the grid, where comparing `t` could not
        // tell the two apart in intervals.)
        let ends_inside = if exit.on_u {
            f.ue <= exit.u
        } else {
            f.ve <= exit.v
        };
        let t_hi = if ends_inside { &f.t1 } else { &exit.t };
        if k > 0 {
            let highest = search.terrain.mipmap().get(k, i >> k, j >> k);
            if search.block_may_hit(&at.t, t_hi, highest) {
                k -= 1;
                continue;
            }
        } else {
            // Only the cell's own triangles, unless the path touches other cells at an end
            // of this part that no other part covers: the ray's start (no part before it),
            // a lattice point it leaves through, or the segment's end. Cells touched where
            // this part begins were covered by the part before, or lie in a skipped block.
            let alone = !(first_part || (exit.on_u && exit.on_v) || ends_inside);
            if alone {
                search.reached(i, j);
            }
            if search.cell_may_hit(i, j, &at.t, t_hi) {
                if alone {
                    search.triangles(i, j)?;
                } else {
                    let mut part = f.clone();
                    (part.t0, part.us, part.vs) = (at.t.clone(), at.u.clone(), at.v.clone());
                    if !ends_inside {
                        (part.t1, part.ue, part.ve) =
                            (exit.t.clone(), exit.u.clone(), exit.v.clone());
                    }
                    runs::walk(&part, &mut |span| search.span(span))?;
                }
            } else if !alone {
                search.reached(i, j);
            }
        }
        if ends_inside {
            return ControlFlow::Continue(());
        }
        // Up a level only into a new parent block, or where the ray climbs: a descending
        // ray's lowest point in the parent it is still in has not changed since the parent
        // failed its test.
        let parent = (1i64 << (k + 1)) - 1;
        let new_parent = (exit.on_u && eu & parent == 0) || (exit.on_v && ev & parent == 0);
        if k < top && (new_parent || !search.dz.is_negative()) {
            k += 1;
        }
        at = exit;
        first_part = false;
    }
}

/// Where the path leaves the block whose far faces are `u = eu` and `v = ev`: on the face it
/// crosses first (both at a corner), with that coordinate exact. The other coordinate and `t`
/// are kept from falling behind `from` by rounding, so every step moves forward.
fn exit_point<S: Scalar>(f: &Frame<S>, from: &Point<S>, eu: i64, ev: i64) -> Point<S> {
    let (tu, tv) = (f.t_at_u(eu), f.t_at_v(ev));
    let at = |o: &S, d: &S, t: &S, least: &S| max(o.clone() + d.clone() * t.clone(), least.clone());
    // A path through a lattice point as far as the arithmetic can tell leaves through the
    // corner: the cells meeting there are then all tested (a float walk that picked one face
    // could leave a hole at the vertex).
    let (t, u, v, on_u, on_v) = if tu.nearly_equal(&tv) {
        (tu, S::from_i64(eu), S::from_i64(ev), true, true)
    } else if tu < tv {
        let v = at(&f.ov, &f.dv, &tu, &from.v);
        (tu, S::from_i64(eu), v, true, false)
    } else {
        let u = at(&f.ou, &f.du, &tv, &from.u);
        (tv, u, S::from_i64(ev), false, true)
    };
    Point {
        t: max(t, from.t.clone()),
        u,
        v,
        on_u,
        on_v,
    }
}
