//! The acceleration data of a store, built from its written samples a few rows at a time (the
//! map may not fit in memory): the mipmap's levels by the same row steps as
//! [`Mipmap::build`](crate::heightfield::Mipmap::build), so they are the same values, the
//! steepest gradient as the terrain finds it, and the count of samples without data. Rows of
//! zeros are not written: the gaps of a sparse mosaic stay unstored.

use super::header::Sections;
use super::StoreError;
use crate::heightfield::mipmap::{
    blocks, first_level_rows, halve_row, halved_rows, Columns, Layout,
};
use crate::heightfield::terrain::{larger, steepest_in_row};
use crate::heightfield::Mipmap;
use std::fs::File;
use std::ops::ControlFlow;
use std::os::unix::fs::FileExt;
use std::path::Path;

/// What building found.
pub struct Built {
    /// The steepest squared gradient, in samples.
    pub steepest: f64,
    /// Samples without data.
    pub holes: u64,
}

/// Reads and writes a store's sections by rows.
struct Rows<'a> {
    file: &'a File,
    path: &'a Path,
    /// Per sample row, how many rows below it some input covers: the rows of a level no
    /// input reaches are zeros (and have no data), and are not read.
    covered_below: Vec<u64>,
}

impl Rows<'_> {
    /// Whether some input covers a sample row under row `j` of level `k` (0: the samples).
    fn covered(&self, k: u32, j: usize) -> bool {
        let h = self.covered_below.len() - 1;
        let (lo, hi) = ((j << k).min(h), ((j + 1) << k).min(h - 1) + 1);
        self.covered_below[hi] > self.covered_below[lo]
    }

    /// Row `j` of a section of `u16` rows `n` long from byte `at`, of level `k`.
    fn read(
        &self,
        (at, k): (u64, u32),
        n: usize,
        j: usize,
        row: &mut Vec<u16>,
    ) -> Result<(), StoreError> {
        if !self.covered(k, j) {
            row.clear();
            row.resize(n, 0);
            return Ok(());
        }
        let first = at + (2 * n * j) as u64;
        if is_hole(self.file, first, 2 * n as u64) {
            row.clear();
            row.resize(n, 0);
            return Ok(());
        }
        let mut bytes = vec![0u8; 2 * n];
        self.file
            .read_exact_at(&mut bytes, first)
            .map_err(StoreError::io(self.path))?;
        row.clear();
        row.extend(
            bytes
                .chunks_exact(2)
                .map(|b| u16::from_le_bytes([b[0], b[1]])),
        );
        Ok(())
    }

    /// Writes `row` as row `j` of a section of rows as long from byte `at`, unless it is all
    /// zeros (as the file already reads there).
    fn write(&self, at: u64, j: usize, row: &[u16]) -> Result<(), StoreError> {
        if row.iter().all(|&v| v == 0) {
            return Ok(());
        }
        let bytes: Vec<u8> = row.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.file
            .write_all_at(&bytes, at + (2 * row.len() * j) as u64)
            .map_err(StoreError::io(self.path))
    }

    /// Which samples of row `j` (of `w`) have data, from the valid bits at byte `at`.
    fn valid(&self, at: u64, w: usize, j: usize) -> Result<Vec<bool>, StoreError> {
        if !self.covered(0, j) {
            return Ok(vec![false; w]);
        }
        let first = j * w;
        let (word0, word1) = (first / 64, (first + w).div_ceil(64));
        let mut bytes = vec![0u8; 8 * (word1 - word0)];
        self.file
            .read_exact_at(&mut bytes, at + 8 * word0 as u64)
            .map_err(StoreError::io(self.path))?;
        let words: Vec<u64> = bytes
            .chunks_exact(8)
            .map(|b| u64::from_le_bytes(b.try_into().unwrap_or([0; 8])))
            .collect();
        Ok((first..first + w)
            .map(|k| words[k / 64 - word0] & (1 << (k % 64)) != 0)
            .collect())
    }
}

/// Whether the `len` bytes of `file` from byte `at` lie in a hole, never written (zeros, as a
/// one input's zero blocks and the gaps of a mosaic are): they are not read, which would fill
/// memory with pages of zeros. Where the system cannot tell, they are read.
fn is_hole(file: &File, at: u64, len: u64) -> bool {
    #[cfg(any(target_os = "linux", target_os = "android"))]
    {
        use std::os::fd::AsRawFd;
        let Ok(offset) = libc::off_t::try_from(at) else {
            return false;
        };
        // SAFETY: the descriptor is open for as long as `file`; the offset lseek moves is not
        // the one positioned reads and writes use.
        let data = unsafe { libc::lseek(file.as_raw_fd(), offset, libc::SEEK_DATA) };
        match u64::try_from(data) {
            Ok(data) => data >= at.saturating_add(len),
            // No data from `at` to the end of the file.
            Err(_) => std::io::Error::last_os_error().raw_os_error() == Some(libc::ENXIO),
        }
    }
    #[cfg(not(any(target_os = "linux", target_os = "android")))]
    {
        let _ = (file, at, len);
        false
    }
}

/// Builds the mipmap, steepest gradient and hole count of the store `file` of `w x h`
/// samples whose rows `covered` some input reaches, reporting the fraction of sample rows
/// done.
pub fn build(
    file: &File,
    path: &Path,
    (w, h): (usize, usize),
    (sections, covered): (&Sections, &[bool]),
    progress: &dyn Fn(f64) -> ControlFlow<()>,
) -> Result<Built, StoreError> {
    let mut covered_below = vec![0u64; h + 1];
    for j in 0..h {
        covered_below[j + 1] = covered_below[j] + u64::from(covered[j]);
    }
    let io = Rows {
        file,
        path,
        covered_below,
    };
    let layout = Mipmap::layout(w, h);
    let (nx, ny) = blocks(1, w, h);
    let (mut columns, mut max, mut min) = (Columns::new(w), Vec::new(), Vec::new());
    let (mut lower, mut lower_row) = (Vec::new(), 0usize);
    let mut level2 = Vec::new();
    let mut rows: [Vec<u16>; 3] = Default::default();
    let mut steepest = 0.0f64;
    let mut holes = 0u64;
    let valid_at = sections.valid.map(|(at, _)| at);
    let mut valid_below = match valid_at {
        Some(at) => Some(io.valid(at, w, 0)?),
        None => None,
    };
    if let Some(valid) = &valid_below {
        holes += valid.iter().filter(|&&v| !v).count() as u64;
    }
    for bj in 0..ny {
        if bj % 64 == 0 && progress(bj as f64 / ny as f64).is_break() {
            return Err(StoreError::Cancelled {
                path: path.to_owned(),
            });
        }
        let js = first_level_rows(bj, h);
        for (row, &j) in rows.iter_mut().zip(&js) {
            io.read((sections.samples.0, 0), w, j, row)?;
        }
        // Cells of sample rows 2bj and 2bj+1 (the last block row's third row repeats); where
        // no input reaches the block row, holes without a slope.
        let gap = !js.iter().any(|&j| io.covered(0, j));
        for (k, j) in [2 * bj, 2 * bj + 1].into_iter().enumerate() {
            if j + 1 >= h {
                break;
            }
            if gap {
                holes += w as u64;
                valid_below = valid_below.map(|_| vec![false; w]);
                continue;
            }
            let (below, above) = (&rows[k], &rows[k + 1]);
            steepest = larger(
                steepest,
                match valid_at {
                    None => steepest_in_row(below, above, |_| true),
                    Some(at) => {
                        let valid_above = io.valid(at, w, j + 1)?;
                        holes += valid_above.iter().filter(|&&v| !v).count() as u64;
                        let below_valid = valid_below.as_deref().unwrap_or(&[]);
                        let cell = |i: usize| {
                            below_valid[i]
                                && below_valid[i + 1]
                                && valid_above[i]
                                && valid_above[i + 1]
                        };
                        let s = steepest_in_row(below, above, cell);
                        valid_below = Some(valid_above);
                        s
                    }
                },
            );
        }
        let [r0, r1, r2] = &rows;
        max.clear();
        min.clear();
        columns.first_level_row([r0, r1, r2], &mut max, &mut min);
        io.write(sections.max.0, bj, &max)?;
        // The level-1 lowest samples are not stored: level 2's are made of them in pairs.
        if bj % 2 == 0 {
            std::mem::swap(&mut lower, &mut min);
            lower_row = bj;
        }
        if bj % 2 == 1 || bj + 1 == ny {
            let pair = halved_rows(lower_row / 2, ny).map(|y| match y == lower_row {
                true => lower.as_slice(),
                false => min.as_slice(),
            });
            level2.clear();
            halve_row(pair, u16::min, &mut level2);
            io.write(sections.min.0, lower_row / 2, &level2)?;
        }
    }
    debug_assert_eq!(nx, max.len());
    upper_levels(&io, &layout, sections, (w, h))?;
    Ok(Built { steepest, holes })
}

/// Levels 2 up of the highest samples and 3 up of the lowest, each from the one below as
/// written.
fn upper_levels(
    io: &Rows<'_>,
    layout: &Layout,
    sections: &Sections,
    (w, h): (usize, usize),
) -> Result<(), StoreError> {
    let stacks = [
        (
            sections.max.0,
            &layout.max,
            1u32,
            u16::max as fn(u16, u16) -> u16,
        ),
        (sections.min.0, &layout.min, 2, u16::min),
    ];
    let (mut a, mut b, mut out) = (Vec::new(), Vec::new(), Vec::new());
    for (at, starts, first, pick) in stacks {
        for k in first..layout.top {
            let (below_start, below_nx) = starts[(k - first) as usize];
            let (above_start, _) = starts[(k + 1 - first) as usize];
            let (_, below_ny) = blocks(k, w, h);
            let (_, above_ny) = blocks(k + 1, w, h);
            let below_at = at + 2 * below_start as u64;
            let above_at = at + 2 * above_start as u64;
            for bj in 0..above_ny {
                let [y0, y1] = halved_rows(bj, below_ny);
                io.read((below_at, k), below_nx, y0, &mut a)?;
                io.read((below_at, k), below_nx, y1, &mut b)?;
                out.clear();
                halve_row([&a, &b], pick, &mut out);
                io.write(above_at, bj, &out)?;
            }
        }
    }
    Ok(())
}
