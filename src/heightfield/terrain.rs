//! A height field with the acceleration data the traversals use.

use super::{CellMaxima, Heightfield, LineMaxima};
use std::time::{Duration, Instant};

/// A height field ready to be ray traced: cell maxima, row and column range maxima, and the
/// height range.
#[derive(Clone, Debug)]
pub struct Terrain {
    field: Heightfield,
    cells: CellMaxima,
    rows: LineMaxima,
    columns: LineMaxima,
    min_sample: u16,
    max_sample: u16,
    max_slope: f64,
    build_time: Duration,
}

impl Terrain {
    /// Builds the acceleration data (timed).
    pub fn new(field: Heightfield) -> Self {
        let start = Instant::now();
        let cells = CellMaxima::build(&field);
        let rows = LineMaxima::rows(&cells);
        let columns = LineMaxima::columns(&cells);
        // No-data samples hold the lowest valid sample: they change neither extreme.
        let min_sample = field.samples().iter().copied().min().unwrap_or(0);
        let max_sample = field.samples().iter().copied().max().unwrap_or(0);
        let max_slope = max_slope(&field);
        Terrain {
            max_slope,
            field,
            cells,
            rows,
            columns,
            min_sample,
            max_sample,
            build_time: start.elapsed(),
        }
    }

    pub fn field(&self) -> &Heightfield {
        &self.field
    }
    /// Heights `[z00, z10, z01, z11]` of the corners of cell `(i, j)`.
    pub fn corner_heights(&self, i: usize, j: usize) -> [f64; 4] {
        let f = &self.field;
        [f.z(i, j), f.z(i + 1, j), f.z(i, j + 1), f.z(i + 1, j + 1)]
    }
    /// Highest height of cell `(i, j)`.
    pub fn cell_max(&self, i: usize, j: usize) -> f64 {
        self.field.height_of(self.cells.get(i, j))
    }
    /// Highest height over cells `lo..=hi` of row `j`.
    pub fn row_max(&self, j: usize, lo: usize, hi: usize) -> f64 {
        self.field.height_of(self.rows.max(j, lo, hi))
    }
    /// Highest height over cells `lo..=hi` of column `i`.
    pub fn column_max(&self, i: usize, lo: usize, hi: usize) -> f64 {
        self.field.height_of(self.columns.max(i, lo, hi))
    }
    /// Lowest and highest height of the field.
    pub fn z_range(&self) -> (f64, f64) {
        (
            self.field.height_of(self.min_sample),
            self.field.height_of(self.max_sample),
        )
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
    /// Bytes of acceleration data beyond the samples.
    pub fn accel_bytes(&self) -> usize {
        let (nx, ny) = self.cells.size();
        nx * ny * 2 + self.rows.bytes() + self.columns.bytes()
    }
}

/// Largest gradient magnitude over all triangles (holes have none). The gradient of `T0` is
/// `(z10 - z00, z11 - z10)`, of `T1` `(z11 - z01, z01 - z00)`.
fn max_slope(field: &Heightfield) -> f64 {
    let mut steepest: f64 = 0.0;
    for j in 0..field.height() - 1 {
        for i in (0..field.width() - 1).filter(|&i| !field.is_hole_cell(i, j)) {
            let (z00, z10) = (field.z(i, j), field.z(i + 1, j));
            let (z01, z11) = (field.z(i, j + 1), field.z(i + 1, j + 1));
            steepest = steepest
                .max((z10 - z00).hypot(z11 - z10))
                .max((z11 - z01).hypot(z01 - z00));
        }
    }
    steepest
}
