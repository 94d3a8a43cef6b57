//! The short walk's path across the grid: its cells one by one, or a block of them at once.

use crate::arith::{larger, smaller};
use crate::geometry::RaySpace;
use crate::heightfield::Terrain;

/// The finest mipmap level whose blocks the walk skips where the ray passes above their
/// highest sample: no cell of such a block passes its cell test, so the answer is the same.
pub(super) const SKIP_LEVEL: u32 = 2;

/// Whether two crossings are too close for their order to be trusted: the near walk's rule.
/// (Crossings are never NaN, so plain comparisons pick the larger: `f64::max`'s care for NaN
/// would cost the walk's loop more than the rest of the rule.)
#[inline(always)]
pub(super) fn nearly(a: f64, b: f64) -> bool {
    (a - b).abs() <= 4e-9 * larger(larger(a.abs(), b.abs()), 1.0)
}

/// A path across the grid in its octant frame (`u` the horizontal axis it moves along most,
/// both axes mirrored to increase, see [`Frame`](super::super::frame::Frame)), at one cell, which it
/// also holds as the index of the cell's first sample, so that a step is an addition.
pub(super) struct Path {
    /// The ray, and its space for the triangle tests, made when a cell first needs them.
    pub(super) o: [f64; 3],
    pub(super) d: [f64; 3],
    ray: Option<RaySpace<f64>>,
    swap: bool,
    flip: [bool; 2],
    o_u: f64,
    o_v: f64,
    inverse_u: f64,
    inverse_v: f64,
    /// The frame cell `(cu, cv)`, and the ray parameter where the path entered it.
    cu: i64,
    cv: i64,
    pub(super) t: f64,
    /// Where the path crosses the next grid line of `u` and of `v`.
    pub(super) next_u: f64,
    pub(super) next_v: f64,
    /// The cell's first sample, and how far that moves with a step along `u` and along `v`.
    pub(super) index: usize,
    stride_u: isize,
    stride_v: isize,
    /// Steps left along `u` and `v` before the path leaves the grid.
    left_u: u32,
    left_v: u32,
}

impl Path {
    /// The path of `o + t*d` from `t = from` (its point there off every grid line by far
    /// more than rounding), else from `t = 0`; `None` where it starts on a grid line or
    /// outside the grid.
    pub(super) fn new(terrain: &Terrain, o: [f64; 3], d: [f64; 3], from: f64) -> Option<Self> {
        Path::starting(terrain, o, d, from, true)
    }

    /// The path of `o + t*d` from `t = from > 0`, its point there off every grid line by far
    /// more than rounding and inside the grid; `None` otherwise.
    pub(super) fn from(terrain: &Terrain, o: [f64; 3], d: [f64; 3], from: f64) -> Option<Self> {
        Path::starting(terrain, o, d, from, false)
    }

    /// [`Path::new`], or [`Path::from`] where `or_origin` is `false`.
    #[inline(always)]
    fn starting(
        terrain: &Terrain,
        o: [f64; 3],
        d: [f64; 3],
        from: f64,
        or_origin: bool,
    ) -> Option<Self> {
        let swap = d[1].abs() > d[0].abs();
        let (ku, kv) = if swap { (1, 0) } else { (0, 1) };
        let flip = [d[ku] < 0.0, d[kv] < 0.0];
        let mirror = |x: f64, flip: bool| if flip { -x } else { x };
        let start = [mirror(o[ku], flip[0]), mirror(o[kv], flip[1])];
        let dir = [mirror(d[ku], flip[0]), mirror(d[kv], flip[1])];
        let later = [0, 1].map(|k| start[k] + dir[k] * from);
        // (A point this far from the grid lines lies in the cell whose lines' crossings,
        // worked out as `step` does, come before and after `from`.)
        let off_lines = |x: [f64; 2]| {
            x.iter().all(|&x| {
                let part = (x - x as i64 as f64).abs();
                smaller(part, 1.0 - part) > 1e-9 * larger(x.abs(), 1.0)
            })
        };
        let (point, t) = match from > 0.0 && off_lines(later) {
            true => (later, from),
            false if or_origin => (start, 0.0),
            false => return None,
        };
        // (Casts, not `fract` and `floor`, which are library calls on the baseline target;
        // the point lies on the grid, far inside the range of `i64`.)
        let whole = point.map(|x| x as i64);
        if (0..2).any(|k| whole[k] as f64 == point[k]) {
            return None;
        }
        let field = terrain.field();
        let w = field.width();
        let size = [w - 1, field.height() - 1];
        let n = if swap { [size[1], size[0]] } else { size };
        let inverse = dir.map(|x| if x == 0.0 { 0.0 } else { 1.0 / x });
        let cell = [0, 1].map(|k| whole[k] - i64::from(whole[k] as f64 > point[k]));
        // The original index along each frame axis, and the steps left before the last.
        let along = [0, 1].map(|k| unmirror(cell[k], flip[k]));
        let mut left = [0u32; 2];
        for k in 0..2 {
            let last = n[k] as i64 - 1;
            if along[k] < 0 || along[k] > last {
                return None;
            }
            let steps = if flip[k] { along[k] } else { last - along[k] };
            left[k] = u32::try_from(steps).ok()?;
        }
        let (i, j) = if swap {
            (along[1], along[0])
        } else {
            (along[0], along[1])
        };
        let stride = |axis: usize, flip: bool| {
            let unit = if axis == 0 { 1 } else { w as isize };
            if flip {
                -unit
            } else {
                unit
            }
        };
        let crossing = |k: usize| {
            if inverse[k] == 0.0 {
                f64::INFINITY
            } else {
                ((cell[k] + 1) as f64 - start[k]) * inverse[k]
            }
        };
        Some(Path {
            o,
            d,
            ray: None,
            swap,
            flip,
            o_u: start[0],
            o_v: start[1],
            inverse_u: inverse[0],
            inverse_v: inverse[1],
            cu: cell[0],
            cv: cell[1],
            t,
            next_u: crossing(0),
            next_v: crossing(1),
            index: j as usize * w + i as usize,
            stride_u: stride(ku, flip[0]),
            stride_v: stride(kv, flip[1]),
            left_u: left[0],
            left_v: left[1],
        })
    }

    /// The ray's space for the triangle tests.
    pub(super) fn ray_space(&mut self) -> &RaySpace<f64> {
        let (o, d) = (self.o, self.d);
        self.ray.get_or_insert_with(|| RaySpace::new(o, d, d))
    }

    /// Whether the path leaves its cell through a corner, or too near one to tell.
    #[inline(always)]
    pub(super) fn at_lattice_point(&self) -> bool {
        nearly(self.next_u, self.next_v)
    }

    /// The original cell `(i, j)` the path is in.
    pub(super) fn cell(&self) -> (usize, usize) {
        let (a, b) = (
            unmirror(self.cu, self.flip[0]) as usize,
            unmirror(self.cv, self.flip[1]) as usize,
        );
        if self.swap {
            (b, a)
        } else {
            (a, b)
        }
    }

    /// The block of mipmap level `level` the cell lies in (original indices).
    pub(super) fn block(&self, level: u32) -> (usize, usize) {
        let (i, j) = self.cell();
        (i >> level, j >> level)
    }

    /// Where the path leaves the cell's block of mipmap level `level`: the first crossing of
    /// the block's far edge along `u` or `v`, from the grid line as [`Path::step`] finds it,
    /// with the axis it crosses (`u` or not) and the edge's frame coordinate there.
    #[inline(always)]
    pub(super) fn block_exit(&self, level: u32) -> (f64, bool, i64) {
        let last = (1i64 << level) - 1;
        let line = |c: i64, flip: bool| {
            // The frame coordinate of the block's far edge: its original cells count down
            // where the axis is mirrored.
            if flip {
                -(unmirror(c, true) & !last)
            } else {
                (c | last) + 1
            }
        };
        let crossing = |line: i64, o: f64, inverse: f64| {
            if inverse == 0.0 {
                f64::INFINITY
            } else {
                (line as f64 - o) * inverse
            }
        };
        let (line_u, line_v) = (line(self.cu, self.flip[0]), line(self.cv, self.flip[1]));
        let (t_u, t_v) = (
            crossing(line_u, self.o_u, self.inverse_u),
            crossing(line_v, self.o_v, self.inverse_v),
        );
        // (Ties go to `u`, as `step` takes them.)
        if t_v < t_u {
            (t_v, false, line_v)
        } else {
            (t_u, true, line_u)
        }
    }

    /// Moves to the first cell past the block the path leaves at `t_exit` across the edge at
    /// `line` of axis `u` (`through_u`) or `v` (see [`Path::block_exit`]): the cell
    /// [`Path::step`] would reach, found from the other axis' grid lines with the same
    /// arithmetic; `None` where the path leaves through a corner, or too near one to tell, or
    /// off the grid.
    #[inline(always)]
    pub(super) fn leave_block(&mut self, t_exit: f64, through_u: bool, line: i64) -> Option<()> {
        let (c, o, inverse) = match through_u {
            true => (self.cv, self.o_v, self.inverse_v),
            false => (self.cu, self.o_u, self.inverse_u),
        };
        // Where the path leaves cell `c` of the other axis.
        let far = |c: i64| ((c + 1) as f64 - o) * inverse;
        let mut other = c;
        if inverse != 0.0 {
            // A first guess from the position, then the grid lines decide, as `step` does:
            // the path has crossed every line of the other axis it reaches before `t_exit`.
            let guess = (o + t_exit / inverse) as i64 - 1;
            other = guess.max(c);
            while other > c && far(other - 1) >= t_exit {
                other -= 1;
            }
            while far(other) < t_exit {
                other += 1;
            }
            if nearly(far(other), t_exit) || (other > c && nearly(far(other - 1), t_exit)) {
                return None;
            }
        }
        let (new_u, new_v) = if through_u {
            (line, other)
        } else {
            (other, line)
        };
        let (steps_u, steps_v) = (new_u - self.cu, new_v - self.cv);
        self.left_u = self.left_u.checked_sub(u32::try_from(steps_u).ok()?)?;
        self.left_v = self.left_v.checked_sub(u32::try_from(steps_v).ok()?)?;
        self.index = self.index.wrapping_add_signed(
            steps_u as isize * self.stride_u + steps_v as isize * self.stride_v,
        );
        self.cu = new_u;
        self.cv = new_v;
        self.t = t_exit;
        // (An axis the path runs along never crosses a line: its crossing stays infinite.)
        let next = |c: i64, o: f64, inverse: f64| match inverse == 0.0 {
            true => f64::INFINITY,
            false => ((c + 1) as f64 - o) * inverse,
        };
        self.next_u = next(self.cu, self.o_u, self.inverse_u);
        self.next_v = next(self.cv, self.o_v, self.inverse_v);
        Some(())
    }

    /// Moves into the next cell; `None` where that lies off the grid. (A crossing is worked
    /// out from its grid line, as the near walk does, not added up.)
    #[inline(always)]
    pub(super) fn step(&mut self) -> Option<()> {
        if self.next_v < self.next_u {
            self.left_v = self.left_v.checked_sub(1)?;
            self.t = self.next_v;
            self.cv += 1;
            self.next_v = ((self.cv + 1) as f64 - self.o_v) * self.inverse_v;
            self.index = self.index.wrapping_add_signed(self.stride_v);
        } else {
            self.left_u = self.left_u.checked_sub(1)?;
            self.t = self.next_u;
            self.cu += 1;
            self.next_u = ((self.cu + 1) as f64 - self.o_u) * self.inverse_u;
            self.index = self.index.wrapping_add_signed(self.stride_u);
        }
        Some(())
    }
}

/// A frame cell's index along its original axis.
fn unmirror(c: i64, flip: bool) -> i64 {
    if flip {
        -c - 1
    } else {
        c
    }
}
