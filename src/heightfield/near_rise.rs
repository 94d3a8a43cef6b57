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
use crate::geometry::gradient;

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

/// The most `g . u` over the unit vectors `u` from `lo` counter-clockwise to `hi` (less than
/// a half turn apart): how fast a plane of gradient `g` rises along the steepest of those
/// azimuths.
pub(super) fn steepest_rise(lo: [f64; 2], hi: [f64; 2], g: [f64; 2]) -> f64 {
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let dot = |u: [f64; 2]| u[0] * g[0] + u[1] * g[1];
    if cross(lo, g) >= 0.0 && cross(g, hi) >= 0.0 {
        (g[0] * g[0] + g[1] * g[1]).sqrt()
    } else {
        dot(lo).max(dot(hi))
    }
}

/// Cells per side of a block [`ConeRises`] keeps one rise for.
const BLOCK: usize = 4;

/// The rise kept for a block near a hole: no ray is settled there.
const NO_RISE: i8 = i8::MAX;

/// For each block of [`BLOCK`]x[`BLOCK`] cells, the steepest rise along a cone of azimuths
/// over the triangles within `reach` cells of the block, rounded up (a signed byte a block).
#[derive(Clone, Debug)]
pub struct ConeRises {
    nx: usize,
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
        let (cells_x, cells_y) = (field.width() - 1, field.height() - 1);
        // Each cell's steepest triangle, then the most over the cells of each block's reach
        // (rows, then columns).
        let cell_rise = |i: usize, j: usize| {
            if field.is_hole_cell(i, j) {
                return f64::INFINITY;
            }
            let heights = [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(a, b)| field.z(i + a, j + b));
            [0, 1]
                .map(|k| steepest_rise(lo, hi, gradient(k, heights).into()))
                .into_iter()
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let (nx, ny) = (cells_x.div_ceil(BLOCK), cells_y.div_ceil(BLOCK));
        let grow = (reach + 1e-6).ceil() as usize;
        let span =
            |b: usize, n: usize| (b * BLOCK).saturating_sub(grow)..((b + 1) * BLOCK + grow).min(n);
        let cells: Vec<f64> = (0..cells_y)
            .flat_map(|j| (0..cells_x).map(move |i| (i, j)))
            .map(|(i, j)| cell_rise(i, j))
            .collect();
        let across: Vec<f64> = (0..cells_y)
            .flat_map(|j| (0..nx).map(move |bx| (bx, j)))
            .map(|(bx, j)| {
                let row = &cells[j * cells_x..(j + 1) * cells_x];
                row[span(bx, cells_x)]
                    .iter()
                    .copied()
                    .fold(f64::NEG_INFINITY, f64::max)
            })
            .collect();
        let blocks: Vec<f64> = (0..ny)
            .flat_map(|by| (0..nx).map(move |bx| (bx, by)))
            .map(|(bx, by)| {
                span(by, cells_y)
                    .map(|j| across[j * nx + bx])
                    .fold(f64::NEG_INFINITY, f64::max)
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
        let ny = self.rises.len() / self.nx.max(1);
        let (bx, by) = ((x as usize).min(self.nx - 1), (y as usize).min(ny - 1));
        let rise = self.rises[by * self.nx + bx];
        rise != NO_RISE && near.outclimbs(climb, f64::from(rise) * self.unit)
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.rises.len()
    }
}
