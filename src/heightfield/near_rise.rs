//! How fast the surface can rise near a point, along a cone of azimuths: an occlusion ray
//! that starts well inside its own flat triangle and climbs faster than that, by a margin
//! for the rounding of its start, touches no other triangle over its first cells. The
//! surface is continuous where no cell is a hole, so along the ray's path it rises from the
//! start's own height no faster than the steepest of the triangles the path passes over;
//! for the first [`NearStart::INSIDE`] of the way the ray is over its own triangle, which it
//! leaves upwards. The kept bounds ([`SkyBounds`](super::SkyBounds),
//! [`StripBounds`](super::StripBounds)) prove the rest of the way clear; with this, such a
//! ray needs no walk at all.

use super::Heightfield;
use super::Terrain;

/// An occlusion ray's start on its own flat triangle, at least [`NearStart::INSIDE`] inside
/// it: for so short a way from it the ray can meet no other triangle, and beyond that it is
/// above every triangle where it outclimbs their rise by `margin`.
#[derive(Clone, Copy, Debug)]
pub struct NearStart {
    margin: f64,
}

impl NearStart {
    /// How far inside its triangle (horizontally, in cells) a start must lie.
    pub const INSIDE: f64 = 1e-4;

    /// The start at `p` (grid coordinates, `z` on the surface within `room`, and `x`, `y`
    /// within `room` of the true start's) on triangle `triangle` of `cell`: `None` where it
    /// lies within [`NearStart::INSIDE`] of the triangle's edges.
    pub fn on_triangle(
        terrain: &Terrain,
        (cell, triangle): ((usize, usize), u8),
        p: [f64; 3],
        room: f64,
    ) -> Option<NearStart> {
        let (fx, fy) = (p[0] - cell.0 as f64, p[1] - cell.1 as f64);
        // Triangle 0 is the cell's half with `fx >= fy` (see `gradient`).
        let edges = if triangle == 0 {
            [fy, 1.0 - fx, (fx - fy) * std::f64::consts::FRAC_1_SQRT_2]
        } else {
            [fx, 1.0 - fy, (fy - fx) * std::f64::consts::FRAC_1_SQRT_2]
        };
        if !edges.iter().all(|&e| e > NearStart::INSIDE) {
            return None;
        }
        // Past `INSIDE`, the ray must clear the surface by more than its start's room (which
        // the steepest slope spreads over the horizontal part) and its own rounding.
        let room = room * (1.0 + 2.0 * terrain.max_slope()) + 1e-9 * (1.0 + p[2].abs());
        let margin = room / NearStart::INSIDE;
        margin.is_finite().then_some(NearStart { margin })
    }

    /// Whether a ray of `climb` (height per horizontal cell) outclimbs a surface that rises
    /// no faster than `rise` along its azimuth.
    pub fn outclimbs(&self, climb: f64, rise: f64) -> bool {
        climb > rise + self.margin
    }
}

/// Cells per side of a block [`ConeRises`] keeps one rise for.
const BLOCK: usize = 4;

/// The rise kept for a block near a hole: no ray is settled there.
const NO_RISE: i8 = i8::MAX;

/// For each block of 4x4 cells, the steepest rise along a cone of azimuths
/// over the triangles within `reach` cells of the block, rounded up (a signed byte a block).
#[derive(Clone, Debug)]
pub struct ConeRises {
    nx: usize,
    ny: usize,
    rises: Vec<i8>,
    /// Height per horizontal cell per stored unit.
    unit: f64,
    reach: f64,
}

impl ConeRises {
    /// The rises along the azimuths from `lo` counter-clockwise to `hi` (unit vectors less
    /// than a half turn apart, already widened for rounding) over `field`, for ray parts
    /// `reach` cells long.
    pub fn build(field: &Heightfield, (lo, hi): ([f64; 2], [f64; 2]), reach: f64) -> ConeRises {
        let (w, cells_x, cells_y) = (field.width(), field.width() - 1, field.height() - 1);
        let (nx, ny) = (cells_x.div_ceil(BLOCK), cells_y.div_ceil(BLOCK));
        // Each block's steepest triangle, in samples per cell, in one pass over the rows: in
        // `f32`, exact on the samples' differences, the rest rounded up below.
        let ([lx, ly], [hx, hy]) = (lo.map(|c| c as f32), hi.map(|c| c as f32));
        let rise = |gx: f32, gy: f32| {
            let along = (gx * lx + gy * ly).max(gx * hx + gy * hy);
            let inside = lx * gy - ly * gx >= 0.0 && gx * hy - gy * hx >= 0.0;
            if inside {
                (gx * gx + gy * gy).sqrt()
            } else {
                along
            }
        };
        let samples = field.samples();
        let mut own = vec![f32::NEG_INFINITY; nx * ny];
        // (A row of cells at a time, branch-free, so that it runs in lanes.)
        let mut cells = vec![0f32; cells_x];
        for j in 0..cells_y {
            let (below, above) = (&samples[j * w..(j + 1) * w], &samples[(j + 1) * w..]);
            for (i, cell) in cells.iter_mut().enumerate() {
                let [a, b] = [below[i], below[i + 1]].map(f32::from);
                let [c, d] = [above[i], above[i + 1]].map(f32::from);
                // The cell's two triangles (see `gradient`).
                *cell = rise(b - a, d - b).max(rise(d - c, c - a));
            }
            let blocks = &mut own[(j / BLOCK) * nx..(j / BLOCK + 1) * nx];
            for (best, four) in blocks.iter_mut().zip(cells.chunks(BLOCK)) {
                *best = four.iter().copied().fold(*best, f32::max);
            }
        }
        if field.nodata_count() > 0 {
            for j in 0..cells_y {
                for i in (0..cells_x).filter(|&i| field.is_hole_cell(i, j)) {
                    own[(j / BLOCK) * nx + i / BLOCK] = f32::INFINITY;
                }
            }
        }
        // The most over the blocks within the reach of each (rows, then columns).
        let grow = ((reach + 1e-6) / BLOCK as f64).ceil() as usize;
        let span = |b: usize, n: usize| b.saturating_sub(grow)..(b + grow + 1).min(n);
        let highest = |values: &[f32]| values.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        let across: Vec<f32> = (0..ny * nx)
            .map(|k| highest(&own[(k / nx) * nx..][span(k % nx, nx)]))
            .collect();
        let step = field.step();
        let blocks: Vec<f64> = (0..ny * nx)
            .map(|k| {
                let (bx, by) = (k % nx, k / nx);
                let most = span(by, ny)
                    .map(|b| across[b * nx + bx])
                    .fold(f32::NEG_INFINITY, f32::max);
                // (Up by far more than `f32` rounds a rise of samples, then into heights.)
                let most = f64::from(most);
                (most + 1e-5 * most.abs() + 1e-5) * step
            })
            .collect();
        let steepest = blocks
            .iter()
            .filter(|r| r.is_finite())
            .fold(0.0f64, |m, r| m.max(r.abs()));
        let unit = steepest.max(f64::MIN_POSITIVE) * (1.0 + 1e-9) / f64::from(NO_RISE - 1);
        let limit = f64::from(NO_RISE - 1);
        let rises = blocks
            .iter()
            .map(|&r| match r.is_finite() {
                // (Rounded up, whichever its sign.)
                true => ((r + 1e-9 * steepest) / unit).ceil().clamp(-limit, limit) as i8,
                false => NO_RISE,
            })
            .collect();
        ConeRises {
            nx,
            ny,
            rises,
            unit,
            reach,
        }
    }

    /// Whether a ray from `start` (grid coordinates, inside the map) climbing `climb` along
    /// an azimuth of the cone outclimbs the surface over its first `across` cells
    /// (horizontally; at most the reach built for), as `near` has it.
    pub fn outclimbed(&self, start: [f64; 3], climb: f64, across: f64, near: NearStart) -> bool {
        let (x, y) = (start[0] / BLOCK as f64, start[1] / BLOCK as f64);
        if !(x >= 0.0 && y >= 0.0 && across <= self.reach) {
            return false;
        }
        let (bx, by) = ((x as usize).min(self.nx - 1), (y as usize).min(self.ny - 1));
        let rise = self.rises[by * self.nx + bx];
        rise != NO_RISE && near.outclimbs(climb, f64::from(rise) * self.unit)
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.rises.len()
    }
}
