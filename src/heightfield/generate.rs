//! The project's own terrain generator: fractal noise, erosion-like ridges, a crater and a
//! terraced slope, defined on the unit square so every size shows the same landscape.

use super::{check_size, Heightfield, HeightfieldError};
use rayon::prelude::*;

/// A generated landscape of `size x size` 16-bit samples (maxval 65535).
pub fn landscape(size: usize, seed: u64, z_scale: f64) -> Result<Heightfield, HeightfieldError> {
    // Refused before anything is allocated for it.
    check_size(size, size)?;
    let scale = 1.0 / (size - 1) as f64;
    let at = |k: usize| shape((k % size) as f64 * scale, (k / size) as f64 * scale, seed);
    // Every sample is independent: computed in parallel (deterministic all the same), twice
    // rather than kept as f64 (8 bytes a sample): once for the range, once to quantise.
    let (lo, hi) = (0..size * size)
        .into_par_iter()
        .map(|k| {
            let h = at(k);
            (h, h)
        })
        .reduce(
            || (f64::INFINITY, f64::NEG_INFINITY),
            |a, b| (a.0.min(b.0), a.1.max(b.1)),
        );
    let range = (hi - lo).max(f64::MIN_POSITIVE);
    let samples: Vec<u16> = (0..size * size)
        .into_par_iter()
        .map(|k| ((at(k) - lo) / range * 65535.0).round() as u16)
        .collect();
    Heightfield::from_fn(size, size, 65535, z_scale, |x, y| samples[y * size + x])
}

/// Samples per side of the coarse grid the fixed normalisation of [`landscape_window`] is
/// taken over: about a second of one core, the same for every window.
const RANGE_GRID: usize = 1025;

/// How far the fixed normalisation reaches past the coarse grid's range, as a fraction of it:
/// finer grids find peaks and pits the coarse one passes between.
const RANGE_MARGIN: f64 = 0.03;

/// The samples of one window of a generated landscape of `size x size` samples, `[x, y, w,
/// h]` in image order (column `x`, row `y`, row 0 the northern edge), row by row from the
/// top. Unlike [`landscape`] the heights are normalised over a range fixed by the seed alone
/// (not the window's nor the map's own), so windows of the same map join seamlessly and a
/// map of any size can be made window by window.
pub fn landscape_window(
    size: usize,
    seed: u64,
    [x0, y0, w, h]: [usize; 4],
) -> Result<Vec<u16>, HeightfieldError> {
    check_size(w, h)?;
    if size < 2 || x0.saturating_add(w) > size || y0.saturating_add(h) > size {
        return Err(HeightfieldError::Window {
            window: [x0, y0, w, h],
            size,
        });
    }
    let (lo, hi) = fixed_range(seed);
    let range = hi - lo;
    let scale = 1.0 / (size - 1) as f64;
    Ok((0..w * h)
        .into_par_iter()
        .map(|k| {
            let (column, row) = (x0 + k % w, y0 + k / w);
            // Field y runs north from the southern edge, image rows south from the northern.
            let height = shape(column as f64 * scale, (size - 1 - row) as f64 * scale, seed);
            ((height - lo) / range * 65535.0)
                .round()
                .clamp(0.0, 65535.0) as u16
        })
        .collect())
}

/// The range of heights [`landscape_window`] maps onto 0..65535: the coarse grid's, widened.
fn fixed_range(seed: u64) -> (f64, f64) {
    let scale = 1.0 / (RANGE_GRID - 1) as f64;
    let (lo, hi) = (0..RANGE_GRID * RANGE_GRID)
        .into_par_iter()
        .map(|k| {
            let h = shape(
                (k % RANGE_GRID) as f64 * scale,
                (k / RANGE_GRID) as f64 * scale,
                seed,
            );
            (h, h)
        })
        .reduce(
            || (f64::INFINITY, f64::NEG_INFINITY),
            |a, b| (a.0.min(b.0), a.1.max(b.1)),
        );
    let margin = (hi - lo).max(f64::MIN_POSITIVE) * RANGE_MARGIN;
    (lo - margin, hi + margin)
}

/// Height (arbitrary units) at `(x, y)` in the unit square.
fn shape(x: f64, y: f64, seed: u64) -> f64 {
    // Rolling hills: fractal value noise.
    let hills = fbm(x * 4.0, y * 4.0, seed, 7);
    // Erosion-like ridges, strongest towards the north-west.
    let ridge_mask = smoothstep(0.2, 0.9, (1.0 - x) * 0.6 + y * 0.6);
    let ridges = ridged(x * 3.0 + 11.0, y * 3.0 + 7.0, seed ^ 0x9e37, 6) * ridge_mask;
    let mut h = 0.45 * hills + 0.65 * ridges;
    // A crater in the south-east: a bowl with a raised rim.
    let (cx, cy, r) = (0.7, 0.3, 0.13);
    let d = ((x - cx).powi(2) + (y - cy).powi(2)).sqrt() / r;
    let bowl = if d < 1.0 { -0.55 * (1.0 - d * d) } else { 0.0 };
    let rim = 0.3 * (-((d - 1.0) * 4.0).powi(2)).exp();
    h += bowl + rim;
    // Terraces on the south-west slope: heights snap to steps with soft risers.
    let terrace_mask = smoothstep(0.55, 0.25, x) * smoothstep(0.6, 0.3, y);
    let steps = 9.0;
    let k = (h * steps).floor();
    let frac = h * steps - k;
    let terraced = (k + smoothstep(0.7, 1.0, frac)) / steps;
    h + (terraced - h) * terrace_mask
}

fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Fractal sum of value noise, in about [-1, 1].
fn fbm(x: f64, y: f64, seed: u64, octaves: u32) -> f64 {
    let (mut sum, mut amplitude, mut frequency) = (0.0, 0.5, 1.0);
    for octave in 0..octaves {
        sum += amplitude * value_noise(x * frequency, y * frequency, seed + u64::from(octave));
        amplitude *= 0.5;
        frequency *= 2.03;
    }
    sum
}

/// Ridged multifractal: sharp crests where the noise crosses zero, in about [0, 1].
fn ridged(x: f64, y: f64, seed: u64, octaves: u32) -> f64 {
    let (mut sum, mut amplitude, mut frequency, mut weight) = (0.0, 0.5, 1.0, 1.0);
    for octave in 0..octaves {
        let n = 1.0 - value_noise(x * frequency, y * frequency, seed + u64::from(octave)).abs();
        let n = n * n * weight;
        weight = (n * 2.0).clamp(0.0, 1.0);
        sum += amplitude * n;
        amplitude *= 0.5;
        frequency *= 2.1;
    }
    sum
}

/// Smoothly interpolated lattice noise in [-1, 1].
fn value_noise(x: f64, y: f64, seed: u64) -> f64 {
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (sx, sy) = (fx * fx * (3.0 - 2.0 * fx), fy * fy * (3.0 - 2.0 * fy));
    let (ix, iy) = (x0 as i64, y0 as i64);
    let at = |dx: i64, dy: i64| lattice(ix + dx, iy + dy, seed);
    let bottom = at(0, 0) + (at(1, 0) - at(0, 0)) * sx;
    let top = at(0, 1) + (at(1, 1) - at(0, 1)) * sx;
    bottom + (top - bottom) * sy
}

/// A pseudo-random value in [-1, 1] for a lattice point (SplitMix64 finaliser).
fn lattice(x: i64, y: i64, seed: u64) -> f64 {
    let mut z = seed
        .wrapping_add((x as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15))
        .wrapping_add((y as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uses_the_full_sample_range_and_is_deterministic() {
        let a = landscape(33, 7, 100.0).unwrap();
        let b = landscape(33, 7, 100.0).unwrap();
        assert_eq!(a.samples(), b.samples());
        assert_eq!(a.samples().iter().max(), Some(&65535));
        assert_eq!(a.samples().iter().min(), Some(&0));
    }

    #[test]
    fn a_window_is_the_same_part_of_any_window_holding_it() {
        let whole = landscape_window(40, 3, [0, 0, 40, 40]).unwrap();
        let part = landscape_window(40, 3, [7, 11, 20, 9]).unwrap();
        for (k, sample) in part.iter().enumerate() {
            assert_eq!(*sample, whole[(11 + k / 20) * 40 + 7 + k % 20]);
        }
        // Inside the range, not clipped at either end.
        assert!(whole.iter().all(|&s| s > 0 && s < 65535));
    }

    #[test]
    fn a_window_outside_the_map_is_refused() {
        let error = landscape_window(40, 3, [30, 0, 11, 5]).unwrap_err();
        assert!(error.to_string().contains("30,0,11,5"), "{error}");
        assert!(landscape_window(40, 3, [usize::MAX, 0, 2, 2]).is_err());
    }
}
