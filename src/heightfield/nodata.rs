//! Which samples hold no data (NaN, or a raster's no-data value): one bit per sample, kept
//! only for fields that have holes.

/// A set of no-data samples, by `j * width + i`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NoDataMask {
    bits: Vec<u64>,
    count: usize,
}

impl NoDataMask {
    /// An empty set over `samples` samples.
    pub fn new(samples: usize) -> Self {
        NoDataMask {
            bits: vec![0; samples.div_ceil(64)],
            count: 0,
        }
    }

    /// Marks sample `index` as no-data.
    pub fn insert(&mut self, index: usize) {
        let (word, bit) = (index / 64, 1u64 << (index % 64));
        if self.bits[word] & bit == 0 {
            self.bits[word] |= bit;
            self.count += 1;
        }
    }

    /// Whether sample `index` is no-data.
    #[inline]
    pub fn contains(&self, index: usize) -> bool {
        self.bits[index / 64] & (1u64 << (index % 64)) != 0
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
