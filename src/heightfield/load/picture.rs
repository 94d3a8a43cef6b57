//! Pictures rather than height maps: a JPEG, or a TIFF of colour pixels (RGB, YCbCr, a
//! palette), which can colour a map as an overlay but hold no heights; and the TIFF
//! compressions the decoder reads, the rest named for a message.

use std::io::Read;
use std::path::Path;
use tiff::decoder::Decoder;
use tiff::ColorType;

/// Whether a file's first bytes are a JPEG's start-of-image marker.
pub fn is_jpeg(start: &[u8]) -> bool {
    start.starts_with(&[0xff, 0xd8, 0xff])
}

/// What kind of picture a TIFF of `color` pixels is, if it is one rather than heights.
pub fn tiff_picture(color: ColorType) -> Option<String> {
    match color {
        ColorType::RGB(_) | ColorType::RGBA(_) => Some("an RGB TIFF".into()),
        ColorType::YCbCr(_) => Some("a YCbCr (JPEG-compressed) TIFF".into()),
        ColorType::Palette(_) => Some("a palette TIFF".into()),
        ColorType::CMYK(_) | ColorType::CMYKA(_) => Some("a CMYK TIFF".into()),
        _ => None,
    }
}

/// What kind of picture the file at `path` is, if it is one rather than a height map: a JPEG,
/// or a TIFF of colour pixels.
pub fn picture_kind(path: &Path) -> Option<String> {
    let (file, _) = crate::regular_file::open(path).ok()?;
    let mut reader = std::io::BufReader::new(file);
    let mut start = [0u8; 4];
    reader.read_exact(&mut start).ok()?;
    if is_jpeg(&start) {
        return Some("a JPEG image".into());
    }
    let (file, _) = crate::regular_file::open(path).ok()?;
    let mut decoder = Decoder::new(std::io::BufReader::new(file)).ok()?;
    tiff_picture(decoder.colortype().ok()?)
}

/// The name of a TIFF compression code the decoder cannot read, `None` for those it reads
/// (none, LZW, Deflate, PackBits, JPEG, ZSTD).
pub fn unread_compression(code: u16) -> Option<String> {
    Some(match code {
        1 | 5 | 7 | 8 | 32773 | 32946 | 50000 => return None,
        2..=4 => "CCITT fax coding".into(),
        6 => "old-style JPEG".into(),
        34712 => "JPEG 2000".into(),
        34887 => "LERC".into(),
        34925 => "LZMA".into(),
        50001 => "WebP".into(),
        50002 => "JPEG XL".into(),
        other => format!("compression method {other}"),
    })
}

/// Whether compression `code` may decode to many thousand times its bytes (a uniform tile
/// in ZSTD or JPEG), so that the compressed size says nothing of the image's.
pub fn expands_without_bound(code: u16) -> bool {
    matches!(code, 7 | 50000)
}
