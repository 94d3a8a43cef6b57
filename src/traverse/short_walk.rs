//! The short walk: an `f64` ray that needs looking at only over a few cells, walked cell by
//! cell without the frame, search record and hierarchy a long walk sets up. An occlusion ray
//! is asked only up to a reach a few cells away (where the sun's strip bounds or the sky's
//! bounds prove it clear beyond); a first-hit ray from its clearance, where it may first
//! touch the surface ([`first_hit`]), is handed on to the full walk after its first cells.
//!
//! It asks each cell the block walk's own questions at level 0, in the same arithmetic and
//! from the same numbers: the segment ends where [`clip`](super::frame::clip) and the reach
//! end it, heights are moved by the same [`slack`], the cell test compares the same heights
//! ([`Search::cell_may_hit`](super::search::Search::cell_may_hit)) and the triangles are
//! tested in the same lanes with the same ray space. It visits every cell the path crosses
//! (each crossing worked out from its grid line, as the near walk does), so it tests every
//! triangle the block walk would: where the block walk skips a block, its cells fail their
//! cell tests too. Where the walks could part (a start on a grid line, a crossing through a
//! lattice point, an end on a grid line, a path found under the surface, a long reach) it
//! gives the ray back, and the full walk answers it; a path that leaves the grid ends there,
//! as the full walk's does.

pub(super) mod first_hit;
mod path;

use self::path::{nearly, Path, SKIP_LEVEL};
use super::cell_log::{CellLog, Unrecorded};
use super::counters::HitMiss;
use super::search::slack;
use super::Counters;
use crate::arith::{larger, smaller, SimdPath};
use crate::heightfield::Terrain;

/// The most cells a short walk crosses; a ray whose reach may take it further is walked down
/// the hierarchy, which skips more than it costs over such a distance.
const MOST_CELLS: f64 = 160.0;

/// The coarsest mipmap level whose blocks the walk passes over at once.
const MOST_LEVEL: u32 = 4;

/// An occlusion ray from `o` towards `d` (the start not counting), asked only from `clear`
/// (before which the caller knows it touches no triangle but its own) up to `reach`, its own
/// triangle `start_triangle` left untested: `Some` whether it touches the surface, with its
/// queries, or `None` where the full walk must answer it.
#[inline]
pub(super) fn short_walk(
    terrain: &Terrain,
    o: [f64; 3],
    d: [f64; 3],
    (clear, reach): (f64, f64),
    start_triangle: Option<((usize, usize), u8)>,
) -> Option<(bool, Counters)> {
    let across = reach * (d[0].abs() + d[1].abs());
    if across.is_nan() || across > MOST_CELLS || reach < 0.0 {
        return None;
    }
    let t_end = segment_end(terrain, o, d)?.min(reach);
    // (Where the clear part reaches the end, the walk still looks at its last cell.)
    let mut walk = Path::new(terrain, o, d, smaller(clear, t_end))?;
    let segment = Segment::new(o, d, t_end);
    let mut counters = Counters::default();
    counters.bbox.record(true);
    let occluding = Occluding { start_triangle };
    let log = &mut Unrecorded;
    match segment.walk((terrain, &mut walk), &occluding, (&mut counters, log))? {
        Walked::Touched(()) => Some((true, counters)),
        Walked::Clear => Some((false, counters)),
        Walked::From(_) => None,
    }
}

/// Where a short walk ended.
enum Walked<F> {
    /// At a cell whose test found `F`.
    Touched(F),
    /// Clear of the surface to the segment's end, or to where it leaves the grid.
    Clear,
    /// Clear up to this `t` (where it entered its cell), after its most steps: the full walk
    /// goes on from there.
    From(f64),
}

/// What a short walk asks of a cell that may be touched.
trait Touch {
    /// What it finds there.
    type Found;
    /// The most cells and blocks the walk steps through before it hands on.
    const MOST_STEPS: u32;
    /// Whether the walk passes over blocks at once.
    const SKIPS: bool;
    /// Tests the path's cell, counting its triangle tests: `Some(Some(found))` ends the
    /// walk, `Some(None)` goes on, `None` where the full walk must answer.
    fn cell(&self, at: Crossing<'_>, triangles: &mut HitMiss) -> Option<Option<Self::Found>>;
}

/// A cell a short walk crosses.
struct Crossing<'a> {
    terrain: &'a Terrain,
    /// The path, at the cell.
    walk: &'a mut Path,
    /// The cell's corner samples.
    four: [u16; 4],
    /// The part of the ray across the cell, from `t_lo` to `t_hi`.
    span: (f64, f64),
}

/// An occlusion ray's cell test: any touch after its start, its own triangle left out.
struct Occluding {
    start_triangle: Option<((usize, usize), u8)>,
}

impl Touch for Occluding {
    type Found = ();
    // (Its reach bounds its walk: see `MOST_CELLS`.)
    const MOST_STEPS: u32 = u32::MAX;
    const SKIPS: bool = true;
    #[inline(always)]
    fn cell(&self, at: Crossing<'_>, triangles: &mut HitMiss) -> Option<Option<()>> {
        let own = self.start_triangle;
        let touches = cell_hits(at.terrain, at.walk, at.four, at.span, own, triangles)?;
        Some(touches.then_some(()))
    }
}

/// The ray's segment as the short walk compares it with the cells' samples.
struct Segment {
    /// The start's height moved down, and up, by the block walk's margin.
    oz_low: f64,
    oz_high: f64,
    dz: f64,
    t_end: f64,
    end_doubt: f64,
}

impl Segment {
    /// The segment of `o + t*d` up to `t_end`, with the block walk's margins: heights along
    /// the ray moved down where compared with a highest sample, up where with a lowest.
    fn new(o: [f64; 3], d: [f64; 3], t_end: f64) -> Self {
        let slack = slack(&o[2], &d[2], &t_end);
        let (oz_low, oz_high) = if slack > 0.0 {
            (o[2] - slack, o[2] + slack)
        } else {
            (o[2], o[2])
        };
        Segment {
            oz_low,
            oz_high,
            dz: d[2],
            t_end,
            // Where a crossing comes too near the segment's end for its order to be trusted
            // (as `nearly(t_exit, t_end)` has it, for no `t_exit` below this).
            end_doubt: t_end - 5e-9 * larger(t_end, 1.0),
        }
    }

    /// The short walk's cells from `walk`'s on, in one loop for falling rays and one for the
    /// others: which end of a cell's part of the segment is its lowest point is then known
    /// outside the loop. `None` where the full walk must answer. Its queries are added to
    /// the counters, and the cells tested one by one noted in the log.
    #[inline(always)]
    fn walk<T: Touch, C: CellLog>(
        &self,
        (terrain, walk): (&Terrain, &mut Path),
        touch: &T,
        noted: (&mut Counters, &mut C),
    ) -> Option<Walked<T::Found>> {
        if self.dz < 0.0 {
            cells::<true, T, C>(terrain, walk, self, touch, noted)
        } else {
            cells::<false, T, C>(terrain, walk, self, touch, noted)
        }
    }
}

/// [`Segment::walk`] for a ray that falls (`FALLING`) or not.
#[inline(always)]
fn cells<const FALLING: bool, T: Touch, C: CellLog>(
    terrain: &Terrain,
    walk: &mut Path,
    segment: &Segment,
    touch: &T,
    (counters, log): (&mut Counters, &mut C),
) -> Option<Walked<T::Found>> {
    let field = terrain.field();
    let (samples, w) = (field.samples(), field.width());
    // (Held here, not read through `field` after every write to the counters.)
    let (base, unit) = (field.height_of(0), field.step());
    let height_of = |sample: u16| base + f64::from(sample) * unit;
    let Segment {
        oz_low,
        oz_high,
        dz,
        t_end,
        end_doubt,
    } = *segment;
    let mut cells = HitMiss::default();
    let mut triangles = HitMiss::default();
    let mut blocks = HitMiss::default();
    let top = terrain.mipmap().top();
    let skipping = T::SKIPS && top >= SKIP_LEVEL;
    let coarsest = top.min(MOST_LEVEL);
    // The level of the next block to test: one up after a block passed over, one down
    // after one that may be touched, as the block walk climbs and descends.
    let mut level = SKIP_LEVEL;
    // Where the path leaves the block of the finest level it was last tested in.
    let mut block_until = f64::NEG_INFINITY;
    let mut steps = 0;
    let walked = loop {
        // (A walk without a most steps counts none.)
        if T::MOST_STEPS < u32::MAX {
            if steps == T::MOST_STEPS {
                break Walked::From(walk.t);
            }
            steps += 1;
        }
        let t_lo = walk.t;
        if skipping && t_lo >= block_until {
            let (t_exit, through_u, line) = walk.block_exit(level);
            let t_hi = if t_end < t_exit { t_end } else { t_exit };
            let t_low_point = if FALLING { t_hi } else { t_lo };
            let (bi, bj) = walk.block(level);
            let highest = terrain.mipmap().highest(level, bi, bj);
            // Above the block's highest sample, no cell of it passes its cell test.
            if !blocks.record(oz_low + dz * t_low_point <= height_of(highest)) {
                if t_end < t_exit {
                    if nearly(t_exit, t_end) {
                        return None;
                    }
                    break Walked::Clear;
                }
                walk.leave_block(t_exit, through_u, line)?;
                level = coarsest.min(level + 1);
                continue;
            }
            if level > SKIP_LEVEL {
                level -= 1;
                continue;
            }
            block_until = t_exit;
        }
        let t_exit = smaller(walk.next_u, walk.next_v);
        if walk.at_lattice_point()
            || t_lo >= t_exit
            || (t_exit >= end_doubt && nearly(t_exit, t_end))
        {
            return None;
        }
        let ends_inside = t_end < t_exit;
        let t_hi = if ends_inside { t_end } else { t_exit };
        let corners = &samples[walk.index..walk.index + w + 2];
        let four = [corners[0], corners[1], corners[w], corners[w + 1]];
        let lowest = four[0].min(four[1]).min(four[2].min(four[3]));
        let highest = four[0].max(four[1]).max(four[2].max(four[3]));
        let (t_low_point, t_high_point) = if FALLING { (t_hi, t_lo) } else { (t_lo, t_hi) };
        if oz_high + dz * t_high_point < height_of(lowest) {
            // Under the surface: the block walk changes its tests there.
            return None;
        }
        let may_hit = oz_low + dz * t_low_point <= height_of(highest);
        log.reached(walk.cell());
        // (The lanes test the whole cell, past the segment's end too.)
        let span = (t_lo, t_exit);
        if cells.record(may_hit) {
            let at = Crossing {
                terrain,
                walk,
                four,
                span,
            };
            if let Some(found) = touch.cell(at, &mut triangles)? {
                break Walked::Touched(found);
            }
        }
        // (Off the grid the full walk ends as well, with nothing found.)
        if ends_inside || walk.step().is_none() {
            break Walked::Clear;
        }
    };
    counters.block += blocks;
    counters.cell += cells;
    counters.triangle += triangles;
    Some(walked)
}

/// Whether the ray touches a triangle of the path's cell (with corner samples `four`, crossed
/// from `t_lo` to `t_hi` in `span`) other than `start_triangle` after its start, counting the triangle
/// tests; `None` where the lanes cannot answer.
// (Out of line: the walk's loop keeps its registers for the cells that need no test.)
#[inline(never)]
fn cell_hits(
    terrain: &Terrain,
    walk: &mut Path,
    four: [u16; 4],
    span: (f64, f64),
    start_triangle: Option<((usize, usize), u8)>,
    triangles: &mut HitMiss,
) -> Option<bool> {
    let own = start_triangle
        .filter(|&(cell, _)| cell == walk.cell())
        .map(|(_, k)| k);
    let Some(((i, j), heights)) = cell_to_test(terrain, walk, four, span, own) else {
        return Some(false);
    };
    let hits = walk
        .ray_space()
        .cell_in_lanes(SimdPath::active(), (i, j), heights)?;
    for (triangle, hit) in (0u8..2).zip(hits) {
        if start_triangle == Some(((i, j), triangle)) {
            continue;
        }
        // A hit counts where the ray touches the triangle after its start (as the search's
        // rule has it, a NaN is not before it).
        let counts = hit.is_some_and(|hit| hit.t_last.is_none_or(|t| t > 0.0 || t.is_nan()));
        if triangles.record(counts) {
            return Some(true);
        }
    }
    Some(false)
}

/// The path's cell and its corner heights (samples `four`), unless it is a hole or the ray
/// passes clearly above its triangles (leaving out triangle `own`) while it crosses it, in
/// `span` ([`passes_above`]): then no triangle test can find a touch.
#[inline(always)]
fn cell_to_test(
    terrain: &Terrain,
    walk: &Path,
    four: [u16; 4],
    span: (f64, f64),
    own: Option<u8>,
) -> Option<((usize, usize), [f64; 4])> {
    let field = terrain.field();
    let cell = walk.cell();
    if field.is_hole_cell(cell.0, cell.1) {
        return None;
    }
    let heights = four.map(|sample| field.height_of(sample));
    (!passes_above(walk, cell, heights, span, own)).then_some((cell, heights))
}

/// Whether the ray passes clearly above both triangles of cell `(i, j)` (corner heights
/// `heights`) while it crosses it, from `t_lo` to `t_hi`, leaving out triangle `own` (the
/// ray's start lies on it): then no triangle test can find a touch. The surface is planar on
/// each triangle, so the ray clears it where it clears it at the ends of its path over each
/// triangle: where it enters and leaves the cell and where it crosses the diagonal. Each
/// must clear by far more than rounding can move the ray or the surface; a path over `own`
/// alone needs nothing, and near the diagonal or near the surface the lanes decide.
fn passes_above(
    walk: &Path,
    (i, j): (usize, usize),
    [z00, z10, z01, z11]: [f64; 4],
    (t_lo, t_hi): (f64, f64),
    own: Option<u8>,
) -> bool {
    let ([ox, oy, oz], [dx, dy, dz]) = (walk.o, walk.d);
    let at = |t: f64| (ox + dx * t - i as f64, oy + dy * t - j as f64, oz + dz * t);
    // (The triangle of a point: 0 where `fx >= fy`, as `Heightfield::surface_z` splits.)
    let plane = |k: u8, fx: f64, fy: f64| {
        if k == 0 {
            z00 + fx * (z10 - z00) + fy * (z11 - z10)
        } else {
            z00 + fy * (z01 - z00) + fx * (z11 - z01)
        }
    };
    let room = 1e-9 * (1.0 + oz.abs() + z00.abs() + z11.abs() + (dz * t_hi).abs());
    let (a, b) = (at(t_lo), at(t_hi));
    let (side_a, side_b) = (a.0 - a.1, b.0 - b.1);
    // Too near the diagonal to tell which triangle a point is over.
    if side_a.abs() <= room || side_b.abs() <= room {
        return false;
    }
    let (k_a, k_b) = (u8::from(side_a < 0.0), u8::from(side_b < 0.0));
    let clears =
        |k: u8, (fx, fy, z): (f64, f64, f64)| Some(k) == own || z - plane(k, fx, fy) > room;
    if k_a == k_b {
        return clears(k_a, a) && clears(k_b, b);
    }
    // The diagonal's crossing, over both triangles.
    let s = side_a / (side_a - side_b);
    let m = (
        a.0 + s * (b.0 - a.0),
        a.1 + s * (b.1 - a.1),
        a.2 + s * (b.2 - a.2),
    );
    clears(k_a, a) && clears(k_a, m) && clears(k_b, m) && clears(k_b, b)
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
