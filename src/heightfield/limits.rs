//! Size limits, checked from a file's header before any sample is decoded, so that a huge
//! header or a decompression bomb is refused without allocating.

use super::LoadError;

/// Largest number of samples accepted (2^31: a 46341x46341 map, 4 GiB of 16-bit samples).
pub const MAX_SAMPLES: u64 = 1 << 31;

/// Largest decoded image accepted, in bytes (8 GiB: 2^31 samples of `f32`, or an RGB image of
/// 2^31 8-bit pixels); the field built from it then takes 2 bytes per sample.
pub const MAX_DECODED_BYTES: u64 = 8 << 30;

/// Refuses a raster of `width` x `height` pixels of `bytes_per_pixel` bytes that is too small,
/// has too many samples or would take too much memory to decode.
pub(super) fn check_header(
    name: &str,
    width: u64,
    height: u64,
    bytes_per_pixel: u64,
) -> Result<(), LoadError> {
    check_least(name, width, height)?;
    let name = name.to_owned();
    let samples = width.saturating_mul(height);
    if samples > MAX_SAMPLES {
        return Err(LoadError::TooManySamples {
            name,
            width,
            height,
        });
    }
    let bytes = samples.saturating_mul(bytes_per_pixel);
    if bytes > MAX_DECODED_BYTES {
        return Err(LoadError::TooMuchMemory {
            name,
            width,
            height,
            bytes,
        });
    }
    Ok(())
}

/// Refuses a raster of `width` x `height` pixels too small for a field (read in parts, it may
/// be larger than a field in memory may).
pub(super) fn check_least(name: &str, width: u64, height: u64) -> Result<(), LoadError> {
    if width < 2 || height < 2 {
        return Err(LoadError::TooSmall {
            name: name.to_owned(),
            width,
            height,
        });
    }
    Ok(())
}
