//! PNG through the `png` crate: grayscale (8/16-bit, alpha ignored) as it is, RGB(A) as
//! luminance or a terrain-RGB encoding. Ancillary chunks that inflate (iCCP, zTXt, iTXt) are
//! skipped unread: a height map needs none of them, and one can inflate to gigabytes.

use super::limits::{check_header, MAX_DECODED_BYTES};
use super::raster::{Raster, TerrainRgb, Values};
use super::{decode_error, ColourEncoding, DecodeFailure, LoadError};
use crate::heightfield::georef::Georeferencing;
use png::{BitDepth, ColorType, Decoder, Transformations};
use std::io::{BufRead, Seek};

/// Decoded pixels, channel by channel.
enum Pixels {
    Eight(Vec<u8>),
    Sixteen(Vec<u16>),
}

/// Decodes a PNG from the start of `input`; reading stops at the end of the image data.
pub fn decode(
    input: impl BufRead + Seek,
    name: &str,
    colour: ColourEncoding,
) -> Result<Raster, LoadError> {
    let limits = png::Limits {
        bytes: usize::try_from(MAX_DECODED_BYTES).unwrap_or(usize::MAX),
    };
    let mut decoder = Decoder::new_with_limits(input, limits);
    decoder.set_ignore_text_chunk(true);
    decoder.set_ignore_iccp_chunk(true);
    // Palettes to RGB, fewer than 8 bits to 8, transparency to alpha; 16 bits stay 16.
    decoder.set_transformations(Transformations::EXPAND);
    // Reads up to the image data: the size is checked before any pixel is decoded.
    let mut reader = decoder.read_info().map_err(|e| decode_error(name, e))?;
    let (width, height) = reader.info().size();
    let (colour_type, depth) = reader.output_color_type();
    let channels = colour_type.samples();
    let bytes_per_sample = if depth == BitDepth::Sixteen { 2 } else { 1 };
    check_header(
        name,
        width.into(),
        height.into(),
        (channels * bytes_per_sample) as u64,
    )?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| decode_error(name, DecodeFailure::PngTooLarge))?;
    let mut bytes = Vec::new();
    bytes
        .try_reserve_exact(size)
        .map_err(|_| decode_error(name, DecodeFailure::NoMemory(size)))?;
    bytes.resize(size, 0);
    let frame = reader
        .next_frame(&mut bytes)
        .map_err(|e| decode_error(name, e))?;
    bytes.truncate(frame.buffer_size());
    let pixels = match depth {
        BitDepth::Sixteen => Pixels::Sixteen(
            bytes
                .chunks_exact(2)
                .map(|pair| u16::from_be_bytes([pair[0], pair[1]]))
                .collect(),
        ),
        _ => Pixels::Eight(bytes),
    };
    let encoding = match colour {
        ColourEncoding::Luminance => None,
        ColourEncoding::Mapbox => Some(TerrainRgb::Mapbox),
        ColourEncoding::Terrarium => Some(TerrainRgb::Terrarium),
    };
    let gray = matches!(
        colour_type,
        ColorType::Grayscale | ColorType::GrayscaleAlpha
    );
    let values = match (pixels, gray, encoding) {
        (Pixels::Eight(p), true, _) => unsigned(p, channels, u8::MAX),
        (Pixels::Sixteen(p), true, _) => unsigned(p, channels, u16::MAX),
        (Pixels::Eight(p), false, None) => luminance(&p, channels, u8::MAX),
        (Pixels::Sixteen(p), false, None) => luminance(&p, channels, u16::MAX),
        (Pixels::Eight(bytes), false, Some(encoding)) => Values::TerrainRgb {
            bytes,
            channels,
            encoding,
        },
        (Pixels::Sixteen(_), false, Some(_)) => {
            return Err(LoadError::Unsupported {
                name: name.into(),
                what: format!("a 16-bit {colour_type:?} PNG read as {colour:?}"),
            })
        }
    };
    Ok(Raster {
        width: width as usize,
        height: height as usize,
        values,
        file_nodata: None,
        georef: Georeferencing::None,
    })
}

/// The first channel of pixels of `channels` channels (gray, skipping alpha).
fn unsigned<T: Copy + Into<u16>>(pixels: Vec<T>, channels: usize, maxval: T) -> Values {
    Values::Unsigned {
        samples: pixels.iter().step_by(channels).map(|&s| s.into()).collect(),
        maxval: maxval.into(),
    }
}

/// Rec. 709 luminance `(2126 R + 7152 G + 722 B) / 10000`, rounded to the nearest sample (a
/// gray pixel keeps its value: the weights sum to 10000).
fn luminance<T: Copy + Into<u16>>(pixels: &[T], channels: usize, maxval: T) -> Values {
    let samples = pixels
        .chunks_exact(channels)
        .map(|p| {
            let [r, g, b] = [p[0], p[1], p[2]].map(|c| u64::from(c.into()));
            ((2126 * r + 7152 * g + 722 * b + 5000) / 10000) as u16
        })
        .collect();
    Values::Unsigned {
        samples,
        maxval: maxval.into(),
    }
}
