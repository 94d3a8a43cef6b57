//! A TIFF overlay's pixels as RGBA bytes, through the `tiff` crate: gray, RGB and RGBA of 8 or
//! 16 bits, and YCbCr, as GDAL writes JPEG-compressed orthophotos (`COMPRESS=JPEG
//! PHOTOMETRIC=YCBCR`), turned to RGB by the JFIF equations (ITU-T T.871) the JPEG was made
//! with.

use super::error::{TiffRgbaError, MOST_OVERLAY_PIXELS};
use std::io::{Read, Seek};
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::ColorType;

/// Pixels along x and y, and RGBA bytes by rows from the top.
pub struct Rgba {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<u8>,
}

/// Decodes the first image of a TIFF as RGBA bytes, or says why it cannot.
pub fn decode(input: impl Read + Seek) -> Result<Rgba, TiffRgbaError> {
    let mut decoder = Decoder::new(input)?;
    let (width, height) = decoder.dimensions()?;
    if u64::from(width) * u64::from(height) > MOST_OVERLAY_PIXELS {
        return Err(TiffRgbaError::TooLarge { width, height });
    }
    let color = decoder.colortype()?;
    let limit = usize::try_from(MOST_OVERLAY_PIXELS * 8).unwrap_or(usize::MAX);
    let mut limits = Limits::default();
    limits.decoding_buffer_size = limit;
    limits.intermediate_buffer_size = limit;
    let mut decoder = decoder.with_limits(limits);
    let bytes: Vec<u8> = match decoder.read_image()? {
        DecodingResult::U8(v) => v,
        // The high byte of 16-bit samples.
        DecodingResult::U16(v) => v.into_iter().map(|s| (s >> 8) as u8).collect(),
        _ => return Err(TiffRgbaError::Samples(color)),
    };
    let channels = match color {
        ColorType::Gray(8 | 16) => 1,
        ColorType::GrayA(8 | 16) => 2,
        ColorType::RGB(8 | 16) | ColorType::YCbCr(8) => 3,
        ColorType::RGBA(8 | 16) => 4,
        other => return Err(TiffRgbaError::Colour(other)),
    };
    let count = width as usize * height as usize;
    if bytes.len() < count * channels {
        return Err(TiffRgbaError::Short);
    }
    let ycbcr = matches!(color, ColorType::YCbCr(_));
    let pixels = bytes
        .chunks_exact(channels)
        .take(count)
        .flat_map(|p| match (channels, ycbcr) {
            (1, _) => [p[0], p[0], p[0], 255],
            (2, _) => [p[0], p[0], p[0], p[1]],
            (3, true) => rgb_of_ycbcr(p[0], p[1], p[2]),
            (3, false) => [p[0], p[1], p[2], 255],
            _ => [p[0], p[1], p[2], p[3]],
        })
        .collect();
    Ok(Rgba {
        width,
        height,
        pixels,
    })
}

/// JFIF's YCbCr to RGB (full range, BT.601 weights), rounded and clamped.
fn rgb_of_ycbcr(y: u8, cb: u8, cr: u8) -> [u8; 4] {
    let (y, cb, cr) = (f64::from(y), f64::from(cb) - 128.0, f64::from(cr) - 128.0);
    let byte = |v: f64| v.round().clamp(0.0, 255.0) as u8;
    [
        byte(y + 1.402 * cr),
        byte(y - 0.344_136 * cb - 0.714_136 * cr),
        byte(y + 1.772 * cb),
        255,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jfif_colours_round_trip() {
        // Pure red in JFIF: Y 76.245, Cb 84.97, Cr 255.5 (T.871's forward equations).
        assert_eq!(rgb_of_ycbcr(76, 85, 255), [254, 0, 0, 255]);
        assert_eq!(rgb_of_ycbcr(128, 128, 128), [128, 128, 128, 255]);
    }
}
