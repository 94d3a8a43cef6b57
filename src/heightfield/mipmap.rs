//! The min-max mipmap (Tevs, Ihrke & Seidel 2008, with the lowest samples too): the highest
//! sample over aligned square blocks of `2^k x 2^k` cells, for every level `k >= 1`, and the
//! lowest for every level `k >= 2`. Level 0 (one cell) is not stored: the four corner samples
//! give it. The lowest samples of level 1 are not stored either (a level-1 block's lowest
//! sample is bounded by its level-2 parent's): together that keeps the structure at about
//! 5/6 of a byte per sample.

use super::fetch::Window;
use super::{Heightfield, Values};

/// The first level whose lowest samples are stored.
const LOWEST_FROM: u32 = 2;

/// Highest and lowest samples over aligned blocks of cells; level `k` block `(bi, bj)` covers
/// cells `[bi * 2^k, (bi+1) * 2^k) x [bj * 2^k, (bj+1) * 2^k)`, clipped to the grid.
#[derive(Clone, Debug)]
pub struct Mipmap {
    /// Highest samples, levels 1 to the top.
    max: Levels<1>,
    /// Lowest samples, levels [`LOWEST_FROM`] to the top.
    min: Levels<LOWEST_FROM>,
}

/// One value per block of each level from `FIRST` up, in one allocation, so that a lookup is
/// one index computation and one bounds check.
#[derive(Clone, Debug)]
struct Levels<const FIRST: u32> {
    /// Every level's blocks, the finest first, each by `bj * nx + bi`.
    values: Values<u16>,
    /// Per level `k` (index `k - FIRST`): where its blocks start in `values`, and blocks
    /// along x.
    starts: Vec<(usize, usize)>,
}

/// Where the levels of a mipmap lie in its values: per level of each stack, where its blocks
/// start and how many lie along x.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Layout {
    /// The coarsest level.
    pub top: u32,
    /// The highest samples' levels, from 1.
    pub max: Vec<(usize, usize)>,
    /// Values of the highest samples, all levels.
    pub max_len: usize,
    /// The lowest samples' levels, from [`LOWEST_FROM`].
    pub min: Vec<(usize, usize)>,
    /// Values of the lowest samples, all levels.
    pub min_len: usize,
}

impl Layout {
    /// The finest level whose blocks, with all above it, are at most `most` values in both
    /// stacks together (the top, if none is): where its highest and its lowest samples start.
    pub fn upper_levels(&self, most: usize) -> (usize, usize) {
        let from = |k: u32| {
            let (max, min) = (
                self.max[(k - 1) as usize].0,
                self.min[(k - LOWEST_FROM) as usize].0,
            );
            (max, min, self.max_len - max + self.min_len - min)
        };
        let k = (LOWEST_FROM..=self.top)
            .find(|&k| from(k).2 <= most)
            .unwrap_or(self.top);
        let (max, min, _) = from(k);
        (max, min)
    }
}

/// The level whose one block covers a `w x h` grid (level 2 at least, for the lowest samples:
/// a grid of one or two cells has its one block twice).
fn top_level(w: usize, h: usize) -> u32 {
    let cells = (w - 1).max(h - 1);
    (1..)
        .find(|&k| cells <= 1 << k)
        .unwrap_or(1)
        .max(LOWEST_FROM)
}

/// One level while it is built: `nx` blocks along x, by `bj * nx + bi`.
#[derive(Clone, Debug)]
struct Level {
    nx: usize,
    values: Vec<u16>,
}

impl Mipmap {
    /// Builds every level up to the one whose single block covers the grid (level 2 at
    /// least, for the lowest samples: a grid of one or two cells has its one block twice).
    pub fn build(field: &Heightfield) -> Self {
        let top = top_level(field.width(), field.height());
        let (highest, lowest) = first_level(field);
        let lowest = halve(&lowest.values, lowest.nx, u16::min);
        Mipmap {
            max: Levels::stacked(highest, top, u16::max),
            min: Levels::stacked(lowest, top, u16::min),
        }
    }

    /// A mipmap of a `w x h` grid from its levels' values as [`Mipmap::layout`] lays them
    /// out (read from a tile store), or `None` where their lengths do not fit the grid.
    pub(super) fn from_values(
        w: usize,
        h: usize,
        max: Values<u16>,
        min: Values<u16>,
    ) -> Option<Self> {
        let layout = Mipmap::layout(w, h);
        (max.len() == layout.max_len && min.len() == layout.min_len).then(|| Mipmap {
            max: Levels {
                values: max,
                starts: layout.max,
            },
            min: Levels {
                values: min,
                starts: layout.min,
            },
        })
    }

    /// Where each level of a `w x h` grid's mipmap lies in its values, as [`Mipmap::build`]
    /// stacks them.
    pub(super) fn layout(w: usize, h: usize) -> Layout {
        let top = top_level(w, h);
        let stack = |first: u32| {
            let mut starts = Vec::new();
            let mut len = 0;
            for k in first..=top {
                let (nx, ny) = blocks(k, w, h);
                starts.push((len, nx));
                len += nx * ny;
            }
            (starts, len)
        };
        let ((max, max_len), (min, min_len)) = (stack(1), stack(LOWEST_FROM));
        Layout {
            top,
            max,
            max_len,
            min,
            min_len,
        }
    }

    /// The coarsest level (its one block covers the grid).
    pub fn top(&self) -> u32 {
        self.max.starts.len() as u32
    }

    /// Highest sample of block `(bi, bj)` at level `k` (`1 <= k <= top`).
    #[inline]
    pub fn highest(&self, k: u32, bi: usize, bj: usize) -> u16 {
        self.max.get(k, bi, bj)
    }

    /// A lower bound of the samples of block `(bi, bj)` at level `k` (`1 <= k <= top`): the
    /// lowest sample, or on a level whose lowest samples are not stored, that of the block
    /// around it on the first level that has them (no higher than the block's own).
    #[inline]
    pub fn lowest(&self, k: u32, bi: usize, bj: usize) -> u16 {
        let up = LOWEST_FROM.saturating_sub(k);
        self.min.get(k + up, bi >> up, bj >> up)
    }

    /// The `n x n` blocks of level `k` from `(bi, bj)` on (reaching past the level's far
    /// edges where the blocks do, see [`Window`]), in [`Mipmap::highest_values`].
    #[inline]
    pub fn blocks_window(&self, k: u32, bi: usize, bj: usize, n: usize) -> Window {
        self.max.window(k, bi, bj, n)
    }

    /// Every level's highest samples, level 1 first, each level by `bj * nx + bi`.
    pub fn highest_values(&self) -> &[u16] {
        &self.max.values
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.max.bytes() + self.min.bytes()
    }
}

impl<const FIRST: u32> Levels<FIRST> {
    /// Level `FIRST`, and above it the levels up to `top` that `pick` (the highest or lowest
    /// of two samples) makes of it.
    fn stacked(first: Level, top: u32, pick: fn(u16, u16) -> u16) -> Self {
        let mut values = first.values;
        values.reserve(values.len() / 3 + top as usize);
        let mut starts = vec![(0, first.nx)];
        for _ in FIRST..top {
            let (start, nx) = starts[starts.len() - 1];
            let next = halve(&values[start..], nx, pick);
            starts.push((values.len(), next.nx));
            values.extend_from_slice(&next.values);
        }
        Levels {
            values: Values::owned(values),
            starts,
        }
    }

    #[inline]
    fn get(&self, k: u32, bi: usize, bj: usize) -> u16 {
        let (start, nx) = self.starts[(k - FIRST) as usize];
        self.values[start + bj * nx + bi]
    }

    fn window(&self, k: u32, bi: usize, bj: usize, n: usize) -> Window {
        let (start, nx) = self.starts[(k - FIRST) as usize];
        Window {
            first: start + bj * nx + bi,
            len: n,
            rows: n,
            stride: nx,
        }
    }

    fn bytes(&self) -> usize {
        self.values.len() * 2 + self.starts.len() * 16
    }
}

/// Level 1, highest and lowest samples: each block's 3x3 corner samples (fewer at the grid's
/// far edges).
fn first_level(field: &Heightfield) -> (Level, Level) {
    let (w, h) = (field.width(), field.height());
    let (nx, ny) = ((w - 1).div_ceil(2), (h - 1).div_ceil(2));
    let rows: Vec<&[u16]> = field.samples().chunks_exact(w).collect();
    let (mut max, mut min) = (Vec::with_capacity(nx * ny), Vec::with_capacity(nx * ny));
    let mut columns = Columns::new(w);
    for bj in 0..ny {
        let block_rows = first_level_rows(bj, h).map(|j| rows[j]);
        columns.first_level_row(block_rows, &mut max, &mut min);
    }
    (Level { nx, values: max }, Level { nx, values: min })
}

/// The sample rows under level-1 block row `bj` of a grid `h` samples high. (An edge block's
/// last row repeated changes neither extreme.)
pub(super) fn first_level_rows(bj: usize, h: usize) -> [usize; 3] {
    [2 * bj, 2 * bj + 1, (2 * bj + 2).min(h - 1)]
}

/// Blocks along x and y of level `k >= 1` over a grid of `w x h` samples.
pub(super) fn blocks(k: u32, w: usize, h: usize) -> (usize, usize) {
    ((w - 1).div_ceil(1 << k), (h - 1).div_ceil(1 << k))
}

/// The columns' extremes of one row of level-1 blocks, reused from row to row.
pub(super) struct Columns {
    max: Vec<u16>,
    min: Vec<u16>,
}

impl Columns {
    /// Room for rows of `w` samples.
    pub(super) fn new(w: usize) -> Self {
        Columns {
            max: vec![0; w],
            min: vec![0; w],
        }
    }

    /// Appends the highest and lowest samples of the level-1 blocks over the three sample
    /// `rows` to `max` and `min`. The rows are first reduced column by column, which the
    /// compiler vectorises, and those columns then in threes.
    pub(super) fn first_level_row(
        &mut self,
        [r0, r1, r2]: [&[u16]; 3],
        max: &mut Vec<u16>,
        min: &mut Vec<u16>,
    ) {
        let w = r0.len();
        let columns = self.max.iter_mut().zip(&mut self.min);
        for (((hi, lo), &a), (&b, &c)) in columns.zip(r0).zip(r1.iter().zip(r2)) {
            *hi = a.max(b).max(c);
            *lo = a.min(b).min(c);
        }
        for bi in 0..(w - 1).div_ceil(2) {
            // (An edge block's last column repeated changes neither extreme.)
            let columns = [2 * bi, 2 * bi + 1, (2 * bi + 2).min(w - 1)];
            let [a, b, c] = columns.map(|x| self.max[x]);
            max.push(a.max(b).max(c));
            let [a, b, c] = columns.map(|x| self.min[x]);
            min.push(a.min(b).min(c));
        }
    }
}

/// The level above the `nx`-wide `below`: each block what `pick` makes of its (up to) four
/// children.
fn halve(below: &[u16], nx: usize, pick: fn(u16, u16) -> u16) -> Level {
    let ny = below.len() / nx;
    let (up_x, up_y) = (nx.div_ceil(2), ny.div_ceil(2));
    let mut values = Vec::with_capacity(up_x * up_y);
    for bj in 0..up_y {
        let rows = halved_rows(bj, ny).map(|y| &below[y * nx..(y + 1) * nx]);
        halve_row(rows, pick, &mut values);
    }
    Level { nx: up_x, values }
}

/// The rows of a level `ny` blocks high under row `bj` of the level above. (An edge block's
/// one child repeated changes neither extreme.)
pub(super) fn halved_rows(bj: usize, ny: usize) -> [usize; 2] {
    [2 * bj, (2 * bj + 1).min(ny - 1)]
}

/// Appends to `out` the row of the level above the two block `rows`: each block what `pick`
/// makes of its (up to) four children.
pub(super) fn halve_row(rows: [&[u16]; 2], pick: fn(u16, u16) -> u16, out: &mut Vec<u16>) {
    let nx = rows[0].len();
    for bi in 0..nx.div_ceil(2) {
        let (x0, x1) = (2 * bi, (2 * bi + 1).min(nx - 1));
        out.push(pick(
            pick(rows[0][x0], rows[0][x1]),
            pick(rows[1][x0], rows[1][x1]),
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_blocks_window_holds_every_block_under_it() {
        for (w, h) in [(2, 2), (13, 6), (17, 33), (70, 37)] {
            let field = Heightfield::from_fn(w, h, 255, 1.0, |_, _| 0).unwrap();
            let mipmap = Mipmap::build(&field);
            for k in 1..=mipmap.top() {
                let (start, nx) = mipmap.max.starts[k as usize - 1];
                let ny = (h - 1).div_ceil(1 << k);
                for (bj, bi) in (0..ny)
                    .step_by(4)
                    .flat_map(|bj| (0..nx).step_by(4).map(move |bi| (bj, bi)))
                {
                    let window = mipmap.blocks_window(k, bi, bj, 4);
                    let under = (bj..(bj + 4).min(ny))
                        .flat_map(|y| (bi..(bi + 4).min(nx)).map(move |x| start + y * nx + x));
                    for at in under {
                        assert!(window.contains(at), "{w}x{h} level {k}: {at} in {window:?}");
                    }
                    assert_eq!(
                        window.len * window.rows,
                        16,
                        "{w}x{h} level {k}: nothing more"
                    );
                }
            }
        }
    }

    #[test]
    fn blocks_hold_the_extremes_of_their_cells() {
        for (w, h) in [(2, 2), (3, 2), (5, 3), (13, 6), (17, 33)] {
            let field = Heightfield::from_fn(w, h, 1000, 1.0, |x, y| {
                ((x * 7919 + y * 104729) % 997) as u16
            })
            .unwrap();
            let mipmap = Mipmap::build(&field);
            let cells = (w - 1).max(h - 1);
            assert!(1 << mipmap.top() >= cells, "{w}x{h}: top covers the grid");
            for k in 1..=mipmap.top() {
                let size = 1usize << k;
                for bj in 0..(h - 1).div_ceil(size) {
                    for bi in 0..(w - 1).div_ceil(size) {
                        let samples = |size: usize, bi: usize, bj: usize| {
                            let xs = bi * size..=((bi + 1) * size).min(w - 1);
                            let ys = bj * size..=((bj + 1) * size).min(h - 1);
                            ys.flat_map(move |y| xs.clone().map(move |x| (x, y)))
                                .map(|(x, y)| field.sample(x, y))
                        };
                        let want = samples(size, bi, bj).max().unwrap();
                        assert_eq!(
                            mipmap.highest(k, bi, bj),
                            want,
                            "{w}x{h} level {k} ({bi},{bj})"
                        );
                        // The lowest sample where it is stored, else the parent's on the
                        // first level that stores it.
                        let up = LOWEST_FROM.saturating_sub(k);
                        let lowest = samples(size << up, bi >> up, bj >> up).min().unwrap();
                        assert_eq!(
                            mipmap.lowest(k, bi, bj),
                            lowest,
                            "{w}x{h} level {k} ({bi},{bj})"
                        );
                        assert!(lowest <= samples(size, bi, bj).min().unwrap());
                    }
                }
            }
        }
    }

    #[test]
    fn the_layout_is_where_build_stacks_the_levels() {
        for (w, h) in [
            (2, 2),
            (3, 2),
            (5, 3),
            (13, 6),
            (17, 33),
            (70, 37),
            (1025, 3),
        ] {
            let field =
                Heightfield::from_fn(w, h, 255, 1.0, |x, y| ((x ^ y) % 256) as u16).unwrap();
            let built = Mipmap::build(&field);
            let layout = Mipmap::layout(w, h);
            assert_eq!(layout.top, built.top(), "{w}x{h}");
            assert_eq!(layout.max, built.max.starts, "{w}x{h}");
            assert_eq!(layout.min, built.min.starts, "{w}x{h}");
            assert_eq!(layout.max_len, built.max.values.len(), "{w}x{h}");
            assert_eq!(layout.min_len, built.min.values.len(), "{w}x{h}");
        }
    }

    #[test]
    fn it_holds_five_sixths_of_a_byte_per_sample() {
        let field = Heightfield::from_fn(1025, 1025, 255, 1.0, |_, _| 0).unwrap();
        let per_sample = Mipmap::build(&field).bytes() as f64 / (1025.0 * 1025.0);
        // Highest samples: 2 bytes for a quarter of the samples, a sixteenth, ...: 2/3; lowest
        // from level 2 on: 1/6.
        assert!((per_sample - 5.0 / 6.0).abs() < 0.01, "{per_sample}");
    }
}
