//! PNG through the `image` crate: grayscale (8/16-bit, alpha ignored) as it is, RGB(A) as
//! luminance or a terrain-RGB encoding.

use super::limits::{check_header, MAX_DECODED_BYTES};
use super::raster::{Raster, TerrainRgb, Values};
use super::{decode_error, ColourEncoding, LoadError};
use crate::heightfield::georef::Georeferencing;
use image::codecs::png::PngDecoder;
use image::{DynamicImage, ImageDecoder, Limits};
use std::io::{BufRead, Seek};

/// Decodes a PNG from the start of `input`; reading stops at the end of the image data.
pub fn decode(
    input: impl BufRead + Seek,
    name: &str,
    colour: ColourEncoding,
) -> Result<Raster, LoadError> {
    let mut limits = Limits::no_limits();
    limits.max_alloc = Some(MAX_DECODED_BYTES);
    // Reads the header only: the size is checked before any pixel is decoded.
    let decoder = PngDecoder::with_limits(input, limits).map_err(|e| decode_error(name, e))?;
    let (width, height) = decoder.dimensions();
    let bytes_per_pixel = decoder.color_type().bytes_per_pixel();
    check_header(name, width.into(), height.into(), bytes_per_pixel.into())?;
    let image = DynamicImage::from_decoder(decoder).map_err(|e| decode_error(name, e))?;
    let encoding = match colour {
        ColourEncoding::Luminance => None,
        ColourEncoding::Mapbox => Some(TerrainRgb::Mapbox),
        ColourEncoding::Terrarium => Some(TerrainRgb::Terrarium),
    };
    let values = match (image, encoding) {
        (DynamicImage::ImageLuma8(buf), _) => unsigned(buf.into_raw(), 1, u8::MAX),
        (DynamicImage::ImageLumaA8(buf), _) => unsigned(buf.into_raw(), 2, u8::MAX),
        (DynamicImage::ImageLuma16(buf), _) => Values::Unsigned {
            samples: buf.into_raw(),
            maxval: u16::MAX,
        },
        (DynamicImage::ImageLumaA16(buf), _) => unsigned(buf.into_raw(), 2, u16::MAX),
        (DynamicImage::ImageRgb8(buf), None) => luminance(&buf.into_raw(), 3, u8::MAX),
        (DynamicImage::ImageRgba8(buf), None) => luminance(&buf.into_raw(), 4, u8::MAX),
        (DynamicImage::ImageRgb16(buf), None) => luminance(&buf.into_raw(), 3, u16::MAX),
        (DynamicImage::ImageRgba16(buf), None) => luminance(&buf.into_raw(), 4, u16::MAX),
        (DynamicImage::ImageRgb8(buf), Some(encoding)) => Values::TerrainRgb {
            bytes: buf.into_raw(),
            channels: 3,
            encoding,
        },
        (DynamicImage::ImageRgba8(buf), Some(encoding)) => Values::TerrainRgb {
            bytes: buf.into_raw(),
            channels: 4,
            encoding,
        },
        (other, _) => {
            return Err(LoadError::Unsupported {
                name: name.into(),
                what: format!("a {:?} PNG read as {colour:?}", other.color()),
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
