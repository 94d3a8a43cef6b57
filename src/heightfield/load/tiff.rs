//! TIFF through the `tiff` crate: one band of 8/16-bit unsigned samples (as grayscale
//! images), or signed integer or floating-point samples (DEMs, in their own units), with a
//! GeoTIFF's GDAL_NODATA value and georeferencing.

use super::geotiff;
use super::limits::{check_header, check_least, MAX_DECODED_BYTES};
use super::picture;
use super::raster::{Raster, Values};
use super::{decode_error, LoadError};
use crate::heightfield::georef::Georeferencing;
use std::io::{Read, Seek};
use thiserror::Error;
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;
use tiff::ColorType;

/// Why a TIFF's strips or tiles cannot hold its image.
#[derive(Debug, Error)]
pub enum ChunkError {
    /// No strip offsets tag.
    #[error("it has no strip offsets ({0})")]
    NoOffsets(tiff::TiffError),
    /// No byte counts tag for the strips or tiles.
    #[error("it has no {what} byte counts ({reason})")]
    NoCounts {
        /// "strip" or "tile".
        what: &'static str,
        /// The decoder's error.
        reason: tiff::TiffError,
    },
    /// A strip or tile reaches past the end of the file.
    #[error(
        "{what} {index} lies past the end of the file ({count} bytes at offset {offset}, the \
         file is {len} bytes)"
    )]
    PastEnd {
        /// "strip" or "tile".
        what: &'static str,
        /// Which one.
        index: usize,
        /// Its bytes.
        count: u64,
        /// Where it starts.
        offset: u64,
        /// The file's bytes.
        len: u64,
    },
    /// Fewer strips or tiles than the image's size needs.
    #[error("it has {got} {what}s, where its size needs {needed}")]
    Count {
        /// "strip" or "tile".
        what: &'static str,
        /// The chunks its tags give.
        got: usize,
        /// The chunks its size needs.
        needed: usize,
    },
    /// A strip or tile that decodes to another number of samples than its size holds.
    #[error("{what} {index} does not decode to its {w}x{h} samples")]
    Size {
        /// "strip" or "tile".
        what: &'static str,
        /// Which one.
        index: usize,
        /// Its samples along x.
        w: usize,
        /// Along y.
        h: usize,
    },
    /// Too few compressed bytes for the decoded size the header claims.
    #[error(
        "its {what}s hold {total} bytes, which cannot decode to the {needed} bytes its header \
         claims"
    )]
    TooFew {
        /// "strip" or "tile".
        what: &'static str,
        /// Their bytes.
        total: u64,
        /// The bytes the samples take.
        needed: u64,
    },
}

/// What a TIFF's first directory says of its image, read before any sample is.
pub(super) struct Described {
    pub width: u32,
    pub height: u32,
    /// Bits per sample.
    pub bits: u16,
    /// The no-data value the file itself declares (GDAL_NODATA).
    pub file_nodata: Option<f64>,
    pub georef: Georeferencing,
}

/// Reads the size, sample type, no-data value and georeferencing of the first image of the
/// TIFF `decoder` reads, `len` bytes long, and checks that its strips or tiles lie within the
/// file; its size is checked against the limits of a map decoded `whole`, else only against
/// the least a field has.
pub(super) fn describe<R: Read + Seek>(
    decoder: &mut Decoder<R>,
    len: u64,
    name: &str,
    whole: bool,
) -> Result<Described, LoadError> {
    let unsupported = |what: String| LoadError::Unsupported {
        name: name.into(),
        what,
    };
    let (width, height) = decoder.dimensions().map_err(|e| decode_error(name, e))?;
    let compression = decoder
        .get_tag_unsigned::<u16>(Tag::Compression)
        .unwrap_or(1);
    if let Some(method) = picture::unread_compression(compression) {
        return Err(LoadError::Compression {
            name: name.into(),
            method,
        });
    }
    let bits = match decoder.colortype().map_err(|e| decode_error(name, e))? {
        ColorType::Gray(bits @ (8 | 16 | 32 | 64)) => bits,
        other => {
            return Err(match picture::tiff_picture(other) {
                Some(what) => LoadError::Picture {
                    name: name.into(),
                    what,
                },
                None => unsupported(format!("a {other:?} TIFF")),
            })
        }
    };
    match whole {
        true => check_header(name, width.into(), height.into(), u64::from(bits / 8))?,
        false => check_least(name, width.into(), height.into())?,
    }
    let needed = u64::from(width) * u64::from(height) * u64::from(bits / 8);
    check_chunks(decoder, len, needed).map_err(|reason| decode_error(name, reason))?;
    let file_nodata = decoder
        .get_tag_ascii_string(Tag::GdalNodata)
        .ok()
        .and_then(|text| text.trim_matches(['\0', ' ']).parse::<f64>().ok());
    let georef = geotiff::georeferencing(decoder, height);
    Ok(Described {
        width,
        height,
        bits: bits.into(),
        file_nodata,
        georef,
    })
}

/// The decoder's limits for buffers of up to [`MAX_DECODED_BYTES`].
pub(super) fn limits() -> Limits {
    let buffer_limit = usize::try_from(MAX_DECODED_BYTES).unwrap_or(usize::MAX);
    let mut limits = Limits::default();
    limits.decoding_buffer_size = buffer_limit;
    limits.intermediate_buffer_size = buffer_limit;
    limits
}

/// Decodes the first image of a TIFF from `input`, reading only what its directory points at.
pub fn decode(input: impl Read + Seek, len: u64, name: &str) -> Result<Raster, LoadError> {
    // Reads the header and the first directory only: the size is checked before decoding.
    let mut decoder = Decoder::new(input).map_err(|e| decode_error(name, e))?;
    let described = describe(&mut decoder, len, name, true)?;
    let mut decoder = decoder.with_limits(limits());
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
        _ => return Err(unsupported_type(name, described.bits)),
    };
    Ok(Raster {
        width: described.width as usize,
        height: described.height as usize,
        values,
        file_nodata: described.file_nodata,
        georef: described.georef,
    })
}

/// A TIFF of `bits`-bit samples of a type not read (64-bit integers, 16-bit floats).
pub(super) fn unsupported_type(name: &str, bits: u16) -> LoadError {
    LoadError::Unsupported {
        name: name.into(),
        what: format!("a TIFF of {bits}-bit samples of this type"),
    }
}

/// The most bytes a compressed byte decodes to in the codecs read (Deflate's limit is about
/// 1032, LZW's about 1500): more claimed than this is a corrupt or forged header.
const MOST_EXPANSION: u64 = 4096;

/// Checks, before any buffer is made, that the image's strips or tiles lie within the file's
/// `len` bytes and can hold the `needed` bytes of its samples.
fn check_chunks<R: Read + Seek>(
    decoder: &mut Decoder<R>,
    len: u64,
    needed: u64,
) -> Result<(), ChunkError> {
    let (offsets, counts, what) = match decoder.get_tag_u64_vec(Tag::TileOffsets) {
        Ok(offsets) => (
            offsets,
            decoder.get_tag_u64_vec(Tag::TileByteCounts),
            "tile",
        ),
        Err(_) => (
            decoder
                .get_tag_u64_vec(Tag::StripOffsets)
                .map_err(ChunkError::NoOffsets)?,
            decoder.get_tag_u64_vec(Tag::StripByteCounts),
            "strip",
        ),
    };
    let counts = counts.map_err(|reason| ChunkError::NoCounts { what, reason })?;
    let mut total = 0u64;
    for (index, (&offset, &count)) in offsets.iter().zip(&counts).enumerate() {
        if offset.checked_add(count).is_none_or(|end| end > len) {
            return Err(ChunkError::PastEnd {
                what,
                index,
                count,
                offset,
                len,
            });
        }
        total = total.saturating_add(count);
    }
    let compression = decoder
        .get_tag_unsigned::<u16>(Tag::Compression)
        .unwrap_or(1);
    let most = match compression {
        1 => total,
        // The decoded size is bounded by the header's, checked before.
        c if picture::expands_without_bound(c) => u64::MAX,
        _ => total.saturating_mul(MOST_EXPANSION),
    };
    if most < needed {
        return Err(ChunkError::TooFew {
            what,
            total,
            needed,
        });
    }
    Ok(())
}
