//! A height field with the acceleration data the traversals use.

use super::fetch::FETCH_AHEAD_BYTES;
use super::{CellMaxima, Heightfield, LineMaxima, Mipmap, Preview, SkyBounds, StripBounds};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant};

/// A height field ready to be ray traced: the min-max mipmap, the height range, and (built on
/// first use, for the run method) row and column range maxima.
#[derive(Clone, Debug)]
pub struct Terrain {
    field: Heightfield,
    mipmap: Mipmap,
    lines: OnceLock<Lines>,
    /// The coarse stand-in of a mapped map, made on first use.
    preview: OnceLock<Option<Arc<Preview>>>,
    /// The strip bounds of the last direction asked for (see [`Terrain::strip_bounds`]).
    strips: Memo<([f64; 3], f64), StripBounds>,
    /// The sky bounds of the last reach asked for (see [`Terrain::sky_bounds`]).
    sky: Memo<f64, SkyBounds>,
    max_slope: f64,
    /// The box every ray is clipped to, `(lowest corner, highest corner)`: cells in x and y,
    /// the height range in z (kept: every ray asks for it).
    bounds: ([f64; 3], [f64; 3]),
    /// Whether walks fetch ahead (the map is larger than the caches).
    fetch_ahead: bool,
    /// World coordinates per grid coordinate, where cells are not square.
    world_from_grid: Option<[f64; 3]>,
    build_time: Duration,
}

impl Terrain {
    /// Builds the acceleration data every method uses (timed).
    pub fn new(field: Heightfield) -> Self {
        let start = Instant::now();
        let prebuilt = field.prebuilt.clone();
        let mipmap = match &prebuilt {
            Some(ready) => ready.mipmap.clone(),
            None => Mipmap::build(&field),
        };
        // (No-data samples hold the lowest valid sample: they change neither extreme.)
        let top = mipmap.top();
        let (min_sample, max_sample) = (mipmap.lowest(top, 0, 0), mipmap.highest(top, 0, 0));
        let steepest = match &prebuilt {
            Some(ready) => ready.steepest,
            None => steepest(&field),
        };
        let max_slope = field.step() * steepest.sqrt();
        let (z_lo, z_hi) = (field.height_of(min_sample), field.height_of(max_sample));
        let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
        Terrain {
            max_slope,
            bounds: ([0.0, 0.0, z_lo], [w, h, z_hi]),
            world_from_grid: world_from_grid(&field),
            fetch_ahead: field.samples().len() * 2 >= FETCH_AHEAD_BYTES,
            field,
            mipmap,
            lines: OnceLock::new(),
            preview: OnceLock::new(),
            strips: Memo::default(),
            sky: Memo::default(),
            build_time: start.elapsed(),
        }
    }

    /// The height field.
    pub fn field(&self) -> &Heightfield {
        &self.field
    }

    /// The height field, without the acceleration data.
    pub fn into_field(self) -> Heightfield {
        self.field
    }

    /// How grid coordinates scale into the world's, per axis, on a georeferenced field whose
    /// cells are not square: one world unit is a cell's height along y, so x is scaled by a
    /// cell's width over its height. `None` where world and grid coordinates are the same.
    pub fn world_from_grid(&self) -> Option<[f64; 3]> {
        self.world_from_grid
    }

    /// A point of the world in grid coordinates.
    pub fn grid_point(&self, point: [f64; 3]) -> [f64; 3] {
        match self.world_from_grid {
            Some(scale) => std::array::from_fn(|k| point[k] / scale[k]),
            None => point,
        }
    }

    /// A point in grid coordinates in the world.
    pub fn world_point(&self, point: [f64; 3]) -> [f64; 3] {
        match self.world_from_grid {
            Some(scale) => std::array::from_fn(|k| point[k] * scale[k]),
            None => point,
        }
    }
    /// A walk goes down into block `(bi, bj)` of level `k`: on a map larger than the caches,
    /// asks the processor to fetch what it will read two levels below: the samples of a block
    /// of 4x4 cells, the 4x4 blocks under a block of level 3 or 4.
    #[inline(always)]
    pub fn fetch_below(&self, k: u32, bi: usize, bj: usize) {
        if !self.fetch_ahead {
            return;
        }
        match k {
            2 => {
                let cells = self.field.cells_window(bi << 2, bj << 2, 4);
                cells.prefetch(self.field.samples());
            }
            3 | 4 => {
                let blocks = self.mipmap.blocks_window(k - 2, bi << 2, bj << 2, 4);
                blocks.prefetch(self.mipmap.highest_values());
            }
            _ => {}
        }
    }
    /// Heights `[z00, z10, z01, z11]` of the corners of cell `(i, j)`.
    // (One index for the four samples, as `cell_sample_range` reads them: this is read for
    // every cell whose triangles are tested.)
    #[inline]
    pub fn corner_heights(&self, i: usize, j: usize) -> [f64; 4] {
        let (f, w) = (&self.field, self.field.width());
        let below = j * w + i;
        let s = &f.samples()[below..below + w + 2];
        [s[0], s[1], s[w], s[w + 1]].map(|sample| f.height_of(sample))
    }
    /// Lowest and highest sample of cell `(i, j)`.
    #[inline]
    pub fn cell_sample_range(&self, i: usize, j: usize) -> (u16, u16) {
        let (w, s) = (self.field.width(), self.field.samples());
        let (below, above) = (j * w + i, (j + 1) * w + i);
        let corners = [s[below], s[below + 1], s[above], s[above + 1]];
        let lowest = corners[0].min(corners[1]).min(corners[2].min(corners[3]));
        let highest = corners[0].max(corners[1]).max(corners[2].max(corners[3]));
        (lowest, highest)
    }
    /// Highest sample over the cells of block `(bi, bj)` of mipmap level `k` (level 0: a cell).
    #[inline]
    pub fn block_max_sample(&self, k: u32, bi: usize, bj: usize) -> u16 {
        if k == 0 {
            self.cell_sample_range(bi, bj).1
        } else {
            self.mipmap.highest(k, bi, bj)
        }
    }
    /// The min-max mipmap.
    pub fn mipmap(&self) -> &Mipmap {
        &self.mipmap
    }
    /// Highest height over cells `lo..=hi` of row `j`.
    pub fn row_max(&self, j: usize, lo: usize, hi: usize) -> f64 {
        self.field.height_of(self.lines().rows.max(j, lo, hi))
    }
    /// Highest height over cells `lo..=hi` of column `i`.
    pub fn column_max(&self, i: usize, lo: usize, hi: usize) -> f64 {
        self.field.height_of(self.lines().columns.max(i, lo, hi))
    }
    /// The row and column range maxima, built on first use (only the run method asks).
    pub fn lines(&self) -> &Lines {
        self.lines.get_or_init(|| Lines::build(&self.field))
    }
    /// The strip bounds for rays in `dir` (grid coordinates) or within `half` (radians) of it,
    /// built on first use and kept while the same disc is asked for (a sun that stays put
    /// while the camera moves); `None` where they cannot help (see [`StripBounds::build`]).
    /// A map mapped from a tile store has none: building them reads every sample, which
    /// there may be more of than memory holds.
    pub fn strip_bounds(&self, dir: [f64; 3], half: f64) -> Option<Arc<StripBounds>> {
        if self.field.is_mapped() {
            return None;
        }
        self.strips
            .get_or_make((dir, half), || StripBounds::build(&self.field, dir, half))
    }
    /// The sky bounds for sky-light rays that look `reach` far (grid units, horizontally),
    /// kept while the same reach is asked for; each block's are made when a ray first asks.
    /// `None` where they cannot help (see [`SkyBounds::new`]).
    pub fn sky_bounds(&self, reach: f64) -> Option<Arc<SkyBounds>> {
        self.sky.get_or_make(reach, || SkyBounds::new(self, reach))
    }
    /// The same terrain with its box's height range widened to `lo..hi` (a range that holds
    /// its own): colours by height then follow that range.
    pub(super) fn with_z_range(mut self, lo: f64, hi: f64) -> Self {
        self.bounds.0[2] = self.bounds.0[2].min(lo);
        self.bounds.1[2] = self.bounds.1[2].max(hi);
        self
    }
    /// A coarse stand-in for a map mapped from a tile store, made once from its mipmap's
    /// upper levels (see [`Preview`]); `None` for a map held in memory or small enough.
    pub fn preview(&self) -> Option<&Preview> {
        if !self.field.is_mapped() {
            return None;
        }
        self.preview
            .get_or_init(|| Preview::of(self).map(Arc::new))
            .as_deref()
    }
    /// Lowest and highest height of the field.
    pub fn z_range(&self) -> (f64, f64) {
        (self.bounds.0[2], self.bounds.1[2])
    }
    /// The box that holds the surface: `[0, W-1] x [0, H-1] x` the height range, as its
    /// lowest and highest corners.
    pub fn bounds(&self) -> &([f64; 3], [f64; 3]) {
        &self.bounds
    }
    /// The steepest gradient of any triangle (height per unit of horizontal distance): no
    /// path on the surface climbs faster, which bounds where shadows can fall.
    pub fn max_slope(&self) -> f64 {
        self.max_slope
    }
    /// Time spent building the acceleration data.
    pub fn build_time(&self) -> Duration {
        self.build_time
    }
    /// Bytes of acceleration data beyond the samples that every method uses (the mipmap).
    pub fn accel_bytes(&self) -> usize {
        self.mipmap.bytes()
    }
}

/// The bounds last made for a key (none where they cannot help), with the key.
#[derive(Debug)]
struct Memo<K, T>(Mutex<Option<(K, Option<Arc<T>>)>>);

impl<K: PartialEq + Copy, T> Memo<K, T> {
    /// The bounds for `key`: those kept if made for it, else `make`'s, kept in their place.
    fn get_or_make(&self, key: K, make: impl FnOnce() -> Option<T>) -> Option<Arc<T>> {
        let mut kept = self
            .0
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some((at, bounds)) = kept.as_ref() {
            if *at == key {
                return bounds.clone();
            }
        }
        let bounds = make().map(Arc::new);
        *kept = Some((key, bounds.clone()));
        bounds
    }
}

impl<K, T> Default for Memo<K, T> {
    fn default() -> Self {
        Memo(Mutex::new(None))
    }
}

impl<K: Clone, T> Clone for Memo<K, T> {
    fn clone(&self) -> Self {
        let kept = self
            .0
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        Memo(Mutex::new(kept.clone()))
    }
}

/// Range maxima along rows and columns of cells, for the run test.
#[derive(Clone, Debug)]
pub struct Lines {
    rows: LineMaxima,
    columns: LineMaxima,
    build_time: Duration,
}

impl Lines {
    fn build(field: &Heightfield) -> Self {
        let start = Instant::now();
        let cells = CellMaxima::build(field);
        let (rows, columns) = (LineMaxima::rows(&cells), LineMaxima::columns(&cells));
        Lines {
            rows,
            columns,
            build_time: start.elapsed(),
        }
    }
    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.rows.bytes() + self.columns.bytes()
    }
    /// Time the build took.
    pub fn build_time(&self) -> Duration {
        self.build_time
    }
}

/// Largest squared gradient magnitude over all triangles, in samples (holes have none): the
/// map's steepest slope is the square root of it times a sample step. The gradient of `T0` is
/// `(z10 - z00, z11 - z10)`, of `T1` `(z11 - z01, z01 - z00)`; compared as squares of sample
/// differences, exact in `f64` (below 2^33), so one square root is taken in all.
fn steepest(field: &Heightfield) -> f64 {
    let w = field.width();
    let rows: Vec<&[u16]> = field.samples().chunks_exact(w).collect();
    let holes = field.nodata_count() > 0;
    rows.windows(2)
        .enumerate()
        .map(|(j, pair)| match holes {
            true => steepest_in_row(pair[0], pair[1], |i| !field.is_hole_cell(i, j)),
            // (Without the test, the compiler vectorises the row.)
            false => steepest_in_row(pair[0], pair[1], |_| true),
        })
        .fold(0.0, larger)
}

/// The largest squared gradient, in samples, of the triangles of the cells between sample
/// rows `below` and `above` that `counted` (by column).
#[inline(always)]
pub(super) fn steepest_in_row(
    below: &[u16],
    above: &[u16],
    counted: impl Fn(usize) -> bool,
) -> f64 {
    let square = |a: u16, b: u16| f64::from(a.abs_diff(b)).powi(2);
    let n = below.len() - 1;
    let cells = below[..n]
        .iter()
        .zip(&below[1..])
        .zip(above[..n].iter().zip(&above[1..]));
    cells
        .enumerate()
        .map(|(i, ((&z00, &z10), (&z01, &z11)))| {
            let t0 = square(z10, z00) + square(z11, z10);
            let t1 = square(z11, z01) + square(z01, z00);
            if counted(i) {
                larger(t0, t1)
            } else {
                0.0
            }
        })
        .fold(0.0, larger)
}

/// The larger of two numbers that are not NaN (in the form the compiler vectorises).
#[inline(always)]
pub(super) fn larger(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// World coordinates per grid coordinate of a field with non-square cells (see
/// [`Terrain::world_from_grid`]).
pub(crate) fn world_from_grid(field: &Heightfield) -> Option<[f64; 3]> {
    let [x, y] = field.cell_metres()?;
    let stretch = x / y;
    (stretch.is_finite() && stretch > 0.0 && stretch != 1.0).then_some([stretch, 1.0, 1.0])
}
