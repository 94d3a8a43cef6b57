//! Bounds of the terrain's shadow for one sun direction, swept once over the map, so that most
//! hard shadow rays towards that sun are settled by a look-up (see [`SunSweep::verdict`]).
//!
//! With `d` the direction towards the sun in grid coordinates and `a` its dominant horizontal
//! axis, one step `d / |d_a|` moves a point exactly one column along `a`, by `dv` (at most one
//! cell) across it and by `dz` up. A cell shifted by one step overlaps at most two cells of the
//! next column, so per cell, from the sun's side column by column:
//! - `U(C)`, the larger of the highest corner of the cells the cell's step sweeps over and the
//!   next column's `U` less `dz` over the cells it lands on, bounds the terrain over the ray
//!   from above: `h(p + t d) - t dz <= U(C)` for every point `p` of `C` and `t > 0` (where
//!   `p + t d` lies off the map, nothing is there);
//! - `L(C)`, the least over the cells it lands on of the larger of their `L` and their lowest
//!   corner, less `dz` (no bound where it may land off the map or on a hole), bounds it from
//!   below: for every point `p` of `C` some `t > 0` has `h(p + t d) - t dz >= L(C)`.
//!
//! The sweep runs over the aligned blocks of `2^k x 2^k` cells of one level of the mipmap
//! instead of cells, with their highest and lowest samples as corners and `2^k` columns to a
//! step (the same geometry, scaled): its bounds hold for every point of a block, so a look-up
//! one column ahead of a point reads its block's. Bounds are quantised to 16 bits over the
//! height range (`U` rounded up, `L` down).

mod cache;
mod verdict;

pub use cache::SweepCache;
pub use verdict::{SweepStart, Verdict};

use super::Terrain;

/// The shadow bounds of one terrain for one sun direction.
#[derive(Clone, Debug)]
pub struct SunSweep {
    /// The direction towards the sun (grid coordinates) the table was swept for.
    dir: [f64; 3],
    /// The dominant horizontal axis (0 for x, 1 for y).
    axis: usize,
    /// One step along the direction: one column along `axis` (x, y and z components).
    step: [f64; 3],
    /// Cells along x and y.
    cells: [usize; 2],
    /// The mipmap level of the blocks.
    level: u32,
    /// Cells per block side.
    block: usize,
    /// Blocks along x.
    blocks_x: usize,
    /// Per block, the largest `U` of its cells, quantised up.
    upper: Vec<u16>,
    /// Per block, the least `L` of its cells, quantised down (0: no bound).
    lower: Vec<u16>,
    /// The height of code 0, and the height per code.
    z0: f64,
    quantum: f64,
}

/// The mipmap level whose blocks the sweep runs over for a map of `samples` samples: 4x4
/// cells (0.25 bytes per sample), 8x8 from 16 million samples on (0.06).
fn level(samples: usize) -> u32 {
    if samples < 1 << 24 {
        2
    } else {
        3
    }
}

impl SunSweep {
    /// Sweeps `terrain` for a sun in direction `dir` (grid coordinates); `None` where the
    /// sweep bounds nothing: the sun on or below the horizon or straight overhead, or a map
    /// without a height range or cells.
    pub fn build(terrain: &Terrain, dir: [f64; 3]) -> Option<SunSweep> {
        SunSweep::build_on_level(terrain, dir, level(terrain.field().samples().len()))
    }

    /// [`SunSweep::build`] over the blocks of mipmap level `k` (at least 1; no higher than
    /// the mipmap's top).
    pub fn build_on_level(terrain: &Terrain, dir: [f64; 3], k: u32) -> Option<SunSweep> {
        let k = k.clamp(1, terrain.mipmap().top().max(1));
        let block = 1usize << k;
        let field = terrain.field();
        let cells = [field.width() - 1, field.height() - 1];
        let (z_lo, z_hi) = terrain.z_range();
        let axis = usize::from(dir[1].abs() > dir[0].abs());
        let along = dir[axis].abs();
        let usable =
            dir[2] > 0.0 && along > 0.0 && z_hi > z_lo && dir.iter().all(|c| c.is_finite());
        if !usable || cells[0] == 0 || cells[1] == 0 {
            return None;
        }
        let step = dir.map(|c| c / along);
        let blocks = cells.map(|n| n.div_ceil(block));
        let mut sweep = SunSweep {
            dir,
            axis,
            step,
            cells,
            level: k,
            block,
            blocks_x: blocks[0],
            upper: vec![0; blocks[0] * blocks[1]],
            lower: vec![u16::MAX; blocks[0] * blocks[1]],
            z0: z_lo,
            quantum: (z_hi - z_lo) / f64::from(u16::MAX - 1),
        };
        sweep.sweep(terrain);
        Some(sweep)
    }

    /// The direction the table was swept for.
    pub fn dir(&self) -> [f64; 3] {
        self.dir
    }

    /// Bytes the table holds.
    pub fn bytes(&self) -> usize {
        (self.upper.len() + self.lower.len()) * std::mem::size_of::<u16>()
    }

    /// Fills the blocks' bounds, block column by block column from the sun's side.
    fn sweep(&mut self, terrain: &Terrain) {
        let b = self.block;
        let cells = [self.cells[self.axis], self.cells[1 - self.axis]];
        let [columns, rows] = cells.map(|n| n.div_ceil(b));
        // Blocks wholly on the map: a lower bound needs its landing blocks to be.
        let [whole_columns, whole_rows] = cells.map(|n| n / b);
        let forward = self.step[self.axis] > 0.0;
        let (dv, dz) = (self.step[1 - self.axis], self.step[2] * b as f64);
        // Rows a block's step sweeps over (from its own row), and the rows it lands on.
        let swept = (dv.min(0.0).floor() as i64, dv.max(0.0).ceil() as i64);
        let lands = (dv.floor() as i64, dv.ceil() as i64);
        let in_rows = |v: i64| (0..rows as i64).contains(&v);
        let whole = |v: i64| (0..whole_rows as i64).contains(&v);
        // The next column's (towards the sun), and whether it lies wholly on the map.
        let mut next: Option<(Column, bool)> = None;
        for k in 0..columns {
            let c = if forward { columns - 1 - k } else { k };
            let mut column = Column::corners(terrain, self.axis, self.level, c, rows);
            for v in 0..rows {
                let vi = v as i64;
                let mut u = f64::NEG_INFINITY;
                for w in (vi + swept.0..=vi + swept.1).filter(|&w| in_rows(w)) {
                    u = u.max(column.high[w as usize]);
                    if let Some((next, _)) = &next {
                        u = u.max(next.high[w as usize]);
                    }
                }
                let mut l = f64::NEG_INFINITY;
                if let Some((next, next_whole)) = &next {
                    let landing = vi + lands.0..=vi + lands.1;
                    for w in landing.clone().filter(|&w| in_rows(w)) {
                        u = u.max(next.upper[w as usize] - dz);
                    }
                    if *next_whole && landing.clone().all(whole) {
                        let least = landing
                            .map(|w| next.lower[w as usize].max(next.low[w as usize]))
                            .fold(f64::INFINITY, f64::min);
                        l = least - dz;
                    }
                }
                column.upper[v] = u;
                column.lower[v] = l;
                let (i, j) = cell(self.axis, c, v);
                self.keep(j * self.blocks_x + i, u, l);
            }
            next = Some((column, c < whole_columns));
        }
    }

    /// Keeps block `at`'s bounds, quantised.
    fn keep(&mut self, at: usize, upper: f64, lower: f64) {
        let up = ((upper - self.z0) / self.quantum).ceil();
        self.upper[at] = up.clamp(0.0, f64::from(u16::MAX)) as u16;
        // Code 0 bounds nothing: a bound below the lowest sample settles no point.
        let down = ((lower - self.z0) / self.quantum).floor();
        self.lower[at] = if down >= 1.0 {
            down.min(f64::from(u16::MAX)) as u16
        } else {
            0
        };
    }

    /// The height of an upper bound's code.
    fn upper_height(&self, code: u16) -> f64 {
        self.z0 + f64::from(code) * self.quantum
    }

    /// The height of a lower bound's code (code 0: no bound).
    fn lower_height(&self, code: u16) -> f64 {
        match code {
            0 => f64::NEG_INFINITY,
            _ => self.z0 + f64::from(code) * self.quantum,
        }
    }
}

/// The block `(bi, bj)` of column `c` along `axis`, row `v` across it.
fn cell(axis: usize, c: usize, v: usize) -> (usize, usize) {
    if axis == 0 {
        (c, v)
    } else {
        (v, c)
    }
}

/// One column of blocks across the sweep: their highest and lowest samples' heights and
/// bounds.
struct Column {
    high: Vec<f64>,
    /// Negative infinity on a map with holes: the surface may be missing anywhere.
    low: Vec<f64>,
    upper: Vec<f64>,
    lower: Vec<f64>,
}

impl Column {
    /// Column `c` along `axis` of `rows` blocks of mipmap level `k`, its bounds not yet
    /// known.
    fn corners(terrain: &Terrain, axis: usize, k: u32, c: usize, rows: usize) -> Column {
        let field = terrain.field();
        let (mipmap, holes) = (terrain.mipmap(), field.nodata_count() > 0);
        // (Heights grow with samples, as the terrain's height range takes them.)
        let (high, low) = (0..rows)
            .map(|v| {
                let (bi, bj) = cell(axis, c, v);
                let low = match holes {
                    true => f64::NEG_INFINITY,
                    false => field.height_of(mipmap.lowest(k, bi, bj)),
                };
                (field.height_of(mipmap.highest(k, bi, bj)), low)
            })
            .unzip();
        Column {
            high,
            low,
            upper: vec![f64::NEG_INFINITY; rows],
            lower: vec![f64::NEG_INFINITY; rows],
        }
    }
}
