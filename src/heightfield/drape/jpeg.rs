//! JPEG overlays through `zune-jpeg` in strict mode: entropy-coded data that ends early or
//! breaks off is refused, not filled with grey. A file too short to hold the data of the frame
//! its header declares is refused before the pixels are allocated: every 8x8 block of every
//! component takes at least one bit (its DC coefficient's Huffman code, in a baseline or a
//! progressive first scan; the decoder reads no arithmetic-coded JPEG), and a minimum coded
//! unit holds at least one block of each component.

use std::io::{BufRead, Seek};
use zune_jpeg::zune_core::colorspace::ColorSpace;
use zune_jpeg::zune_core::options::DecoderOptions;
use zune_jpeg::{JpegDecoder, SampleRatios};

/// A JPEG's pixels as RGBA bytes, by rows from the top.
pub struct Pixels {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
}

/// Decodes the JPEG in `input`, a file of `len` bytes, after `admit` has accepted its size (else
/// its refusal).
pub fn decode<E>(
    input: impl BufRead + Seek,
    len: u64,
    admit: impl FnOnce(u32, u32) -> Result<(), E>,
    fail: impl Fn(String) -> E,
) -> Result<Pixels, E> {
    // The size limit is `admit`'s, so that its message names it.
    let options = DecoderOptions::default()
        .set_strict_mode(true)
        .set_max_width(usize::from(u16::MAX))
        .set_max_height(usize::from(u16::MAX))
        .jpeg_set_out_colorspace(ColorSpace::RGBA);
    let mut decoder = JpegDecoder::new_with_options(input, options);
    decoder.decode_headers().map_err(|e| fail(e.to_string()))?;
    let info = decoder
        .info()
        .ok_or_else(|| fail("it has no frame header".into()))?;
    let (width, height) = (u32::from(info.width), u32::from(info.height));
    if width == 0 || height == 0 {
        return Err(fail(format!("it is {width}x{height} pixels")));
    }
    admit(width, height)?;
    let least = least_bytes(width, height, info.sample_ratio, info.components);
    if len < least {
        return Err(fail(format!(
            "it is truncated or corrupt: a file of {len} bytes cannot hold the {width}x{height} \
             pixels its header claims (their coded blocks take at least {least} bytes)"
        )));
    }
    let rgba = decoder.decode().map_err(|e| fail(e.to_string()))?;
    Ok(Pixels {
        width,
        height,
        rgba,
    })
}

/// The fewest bytes the entropy-coded data of a `width` x `height` frame of `components` can
/// take: one bit for each component in each minimum coded unit, whose size the largest
/// sampling factors give.
fn least_bytes(width: u32, height: u32, sampling: SampleRatios, components: u8) -> u64 {
    let (h_max, v_max) = match sampling {
        SampleRatios::H => (2, 1),
        SampleRatios::V => (1, 2),
        SampleRatios::HV => (2, 2),
        SampleRatios::Generic(h, v) => (h.max(1) as u64, v.max(1) as u64),
        SampleRatios::None => (1, 1),
    };
    let units = u64::from(width).div_ceil(8 * h_max) * u64::from(height).div_ceil(8 * v_max);
    (units * u64::from(components.max(1))).div_ceil(8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_least_data_is_a_bit_per_component_of_each_coded_unit() {
        // 4:2:0 colour: 16x16 units, 500 x 500 of them, three bits each.
        assert_eq!(least_bytes(8000, 8000, SampleRatios::HV, 3), 93_750);
        // Grey: one 8x8 block a unit, rounded up at the edges (2 x 2 units of one bit).
        assert_eq!(least_bytes(9, 16, SampleRatios::None, 1), 1);
        assert_eq!(least_bytes(8000, 8000, SampleRatios::None, 1), 125_000);
    }
}
