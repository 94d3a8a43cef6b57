//! The octant frame: every ray is walked as if its projection went towards +u and +v with
//! slope `dv/du` in `[0, 1]`, by mirroring axes (negation, exact in every arithmetic) and
//! exchanging x and y. Cells are named by frame indices `(cu, cv)` until they are reported.

use super::search::Follower;
use crate::arith::scalar::Scalar;
use crate::geometry::Clipped;

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
