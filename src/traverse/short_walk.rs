//! The short walk: an `f64` occlusion ray that needs looking at only up to a reach a few cells
//! away (where the sun's strip bounds or the sky's bounds prove it clear beyond), walked cell
//! by cell from its start, without the frame, search record and hierarchy a long walk sets up.
//!
//! It asks each cell the block walk's own questions at level 0, in the same arithmetic and
//! from the same numbers: the segment ends where [`clip`](super::frame::clip) and the reach
//! end it, heights are moved by the same [`slack`], the cell test compares the same heights
//! ([`Search::cell_may_hit`](super::search::Search::cell_may_hit)) and the triangles are
//! tested in the same lanes with the same ray space. It visits every cell the path crosses
//! (each crossing worked out from its grid line, as the near walk does), so it tests every
//! triangle the block walk would: where the block walk skips a block, its cells fail their
//! cell tests too. Where the walks could part (a start on a grid line, a crossing through a
//! lattice point, an end on a grid line, a path leaving the grid or found under the surface,
//! a long reach) it gives the ray back, and the full walk answers it.

use super::search::slack;
use super::Counters;
use crate::arith::SimdPath;
use crate::geometry::RaySpace;
use crate::heightfield::Terrain;

/// The most cells a short walk crosses; a ray whose reach may take it further is walked down
/// the hierarchy, which skips more than it costs over such a distance.
const MOST_CELLS: f64 = 6.0;

/// An occlusion ray from `o` towards `d` (the start not counting), asked only up to `reach`,
/// its own triangle `start_triangle` left untested: `Some` whether it touches the surface, with
/// its queries, or `None` where the full walk must answer it.
#[inline]
pub(super) fn short_walk(
    terrain: &Terrain,
    o: [f64; 3],
    d: [f64; 3],
    reach: f64,
    start_triangle: Option<((usize, usize), u8)>,
) -> Option<(bool, Counters)> {
    let across = reach * (d[0].abs() + d[1].abs());
    if across.is_nan() || across > MOST_CELLS || reach < 0.0 {
        return None;
    }
    let t_end = segment_end(terrain, o, d)?.min(reach);
    let path = Path::new(terrain, o, d)?;
    let ray = RaySpace::new(o, d, d);
    // The block walk's margins: heights along the ray moved down where compared with a
    // highest sample, up where with a lowest.
    let slack = slack(&o[2], &d[2], &t_end);
    let (oz_low, oz_high) = if slack > 0.0 {
        (o[2] - slack, o[2] + slack)
    } else {
        (o[2], o[2])
    };
    let field = terrain.field();
    let mut counters = Counters::default();
    counters.bbox.record(true);
    let mut walk = path;
    loop {
        let (t_lo, t_exit) = (walk.t, walk.exit());
        if walk.at_lattice_point() || nearly(t_exit, t_end) || t_lo >= t_exit {
            return None;
        }
        let ends_inside = t_end < t_exit;
        let t_hi = if ends_inside { t_end } else { t_exit };
        let (i, j) = walk.cell()?;
        let (lowest, highest) = terrain.cell_sample_range(i, j);
        let (t_low_point, t_high_point) = if d[2] < 0.0 {
            (t_hi, t_lo)
        } else {
            (t_lo, t_hi)
        };
        if oz_high + d[2] * t_high_point < field.height_of(lowest) {
            // Under the surface: the block walk changes its tests there.
            return None;
        }
        let may_hit = oz_low + d[2] * t_low_point <= field.height_of(highest);
        if counters.cell.record(may_hit) && !field.is_hole_cell(i, j) {
            let heights = terrain.corner_heights(i, j);
            let hits = ray.cell_in_lanes(SimdPath::active(), (i, j), heights)?;
            for (triangle, hit) in (0u8..2).zip(hits) {
                if start_triangle == Some(((i, j), triangle)) {
                    continue;
                }
                // A hit counts where the ray touches the triangle after its start (as the
                // search's rule has it, a NaN is not before it).
                let counts =
                    hit.is_some_and(|hit| hit.t_last.is_none_or(|t| t > 0.0 || t.is_nan()));
                if counters.triangle.record(counts) {
                    return Some((true, counters));
                }
            }
        }
        if ends_inside {
            return Some((false, counters));
        }
        walk.step();
    }
}

/// Where the ray leaves the terrain's box, lengthened by its rounding as
/// [`clip`](super::frame::clip) does, for a ray starting inside the box (`None` otherwise).
fn segment_end(terrain: &Terrain, o: [f64; 3], d: [f64; 3]) -> Option<f64> {
    let (lo, hi) = terrain.bounds();
    let mut t1 = f64::INFINITY;
    for k in 0..3 {
        if !(o[k] >= lo[k] && o[k] <= hi[k]) {
            return None;
        }
        if d[k] != 0.0 {
            let far = if d[k] < 0.0 { lo[k] } else { hi[k] };
            t1 = t1.min((far - o[k]) / d[k]);
        }
    }
    Some(t1 + 8.0 * f64::EPSILON * t1.abs())
}

/// Whether two crossings are too close for their order to be trusted: the near walk's rule.
fn nearly(a: f64, b: f64) -> bool {
    (a - b).abs() <= 4e-9 * a.abs().max(b.abs()).max(1.0)
}

/// A path across the grid in its octant frame (`u` the horizontal axis it moves along most,
/// both axes mirrored to increase, see [`Frame`](super::frame::Frame)), at one cell.
#[derive(Clone, Copy)]
struct Path {
    swap: bool,
    flip: [bool; 2],
    o: [f64; 2],
    inverse: [f64; 2],
    /// The frame cell `(cu, cv)`, and the ray parameter where the path entered it.
    cell: [i64; 2],
    t: f64,
    /// Where the path crosses the next grid line of `u` and of `v`.
    next: [f64; 2],
    /// The valid frame cells, inclusive, per axis.
    valid: [(i64, i64); 2],
    /// The grid's cells per row, per column.
    size: [usize; 2],
}

impl Path {
    /// The path of `o + t*d` from `t = 0`, or `None` where it starts on a grid line.
    fn new(terrain: &Terrain, o: [f64; 3], d: [f64; 3]) -> Option<Self> {
        let swap = d[1].abs() > d[0].abs();
        let (ku, kv) = if swap { (1, 0) } else { (0, 1) };
        let flip = [d[ku] < 0.0, d[kv] < 0.0];
        let mirror = |x: f64, flip: bool| if flip { -x } else { x };
        let o = [mirror(o[ku], flip[0]), mirror(o[kv], flip[1])];
        let dir = [mirror(d[ku], flip[0]), mirror(d[kv], flip[1])];
        // (Casts, not `fract` and `floor`, which are library calls on the baseline target;
        // the start lies on the grid, far inside the range of `i64`.)
        let whole = o.map(|x| x as i64);
        if (0..2).any(|k| whole[k] as f64 == o[k]) {
            return None;
        }
        let field = terrain.field();
        let size = [field.width() - 1, field.height() - 1];
        let cells = |n: usize, flip: bool| {
            let n = n as i64;
            if flip {
                (-n, -1)
            } else {
                (0, n - 1)
            }
        };
        let n = if swap { [size[1], size[0]] } else { size };
        let inverse = dir.map(|x| if x == 0.0 { 0.0 } else { 1.0 / x });
        let cell = [0, 1].map(|k| whole[k] - i64::from(whole[k] as f64 > o[k]));
        let mut path = Path {
            swap,
            flip,
            o,
            inverse,
            cell,
            t: 0.0,
            next: [0.0; 2],
            valid: [cells(n[0], flip[0]), cells(n[1], flip[1])],
            size,
        };
        path.next = [0, 1].map(|k| path.crossing(k));
        Some(path)
    }

    /// Where the path crosses the next grid line of axis `k` (never, moving along the other).
    fn crossing(&self, k: usize) -> f64 {
        if self.inverse[k] == 0.0 {
            return f64::INFINITY;
        }
        ((self.cell[k] + 1) as f64 - self.o[k]) * self.inverse[k]
    }

    /// Where the path leaves its cell.
    fn exit(&self) -> f64 {
        self.next[0].min(self.next[1])
    }

    /// Whether the path leaves its cell through a corner, or too near one to tell.
    fn at_lattice_point(&self) -> bool {
        nearly(self.next[0], self.next[1])
    }

    /// The original cell `(i, j)` the path is in, or `None` outside the grid.
    fn cell(&self) -> Option<(usize, usize)> {
        let [(u0, u1), (v0, v1)] = self.valid;
        let [cu, cv] = self.cell;
        if cu < u0 || cu > u1 || cv < v0 || cv > v1 {
            return None;
        }
        let unmirror = |c: i64, flip: bool| (if flip { -c - 1 } else { c }) as usize;
        let (a, b) = (unmirror(cu, self.flip[0]), unmirror(cv, self.flip[1]));
        let (i, j) = if self.swap { (b, a) } else { (a, b) };
        (i < self.size[0] && j < self.size[1]).then_some((i, j))
    }

    /// Moves into the next cell.
    fn step(&mut self) {
        let k = usize::from(self.next[1] < self.next[0]);
        self.t = self.next[k];
        self.cell[k] += 1;
        self.next[k] = self.crossing(k);
    }
}
