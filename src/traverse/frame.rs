//! The octant frame: every ray is walked as if its projection went towards +u and +v with
//! slope `dv/du` in `[0, 1]`, by mirroring axes (negation, exact in every arithmetic) and
//! exchanging x and y. Cells are named by frame indices `(cu, cv)` until they are reported. A
//! ray comes into its frame clipped to the terrain's box ([`clip`]).

use crate::arith::scalar::Scalar;
use crate::geometry::{clip_to_box, Clipped};
use crate::heightfield::Terrain;
use std::ops::ControlFlow;

/// A span of cells the walk reached, in visiting order: one row of cells (`rows == 1`), or
/// two rows walked side by side column by column when the path runs along the grid line
/// between them (`rows == 2`: rows `row` and `row + 1`). `t_lo..=t_hi` is the part of the ray
/// inside the span's rows.
#[derive(Clone, Debug)]
pub struct Span<S> {
    pub row: i64,
    pub rows: u8,
    pub cols: (i64, i64),
    pub t_lo: S,
    pub t_hi: S,
}

/// The clipped ray in frame coordinates.
#[derive(Clone, Debug)]
pub struct Frame<S> {
    /// Frame u is the original y (else x).
    pub swap: bool,
    /// The original axis that became u (v) is mirrored.
    pub flip_u: bool,
    pub flip_v: bool,
    pub ou: S,
    pub ov: S,
    pub du: S,
    pub dv: S,
    /// `1/du` and `1/dv` (zero where the component is zero: never used then).
    pub inv_du: S,
    pub inv_dv: S,
    /// The clipped segment `[t0, t1]` and its end points.
    pub t0: S,
    pub t1: S,
    pub us: S,
    pub vs: S,
    pub ue: S,
    pub ve: S,
    /// Valid frame cell indices, inclusive.
    pub cols: (i64, i64),
    pub rows: (i64, i64),
}

impl<S: Scalar> Frame<S> {
    /// `o`, `d` in the ray's arithmetic; `d_f64` chooses the octant identically in all of them;
    /// `(t0, t1)` is the clip range; `size` is the sample grid's (W, H).
    // (Inlined by hand: once per ray, and its result is large.)
    #[inline(always)]
    pub fn new(
        o: &[S; 3],
        d: &[S; 3],
        d_f64: [f64; 3],
        clipped: Clipped<S>,
        size: (usize, usize),
    ) -> Self {
        let Clipped {
            t0,
            t1,
            entry_face,
            exit_face,
        } = clipped;
        let swap = d_f64[1].abs() > d_f64[0].abs();
        let (ku, kv) = if swap { (1, 0) } else { (0, 1) };
        let (flip_u, flip_v) = (d_f64[ku] < 0.0, d_f64[kv] < 0.0);
        let mirror = |x: S, flip: bool| if flip { -x } else { x };
        let ou = mirror(o[ku].clone(), flip_u);
        let ov = mirror(o[kv].clone(), flip_v);
        let du = mirror(d[ku].clone(), flip_u);
        let dv = mirror(d[kv].clone(), flip_v);
        let at = |o: &S, d: &S, t: &S| o.clone() + d.clone() * t.clone();
        let (mut us, mut vs) = (at(&ou, &du, &t0), at(&ov, &dv, &t0));
        let (mut ue, mut ve) = (at(&ou, &du, &t1), at(&ov, &dv, &t1));
        // An end on a side of the box lies exactly on that side.
        for (face, u, v) in [
            (entry_face, &mut us, &mut vs),
            (exit_face, &mut ue, &mut ve),
        ] {
            match face {
                Some((axis, value)) if axis == ku => *u = mirror(value, flip_u),
                Some((axis, value)) if axis == kv => *v = mirror(value, flip_v),
                _ => {}
            }
        }
        let cells = |n: usize, flip: bool| {
            let n = n as i64 - 1;
            if flip {
                (-n, -1)
            } else {
                (0, n - 1)
            }
        };
        let inverse = |x: &S| {
            if x.is_zero() {
                S::zero()
            } else {
                S::one() / x.clone()
            }
        };
        let (inv_du, inv_dv) = (inverse(&du), inverse(&dv));
        let (nu, nv) = if swap {
            (size.1, size.0)
        } else {
            (size.0, size.1)
        };
        Frame {
            swap,
            flip_u,
            flip_v,
            ou,
            ov,
            du,
            dv,
            inv_du,
            inv_dv,
            t0,
            t1,
            us,
            vs,
            ue,
            ve,
            cols: cells(nu, flip_u),
            rows: cells(nv, flip_v),
        }
    }

    /// The same path from `t` on (`t` within the segment).
    fn start_at(&mut self, t: S) {
        self.us = self.ou.clone() + self.du.clone() * t.clone();
        self.vs = self.ov.clone() + self.dv.clone() * t.clone();
        self.t0 = t;
    }

    /// The same path up to `t` (`t` within the segment).
    fn end_at(&mut self, t: S) {
        self.ue = self.ou.clone() + self.du.clone() * t.clone();
        self.ve = self.ov.clone() + self.dv.clone() * t.clone();
        self.t1 = t;
    }

    /// The part of the path from `from` to `to`, given in `f64` with room for the rounding of
    /// the segment's ends (an end beyond the segment's keeps the segment's); `None` if the
    /// part lies wholly outside the segment.
    pub fn stretch(&self, from: f64, to: f64) -> Option<Self> {
        let mut part = self.clone();
        part.keep(from, to).then_some(part)
    }

    /// [`Frame::stretch`] in place: `false` (the frame left as it was) if the part lies
    /// wholly outside the segment.
    // (In place: a frame is large, and each ray's is cut once or twice before its walk.)
    pub fn keep(&mut self, from: f64, to: f64) -> bool {
        let (t0, t1) = (self.t0.to_f64(), self.t1.to_f64());
        if to < t0 || from > t1 {
            return false;
        }
        if from > t0 {
            self.start_at(S::from_f64(from));
        }
        if to < t1 {
            self.end_at(S::from_f64(to));
        }
        true
    }

    /// The original cell `(i, j)` of frame cell `(cu, cv)` (which must be valid).
    pub fn cell(&self, cu: i64, cv: i64) -> (usize, usize) {
        let unmirror = |c: i64, flip: bool| (if flip { -c - 1 } else { c }) as usize;
        let (a, b) = (unmirror(cu, self.flip_u), unmirror(cv, self.flip_v));
        if self.swap {
            (b, a)
        } else {
            (a, b)
        }
    }

    /// The ray parameter where the path crosses the grid line `u = k` (`du` non-zero).
    pub fn t_at_u(&self, k: i64) -> S {
        (S::from_i64(k) - self.ou.clone()) * self.inv_du.clone()
    }

    /// The ray parameter where the path crosses the grid line `v = k` (`dv` non-zero).
    pub fn t_at_v(&self, k: i64) -> S {
        (S::from_i64(k) - self.ov.clone()) * self.inv_dv.clone()
    }

    /// Clamps a span to the grid and hands it to `follower`; empty spans are dropped.
    pub fn emit(
        &self,
        mut span: Span<S>,
        follower: &mut impl Follower<S>,
    ) -> std::ops::ControlFlow<()> {
        let (lo, hi) = (span.cols.0.max(self.cols.0), span.cols.1.min(self.cols.1));
        let first = span.row.max(self.rows.0);
        let last = (span.row + i64::from(span.rows) - 1).min(self.rows.1);
        if lo > hi || first > last {
            return std::ops::ControlFlow::Continue(());
        }
        span.cols = (lo, hi);
        span.row = first;
        span.rows = (last - first + 1) as u8;
        follower.span(self, span)
    }
}

/// The ray clipped to the terrain's box, in the octant frame.
pub(super) fn clip<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
) -> Option<Frame<S>> {
    let (lo, hi) = terrain.bounds();
    clip_to(
        terrain,
        o,
        d,
        dir_f64,
        lo.map(S::from_f64),
        hi.map(S::from_f64),
    )
}

/// The ray clipped to the terrain's box grown by `grow` (positive) on every side.
pub(super) fn clip_grown<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    grow: [f64; 3],
) -> Option<Frame<S>> {
    let (lo, hi) = terrain.bounds();
    // Rounded outwards: the grown box contains every point within `grow` of the box. (In
    // straight code: an array's `map` goes out of line here.)
    let low = |k: usize| S::from_f64((lo[k] - grow[k]).next_down());
    let high = |k: usize| S::from_f64((hi[k] + grow[k]).next_up());
    let (lo, hi) = ([low(0), low(1), low(2)], [high(0), high(1), high(2)]);
    clip_to(terrain, o, d, dir_f64, lo, hi)
}

/// The ray clipped to the box `[lo, hi]` around the terrain.
#[inline(always)]
fn clip_to<S: Scalar>(
    terrain: &Terrain,
    o: &[S; 3],
    d: &[S; 3],
    dir_f64: [f64; 3],
    lo: [S; 3],
    hi: [S; 3],
) -> Option<Frame<S>> {
    let mut clipped = clip_to_box(o, d, &lo, &hi)?;
    // Floats lengthen the segment by their own rounding, so that the last cells before a box
    // face (flat ground at the lowest height) are not cut off.
    clipped.t1 = clipped.t1.past_rounding();
    let field = terrain.field();
    Some(Frame::new(
        o,
        d,
        dir_f64,
        clipped,
        (field.width(), field.height()),
    ))
}

/// What every walk asks of whoever follows it: the block walks ask for their block, run and
/// cell tests and hand over the cells they cannot skip; the run walk and the DDA hand over
/// spans of cells ([`Follower::span`]).
pub(in crate::traverse) trait Follower<S: Scalar> {
    /// Breaks when nothing at or after `t` can change the answer.
    fn stop_before(&mut self, t: &S) -> ControlFlow<()>;
    /// Whether block `(bi, bj)` of level `k` (a cell when `k` is 0) may be touched by the
    /// path over `[t_lo, t_hi]`.
    fn may_hit(&mut self, k: u32, block: (usize, usize), t_lo: &S, t_hi: &S) -> bool;
    /// Whether a run of blocks of frame `f` may be touched by the path over `[t_lo, t_hi]`
    /// (the hierarchical run walk, [`descend_runs`](super::mipmap::run_levels::descend_runs)). By default every run may be (a
    /// follower of the block walk only, which never asks).
    fn run_may_hit(&mut self, _f: &Frame<S>, _run: &BlockRun, _t_lo: &S, _t_hi: &S) -> bool {
        true
    }
    /// A cell that may be hit, crossed from `at` to `exit` (to the path's end if
    /// `ends_inside`); `alone`: no other cell touches that part where no other part covers
    /// it, so the cell's own triangles are all there is to test.
    fn cell(&mut self, cell: (usize, usize), part: Part<'_, S>) -> ControlFlow<()>;
    /// A span of cells of frame `f` in visiting order, from the walks that go row by row
    /// or cell by cell ([`super::runs`], [`super::dda`]), which the block walks end in.
    fn span(&mut self, f: &Frame<S>, span: Span<S>) -> ControlFlow<()>;
    /// A cell the walk passed by at level 0 without testing its triangles.
    fn passed(&mut self, cell: (usize, usize));
    /// Whether the ray moves away from the samples its block test compares it with (or keeps
    /// level): the highest samples when it climbs above the surface, the lowest when it
    /// descends under it. Then its nearest point to them in a block is where the walk is, and
    /// moves as the walk moves through the block.
    fn moves_away(&self) -> bool;
    /// The path left the grid before its end, at the start of `part` (a path lengthened by
    /// rounding, or grown to cover an exact ray near it); by default nothing is left to do.
    fn left_grid(&mut self, _part: Part<'_, S>) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

/// A point on the path: its ray parameter and frame coordinates, the frame cell they floor
/// to, and whether it lies on the `u` or `v` face of the block it leaves (the start lies on
/// neither).
// (The cell is kept with the point, so that the tests of a descent do not work its two
// floors out again.)
#[derive(Clone)]
pub(in crate::traverse) struct Point<S> {
    pub t: S,
    pub(in crate::traverse) u: S,
    pub(in crate::traverse) v: S,
    pub(in crate::traverse) cell: (i64, i64),
    pub(in crate::traverse) on_u: bool,
    pub(in crate::traverse) on_v: bool,
}

/// A cell's part of the path.
pub(in crate::traverse) struct Part<'a, S> {
    pub frame: &'a Frame<S>,
    /// The cell in frame indices.
    pub uv: (i64, i64),
    pub at: &'a Point<S>,
    pub(in crate::traverse) exit: &'a Point<S>,
    pub(in crate::traverse) ends_inside: bool,
    pub(in crate::traverse) alone: bool,
}

/// A run of the hierarchical run walk: the level-`k` blocks (cells at level 0) in frame row
/// of blocks `row` over frame columns of blocks `blocks` (inclusive).
pub(in crate::traverse) struct BlockRun {
    pub k: u32,
    pub row: i64,
    pub blocks: (i64, i64),
}

/// The highest sample of a run's blocks, or with `lowest` a lower bound of their samples
/// ([`crate::heightfield::Mipmap::lowest`]).
// (Inlined by hand, and a plain loop rather than an iterator's fold: it is most of a run
// test. Block by block: most runs hold one or two blocks, too few for a reduction over slices
// to pay.)
#[inline(always)]
pub(in crate::traverse) fn run_sample<S: Scalar>(
    terrain: &Terrain,
    f: &Frame<S>,
    &BlockRun { k, row, blocks }: &BlockRun,
    lowest: bool,
) -> u16 {
    let mipmap = terrain.mipmap();
    let mut extreme = if lowest { u16::MAX } else { 0 };
    for col in blocks.0..blocks.1 + 1 {
        // Any frame cell of a frame block names the block: mirroring maps multiples of 2^k
        // to multiples of 2^k (a block's first frame cell may lie past a mirrored grid's
        // edge, in the block all the same).
        let (i, j) = f.cell(col << k, row << k);
        let (bi, bj) = (i >> k, j >> k);
        let sample = match (k, lowest) {
            (0, _) => {
                let (lo, hi) = terrain.cell_sample_range(bi, bj);
                if lowest {
                    lo
                } else {
                    hi
                }
            }
            (_, true) => mipmap.lowest(k, bi, bj),
            (_, false) => mipmap.highest(k, bi, bj),
        };
        extreme = if lowest {
            extreme.min(sample)
        } else {
            extreme.max(sample)
        };
    }
    extreme
}

/// How high a hierarchical walk may climb (the mipmap's top level) and, where the caller
/// knows better than the default, the level it starts at.
#[derive(Clone, Copy, Debug)]
pub(in crate::traverse) struct Levels {
    pub top: u32,
    pub start: Option<u32>,
}

impl Levels {
    /// The level the walk starts at: [`first_level`], or lower where the caller knows better.
    pub fn first(self) -> u32 {
        let first = first_level(self.top);
        self.start.map_or(first, |k| k.min(first))
    }
}

/// Blocks an eighth of the grid wide: the two levels above them seldom pass a test (the ray
/// is inside the box, so the top block always fails), and climbing is cheap.
fn first_level(top: u32) -> u32 {
    top.saturating_sub(3)
}
