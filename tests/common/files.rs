//! Height map files written by the tests, byte by byte where a library would refuse to write
//! them (headers that promise more than any file holds).

use tiff::encoder::colortype::{ColorType, Gray32Float};
use tiff::encoder::{TiffEncoder, TiffValue};
use tiff::tags::Tag;

/// A single-band TIFF of `width` x `height` samples in image order, with a GDAL_NODATA tag
/// when `nodata` is given.
pub fn tiff<C: ColorType>(
    width: u32,
    height: u32,
    data: &[C::Inner],
    nodata: Option<&str>,
) -> Vec<u8>
where
    [C::Inner]: TiffValue,
{
    let tags: Vec<(Tag, TagData)> = nodata
        .map(|text| (Tag::GdalNodata, TagData::Ascii(text)))
        .into_iter()
        .collect();
    tagged_tiff::<C>(width, height, data, &tags)
}

/// The value of a tag written by [`tagged_tiff`].
pub enum TagData<'a> {
    /// Text (GDAL_NODATA).
    Ascii(&'a str),
    /// Doubles (ModelPixelScale, ModelTiepoint, ModelTransformation).
    Doubles(&'a [f64]),
    /// Shorts (GeoKeyDirectory).
    Shorts(&'a [u16]),
}

/// A single-band TIFF of `width` x `height` samples in image order with these tags.
pub fn tagged_tiff<C: ColorType>(
    width: u32,
    height: u32,
    data: &[C::Inner],
    tags: &[(Tag, TagData)],
) -> Vec<u8>
where
    [C::Inner]: TiffValue,
{
    let mut bytes = std::io::Cursor::new(Vec::new());
    let mut encoder = TiffEncoder::new(&mut bytes).expect("TIFF encoder");
    let mut image = encoder.new_image::<C>(width, height).expect("TIFF image");
    for (tag, value) in tags {
        let directory = image.encoder();
        match value {
            TagData::Ascii(text) => directory.write_tag(*tag, *text),
            TagData::Doubles(values) => directory.write_tag(*tag, *values),
            TagData::Shorts(values) => directory.write_tag(*tag, *values),
        }
        .expect("TIFF tag");
    }
    image.write_data(data).expect("TIFF data");
    bytes.into_inner()
}

/// Samples along each side of [`dem_bytes`]' DEM.
pub const SIDE: u32 = 17;

/// A flat 17x17 float DEM 100 m high (a 3 m bump in one corner, so that it has relief) with
/// the given pixel scale, its top-left corner at `corner`, in a projected (`model` 1) or
/// geographic (2) CRS.
pub fn dem_bytes(scale: f64, corner: [f64; 2], model: u16) -> Vec<u8> {
    let mut heights = vec![100.0f32; (SIDE * SIDE) as usize];
    heights[0] = 103.0;
    let keys = [1, 1, 0, 1, 1024, 0, 1, model];
    let tags = [
        (Tag::GeoKeyDirectoryTag, TagData::Shorts(&keys)),
        (
            Tag::ModelPixelScaleTag,
            TagData::Doubles(&[scale, scale, 0.0]),
        ),
        (
            Tag::ModelTiepointTag,
            TagData::Doubles(&[0.0, 0.0, 0.0, corner[0], corner[1], 0.0]),
        ),
    ];
    tagged_tiff::<Gray32Float>(SIDE, SIDE, &heights, &tags)
}

/// A PNG whose header declares `width` x `height` pixels of the given PNG colour type and bit
/// depth, followed by a tiny IDAT chunk and IEND: what a decompression bomb or a damaged
/// header looks like before decoding.
pub fn png_header(width: u32, height: u32, bit_depth: u8, colour_type: u8) -> Vec<u8> {
    let mut ihdr = Vec::new();
    ihdr.extend(width.to_be_bytes());
    ihdr.extend(height.to_be_bytes());
    ihdr.extend([bit_depth, colour_type, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png_chunk(&mut png, b"IHDR", &ihdr);
    // A zlib stream of one empty stored block: far fewer bytes than the header promises.
    png_chunk(
        &mut png,
        b"IDAT",
        &[0x78, 0x01, 0x01, 0x00, 0x00, 0xff, 0xff, 0, 0, 0, 1],
    );
    png_chunk(&mut png, b"IEND", &[]);
    png
}

fn png_chunk(png: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    png.extend((data.len() as u32).to_be_bytes());
    let start = png.len();
    png.extend(kind);
    png.extend(data);
    let crc = crc32(&png[start..]);
    png.extend(crc.to_be_bytes());
}

/// CRC-32 (IEEE), as PNG chunks carry it.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A little-endian classic TIFF with one directory declaring `width` x `height` 16-bit gray
/// samples in one strip, and no sample data at all.
pub fn tiff_header(width: u32, height: u32) -> Vec<u8> {
    tiff_directory(&[
        (256, 4, 1, width),    // ImageWidth
        (257, 4, 1, height),   // ImageLength
        (258, 3, 1, 16),       // BitsPerSample
        (259, 3, 1, 1),        // Compression: none
        (262, 3, 1, 1),        // PhotometricInterpretation: black is zero
        (273, 4, 1, 8),        // StripOffsets
        (278, 4, 1, height),   // RowsPerStrip
        (279, 4, 1, u32::MAX), // StripByteCounts
    ])
}

/// A little-endian classic TIFF header and one directory right after it, of `entries`
/// (tag, type, count, value or offset; type 3 is SHORT, 4 is LONG).
pub fn tiff_directory(entries: &[(u16, u16, u32, u32)]) -> Vec<u8> {
    let mut bytes = b"II*\0".to_vec();
    bytes.extend(8u32.to_le_bytes());
    bytes.extend((entries.len() as u16).to_le_bytes());
    for &(tag, kind, count, value) in entries {
        bytes.extend(tag.to_le_bytes());
        bytes.extend(kind.to_le_bytes());
        bytes.extend(count.to_le_bytes());
        if kind == 3 && count == 1 {
            bytes.extend((value as u16).to_le_bytes());
            bytes.extend([0, 0]);
        } else {
            bytes.extend(value.to_le_bytes());
        }
    }
    bytes.extend(0u32.to_le_bytes());
    bytes
}
