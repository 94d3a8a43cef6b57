//! Height fields: samples on a grid, their height mapping, loading, and the per-cell maxima
//! and range-maximum structures the traversals skip empty space with.

mod builtin;
mod generate;
mod load;
mod maxima;
mod mipmap;
mod terrain;

pub use builtin::{Builtin, BUILTINS};
pub use generate::landscape;
pub use load::{load, load_bytes, LoadError};
pub use maxima::{CellMaxima, LineMaxima};
pub use mipmap::MaxMipmap;
pub use terrain::{Lines, Terrain};

use thiserror::Error;

/// Largest number of samples accepted (2^31: a 46341x46341 map, 4 GiB of 16-bit samples).
pub const MAX_SAMPLES: u64 = 1 << 31;

/// Why a height field could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum HeightfieldError {
    #[error("a height field needs at least 2x2 samples, this one is {width}x{height}")]
    TooSmall { width: usize, height: usize },
    #[error("{width}x{height} is {} samples, more than the limit of {MAX_SAMPLES}", *width as u64 * *height as u64)]
    TooLarge { width: usize, height: usize },
    #[error("z scale must be a finite number >= 0, got {0}")]
    BadZScale(f64),
    #[error("maxval must be between 1 and 65535, got {0}")]
    BadMaxval(u32),
    #[error("expected {expected} samples for the given size, got {got}")]
    SampleCount { expected: usize, got: usize },
    #[error("sample {sample} at x={x}, y={y} exceeds maxval {maxval}")]
    SampleAboveMaxval {
        sample: u16,
        x: usize,
        y: usize,
        maxval: u16,
    },
}

/// A grid of height samples (DESIGN 2).
///
/// Sample `(i, j)` sits at `x = i`, `y = j` (y grows north; image row `r` is `j = H-1-r`), and
/// its height is `sample as f64 * (z_scale / maxval)`, computed in `f64`. Those `f64` heights
/// are the exact inputs of exact mode.
#[derive(Clone, Debug)]
pub struct Heightfield {
    width: usize,
    height: usize,
    /// Samples by `j * width + i` (y up).
    samples: Vec<u16>,
    maxval: u16,
    z_scale: f64,
    /// Height of one sample step: `z_scale / maxval`.
    unit: f64,
}

impl Heightfield {
    /// Builds a field from samples in image order (row 0 is the top, the northern edge).
    pub fn from_image_rows(
        width: usize,
        height: usize,
        rows: &[u16],
        maxval: u32,
        z_scale: f64,
    ) -> Result<Self, HeightfieldError> {
        check_size(width, height)?;
        if rows.len() != width * height {
            return Err(HeightfieldError::SampleCount {
                expected: width * height,
                got: rows.len(),
            });
        }
        Self::from_fn(width, height, maxval, z_scale, |i, j| {
            rows[(height - 1 - j) * width + i]
        })
    }

    /// Builds a field from a function of the sample position `(x, y)` (y up).
    pub fn from_fn(
        width: usize,
        height: usize,
        maxval: u32,
        z_scale: f64,
        sample: impl Fn(usize, usize) -> u16,
    ) -> Result<Self, HeightfieldError> {
        check_size(width, height)?;
        if !(z_scale.is_finite() && z_scale >= 0.0) {
            return Err(HeightfieldError::BadZScale(z_scale));
        }
        let maxval = u16::try_from(maxval)
            .ok()
            .filter(|&m| m > 0)
            .ok_or(HeightfieldError::BadMaxval(maxval))?;
        let mut samples = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                let s = sample(x, y);
                if s > maxval {
                    return Err(HeightfieldError::SampleAboveMaxval {
                        sample: s,
                        x,
                        y,
                        maxval,
                    });
                }
                samples.push(s);
            }
        }
        Ok(Heightfield {
            width,
            height,
            samples,
            maxval,
            z_scale,
            unit: z_scale / f64::from(maxval),
        })
    }

    /// Samples along x.
    pub fn width(&self) -> usize {
        self.width
    }
    /// Samples along y.
    pub fn height(&self) -> usize {
        self.height
    }
    /// The sample value that maps to `z_scale`.
    pub fn maxval(&self) -> u16 {
        self.maxval
    }
    /// Height of the sample value `maxval`.
    pub fn z_scale(&self) -> f64 {
        self.z_scale
    }
    /// The raw sample at `(i, j)`.
    pub fn sample(&self, i: usize, j: usize) -> u16 {
        self.samples[j * self.width + i]
    }
    /// The height a sample value maps to.
    pub fn height_of(&self, sample: u16) -> f64 {
        f64::from(sample) * self.unit
    }
    /// The height at sample `(i, j)`.
    pub fn z(&self, i: usize, j: usize) -> f64 {
        self.height_of(self.sample(i, j))
    }
    /// All samples, by `j * width + i`.
    pub fn samples(&self) -> &[u16] {
        &self.samples
    }
}

fn check_size(width: usize, height: usize) -> Result<(), HeightfieldError> {
    if width < 2 || height < 2 {
        return Err(HeightfieldError::TooSmall { width, height });
    }
    if width as u64 * height as u64 > MAX_SAMPLES {
        return Err(HeightfieldError::TooLarge { width, height });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn image_rows_map_to_y_up() {
        // 2x3 image: top row 1 2, middle 3 4, bottom 5 6.
        let f = Heightfield::from_image_rows(2, 3, &[1, 2, 3, 4, 5, 6], 255, 255.0).unwrap();
        assert_eq!(f.sample(0, 0), 5);
        assert_eq!(f.sample(1, 2), 2);
        assert_eq!(f.z(1, 1), 4.0);
    }

    #[test]
    fn rejects_bad_sizes_and_scales() {
        assert_eq!(
            Heightfield::from_fn(1, 5, 255, 1.0, |_, _| 0).unwrap_err(),
            HeightfieldError::TooSmall {
                width: 1,
                height: 5
            }
        );
        assert!(matches!(
            Heightfield::from_fn(2, 2, 255, f64::NAN, |_, _| 0),
            Err(HeightfieldError::BadZScale(_))
        ));
        assert!(matches!(
            Heightfield::from_fn(2, 2, 10, 1.0, |_, _| 11),
            Err(HeightfieldError::SampleAboveMaxval { .. })
        ));
    }
}
