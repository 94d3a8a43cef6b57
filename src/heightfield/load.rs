//! Loading height fields from 8- and 16-bit grayscale PNG and PGM (P2, P5).
//!
//! PNG goes through the `image` crate. PGM is parsed here: `image` rescales samples of an odd
//! maxval to 8 or 16 bits, but DESIGN 2 maps heights by the file's own maxval.

use super::{Heightfield, HeightfieldError, MAX_SAMPLES};
use image::{DynamicImage, ImageFormat, ImageReader};
use std::io::Cursor;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why a file could not be loaded as a height field.
#[derive(Debug, Error)]
pub enum LoadError {
    #[error("cannot read {path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{name} is empty")]
    Empty { name: String },
    #[error("{name} is not a PNG or PGM image")]
    NotAnImage { name: String },
    #[error("{name}: cannot decode the image: {reason}")]
    Decode { name: String, reason: String },
    #[error("{name}: {color} images are not height fields; use 8- or 16-bit grayscale")]
    Color { name: String, color: String },
    #[error("{name}: {source}")]
    Field {
        name: String,
        source: HeightfieldError,
    },
}

/// Loads a height field from a file.
pub fn load(path: &Path, z_scale: f64) -> Result<Heightfield, LoadError> {
    let bytes = std::fs::read(path).map_err(|source| LoadError::Io {
        path: path.to_owned(),
        source,
    })?;
    load_bytes(&bytes, z_scale, &path.display().to_string())
}

/// Loads a height field from the bytes of a file; `name` labels error messages.
pub fn load_bytes(bytes: &[u8], z_scale: f64, name: &str) -> Result<Heightfield, LoadError> {
    let name = name.to_owned();
    if bytes.is_empty() {
        return Err(LoadError::Empty { name });
    }
    let (width, height, samples, maxval) = if bytes.starts_with(b"P2") || bytes.starts_with(b"P5") {
        parse_pgm(bytes, &name)?
    } else {
        decode_png(bytes, &name)?
    };
    Heightfield::from_image_rows(width, height, &samples, maxval, z_scale)
        .map_err(|source| LoadError::Field { name, source })
}

type Raster = (usize, usize, Vec<u16>, u32);

fn decode_png(bytes: &[u8], name: &str) -> Result<Raster, LoadError> {
    let decode_error = |e: image::ImageError| LoadError::Decode {
        name: name.to_owned(),
        reason: e.to_string(),
    };
    let format = image::guess_format(bytes).map_err(|_| LoadError::NotAnImage {
        name: name.to_owned(),
    })?;
    if format != ImageFormat::Png {
        return Err(LoadError::NotAnImage {
            name: name.to_owned(),
        });
    }
    // Refuse oversized images from the header, before any pixel is allocated.
    let reader = ImageReader::with_format(Cursor::new(bytes), format);
    let (w, h) = reader.into_dimensions().map_err(decode_error)?;
    check_dimensions(w as usize, h as usize, name)?;
    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(MAX_SAMPLES * 2 + (1 << 20));
    reader.limits(limits);
    let image = reader.decode().map_err(decode_error)?;
    let (width, height) = (image.width() as usize, image.height() as usize);
    match image {
        DynamicImage::ImageLuma8(buf) => Ok((
            width,
            height,
            buf.into_raw().into_iter().map(u16::from).collect(),
            255,
        )),
        DynamicImage::ImageLuma16(buf) => Ok((width, height, buf.into_raw(), 65535)),
        other => Err(LoadError::Color {
            name: name.to_owned(),
            color: format!("{:?}", other.color()),
        }),
    }
}

fn check_dimensions(width: usize, height: usize, name: &str) -> Result<(), LoadError> {
    let field = |source| LoadError::Field {
        name: name.to_owned(),
        source,
    };
    if width < 2 || height < 2 {
        return Err(field(HeightfieldError::TooSmall { width, height }));
    }
    if width as u64 * height as u64 > MAX_SAMPLES {
        return Err(field(HeightfieldError::TooLarge { width, height }));
    }
    Ok(())
}

/// Parses a binary (P5) or ASCII (P2) PGM with maxval 1..=65535.
fn parse_pgm(bytes: &[u8], name: &str) -> Result<Raster, LoadError> {
    let (width, height, header_end, maxval) =
        parse_pgm_header(bytes).map_err(|reason| LoadError::Decode {
            name: name.to_owned(),
            reason,
        })?;
    // Refuse oversized images before allocating.
    check_dimensions(width, height, name)?;
    parse_pgm_raster(bytes, width * height, header_end, maxval)
        .map_err(|reason| LoadError::Decode {
            name: name.to_owned(),
            reason,
        })
        .map(|samples| (width, height, samples, maxval))
}

/// Width, height, the position after the header, and maxval.
fn parse_pgm_header(bytes: &[u8]) -> Result<(usize, usize, usize, u32), String> {
    let mut pos = 2;
    let mut header = [0u64; 3];
    for (field, name) in header.iter_mut().zip(["width", "height", "maxval"]) {
        *field = pgm_number(bytes, &mut pos).ok_or(format!("PGM header has no valid {name}"))?;
    }
    let [w, h, maxval] = header;
    if maxval == 0 || maxval > 65535 {
        return Err(format!("PGM maxval must be 1..=65535, got {maxval}"));
    }
    let (width, height) = (
        usize::try_from(w).map_err(|_| format!("PGM width {w} is too large"))?,
        usize::try_from(h).map_err(|_| format!("PGM height {h} is too large"))?,
    );
    Ok((width, height, pos, maxval as u32))
}

/// The samples of a PGM raster that starts after the header at `pos`.
fn parse_pgm_raster(
    bytes: &[u8],
    count: usize,
    mut pos: usize,
    maxval: u32,
) -> Result<Vec<u16>, String> {
    let samples = if bytes[1] == b'5' {
        // Exactly one whitespace byte separates the header from the raster.
        let start = pos + 1;
        let bytes_per_sample = if maxval < 256 { 1 } else { 2 };
        let raster = bytes
            .get(start..)
            .filter(|r| r.len() >= count * bytes_per_sample)
            .ok_or(format!(
                "PGM raster is truncated: {} of {} bytes",
                bytes.len().saturating_sub(start),
                count * bytes_per_sample
            ))?;
        if bytes_per_sample == 1 {
            raster[..count].iter().map(|&b| u16::from(b)).collect()
        } else {
            raster[..count * 2]
                .chunks_exact(2)
                .map(|p| u16::from_be_bytes([p[0], p[1]]))
                .collect()
        }
    } else {
        let mut samples = Vec::with_capacity(count);
        for k in 0..count {
            let s = pgm_number(bytes, &mut pos)
                .ok_or(format!("PGM raster ends after {k} of {count} samples"))?;
            samples.push(u16::try_from(s).map_err(|_| format!("PGM sample {s} exceeds 65535"))?);
        }
        samples
    };
    Ok(samples)
}

/// Reads the next decimal number of a PGM header or ASCII raster, skipping whitespace and
/// `#` comments.
fn pgm_number(bytes: &[u8], pos: &mut usize) -> Option<u64> {
    loop {
        match bytes.get(*pos)? {
            b'#' => {
                while *bytes.get(*pos)? != b'\n' {
                    *pos += 1;
                }
            }
            b if b.is_ascii_whitespace() => *pos += 1,
            _ => break,
        }
    }
    let start = *pos;
    while bytes.get(*pos).is_some_and(u8::is_ascii_digit) {
        *pos += 1;
    }
    std::str::from_utf8(&bytes[start..*pos]).ok()?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_pgm_with_comment_and_odd_maxval() {
        let pgm = b"P2\n# a comment\n3 2\n1000\n0 500 1000\n250 750 1\n";
        let f = load_bytes(pgm, 10.0, "t.pgm").unwrap();
        assert_eq!((f.width(), f.height(), f.maxval()), (3, 2, 1000));
        assert_eq!(f.z(2, 1), 10.0);
        assert_eq!(f.z(1, 0), 750.0 * (10.0 / 1000.0));
    }

    #[test]
    fn truncated_binary_pgm_is_an_error() {
        let err = load_bytes(b"P5 4 4 255\n\x01\x02", 1.0, "t.pgm").unwrap_err();
        assert!(err.to_string().contains("truncated"), "{err}");
    }
}
