//! PGM (P2 and P5), parsed here: `image` rescales samples of an odd maxval to 8 or 16 bits,
//! but the surface contract maps heights by the file's own maxval.

use super::limits::check_header;
use super::raster::{Raster, Values};
use super::{decode_error, LoadError};

/// Parses a binary (P5) or ASCII (P2) PGM with maxval 1..=65535.
pub fn decode(bytes: &[u8], name: &str) -> Result<Raster, LoadError> {
    let (width, height, header_end, maxval) =
        parse_header(bytes).map_err(|reason| decode_error(name, reason))?;
    // Refuse oversized images before allocating.
    check_header(name, width, height, 2)?;
    let (width, height) = (width as usize, height as usize);
    let samples = parse_raster(bytes, width * height, header_end, maxval)
        .map_err(|reason| decode_error(name, reason))?;
    Ok(Raster {
        width,
        height,
        values: Values::Unsigned { samples, maxval },
        file_nodata: None,
    })
}

/// Width, height, the position after the header, and maxval.
fn parse_header(bytes: &[u8]) -> Result<(u64, u64, usize, u16), String> {
    let mut pos = 2;
    let mut header = [0u64; 3];
    for (field, name) in header.iter_mut().zip(["width", "height", "maxval"]) {
        *field = number(bytes, &mut pos).ok_or(format!("PGM header has no valid {name}"))?;
    }
    let [w, h, maxval] = header;
    let maxval = u16::try_from(maxval)
        .ok()
        .filter(|&m| m > 0)
        .ok_or(format!("PGM maxval must be 1..=65535, got {maxval}"))?;
    Ok((w, h, pos, maxval))
}

/// The samples of a PGM raster that starts after the header at `pos`.
fn parse_raster(
    bytes: &[u8],
    count: usize,
    mut pos: usize,
    maxval: u16,
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
        // Each ASCII sample takes at least two bytes: a short file must not reserve much.
        let mut samples = Vec::with_capacity(count.min(bytes.len() / 2 + 1));
        for k in 0..count {
            let s = number(bytes, &mut pos)
                .ok_or(format!("PGM raster ends after {k} of {count} samples"))?;
            samples.push(u16::try_from(s).map_err(|_| format!("PGM sample {s} exceeds 65535"))?);
        }
        samples
    };
    Ok(samples)
}

/// Reads the next decimal number of a PGM header or ASCII raster, skipping whitespace and
/// `#` comments.
fn number(bytes: &[u8], pos: &mut usize) -> Option<u64> {
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
    use crate::heightfield::load_bytes;

    #[test]
    fn ascii_pgm_with_comment_and_odd_maxval() {
        let pgm = b"P2\n# a comment\n3 2\n1000\n0 500 1000\n250 750 1\n";
        let f = load_bytes(pgm, 10.0, "t.pgm").unwrap();
        assert_eq!((f.width(), f.height(), f.maxval()), (3, 2, 1000));
        assert_eq!(f.z(2, 1), 10.0);
        assert_eq!(f.z(1, 0), 750.0 * (10.0 / 1000.0));
    }
}
