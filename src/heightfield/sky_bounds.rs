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

use super::Terrain;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Sectors of azimuth, counter-clockwise from +x.
pub const SKY_SECTORS: usize = 16;

/// Cells per side of a block.
const BLOCK: usize = 4;

/// Ring edges (horizontal distance from the ray's start) before the sky distance cuts them:
/// the part nearer than the first is always walked.
const EDGES: [f64; 6] = [2.0, 6.0, 14.0, 30.0, 62.0, 126.0];

/// The most rings a block holds per sector.
const RINGS: usize = EDGES.len();

/// How far each block is grown (cells), and each sector (radians): far more than a start or
/// a direction can be off by rounding.
const PAD: f64 = 1e-6;
const ANGLE_PAD: f64 = 1e-7;

/// Mipmap blocks this size or smaller are not looked into: they count whole in every ring
/// and sector they may reach; and so do blocks this many times their size away or farther.
const FINEST_LEVEL: u32 = 2;
const COARSE: usize = 4;

/// Each sector's ring bounds for one block, in units of [`SkyBounds::unit`] samples.
type BlockBounds = [[u8; RINGS]; SKY_SECTORS];

/// Upper bounds on the terrain around each block, by sector and ring (see the module docs).
#[derive(Debug)]
pub struct SkyBounds {
    /// Ring edges: ring `i` runs from `edges[i]` to `edges[i + 1]`.
    edges: Vec<f64>,
    /// The sectors, each grown by [`ANGLE_PAD`].
    cones: [Cone; SKY_SECTORS],
    /// Blocks along x and y.
    nx: usize,
    ny: usize,
    blocks: Vec<OnceLock<BlockBounds>>,
    /// Samples per stored unit.
    unit: f64,
    base: f64,
    per_step: f64,
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
        let mut edges: Vec<f64> = EDGES.into_iter().filter(|&e| e * 1.5 < reach).collect();
        edges.push(reach);
        let cells = |n: usize| (n - 1).div_ceil(BLOCK);
        let (nx, ny) = (cells(field.width()), cells(field.height()));
        let top = terrain.mipmap().top();
        let highest = terrain.mipmap().highest(top, 0, 0);
        let width = 2.0 * PI / SKY_SECTORS as f64;
        let cones = std::array::from_fn(|s| {
            Cone::new(
                s as f64 * width - ANGLE_PAD,
                (s + 1) as f64 * width + ANGLE_PAD,
            )
        });
        Some(SkyBounds {
            edges,
            cones,
            nx,
            ny,
            blocks: (0..nx * ny).map(|_| OnceLock::new()).collect(),
            unit: f64::from(highest.div_ceil(255).max(1)),
            base: field.height_of(0),
            per_step: 1.0 / field.step(),
        })
    }

    /// The reach the bounds were made for.
    pub fn reach(&self) -> f64 {
        self.edges[self.edges.len() - 1]
    }

    /// Bytes held, every block's bounds made or not.
    pub fn bytes(&self) -> usize {
        self.blocks.len() * std::mem::size_of::<OnceLock<BlockBounds>>()
    }

    /// Whether a ray from `start` (grid coordinates) in direction `dir` certainly touches no
    /// triangle beyond a few cells out, within the reach: `Some(t)` where it is clear from
    /// `start + t * dir` on, so that only `[0, t]` is left to walk. `room` is how far (in
    /// height) the ray's true start may lie below `start`.
    pub fn clear_beyond(
        &self,
        terrain: &Terrain,
        start: [f64; 3],
        dir: [f64; 3],
        room: f64,
    ) -> Option<f64> {
        let across = dir[0].hypot(dir[1]);
        let climb = dir[2] / across;
        if !(climb > 0.0 && climb.is_finite() && start.iter().all(|c| c.is_finite())) {
            return None;
        }
        let (x, y) = (start[0] / BLOCK as f64, start[1] / BLOCK as f64);
        if !(x >= 0.0 && y >= 0.0) {
            return None;
        }
        let (bx, by) = ((x as usize).min(self.nx - 1), (y as usize).min(self.ny - 1));
        if (x as usize) > self.nx || (y as usize) > self.ny {
            return None;
        }
        let angle = dir[1].atan2(dir[0]).rem_euclid(2.0 * PI);
        let sector = ((angle / (2.0 * PI / SKY_SECTORS as f64)) as usize).min(SKY_SECTORS - 1);
        let bounds = self.blocks[by * self.nx + bx].get_or_init(|| self.fill(terrain, bx, by));
        let rings = &bounds[sector];
        let z = (start[2] - self.base) * self.per_step;
        let rise = climb * self.per_step;
        let error = 1e-9 * (z.abs() + rise * self.reach().min(1e9) + f64::from(u16::MAX))
            + room * self.per_step * (1.0 + rise);
        // The nearest edge from which every ring out to the reach is clear.
        let mut from = None;
        for i in (0..self.edges.len() - 1).rev() {
            let bound = f64::from(rings[i]) * self.unit;
            if z + rise * self.edges[i] - error <= bound {
                break;
            }
            from = Some(self.edges[i]);
        }
        from.map(|edge| (edge + 1e-3) / across)
    }

    /// Every sector's ring bounds for block `(bx, by)`, from the mipmap.
    fn fill(&self, terrain: &Terrain, bx: usize, by: usize) -> BlockBounds {
        let field = terrain.field();
        let (cells_x, cells_y) = (field.width() - 1, field.height() - 1);
        let x0 = (bx * BLOCK) as f64 - PAD;
        let y0 = (by * BLOCK) as f64 - PAD;
        let x1 = ((bx + 1) * BLOCK).min(cells_x) as f64 + PAD;
        let y1 = ((by + 1) * BLOCK).min(cells_y) as f64 + PAD;
        let mut out = [[0u8; RINGS]; SKY_SECTORS];
        let top = terrain.mipmap().top();
        let mut stack = Vec::with_capacity(64);
        for (cone, rings) in self.cones.iter().zip(out.iter_mut()) {
            let mut highest = [0u16; RINGS];
            stack.push((top, 0usize, 0usize));
            while let Some((k, i, j)) = stack.pop() {
                let size = 1usize << k;
                let (qx0, qy0) = (i * size, j * size);
                let (qx1, qy1) = ((qx0 + size).min(cells_x), (qy0 + size).min(cells_y));
                if qx0 >= cells_x || qy0 >= cells_y {
                    continue;
                }
                // Where the block's points see the node's: the rectangle of `q - p`.
                let d = [
                    qx0 as f64 - x1,
                    qy0 as f64 - y1,
                    qx1 as f64 - x0,
                    qy1 as f64 - y0,
                ];
                let Some((near, far)) = distances(d) else {
                    continue;
                };
                let Some(rings_met) = self.rings_met(near, far) else {
                    continue;
                };
                let sample = terrain.block_max_sample(k, i, j);
                let gains = rings_met.clone().any(|r| sample > highest[r]);
                if !gains || !cone.meets(d) {
                    continue;
                }
                let coarse = k <= FINEST_LEVEL || (size * COARSE) as f64 <= near;
                if coarse || rings_met.len() == 1 && cone.holds(d) {
                    for r in rings_met {
                        highest[r] = highest[r].max(sample);
                    }
                    continue;
                }
                for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    stack.push((k - 1, 2 * i + a, 2 * j + b));
                }
            }
            for (stored, high) in rings.iter_mut().zip(highest) {
                *stored = (f64::from(high) / self.unit).ceil().min(255.0) as u8;
            }
        }
        out
    }

    /// The rings a distance range `[near, far]` reaches into; `None` if none.
    fn rings_met(&self, near: f64, far: f64) -> Option<std::ops::Range<usize>> {
        let last = self.edges.len() - 1;
        if far < self.edges[0] || near > self.edges[last] {
            return None;
        }
        let ring = |r: f64| self.edges[1..last].iter().filter(|&&e| e <= r).count();
        Some(ring(near.max(self.edges[0]))..ring(far.min(self.edges[last])) + 1)
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

/// The directions between two azimuths (less than a half turn apart).
#[derive(Debug)]
struct Cone {
    lo: [f64; 2],
    hi: [f64; 2],
}

impl Cone {
    fn new(from: f64, to: f64) -> Cone {
        Cone {
            lo: [from.cos(), from.sin()],
            hi: [to.cos(), to.sin()],
        }
    }

    /// Whether direction `c` lies inside (edges included).
    fn inside(&self, c: [f64; 2]) -> bool {
        cross(self.lo, c) >= 0.0 && cross(c, self.hi) >= 0.0
    }

    /// Whether the rectangle `[x0, y0, x1, y1]` may hold a point of the cone (false only
    /// where it certainly does not).
    fn meets(&self, [x0, y0, x1, y1]: [f64; 4]) -> bool {
        if x0 <= 0.0 && x1 >= 0.0 && y0 <= 0.0 && y1 >= 0.0 {
            return true;
        }
        let corners = [[x0, y0], [x1, y0], [x0, y1], [x1, y1]];
        corners.iter().any(|&c| self.inside(c))
            || [self.lo, self.hi]
                .iter()
                .any(|&u| ray_meets(u, [x0, y0, x1, y1]))
    }

    /// Whether every point of the rectangle lies inside.
    fn holds(&self, [x0, y0, x1, y1]: [f64; 4]) -> bool {
        let corners = [[x0, y0], [x1, y0], [x0, y1], [x1, y1]];
        corners.iter().all(|&c| self.inside(c))
    }
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Whether the ray `t * u` (`t >= 0`) meets the rectangle (a slab test, edges included).
fn ray_meets(u: [f64; 2], [x0, y0, x1, y1]: [f64; 4]) -> bool {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for (k, (lo, hi)) in [(x0, x1), (y0, y1)].into_iter().enumerate() {
        if u[k] == 0.0 {
            if lo > 0.0 || hi < 0.0 {
                return false;
            }
            continue;
        }
        let (a, b) = (lo / u[k], hi / u[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 <= t1
}
