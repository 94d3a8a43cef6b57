//! Sky bounds: for every block of [`BLOCK`]x[`BLOCK`] cells and each of [`SKY_SECTORS`]
//! sectors of azimuth, the highest sample in rings of horizontal distance from the block, so
//! that a sky ray from the block that climbs above each ring's bound from its inner edge on is
//! known clear beyond it without a walk. The sky does not move: the bounds are kept for the
//! terrain's lifetime, and each block's are made when a ray first asks (a map's far corners
//! may never be seen).
//!
//! Why a look-up is exact: a ray from `p` in the block, in a direction of sector `s`, passes
//! at horizontal distance `r` from `p` over points `q` with `q - p` in the sector and
//! `|q - p| = r`; ring `i`'s bound is the highest sample of every mipmap block holding such a
//! `q` for some `p` in the block and some `r` in the ring, so where the ray's height at the
//! ring's inner edge exceeds it, the ray passes above the whole ring (it climbs). Blocks are
//! grown by [`PAD`], sectors by [`ANGLE_PAD`], bounds rounded up, and the caller's room covers
//! the rounding of the ray's start.
//!
//! The part nearer than the first ring is bounded by slope: each block keeps, per sector, how
//! fast the surface can rise along the sector's azimuths over every triangle within [`NEAR`]
//! of the block. The surface is continuous where no cell is a hole, so along a ray's path it
//! rises from the start's own height no faster than that: a ray from a point on its own flat
//! triangle that climbs faster, by a margin for the rounding of its start, stays above every
//! other triangle until the rings take over (see [`SkyBounds::unsettled`]).

mod sectors;

use self::sectors::{sector_cones, sector_of, Cone};
use super::near_rise::NearStart;
use super::Terrain;
use crate::geometry::gradient;
use std::sync::OnceLock;

/// Sectors of azimuth, counter-clockwise from +x.
pub const SKY_SECTORS: usize = 16;

/// Cells per side of a block: one mipmap block of level [`BLOCK_LEVEL`].
const BLOCK_LEVEL: u32 = 2;
const BLOCK: usize = 1 << BLOCK_LEVEL;

/// Ring edges (horizontal distance from the ray's start) before the sky distance cuts them:
/// the part nearer than the first is settled by slope or walked.
const EDGES: [f64; 6] = [2.0, 4.0, 8.0, 16.0, 32.0, 64.0];

/// The most rings a block holds per sector.
const RINGS: usize = EDGES.len();

/// How far (horizontally) a ray's near part runs: to the first ring's inner edge, and past it
/// by the little [`SkyBounds::unsettled`] adds to the part it leaves to walk.
const NEAR: f64 = EDGES[0] + NEAR_PAST;
const NEAR_PAST: f64 = 1e-3;

/// The rise stored for a block whose near triangles are not one continuous surface (a hole
/// among them): no ray's near part is settled there.
const NO_RISE: i8 = i8::MAX;

/// How far each block is grown (cells), and each sector (radians): far more than a start or
/// a direction can be off by rounding.
const PAD: f64 = 1e-6;
pub(super) const ANGLE_PAD: f64 = 1e-7;

/// A ring is bounded by mipmap blocks at least this many times smaller than its inner edge
/// (and never smaller than a block), seen from the block of their size around the ray's
/// start.
const COARSE: f64 = 4.0;

/// The most blocks across a ring's look-up pattern: a far ring (an unlimited reach over a
/// large map) is bounded by blocks large enough to keep it this small.
const ACROSS: f64 = 64.0;

/// The part of a sky ray its bounds leave to walk, as `t` along the ray as given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unsettled {
    /// The ray touches no triangle but its own before this (its near part is settled by
    /// slope), or 0.
    pub from: f64,
    /// The ray touches no triangle beyond this (the rings clear it), or `None`: it may, up to
    /// the reach.
    pub to: Option<f64>,
}

/// One block's bounds.
#[derive(Debug)]
struct BlockBounds {
    /// Each sector's ring bounds, in units of [`SkyBounds::unit`] samples.
    rings: [[u8; RINGS]; SKY_SECTORS],
    /// Each sector's steepest rise near the block, in units of [`SkyBounds::rise_unit`] (or
    /// [`NO_RISE`]).
    rises: [i8; SKY_SECTORS],
}

/// Upper bounds on the terrain around each block, by sector and ring (see the module docs).
#[derive(Debug)]
pub struct SkyBounds {
    /// Ring edges: ring `i` runs from `edges[i]` to `edges[i + 1]`.
    edges: Vec<f64>,
    /// Per ring, the mipmap blocks that bound it (see [`RingPattern`]).
    patterns: Vec<RingPattern>,
    /// Blocks along x and y.
    nx: usize,
    ny: usize,
    blocks: Vec<OnceLock<BlockBounds>>,
    /// Samples per stored unit.
    unit: f64,
    base: f64,
    per_step: f64,
    /// The sectors, widened by [`ANGLE_PAD`].
    cones: [Cone; SKY_SECTORS],
    /// Slope per stored unit of rise.
    rise_unit: f64,
}

impl SkyBounds {
    /// Empty bounds for sky rays that look `reach` (grid units, horizontally) far over
    /// `terrain`; `None` where the reach is too short to leave anything beyond the walked
    /// part, or the field is flat.
    pub fn new(terrain: &Terrain, reach: f64) -> Option<SkyBounds> {
        let field = terrain.field();
        if !(reach > EDGES[0] && field.step() > 0.0) {
            return None;
        }
        let mut edges: Vec<f64> = EDGES.into_iter().filter(|&e| e * 1.25 < reach).collect();
        edges.push(reach);
        let cells = |n: usize| (n - 1).div_ceil(BLOCK);
        let (nx, ny) = (cells(field.width()), cells(field.height()));
        let top = terrain.mipmap().top();
        let highest = terrain.mipmap().highest(top, 0, 0);
        let diagonal = ((field.width() - 1) as f64).hypot((field.height() - 1) as f64);
        let top = terrain.mipmap().top();
        let patterns = (0..edges.len() - 1)
            .map(|i| RingPattern::new(edges[i], edges[i + 1].min(diagonal + 1.0), top))
            .collect();
        Some(SkyBounds {
            edges,
            patterns,
            nx,
            ny,
            blocks: (0..nx * ny).map(|_| OnceLock::new()).collect(),
            unit: f64::from(highest.div_ceil(255).max(1)),
            base: field.height_of(0),
            per_step: 1.0 / field.step(),
            cones: sector_cones(),
            rise_unit: terrain.max_slope().max(f64::MIN_POSITIVE) * (1.0 + 1e-9)
                / f64::from(NO_RISE - 1),
        })
    }

    /// The reach the bounds were made for.
    pub fn reach(&self) -> f64 {
        self.edges[self.edges.len() - 1]
    }

    /// Bytes held, every block's bounds made or not.
    pub fn bytes(&self) -> usize {
        let patterns: usize = self.patterns.iter().map(|p| p.blocks.len()).sum();
        self.blocks.len() * std::mem::size_of::<OnceLock<BlockBounds>>()
            + patterns * std::mem::size_of::<((i32, i32), [u16; SKY_SECTORS])>()
    }

    /// The part of a ray from `start` (grid coordinates) in direction `dir`, within the
    /// reach, that the bounds leave to walk (see [`Unsettled`]); `None` where they prove it
    /// touches no triangle but its own all the way. `room` is how far (in height) the ray's
    /// true start may lie below `start`. `near`, where the start lies on its own flat triangle
    /// (see [`NearStart`]), lets the near part be settled too.
    pub fn unsettled(
        &self,
        terrain: &Terrain,
        start: [f64; 3],
        dir: [f64; 3],
        room: f64,
        near: Option<NearStart>,
    ) -> Option<Unsettled> {
        const ALL: Unsettled = Unsettled {
            from: 0.0,
            to: None,
        };
        // (Not `hypot`: a direction cannot overflow, and `hypot` costs as much as the look-up.)
        let across = (dir[0] * dir[0] + dir[1] * dir[1]).sqrt();
        let climb = dir[2] / across;
        if !(climb.is_finite() && start.iter().all(|c| c.is_finite())) {
            return Some(ALL);
        }
        let (x, y) = (start[0] / BLOCK as f64, start[1] / BLOCK as f64);
        if !(x >= 0.0 && y >= 0.0) {
            return Some(ALL);
        }
        let (bx, by) = ((x as usize).min(self.nx - 1), (y as usize).min(self.ny - 1));
        if (x as usize) > self.nx || (y as usize) > self.ny {
            return Some(ALL);
        }
        let sector = sector_of(dir[0], dir[1]);
        let bounds = self.blocks[by * self.nx + bx].get_or_init(|| self.fill(terrain, bx, by));
        let rings = &bounds.rings[sector];
        let z = (start[2] - self.base) * self.per_step;
        let rise = climb * self.per_step;
        let error = 1e-9 * (z.abs() + rise.abs() * self.reach().min(1e9) + f64::from(u16::MAX))
            + room * self.per_step * (1.0 + rise.abs());
        // The nearest edge from which every ring out to the reach is clear: the ray is lowest
        // over a ring at its inner edge if it climbs, at its outer edge if it falls.
        let lowest = usize::from(rise < 0.0);
        let mut beyond = None;
        for i in (0..self.edges.len() - 1).rev() {
            let bound = f64::from(rings[i]) * self.unit;
            if z + rise * self.edges[i + lowest] - error <= bound {
                break;
            }
            beyond = Some(self.edges[i]);
        }
        let rise = bounds.rises[sector];
        let near_clear = near.is_some_and(|near| {
            rise != NO_RISE && near.outclimbs(climb, f64::from(rise) * self.rise_unit)
        });
        if near_clear && beyond == Some(self.edges[0]) {
            return None;
        }
        Some(Unsettled {
            // (Short of the first edge by far more than the rounding of `t`.)
            from: if near_clear {
                self.edges[0] * (1.0 - 1e-9) / across
            } else {
                0.0
            },
            to: beyond.map(|edge| (edge + NEAR_PAST) / across),
        })
    }

    /// Every sector's ring bounds for block `(bx, by)`: the highest sample over each ring's
    /// pattern of mipmap blocks around the block of its level that holds this one.
    // (Out of line: made once per block, it would only crowd the sky ray.)
    #[inline(never)]
    fn fill(&self, terrain: &Terrain, bx: usize, by: usize) -> BlockBounds {
        BlockBounds {
            rings: self.rings(terrain, bx, by),
            rises: self.rises(terrain, bx, by),
        }
    }

    /// Every sector's ring bounds for block `(bx, by)`.
    fn rings(&self, terrain: &Terrain, bx: usize, by: usize) -> [[u8; RINGS]; SKY_SECTORS] {
        let field = terrain.field();
        let (cells_x, cells_y) = (field.width() - 1, field.height() - 1);
        let mut out = [[0u8; RINGS]; SKY_SECTORS];
        for (i, pattern) in self.patterns.iter().enumerate() {
            let k = pattern.level;
            let shift = k - BLOCK_LEVEL;
            let (x, y) = ((bx >> shift) as i64, (by >> shift) as i64);
            let (nx, ny) = (
                cells_x.div_ceil(1 << k) as i64,
                cells_y.div_ceil(1 << k) as i64,
            );
            // (Each block read once, and taken into every sector it bounds at once, through
            // its lanes: all ones for those sectors, zero for the others.)
            let mut highest = [0u16; SKY_SECTORS];
            for (&(dx, dy), lanes) in pattern.blocks.iter().zip(&pattern.lanes) {
                let (qx, qy) = (x + i64::from(dx), y + i64::from(dy));
                if (0..nx).contains(&qx) && (0..ny).contains(&qy) {
                    let block = terrain.block_max_sample(k, qx as usize, qy as usize);
                    for (best, lane) in highest.iter_mut().zip(lanes) {
                        *best = (*best).max(block & lane);
                    }
                }
            }
            for (rings, highest) in out.iter_mut().zip(highest) {
                rings[i] = (f64::from(highest) / self.unit).ceil().min(255.0) as u8;
            }
        }
        out
    }

    /// Every sector's steepest rise along its azimuths over the triangles of the cells within
    /// [`NEAR`] of block `(bx, by)` (grown by [`PAD`]), rounded up; [`NO_RISE`] where one of
    /// those cells is a hole.
    fn rises(&self, terrain: &Terrain, bx: usize, by: usize) -> [i8; SKY_SECTORS] {
        let field = terrain.field();
        let cells = |b: usize, n: usize| {
            let from = (b * BLOCK) as f64 - NEAR - PAD;
            let to = ((b + 1) * BLOCK) as f64 + NEAR + PAD;
            (from.floor().max(0.0) as usize)..=(to.floor() as usize).min(n - 2)
        };
        let (xs, ys) = (cells(bx, field.width()), cells(by, field.height()));
        // A plane of gradient `g` rises along `u` at `g . u`: each sector's rise is the most of
        // that along its two edges, or `|g|` where the sector holds `g`'s own azimuth (the
        // rise along the sector's azimuths peaks at an edge unless it holds the peak).
        let edges: [[f64; 2]; 2 * SKY_SECTORS] =
            std::array::from_fn(|k| [self.cones[k / 2].lo, self.cones[k / 2].hi][k % 2]);
        let mut along = [f64::NEG_INFINITY; 2 * SKY_SECTORS];
        let mut steepest = [f64::NEG_INFINITY; SKY_SECTORS];
        for j in ys {
            for i in xs.clone() {
                if field.is_hole_cell(i, j) {
                    return [NO_RISE; SKY_SECTORS];
                }
                let heights = terrain.corner_heights(i, j);
                for (gx, gy) in [0, 1].map(|k| gradient(k, heights)) {
                    // (Plain comparisons: no NaN here, and they keep the loop in lanes.)
                    for (best, u) in along.iter_mut().zip(&edges) {
                        let rise = gx * u[0] + gy * u[1];
                        *best = if rise > *best { rise } else { *best };
                    }
                    let own = sector_of(gx, gy);
                    for s in [own + SKY_SECTORS - 1, own, own + 1].map(|s| s % SKY_SECTORS) {
                        if self.cones[s].inside([gx, gy]) {
                            steepest[s] = steepest[s].max((gx * gx + gy * gy).sqrt());
                        }
                    }
                }
            }
        }
        std::array::from_fn(|s| {
            let steepest = steepest[s].max(along[2 * s]).max(along[2 * s + 1]);
            // (Rounded up, whichever its sign.)
            let steepest = steepest + 1e-9 * self.rise_unit * f64::from(NO_RISE);
            let units = (steepest / self.rise_unit).ceil();
            units.clamp(-f64::from(NO_RISE - 1), f64::from(NO_RISE - 1)) as i8
        })
    }
}

/// The mipmap blocks of one level that bound a ring in each sector, as offsets from the block
/// of that level holding the ray's start: every block holding a point `q` with `q - p` in the
/// sector and `|q - p|` in the ring, for some `p` in the start's block. Seen from the start's
/// block rather than from the start, the pattern is the same for every start.
#[derive(Debug)]
struct RingPattern {
    level: u32,
    /// Each block of the ring, once, as its offset.
    blocks: Vec<(i32, i32)>,
    /// The sectors each block bounds: lane `s` all ones where it bounds sector `s`, else 0.
    lanes: Vec<[u16; SKY_SECTORS]>,
}

impl RingPattern {
    /// The pattern of the ring from `inner` to `outer` (grid units), on a mipmap whose
    /// coarsest level is `top`.
    fn new(inner: f64, outer: f64, top: u32) -> RingPattern {
        let fine = (inner / COARSE).log2().floor().max(0.0) as u32;
        let small = (2.0 * outer / ACROSS).log2().ceil().max(0.0) as u32;
        let level = fine.max(small).max(BLOCK_LEVEL).min(top.max(BLOCK_LEVEL));
        let size = f64::from(1u32 << level);
        let cones = sector_cones();
        let reach = (outer / size).ceil() as i32 + 1;
        let (mut blocks, mut lanes) = (Vec::new(), Vec::new());
        for dy in -reach..=reach {
            for dx in -reach..=reach {
                // `q - p` for `q` in the block at the offset and `p` in the start's.
                let (x, y) = (f64::from(dx) * size, f64::from(dy) * size);
                let d = [
                    x - size - PAD,
                    y - size - PAD,
                    x + size + PAD,
                    y + size + PAD,
                ];
                let Some((near, far)) = distances(d) else {
                    continue;
                };
                if near > outer || far < inner {
                    continue;
                }
                let sectors = (0..SKY_SECTORS)
                    .filter(|&s| cones[s].meets(d))
                    .fold(0u16, |bits, s| bits | 1 << s);
                if sectors != 0 {
                    blocks.push((dx, dy));
                    lanes.push(std::array::from_fn(|s| {
                        if sectors & 1 << s != 0 {
                            u16::MAX
                        } else {
                            0
                        }
                    }));
                }
            }
        }
        RingPattern {
            level,
            blocks,
            lanes,
        }
    }
}

/// The least and greatest distance from the origin to the rectangle `[x0, y0, x1, y1]`,
/// widened by far more than their rounding.
fn distances([x0, y0, x1, y1]: [f64; 4]) -> Option<(f64, f64)> {
    let nearest = |lo: f64, hi: f64| {
        if lo > 0.0 {
            lo
        } else if hi < 0.0 {
            -hi
        } else {
            0.0
        }
    };
    let farthest = |lo: f64, hi: f64| lo.abs().max(hi.abs());
    let length = |x: f64, y: f64| (x * x + y * y).sqrt();
    let near = length(nearest(x0, x1), nearest(y0, y1)) * (1.0 - 1e-12);
    let far = length(farthest(x0, x1), farthest(y0, y1)) * (1.0 + 1e-12);
    (near.is_finite() && far.is_finite()).then_some((near, far))
}
