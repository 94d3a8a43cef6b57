//! PGM (P2 and P5), parsed here: `image` rescales samples of an odd maxval to 8 or 16 bits,
//! but the surface contract maps heights by the file's own maxval. Read as a stream: what
//! follows the raster is never read.

use super::limits::check_header;
use super::raster::{Raster, Values};
use super::{decode_error, LoadError};
use crate::heightfield::georef::Georeferencing;
use std::io::{self, BufRead};
use thiserror::Error;

/// The most whitespace, comments and digits read for one number: a header or a sample never
/// needs more, and a file of endless spaces is refused instead of read through.
const MOST_PER_NUMBER: u64 = 1 << 20;

/// Bytes of the binary raster read at once.
const BLOCK: usize = 1 << 16;

/// What is wrong with a PGM's header or raster.
#[derive(Debug, Error)]
pub enum PgmError {
    /// The magic number is neither P2 nor P5.
    #[error("not a PGM (P2 or P5)")]
    Magic,
    /// A header field is missing or not a number.
    #[error("PGM header has no valid {0}")]
    Header(&'static str),
    /// Maxval is 0 or above 65535.
    #[error("PGM maxval must be 1..=65535, got {0}")]
    Maxval(u64),
    /// Fewer bytes follow the header than the binary raster needs.
    #[error("PGM raster is truncated: {available} of {needed} bytes")]
    Short {
        /// Bytes after the header.
        available: u64,
        /// Bytes the raster needs.
        needed: usize,
    },
    /// Reading the binary raster stopped early.
    #[error("PGM raster is truncated after {samples} samples ({reason})")]
    Truncated {
        /// Samples read.
        samples: usize,
        /// Why reading stopped.
        reason: Box<PgmError>,
    },
    /// The ASCII raster ends early.
    #[error("PGM raster ends after {read} of {count} samples")]
    Ends {
        /// Samples read.
        read: usize,
        /// Samples the header claims.
        count: usize,
    },
    /// An ASCII sample above 16 bits.
    #[error("PGM sample {0} exceeds 65535")]
    Sample(u64),
    /// The file ends within the header.
    #[error("the file ends in the PGM header")]
    HeaderEnds,
    /// Endless whitespace or digits.
    #[error("more than {MOST_PER_NUMBER} bytes of spaces, comments or digits at byte {0}")]
    TooLong(u64),
    /// A number beyond 64 bits.
    #[error("a number at byte {0} is too large")]
    TooLarge(u64),
    /// Reading the file failed.
    #[error("{0}")]
    Io(#[from] io::Error),
}

/// Parses a binary (P5) or ASCII (P2) PGM with maxval 1..=65535 from the start of a file of
/// `len` bytes.
pub fn decode(input: impl BufRead, len: u64, name: &str) -> Result<Raster, LoadError> {
    let mut scanner = Scanner { input, position: 0 };
    let (binary, width, height, maxval) =
        parse_header(&mut scanner).map_err(|reason| decode_error(name, reason))?;
    // Refuse oversized images before allocating.
    check_header(name, width, height, 2)?;
    let count = (width * height) as usize;
    let remaining = len.saturating_sub(scanner.position);
    let samples = if binary {
        read_binary(scanner, count, remaining, maxval)
    } else {
        read_ascii(scanner, count, remaining)
    }
    .map_err(|reason| decode_error(name, reason))?;
    Ok(Raster {
        width: width as usize,
        height: height as usize,
        values: Values::Unsigned { samples, maxval },
        file_nodata: None,
        georef: Georeferencing::None,
    })
}

/// Whether the raster is binary (P5), then width, height and maxval; the scanner is left at
/// the byte after maxval.
fn parse_header(scanner: &mut Scanner<impl BufRead>) -> Result<(bool, u64, u64, u16), PgmError> {
    let mut magic = [0u8; 2];
    scanner.read_exact(&mut magic)?;
    let binary = match &magic {
        b"P5" => true,
        b"P2" => false,
        _ => return Err(PgmError::Magic),
    };
    let mut header = [0u64; 3];
    for (field, name) in header.iter_mut().zip(["width", "height", "maxval"]) {
        *field = scanner.number()?.ok_or(PgmError::Header(name))?;
    }
    let [w, h, maxval] = header;
    let maxval = u16::try_from(maxval)
        .ok()
        .filter(|&m| m > 0)
        .ok_or(PgmError::Maxval(maxval))?;
    Ok((binary, w, h, maxval))
}

/// A P5 raster of `count` samples; `remaining` bytes follow maxval in the file.
fn read_binary(
    mut scanner: Scanner<impl BufRead>,
    count: usize,
    remaining: u64,
    maxval: u16,
) -> Result<Vec<u16>, PgmError> {
    let bytes_per_sample = if maxval < 256 { 1 } else { 2 };
    let needed = count * bytes_per_sample;
    // Exactly one whitespace byte separates the header from the raster.
    let available = remaining.saturating_sub(1);
    if available < needed as u64 {
        return Err(PgmError::Short { available, needed });
    }
    scanner.read_exact(&mut [0u8])?;
    let mut samples = Vec::with_capacity(count);
    let mut block = vec![0u8; BLOCK.min(needed)];
    while samples.len() < count {
        let take = ((count - samples.len()) * bytes_per_sample).min(block.len());
        let bytes = &mut block[..take];
        scanner
            .read_exact(bytes)
            .map_err(|reason| PgmError::Truncated {
                samples: samples.len(),
                reason: Box::new(reason),
            })?;
        if bytes_per_sample == 1 {
            samples.extend(bytes.iter().map(|&b| u16::from(b)));
        } else {
            let pairs = bytes.chunks_exact(2);
            samples.extend(pairs.map(|p| u16::from_be_bytes([p[0], p[1]])));
        }
    }
    Ok(samples)
}

/// A P2 raster of `count` samples; `remaining` bytes follow maxval in the file.
fn read_ascii(
    mut scanner: Scanner<impl BufRead>,
    count: usize,
    remaining: u64,
) -> Result<Vec<u16>, PgmError> {
    // Each ASCII sample takes at least two bytes: a short file must not reserve much.
    let most = usize::try_from(remaining / 2 + 1).unwrap_or(usize::MAX);
    let mut samples = Vec::with_capacity(count.min(most));
    for k in 0..count {
        let s = scanner.number()?.ok_or(PgmError::Ends { read: k, count })?;
        samples.push(u16::try_from(s).map_err(|_| PgmError::Sample(s))?);
    }
    Ok(samples)
}

/// A PGM's bytes, looked at one at a time through the buffer, counting how many were taken.
struct Scanner<R> {
    input: R,
    position: u64,
}

impl<R: BufRead> Scanner<R> {
    /// The next byte, without taking it; None at the end of the file.
    fn peek(&mut self) -> Result<Option<u8>, PgmError> {
        loop {
            match self.input.fill_buf() {
                Ok(bytes) => return Ok(bytes.first().copied()),
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e.into()),
            }
        }
    }

    fn take(&mut self) {
        self.input.consume(1);
        self.position += 1;
    }

    fn read_exact(&mut self, buf: &mut [u8]) -> Result<(), PgmError> {
        self.input.read_exact(buf).map_err(|e| match e.kind() {
            io::ErrorKind::UnexpectedEof => PgmError::HeaderEnds,
            _ => e.into(),
        })?;
        self.position += buf.len() as u64;
        Ok(())
    }

    /// The next decimal number of a PGM header or ASCII raster, skipping whitespace and `#`
    /// comments; None if something else, or the end of the file, comes first.
    fn number(&mut self) -> Result<Option<u64>, PgmError> {
        let start = self.position;
        let budget = |position: u64| {
            if position - start > MOST_PER_NUMBER {
                Err(PgmError::TooLong(start))
            } else {
                Ok(())
            }
        };
        let mut in_comment = false;
        loop {
            budget(self.position)?;
            match self.peek()? {
                None => return Ok(None),
                Some(b'\n') => in_comment = false,
                Some(_) if in_comment => {}
                Some(b'#') => in_comment = true,
                Some(b) if b.is_ascii_whitespace() => {}
                Some(_) => break,
            }
            self.take();
        }
        let mut value: Option<u64> = None;
        while let Some(digit) = self.peek()?.filter(u8::is_ascii_digit) {
            budget(self.position)?;
            let so_far = value.unwrap_or(0);
            let next = so_far
                .checked_mul(10)
                .and_then(|v| v.checked_add(u64::from(digit - b'0')));
            value = Some(next.ok_or(PgmError::TooLarge(start))?);
            self.take();
        }
        Ok(value)
    }
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

    #[test]
    fn what_follows_the_raster_is_not_read() {
        let mut pgm = b"P5 2 2 255\n\x01\x02\x03\x04".to_vec();
        pgm.extend(b"trailing bytes that are not samples");
        let f = load_bytes(&pgm, 255.0, "t.pgm").unwrap();
        assert_eq!(f.samples(), [3, 4, 1, 2]);
    }

    #[test]
    fn endless_spaces_and_long_numbers_are_refused() {
        let mut spaces = b"P2 2 2 255\n1 2".to_vec();
        spaces.resize(spaces.len() + (1 << 20) + 10, b' ');
        spaces.extend(b"3 4\n");
        let error = load_bytes(&spaces, 1.0, "spaces.pgm").unwrap_err();
        assert!(
            error.to_string().contains("spaces, comments or digits"),
            "{error}"
        );
        let long = b"P2 2 2 99999999999999999999999\n1 2 3 4\n";
        let error = load_bytes(long, 1.0, "long.pgm").unwrap_err();
        assert!(error.to_string().contains("too large"), "{error}");
    }
}
