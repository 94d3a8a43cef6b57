//! Writing inputs' rows into a store: a mosaic's tiles quantised as the store's, their samples
//! with data only (where tiles overlap, the one written last wins), or a store's one input as
//! it is, holes and all.

use super::header::{Header, Sections};
use super::StoreError;
use crate::heightfield::load::raster::ValueRange;
use crate::heightfield::{Heightfield, Quantisation};
use std::fs::File;
use std::ops::Range;
use std::os::unix::fs::FileExt;
use std::path::Path;

/// Samples in a block of a one input's row that is not written where all are zeros, as the
/// file already reads there: 4 KiB, a page.
const ZERO_BLOCK: usize = 2048;

/// Where and how an input's rows go into a store.
#[derive(Clone, Copy, Debug)]
pub(super) struct Placing {
    /// Where its sample `(0, 0)` goes.
    pub at: [u64; 2],
    /// How its own samples map to heights.
    pub own: Quantisation,
    /// How the store's do.
    pub store: Quantisation,
    /// Whether it is the store's one input, written as it is, holes and all.
    pub whole: bool,
}

/// Writes inputs' samples and valid bits into a store.
pub(super) struct Writer<'a> {
    file: &'a File,
    path: &'a Path,
    width: u64,
    samples_at: u64,
    valid_at: Option<u64>,
}

impl<'a> Writer<'a> {
    /// The writer into the store `file` at `path` of `header`, its sections as `sections`.
    pub fn of((file, path): (&'a File, &'a Path), header: &Header, sections: &Sections) -> Self {
        Writer {
            file,
            path,
            width: header.width,
            samples_at: sections.samples.0,
            valid_at: sections.valid.map(|(at, _)| at),
        }
    }

    /// Writes every row of the field `field` placed as `placing` says.
    pub fn field(&self, field: &Heightfield, placing: &Placing) -> Result<(), StoreError> {
        let w = field.width();
        let (mut valid, mut row) = (Vec::with_capacity(w), Vec::with_capacity(w));
        for (j, samples) in field.samples().chunks_exact(w).enumerate() {
            valid.clear();
            valid.extend((0..w).map(|i| !field.is_nodata(i, j)));
            self.input_row(placing, j, (samples, &valid), &mut row)?;
        }
        Ok(())
    }

    /// Writes row `j` of an input placed as `placing` says, of `samples` as the input holds
    /// them and whether each has `valid` data, through the buffer `row`: the samples with data
    /// quantised as the store's, or, where the input is the store's one input, every sample as
    /// it is.
    pub fn input_row(
        &self,
        placing: &Placing,
        j: usize,
        (samples, valid): (&[u16], &[bool]),
        row: &mut Vec<(u16, bool)>,
    ) -> Result<(), StoreError> {
        let (lowest, step) = match placing.store {
            Quantisation::Offset { lowest, step } => (lowest, step),
            Quantisation::Maxval(_) => (0.0, 1.0),
        };
        let first = (placing.at[1] + j as u64) * self.width + placing.at[0];
        row.clear();
        row.extend(
            samples
                .iter()
                .zip(valid)
                .map(|(&s, &valid)| match placing.whole {
                    true => (s, valid),
                    false if valid => {
                        let v = height(placing.own, s);
                        (ValueRange::sample(v, lowest, step), true)
                    }
                    false => (0, false),
                }),
        );
        self.row(first, row, placing.whole)
    }

    /// Writes one row of samples from sample `first` on, each with whether it has data: the
    /// runs of samples with data, marked valid, or where `all`, every sample but blocks of
    /// zeros.
    fn row(&self, first: u64, row: &[(u16, bool)], all: bool) -> Result<(), StoreError> {
        for run in runs(row, all) {
            let bytes: Vec<u8> = row[run.clone()]
                .iter()
                .flat_map(|s| s.0.to_le_bytes())
                .collect();
            self.file
                .write_all_at(&bytes, self.samples_at + 2 * (first + run.start as u64))
                .map_err(StoreError::io(self.path))?;
        }
        let Some(valid_at) = self.valid_at else {
            return Ok(());
        };
        let (word0, word1) = (first / 64, (first + row.len() as u64).div_ceil(64));
        let mut bytes = vec![0u8; 8 * (word1 - word0) as usize];
        let at = valid_at + 8 * word0;
        self.file
            .read_exact_at(&mut bytes, at)
            .map_err(StoreError::io(self.path))?;
        for (i, sample) in row.iter().enumerate() {
            if sample.1 {
                let k = first + i as u64 - 64 * word0;
                bytes[(k / 8) as usize] |= 1 << (k % 8);
            }
        }
        self.file
            .write_all_at(&bytes, at)
            .map_err(StoreError::io(self.path))
    }
}

/// The height (at z scale 1) of the sample `s` of an input quantised as `q`: what a field of
/// it loaded at z scale 1 holds there.
fn height(q: Quantisation, s: u16) -> f64 {
    match q {
        Quantisation::Offset { lowest, step } => lowest + f64::from(s) * step,
        Quantisation::Maxval(_) => f64::from(s),
    }
}

/// The runs of `row` to write: those of samples with data, or where `all`, those of blocks not
/// all zeros (a store's one input writes every sample, and zeros are what the file holds
/// unwritten).
fn runs(row: &[(u16, bool)], all: bool) -> Vec<Range<usize>> {
    let mut runs: Vec<Range<usize>> = Vec::new();
    let mut add = |run: Range<usize>| match runs.last_mut() {
        Some(last) if last.end == run.start => last.end = run.end,
        _ => runs.push(run),
    };
    match all {
        true => {
            for (k, block) in row.chunks(ZERO_BLOCK).enumerate() {
                if block.iter().any(|s| s.0 != 0) {
                    add(k * ZERO_BLOCK..k * ZERO_BLOCK + block.len());
                }
            }
        }
        false => {
            for (k, sample) in row.iter().enumerate() {
                if sample.1 {
                    add(k..k + 1);
                }
            }
        }
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_are_the_samples_with_data_or_the_blocks_not_all_zeros() {
        let row: Vec<(u16, bool)> = [(1, true), (0, true), (0, false), (7, true)].into();
        assert_eq!(runs(&row, false), [0..2, 3..4]);
        let mut long = vec![(0u16, true); 3 * ZERO_BLOCK + 5];
        long[ZERO_BLOCK + 3].0 = 9;
        long[3 * ZERO_BLOCK + 1].0 = 9;
        assert_eq!(
            runs(&long, true),
            [
                ZERO_BLOCK..2 * ZERO_BLOCK,
                3 * ZERO_BLOCK..3 * ZERO_BLOCK + 5
            ]
        );
    }
}
