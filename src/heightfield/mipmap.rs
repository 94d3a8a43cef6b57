//! The max-mipmap (Tevs, Ihrke & Seidel 2008): the highest sample over aligned square blocks
//! of `2^k x 2^k` cells, for every level `k >= 1`. Level 0 (one cell) is not stored: the four
//! corner samples give it, which keeps the structure at about 2/3 of a byte per sample.

use super::fetch::Window;
use super::Heightfield;

/// Highest samples over aligned blocks of cells; level `k` block `(bi, bj)` covers cells
/// `[bi * 2^k, (bi+1) * 2^k) x [bj * 2^k, (bj+1) * 2^k)`, clipped to the grid.
#[derive(Clone, Debug)]
pub struct MaxMipmap {
    /// Every level's blocks, level 1 first, each by `bj * nx + bi`: one allocation, so that
    /// a lookup is one index computation and one bounds check.
    max: Vec<u16>,
    /// Per level `k` (index `k - 1`): where its blocks start in `max`, and blocks along x.
    levels: Vec<(usize, usize)>,
}

#[derive(Clone, Debug)]
struct Level {
    /// Blocks along x and y.
    nx: usize,
    ny: usize,
    /// By `bj * nx + bi`.
    max: Vec<u16>,
}

impl MaxMipmap {
    /// Builds every level up to the one whose single block covers the grid.
    pub fn build(field: &Heightfield) -> Self {
        let (cells_x, cells_y) = (field.width() - 1, field.height() - 1);
        let mut built = vec![first_level(field)];
        while cells_x.max(cells_y) > 1 << built.len() {
            let below = &built[built.len() - 1];
            built.push(halve(below));
        }
        let mut levels = Vec::with_capacity(built.len());
        let mut max = Vec::with_capacity(built.iter().map(|l| l.max.len()).sum());
        for level in built {
            levels.push((max.len(), level.nx));
            max.extend_from_slice(&level.max);
        }
        MaxMipmap { max, levels }
    }

    /// The coarsest level (its one block covers the grid).
    pub fn top(&self) -> u32 {
        self.levels.len() as u32
    }

    /// Highest sample of block `(bi, bj)` at level `k` (`1 <= k <= top`).
    #[inline]
    pub fn get(&self, k: u32, bi: usize, bj: usize) -> u16 {
        let (start, nx) = self.levels[k as usize - 1];
        self.max[start + bj * nx + bi]
    }

    /// The `n x n` blocks of level `k` from `(bi, bj)` on (those inside the level), in
    /// [`MaxMipmap::values`].
    #[inline]
    pub fn blocks_window(&self, k: u32, bi: usize, bj: usize, n: usize) -> Window {
        let (start, nx) = self.levels[k as usize - 1];
        let end = self
            .levels
            .get(k as usize)
            .map_or(self.max.len(), |next| next.0);
        let rows = (end - start) / nx;
        Window {
            first: start + bj * nx + bi,
            len: n.min(nx - bi),
            rows: (bj + n).min(rows) - bj,
            stride: nx,
        }
    }

    /// Every level's blocks, level 1 first, each level by `bj * nx + bi`.
    pub fn values(&self) -> &[u16] {
        &self.max
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.max.len() * 2 + self.levels.len() * 16
    }
}

/// Level 1: each block's 3x3 corner samples (fewer at the grid's far edges). Rows of samples
/// are first reduced in pairs of columns, so every sample is read about twice.
fn first_level(field: &Heightfield) -> Level {
    let (w, h) = (field.width(), field.height());
    let (nx, ny) = ((w - 1).div_ceil(2), (h - 1).div_ceil(2));
    let samples = field.samples();
    // Per sample row: the maximum over each block's sample columns 2bi..=2bi+2.
    let row_blocks = |row: &[u16]| -> Vec<u16> {
        (0..nx)
            .map(|bi| {
                let hi = (2 * bi + 2).min(w - 1);
                row[2 * bi..=hi].iter().copied().max().unwrap_or(0)
            })
            .collect()
    };
    let rows: Vec<Vec<u16>> = samples.chunks_exact(w).map(row_blocks).collect();
    let mut max = Vec::with_capacity(nx * ny);
    for bj in 0..ny {
        let hi = (2 * bj + 2).min(h - 1);
        for bi in 0..nx {
            max.push(rows[2 * bj..=hi].iter().map(|r| r[bi]).max().unwrap_or(0));
        }
    }
    Level { nx, ny, max }
}

/// The next level: each block the maximum of its (up to) four children.
fn halve(below: &Level) -> Level {
    let (nx, ny) = (below.nx.div_ceil(2), below.ny.div_ceil(2));
    let mut max = Vec::with_capacity(nx * ny);
    for bj in 0..ny {
        let rows = 2 * bj..(2 * bj + 2).min(below.ny);
        for bi in 0..nx {
            let cols = 2 * bi..(2 * bi + 2).min(below.nx);
            let children = rows
                .clone()
                .flat_map(|cj| cols.clone().map(move |ci| below.max[cj * below.nx + ci]));
            max.push(children.max().unwrap_or(0));
        }
    }
    Level { nx, ny, max }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_blocks_window_is_every_block_under_it_inside_its_level() {
        for (w, h) in [(2, 2), (13, 6), (17, 33), (70, 37)] {
            let field = Heightfield::from_fn(w, h, 255, 1.0, |_, _| 0).unwrap();
            let mipmap = MaxMipmap::build(&field);
            for k in 1..=mipmap.top() {
                let (start, nx) = mipmap.levels[k as usize - 1];
                let ny = (h - 1).div_ceil(1 << k);
                for (bj, bi) in (0..ny)
                    .step_by(4)
                    .flat_map(|bj| (0..nx).step_by(4).map(move |bi| (bj, bi)))
                {
                    let window = mipmap.blocks_window(k, bi, bj, 4);
                    assert!(
                        window.end() <= start + nx * ny,
                        "{w}x{h} level {k}: {window:?}"
                    );
                    let under = (bj..(bj + 4).min(ny))
                        .flat_map(|y| (bi..(bi + 4).min(nx)).map(move |x| start + y * nx + x));
                    let mut count = 0;
                    for at in under {
                        assert!(window.contains(at), "{w}x{h} level {k}: {at} in {window:?}");
                        count += 1;
                    }
                    assert_eq!(
                        window.len * window.rows,
                        count,
                        "{w}x{h} level {k}: nothing more"
                    );
                }
            }
        }
    }

    #[test]
    fn blocks_hold_the_highest_sample_of_their_cells() {
        for (w, h) in [(2, 2), (3, 2), (13, 6), (17, 33)] {
            let field = Heightfield::from_fn(w, h, 1000, 1.0, |x, y| {
                ((x * 7919 + y * 104729) % 997) as u16
            })
            .unwrap();
            let mipmap = MaxMipmap::build(&field);
            let cells = (w - 1).max(h - 1);
            assert!(1 << mipmap.top() >= cells, "{w}x{h}: top covers the grid");
            for k in 1..=mipmap.top() {
                let size = 1usize << k;
                for bj in 0..(h - 1).div_ceil(size) {
                    for bi in 0..(w - 1).div_ceil(size) {
                        let xs = bi * size..=((bi + 1) * size).min(w - 1);
                        let ys = bj * size..=((bj + 1) * size).min(h - 1);
                        let want = ys
                            .flat_map(|y| xs.clone().map(move |x| (x, y)))
                            .map(|(x, y)| field.sample(x, y))
                            .max()
                            .unwrap();
                        assert_eq!(mipmap.get(k, bi, bj), want, "{w}x{h} level {k} ({bi},{bj})");
                    }
                }
            }
        }
    }
}
