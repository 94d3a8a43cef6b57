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
//! In arithmetics without rounding, an `f64` walk clears the way ([`clear_way`]): it skips only
//! blocks the ray clears with room for every rounding it made and for the exact ray's distance
//! from it, so the exact walk follows only the stretches between (from just before the first
//! cell that may be hit, for a camera ray).

use super::counters::Counters;
use super::degenerate::is_point;
use super::frame::Frame;
use super::runs;
use super::scalar::{max, Scalar, F64_TOLERANCE};
use super::search::Search;
use super::Query;
use crate::heightfield::Terrain;
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

/// What the block walk asks of whoever follows it.
trait Follower<S: Scalar> {
    /// Breaks when nothing at or after `t` can change the answer.
    fn stop_before(&mut self, t: &S) -> ControlFlow<()>;
    /// Whether block `(bi, bj)` of level `k` (a cell when `k` is 0) may be touched by the
    /// path over `[t_lo, t_hi]`.
    fn may_hit(&mut self, k: u32, block: (usize, usize), t_lo: &S, t_hi: &S) -> bool;
    /// A cell that may be hit, crossed from `at` to `exit` (to the path's end if
    /// `ends_inside`); `alone`: no other cell touches that part where no other part covers
    /// it, so the cell's own triangles are all there is to test.
    fn cell(&mut self, cell: (usize, usize), part: Part<'_, S>) -> ControlFlow<()>;
    /// A cell the walk passed by at level 0 without testing its triangles.
    fn passed(&mut self, cell: (usize, usize));
    /// Whether the ray climbs (or is level): then its lowest point in a block changes as the
    /// walk moves through the block.
    fn climbs(&self) -> bool;
}

/// A cell's part of the path.
struct Part<'a, S> {
    frame: &'a Frame<S>,
    at: &'a Point<S>,
    exit: &'a Point<S>,
    ends_inside: bool,
    alone: bool,
}

/// Walks the path block by block, handing the cells of blocks that may be hit to `search`.
/// `level`: the level to start at where the caller knows better than the default: 0 where the
/// path starts next to the surface (on it, or just before a cell an `f64` walk found may be
/// hit), where every block around the start would fail its test, or the level of blocks a
/// beam around the ray found may be touched.
pub fn walk<S: Scalar>(
    f: &Frame<S>,
    search: &mut Search<'_, S>,
    level: Option<u32>,
) -> ControlFlow<()> {
    if !has_blocks(f) {
        return runs::walk(f, &mut |span| search.span(span));
    }
    let top = search.terrain.mipmap().top();
    descend(f, top, start_level(top, level), search)
}

/// The level a walk starts at: [`first_level`], or lower where the caller knows better.
fn start_level(top: u32, level: Option<u32>) -> u32 {
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
fn has_blocks<S: Scalar>(f: &Frame<S>) -> bool {
    let beyond = f.us.floor_i64() > f.cols.1 || f.vs.floor_i64() > f.rows.1;
    !(is_point(f) || f.dv.is_zero() || beyond)
}

/// The block walk from level `k`, down to cells and up again (at most to `top`).
fn descend<S: Scalar>(
    f: &Frame<S>,
    top: u32,
    mut k: u32,
    follower: &mut impl Follower<S>,
) -> ControlFlow<()> {
    let mut at = Point {
        t: f.t0.clone(),
        u: f.us.clone(),
        v: f.vs.clone(),
        on_u: false,
        on_v: false,
    };
    let mut first_part = true;
    // A climbing ray moved on to a new block: whether it may move up a level there.
    let mut try_climb = false;
    loop {
        follower.stop_before(&at.t)?;
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
        // A climbing ray is lowest where it is now, so the parent block's test is the one it
        // would fail or pass after moving up, asked before the exit from the parent is worked
        // out: a ray that grazes the surface does not move up only to come down again.
        let mut known_clear = false;
        if std::mem::take(&mut try_climb) && k < top {
            let parent = (i >> (k + 1), j >> (k + 1));
            if !follower.may_hit(k + 1, parent, &at.t, &at.t) {
                (k, known_clear) = (k + 1, true);
            }
        }
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
        let may_hit = !known_clear && follower.may_hit(k, (i >> k, j >> k), &at.t, t_hi);
        if k > 0 && may_hit {
            k -= 1;
            continue;
        }
        if k == 0 && may_hit {
            // Cells touched where this part begins were covered by the part before, or lie
            // in a skipped block; others are touched at the ray's start (no part before it),
            // at a lattice point it leaves through, or at the segment's end.
            let alone = !(first_part || (exit.on_u && exit.on_v) || ends_inside);
            let part = Part {
                frame: f,
                at: &at,
                exit: &exit,
                ends_inside,
                alone,
            };
            follower.cell((i, j), part)?;
        } else if k == 0 {
            follower.passed((i, j));
        }
        if ends_inside {
            return ControlFlow::Continue(());
        }
        // Up a level only into a new parent block, or where the ray climbs: a descending
        // ray's lowest point in the parent it is still in has not changed since the parent
        // failed its test.
        let parent = (1i64 << (k + 1)) - 1;
        let new_parent = (exit.on_u && eu & parent == 0) || (exit.on_v && ev & parent == 0);
        if follower.climbs() {
            try_climb = true;
        } else if k < top && new_parent {
            k += 1;
        }
        at = exit;
        first_part = false;
    }
}

impl<S: Scalar> Follower<S> for Search<'_, S> {
    fn stop_before(&mut self, t: &S) -> ControlFlow<()> {
        Search::stop_before(self, t)
    }
    // Inlined by hand: LLVM's choice flips with unrelated code elsewhere in the crate, and
    // the call costs a fifth of the walk's time.
    #[inline(always)]
    fn may_hit(&mut self, k: u32, (bi, bj): (usize, usize), t_lo: &S, t_hi: &S) -> bool {
        if k == 0 {
            self.cell_may_hit(bi, bj, t_lo, t_hi)
        } else {
            let highest = self.terrain.mipmap().get(k, bi, bj);
            self.block_may_hit(t_lo, t_hi, highest)
        }
    }
    fn cell(&mut self, (i, j): (usize, usize), part: Part<'_, S>) -> ControlFlow<()> {
        if part.alone {
            self.reached(i, j);
            return self.triangles(i, j);
        }
        let (at, exit) = (part.at, part.exit);
        let mut frame = part.frame.clone();
        (frame.t0, frame.us, frame.vs) = (at.t.clone(), at.u.clone(), at.v.clone());
        if !part.ends_inside {
            (frame.t1, frame.ue, frame.ve) = (exit.t.clone(), exit.u.clone(), exit.v.clone());
        }
        runs::walk(&frame, &mut |span| self.span(span))
    }
    fn passed(&mut self, (i, j): (usize, usize)) {
        self.reached(i, j);
    }
    fn climbs(&self) -> bool {
        !self.dz.is_negative()
    }
}

/// A stretch of the path that may touch the surface, as an `f64` walk found it: `t` from
/// `from` to `to`, and the room to leave around it.
#[derive(Clone, Copy, Debug)]
pub struct Stretch {
    pub from: f64,
    pub to: f64,
    /// Far more than the rounding of any `t` the `f64` walk computed and than the exact
    /// ray's distance from its path (divided by the smaller direction component, as a `t`):
    /// an exact walk from `from - margin` to `to + margin` starts and ends inside blocks the
    /// `f64` walk skipped (or cells it found may be hit), clear of the faces between them.
    pub margin: f64,
}

impl Stretch {
    /// The stretch with room around it, from..to.
    pub fn widened(&self) -> (f64, f64) {
        (self.from - self.margin, self.to + self.margin)
    }
}

/// An `f64` ray near an exact one, for an `f64` walk to clear the way for it.
pub struct Approximation {
    /// Its frame, covering the exact ray's segment.
    pub frame: Frame<f64>,
    pub oz: f64,
    pub dz: f64,
    /// How far the exact origin may be from this ray's, per axis (the direction is the same).
    pub radius: [f64; 3],
    /// The level to start at where it is known better than the default (a beam's).
    pub level: Option<u32>,
}

/// Walks the `f64` ray near one traced in an arithmetic without rounding, and hands each
/// [`Stretch`] of the path that may touch the surface, in order, to `search`; breaks when
/// `search` does. Between the stretches the exact ray touches nothing, so an exact walk only
/// follows the stretches: the approach to the first hit, and what lies between the places a
/// shadow ray grazes the surface, are left to the `f64` walk. For a first-hit query the first
/// stretch runs to the segment's end: a camera ray mostly hits where it first may, and
/// measured, its exact walk is faster on from there than an `f64` walk gathering more
/// stretches.
///
/// The exact ray is `o + t*d` with `d` an `f64` and `o` within `radius` (per axis) of the
/// `f64` origin. The walk skips blocks only where the ray stays above them with room for that
/// and for every rounding it made: the positions (within `pos` of the exact path), the `t` of
/// block faces (within `dt`) and the heights along the ray (within `z_err`). The surface rises
/// at most `max_slope` per unit of horizontal distance, so beyond a block by `pos` it is at
/// most that much higher.
pub fn clear_way(
    ray: &Approximation,
    terrain: &Terrain,
    query: Query,
    counters: &mut Counters,
    search: &mut impl FnMut(Stretch) -> ControlFlow<()>,
) -> ControlFlow<()> {
    let (f, oz, dz, radius) = (&ray.frame, ray.oz, ray.dz, ray.radius);
    if !has_blocks(f) {
        return search(Stretch {
            from: f64::NEG_INFINITY,
            to: f64::INFINITY,
            margin: 0.0,
        });
    }
    let eps = f64::EPSILON;
    let t_max = f.t1.abs().max(f.t0.abs());
    let d_xy = f.du.abs().max(f.dv.abs());
    // Face crossings `(k - o) * (1/d)` carry three roundings; clip ends as many.
    let dt = 4.0 * eps * t_max + f64::MIN_POSITIVE;
    let coords = f.ou.abs().max(f.ov.abs()) + d_xy * t_max;
    // Two axes, each off by its own rounding and by the face crossing's `dt`; the tested
    // span lengthened by `dt` at both ends moves as far again. An exit within the `f64`
    // tolerance of a corner is snapped onto it (`exit_point`): as far off as that tolerance.
    // The exact origin is off by its radius.
    let snap = F64_TOLERANCE * t_max.max(1.0) * d_xy;
    let off = radius[0].max(radius[1]);
    let pos = 2.0 * (4.0 * eps * coords + d_xy * dt) + 2.0 * d_xy * dt + 2.0 * snap + off;
    let rise = terrain.max_slope() * (1.0 + 1e-9) * pos;
    let z_err = 4.0 * eps * (oz.abs() + dz.abs() * t_max) + dz.abs() * dt + radius[2];
    let mut clearing = Clearing {
        terrain,
        dz,
        oz,
        room: (z_err + rise) * (1.0 + 1e-6),
        counters,
        // (`has_blocks`: neither component is zero.)
        off_faces: 4.0 * (off + 4.0 * eps * coords) / f.du.abs().min(f.dv.abs()),
        first_only: query == Query::FirstHit,
        stretch: None,
        search,
    };
    let top = terrain.mipmap().top();
    // A shadow ray starts on the surface, where every block around it fails its test.
    let first = if query == Query::Shadow {
        0
    } else {
        start_level(top, ray.level)
    };
    descend(f, top, first, &mut clearing)?;
    clearing.flush()
}

/// The most cells a stretch gathers before it is searched.
const STRETCH_CELLS: u32 = 4;

/// Follows an `f64` walk, gathering the parts of cells that may be hit into stretches.
struct Clearing<'a, F> {
    terrain: &'a Terrain,
    oz: f64,
    dz: f64,
    /// What the ray must clear a block's highest sample by.
    room: f64,
    counters: &'a mut Counters,
    /// The `t` that moves the exact path off a face it may lie on as far as intervals tell.
    off_faces: f64,
    /// Hand the search only one stretch, from the first cell that may be hit to the end.
    first_only: bool,
    /// The stretch gathered since the last skipped block, and its cells.
    stretch: Option<(Stretch, u32)>,
    search: &'a mut F,
}

impl<F: FnMut(Stretch) -> ControlFlow<()>> Clearing<'_, F> {
    /// Hands the stretch gathered to the search.
    fn flush(&mut self) -> ControlFlow<()> {
        match self.stretch.take() {
            Some((stretch, _)) => (self.search)(stretch),
            None => ControlFlow::Continue(()),
        }
    }
}

impl<F: FnMut(Stretch) -> ControlFlow<()>> Follower<f64> for Clearing<'_, F> {
    fn stop_before(&mut self, t: &f64) -> ControlFlow<()> {
        // The walk moved on past the stretch and its room: a block was skipped since.
        match self.stretch {
            Some((stretch, _)) if *t > stretch.to + 2.0 * stretch.margin => self.flush(),
            _ => ControlFlow::Continue(()),
        }
    }
    // (Inlined by hand, as the search's.)
    #[inline(always)]
    fn may_hit(&mut self, k: u32, (bi, bj): (usize, usize), t_lo: &f64, t_hi: &f64) -> bool {
        let highest = self.terrain.block_max_sample(k, bi, bj);
        let highest = self.terrain.field().height_of(highest);
        let t = if self.dz < 0.0 { *t_hi } else { *t_lo };
        let lowest = self.oz + self.dz * t;
        // The comparison's own operands are rounded too.
        let room = self.room + 4.0 * f64::EPSILON * (lowest.abs() + highest.abs());
        self.counters.block.record(lowest - room <= highest)
    }
    fn cell(&mut self, _cell: (usize, usize), part: Part<'_, f64>) -> ControlFlow<()> {
        let to = if part.ends_inside {
            part.frame.t1
        } else {
            part.exit.t
        };
        let (from, cells) = match self.stretch {
            Some((stretch, cells)) => (stretch.from, cells + 1),
            None => (part.at.t, 1),
        };
        let margin = 1e-9 * (from.abs().max(to.abs()) + 1.0) + self.off_faces;
        if self.first_only {
            let rest = Stretch {
                to: f64::INFINITY,
                ..Stretch { from, to, margin }
            };
            (self.search)(rest)?;
            return ControlFlow::Break(());
        }
        self.stretch = Some((Stretch { from, to, margin }, cells));
        // A long stretch is searched before it ends: past a hit the ray runs inside the
        // terrain, where every block fails its test, to the end of the segment.
        if cells >= STRETCH_CELLS {
            return self.flush();
        }
        ControlFlow::Continue(())
    }
    fn passed(&mut self, _cell: (usize, usize)) {}
    fn climbs(&self) -> bool {
        self.dz >= 0.0
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
