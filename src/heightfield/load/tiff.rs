//! TIFF through the `tiff` crate: one band of 8/16-bit unsigned samples (as grayscale
//! images), or signed integer or floating-point samples (DEMs, in their own units), with a
//! GeoTIFF's GDAL_NODATA value and georeferencing.

use super::geotiff;
use super::limits::{check_header, MAX_DECODED_BYTES};
use super::raster::{Raster, Values};
use super::{decode_error, LoadError};
use std::io::{Read, Seek};
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;
use tiff::ColorType;

/// Decodes the first image of a TIFF from `input`, reading only what its directory points at.
pub fn decode(input: impl Read + Seek, name: &str) -> Result<Raster, LoadError> {
    let unsupported = |what: String| LoadError::Unsupported {
        name: name.into(),
        what,
    };
    // Reads the header and the first directory only: the size is checked before decoding.
    let mut decoder = Decoder::new(input).map_err(|e| decode_error(name, e))?;
    let (width, height) = decoder.dimensions().map_err(|e| decode_error(name, e))?;
    let bits = match decoder.colortype().map_err(|e| decode_error(name, e))? {
        ColorType::Gray(bits @ (8 | 16 | 32 | 64)) => bits,
        other => return Err(unsupported(format!("a {other:?} TIFF"))),
    };
    check_header(name, width.into(), height.into(), u64::from(bits / 8))?;
    let file_nodata = decoder
        .get_tag_ascii_string(Tag::GdalNodata)
        .ok()
        .and_then(|text| text.trim_matches(['\0', ' ']).parse::<f64>().ok());
    let georef = geotiff::georeferencing(&mut decoder, height);
    let buffer_limit = usize::try_from(MAX_DECODED_BYTES).unwrap_or(usize::MAX);
    let mut limits = Limits::default();
    limits.decoding_buffer_size = buffer_limit;
    limits.intermediate_buffer_size = buffer_limit;
    let mut decoder = decoder.with_limits(limits);
    let values = match decoder.read_image().map_err(|e| decode_error(name, e))? {
        DecodingResult::U8(v) => Values::Unsigned {
            samples: v.into_iter().map(u16::from).collect(),
            maxval: u8::MAX.into(),
        },
        DecodingResult::U16(samples) => Values::Unsigned {
            samples,
            maxval: u16::MAX,
        },
        DecodingResult::I8(v) => Values::I8(v),
        DecodingResult::I16(v) => Values::I16(v),
        DecodingResult::I32(v) => Values::I32(v),
        DecodingResult::U32(v) => Values::U32(v),
        DecodingResult::F32(v) => Values::F32(v),
        DecodingResult::F64(v) => Values::F64(v),
        _ => {
            return Err(unsupported(format!(
                "a TIFF of {bits}-bit samples of this type"
            )))
        }
    };
    Ok(Raster {
        width: width as usize,
        height: height as usize,
        values,
        file_nodata,
        georef,
    })
}
