//! Highest sample of every cell, and range maxima along rows and columns of cells.

use super::Heightfield;

/// The highest of the four corner samples of every cell, by `j * (W-1) + i`.
#[derive(Clone, Debug)]
pub struct CellMaxima {
    cells_x: usize,
    cells_y: usize,
    max: Vec<u16>,
}

impl CellMaxima {
    /// The cell maxima of `field`.
    pub fn build(field: &Heightfield) -> Self {
        let (cells_x, cells_y) = (field.width() - 1, field.height() - 1);
        let mut max = Vec::with_capacity(cells_x * cells_y);
        for j in 0..cells_y {
            for i in 0..cells_x {
                let corners = [
                    field.sample(i, j),
                    field.sample(i + 1, j),
                    field.sample(i, j + 1),
                    field.sample(i + 1, j + 1),
                ];
                max.push(corners.into_iter().max().unwrap_or(0));
            }
        }
        CellMaxima {
            cells_x,
            cells_y,
            max,
        }
    }

    /// Highest sample of cell `(i, j)`.
    pub fn get(&self, i: usize, j: usize) -> u16 {
        self.max[j * self.cells_x + i]
    }

    /// Cells along x and along y.
    pub fn size(&self) -> (usize, usize) {
        (self.cells_x, self.cells_y)
    }
}

/// Range maxima of cell maxima along lines of cells (rows, or columns), answered in
/// O(log n) from aligned power-of-two blocks: level `k` holds the maximum of cells
/// `[b * 2^k, (b+1) * 2^k)` of each line. Memory: about twice the cell maxima.
#[derive(Clone, Debug)]
pub struct LineMaxima {
    /// `levels[k]` has `lines * blocks[k]` entries, line-major.
    levels: Vec<Vec<u16>>,
    /// Blocks per line at each level.
    blocks: Vec<usize>,
}

impl LineMaxima {
    /// Maxima along rows of cells (a line is a fixed `j`, cells indexed by `i`).
    pub fn rows(cells: &CellMaxima) -> Self {
        let (nx, ny) = cells.size();
        Self::build(nx, ny, |line, k| cells.get(k, line))
    }

    /// Maxima along columns of cells (a line is a fixed `i`, cells indexed by `j`).
    pub fn columns(cells: &CellMaxima) -> Self {
        let (nx, ny) = cells.size();
        Self::build(ny, nx, |line, k| cells.get(line, k))
    }

    fn build(len: usize, lines: usize, cell: impl Fn(usize, usize) -> u16) -> Self {
        let mut level0 = Vec::with_capacity(len * lines);
        for line in 0..lines {
            level0.extend((0..len).map(|k| cell(line, k)));
        }
        let (mut levels, mut blocks) = (vec![level0], vec![len]);
        while blocks[blocks.len() - 1] > 1 {
            let (below, n) = (&levels[levels.len() - 1], blocks[blocks.len() - 1]);
            let mut next = Vec::with_capacity(n.div_ceil(2) * lines);
            for line in below.chunks(n) {
                next.extend(
                    line.chunks(2)
                        .map(|pair| pair.iter().copied().max().unwrap_or(0)),
                );
            }
            levels.push(next);
            blocks.push(n.div_ceil(2));
        }
        LineMaxima { levels, blocks }
    }

    /// Highest cell maximum among cells `lo..=hi` of line `line`.
    pub fn max(&self, line: usize, lo: usize, hi: usize) -> u16 {
        let (mut lo, end) = (lo, hi + 1);
        let mut best = 0;
        while lo < end {
            // The largest aligned block that starts at `lo` and ends by `end`.
            let k = (lo.trailing_zeros()).min((end - lo).ilog2()) as usize;
            best = best.max(self.levels[k][line * self.blocks[k] + (lo >> k)]);
            lo += 1 << k;
        }
        best
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.levels.iter().map(|l| l.len() * 2).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_maxima_match_brute_force() {
        let field = Heightfield::from_fn(13, 6, 1000, 1.0, |x, y| {
            ((x * 7919 + y * 104729) % 997) as u16
        })
        .unwrap();
        let cells = CellMaxima::build(&field);
        let (rows, cols) = (LineMaxima::rows(&cells), LineMaxima::columns(&cells));
        let (nx, ny) = cells.size();
        for j in 0..ny {
            for lo in 0..nx {
                for hi in lo..nx {
                    let want = (lo..=hi).map(|i| cells.get(i, j)).max().unwrap();
                    assert_eq!(rows.max(j, lo, hi), want, "row {j} [{lo},{hi}]");
                }
            }
        }
        for i in 0..nx {
            for lo in 0..ny {
                for hi in lo..ny {
                    let want = (lo..=hi).map(|j| cells.get(i, j)).max().unwrap();
                    assert_eq!(cols.max(i, lo, hi), want, "column {i} [{lo},{hi}]");
                }
            }
        }
    }
}
