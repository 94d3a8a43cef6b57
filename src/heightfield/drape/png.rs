//! PNG overlays through the `png` crate, with their ancillary chunks that inflate (an ICC
//! profile, compressed text) skipped unread: an overlay's colours need none of them, and one
//! can inflate to gigabytes.

use png::{BitDepth, ColorType, Decoder, Transformations};
use std::io::BufRead;

/// A PNG's pixels as RGBA bytes, by rows from the top.
pub struct Pixels {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
}

/// The most a byte of deflate data inflates to.
const MOST_EXPANSION: u64 = 1032;

/// Decodes the PNG in `input`, a file of `len` bytes, after `admit` has accepted its size (else
/// its refusal).
pub fn decode<E>(
    input: impl BufRead + std::io::Seek,
    len: u64,
    admit: impl FnOnce(u32, u32) -> Result<(), E>,
    fail: impl Fn(String) -> E,
) -> Result<Pixels, E> {
    let mut decoder = Decoder::new(input);
    decoder.set_ignore_iccp_chunk(true);
    decoder.set_ignore_text_chunk(true);
    // Palettes to RGB, fewer than 8 bits to 8, and an alpha channel always.
    decoder.set_transformations(Transformations::EXPAND | Transformations::ALPHA);
    let mut reader = decoder.read_info().map_err(|e| fail(e.to_string()))?;
    let (width, height) = reader.info().size();
    if width == 0 || height == 0 {
        return Err(fail(format!("it is {width}x{height} pixels")));
    }
    admit(width, height)?;
    let raw = reader.info().raw_bytes() as u64;
    if len.saturating_mul(MOST_EXPANSION) < raw {
        return Err(fail(format!(
            "it is truncated or corrupt: a file of {len} bytes cannot inflate to the {raw} \
             bytes of pixels its header claims"
        )));
    }
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| fail("its pixels do not fit in memory".into()))?;
    // Zeroed by the allocator: pages the decoder never reaches cost no memory.
    let mut bytes = vec![0; size];
    let frame = reader
        .next_frame(&mut bytes)
        .map_err(|e| fail(e.to_string()))?;
    bytes.truncate(frame.buffer_size());
    let (colour, depth) = reader.output_color_type();
    let channels = match depth {
        BitDepth::Sixteen => bytes
            .chunks_exact(2)
            .map(|pair| eight_bits(u16::from_be_bytes([pair[0], pair[1]])))
            .collect(),
        _ => bytes,
    };
    let rgba = match colour {
        ColorType::Rgba => channels,
        ColorType::GrayscaleAlpha => channels
            .chunks_exact(2)
            .flat_map(|ga| [ga[0], ga[0], ga[0], ga[1]])
            .collect(),
        other => return Err(fail(format!("its pixels decode as {other:?}"))),
    };
    Ok(Pixels {
        width,
        height,
        rgba,
    })
}

/// A 16-bit channel value as the nearest 8-bit one.
fn eight_bits(value: u16) -> u8 {
    ((u32::from(value) * 255 + 32767) / 65535) as u8
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Cursor;

    /// A `width` x `height` PNG of `colour` and `depth` (a palette with transparency for
    /// `Indexed`).
    fn encoded(colour: ColorType, depth: BitDepth, (width, height): (u32, u32)) -> Vec<u8> {
        let bits = colour.samples() * depth as usize;
        let row = (width as usize * bits).div_ceil(8);
        let data: Vec<u8> = (0..row * height as usize)
            .map(|k| (k * 73 + 11) as u8)
            .collect();
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(colour);
        encoder.set_depth(depth);
        if colour == ColorType::Indexed {
            encoder.set_palette(
                (0..=255u8)
                    .flat_map(|i| [i, 255 - i, i / 2])
                    .collect::<Vec<_>>(),
            );
            encoder.set_trns((0..=255u8).map(|i| i.wrapping_mul(3)).collect::<Vec<_>>());
        }
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(&data).unwrap();
        writer.finish().unwrap();
        bytes
    }

    #[test]
    fn every_colour_type_decodes_to_the_rgba_the_image_crate_gives() {
        use ColorType::*;
        for (colour, depth) in [
            (Grayscale, BitDepth::One),
            (Grayscale, BitDepth::Eight),
            (Grayscale, BitDepth::Sixteen),
            (GrayscaleAlpha, BitDepth::Eight),
            (GrayscaleAlpha, BitDepth::Sixteen),
            (Rgb, BitDepth::Eight),
            (Rgb, BitDepth::Sixteen),
            (Rgba, BitDepth::Eight),
            (Rgba, BitDepth::Sixteen),
            (Indexed, BitDepth::Four),
            (Indexed, BitDepth::Eight),
        ] {
            let bytes = encoded(colour, depth, (5, 3));
            let expected = image::load_from_memory(&bytes).unwrap().into_rgba8();
            let len = bytes.len() as u64;
            let got = decode(Cursor::new(bytes), len, |_, _| Ok(()), |e| e).unwrap();
            assert_eq!((got.width, got.height), expected.dimensions());
            assert_eq!(got.rgba, expected.into_raw(), "{colour:?} {depth:?}");
        }
    }

    #[test]
    fn a_header_claiming_more_than_its_file_can_inflate_to_is_corrupt() {
        // 100 rows of a filter byte and 300 bytes of pixels: more than 10 bytes can hold.
        let bytes = encoded(ColorType::Rgb, BitDepth::Eight, (100, 100));
        let message = decode(Cursor::new(bytes), 10, |_, _| Ok(()), |e| e)
            .err()
            .expect("refused");
        assert!(
            message.contains("a file of 10 bytes cannot inflate to the 30100 bytes"),
            "{message}"
        );
    }
}
