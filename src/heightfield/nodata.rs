//! Which samples hold no data (NaN, or a raster's no-data value): one bit per sample, kept
//! only for fields that have holes.

use super::Values;

/// A set of no-data samples, by `j * width + i`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NoDataMask {
    bits: Values<u64>,
    count: usize,
    /// Whether a set bit is a sample with data (as a tile store keeps them) rather than one
    /// without.
    valid_bits: bool,
}

impl NoDataMask {
    /// An empty set over `samples` samples.
    pub fn new(samples: usize) -> Self {
        NoDataMask {
            bits: Values::owned(vec![0; samples.div_ceil(64)]),
            count: 0,
            valid_bits: false,
        }
    }

    /// The set whose samples with data are the set bits of `valid`, `count` samples without.
    pub(super) fn of_valid(valid: Values<u64>, count: usize) -> Self {
        NoDataMask {
            bits: valid,
            count,
            valid_bits: true,
        }
    }

    /// Marks sample `index` as no-data.
    pub fn insert(&mut self, index: usize) {
        if !self.contains(index) {
            let (word, bit) = (index / 64, 1u64 << (index % 64));
            self.bits.make_mut()[word] ^= bit;
            self.count += 1;
        }
    }

    /// Whether sample `index` is no-data.
    #[inline]
    pub fn contains(&self, index: usize) -> bool {
        (self.bits[index / 64] & (1u64 << (index % 64)) != 0) != self.valid_bits
    }

    /// How many samples are no-data.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.bits.len() * 8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_each_sample_once() {
        let mut mask = NoDataMask::new(130);
        for index in [0, 63, 64, 129, 64] {
            mask.insert(index);
        }
        assert_eq!(mask.count(), 4);
        let set: Vec<usize> = (0..130).filter(|&k| mask.contains(k)).collect();
        assert_eq!(set, [0, 63, 64, 129]);
    }
}
