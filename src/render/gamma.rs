//! Linear light to display bytes with a gamma of 2.2, without a `powf` per channel: the byte
//! of `v` is how many of 255 thresholds `v` reaches. The thresholds are found once, by
//! bisection on the formula itself, so the table gives the formula's bytes exactly. A second
//! table, over 256 buckets per octave of `v`, holds the byte where each bucket starts: a bucket
//! spans so little (0.4% of `v`, under half a byte at the curve's steepest) that it reaches
//! at most one more threshold, so one lookup and one comparison give the byte. 16-bit values
//! (`words`, for 16-bit TIFFs) take the formula itself: only those renders pay its `powf`.

use std::sync::LazyLock;

/// The byte the formula gives: `v^(1/2.2)` scaled to 0..=255 and rounded.
fn byte_by_formula(v: f64) -> u8 {
    (v.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0 + 0.5) as u8
}

/// Buckets start at this value (below it every byte is 0: the first threshold is near 1e-6).
const LOWEST: f64 = 1.0 / (1u64 << 24) as f64;

/// A bucket is a value's bits from the exponent to the 8 leading fraction bits.
const BUCKET_SHIFT: u32 = 44;

/// Buckets from `LOWEST` up to 1, 1 included.
const BUCKETS: usize = bucket(1.0) + 1;

const fn bucket(v: f64) -> usize {
    ((v.to_bits() - LOWEST.to_bits()) >> BUCKET_SHIFT) as usize
}

/// The two tables, built together on first use.
struct Tables {
    /// `thresholds[k - 1]`: the least `v` in [0, 1] whose byte is at least `k`.
    thresholds: [f64; 255],
    /// The byte at the start of each bucket.
    bucket_start: [u8; BUCKETS],
}

static TABLES: LazyLock<Tables> = LazyLock::new(|| {
    let thresholds = std::array::from_fn(|index| {
        let k = index as u8 + 1;
        // Non-negative floats order like their bits: bisect on those.
        let (mut below, mut at) = (0u64, 1f64.to_bits());
        while at - below > 1 {
            let mid = below + (at - below) / 2;
            if byte_by_formula(f64::from_bits(mid)) >= k {
                at = mid;
            } else {
                below = mid;
            }
        }
        f64::from_bits(at)
    });
    let bucket_start = std::array::from_fn(|n| {
        let start = f64::from_bits(LOWEST.to_bits() + ((n as u64) << BUCKET_SHIFT));
        byte_by_thresholds(&thresholds, start)
    });
    Tables {
        thresholds,
        bucket_start,
    }
});

/// The byte by counting thresholds (a binary search).
fn byte_by_thresholds(thresholds: &[f64; 255], v: f64) -> u8 {
    thresholds.partition_point(|&threshold| v >= threshold) as u8
}

/// The display bytes of a linear colour's three channels, each clamped to [0, 1] (NaN gives
/// 0).
#[inline(always)]
pub fn bytes(c: [f64; 3]) -> [u8; 3] {
    let tables = &*TABLES;
    c.map(|v| tables.byte(v))
}

/// A linear colour as 0x00RRGGBB.
#[inline(always)]
pub fn pack([r, g, b]: [f64; 3]) -> u32 {
    // (Channel by channel, not by `map`: the map is not inlined, and this runs per pixel.)
    let tables = &*TABLES;
    let byte = |v: f64| u32::from(tables.byte(v));
    (byte(r) << 16) | (byte(g) << 8) | byte(b)
}

impl Tables {
    /// The display byte of linear value `v`.
    #[inline(always)]
    fn byte(&self, v: f64) -> u8 {
        if v >= 1.0 {
            return 255;
        }
        if v.is_nan() || v < LOWEST {
            return 0;
        }
        let start = self.bucket_start[bucket(v)];
        let next = self.thresholds.get(usize::from(start));
        start + u8::from(next.is_some_and(|&threshold| v >= threshold))
    }
}

/// A linear colour as a display shows it: each channel clamped to [0, 1], NaN as 0. Bytes and
/// words encode this; the samples of a pixel are averaged as this, so that a sample brighter
/// than white counts as white, as its bytes do.
pub fn shown(c: [f64; 3]) -> [f64; 3] {
    c.map(|v| {
        if v >= 1.0 {
            1.0
        } else if v > 0.0 {
            v
        } else {
            0.0
        }
    })
}

/// The 16-bit display values of a linear colour's three channels by the bytes' formula
/// (`v^(1/2.2)` scaled to 0..=65535 and rounded), each clamped to [0, 1] (NaN gives 0): a
/// word `w` lies within half a byte of its colour's byte times 257.
pub fn words(c: [f64; 3]) -> [u16; 3] {
    c.map(|v| (v.clamp(0.0, 1.0).powf(1.0 / 2.2) * 65535.0 + 0.5) as u16)
}

/// The linear value whose display byte is `b` by the formula (`(b / 255)^2.2`).
pub fn linear(b: u8) -> f64 {
    LINEAR[usize::from(b)]
}

static LINEAR: LazyLock<[f64; 256]> =
    LazyLock::new(|| std::array::from_fn(|b| (b as f64 / 255.0).powf(2.2)));

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_gives_the_formulas_bytes() {
        let mut values: Vec<f64> = (0..=100_000).map(|i| f64::from(i) / 100_000.0).collect();
        // Either side of every threshold, and outside the range.
        for &t in TABLES.thresholds.iter() {
            values.extend([t, t.next_down(), t.next_up()]);
        }
        values.extend([-1.0, 2.0, f64::INFINITY, f64::NEG_INFINITY, 1e-300]);
        // Either side of every bucket's start.
        for n in 0..=bucket(1.0) as u64 {
            let start = f64::from_bits(LOWEST.to_bits() + (n << BUCKET_SHIFT));
            values.extend([start, start.next_down()]);
        }
        for v in values {
            assert_eq!(TABLES.byte(v), byte_by_formula(v), "v = {v:e}");
            let formula = [v, 0.5, -v].map(byte_by_formula);
            assert_eq!(bytes([v, 0.5, -v]), formula, "v = {v:e}");
        }
        assert_eq!(bytes([f64::NAN; 3]), [0; 3]);
    }

    #[test]
    fn every_byte_comes_back_from_its_linear_value() {
        for b in 0..=255u8 {
            assert_eq!(bytes([linear(b); 3]), [b; 3]);
        }
    }

    #[test]
    fn words_round_to_the_bytes_within_one() {
        for i in 0..=20_000 {
            let v = f64::from(i) / 20_000.0;
            let (word, byte) = (words([v; 3])[0], bytes([v; 3])[0]);
            let rounded = (u32::from(word) + 128) / 257;
            assert!(rounded.abs_diff(u32::from(byte)) <= 1, "v = {v}");
        }
        assert_eq!(words([f64::NAN, -1.0, 2.0]), [0, 0, 65535]);
        assert_eq!(words([linear(128); 3]), [128 * 257; 3]);
    }
}
