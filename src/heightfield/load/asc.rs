//! ESRI ASCII grids (`.asc`): a header of `ncols`, `nrows`, `xllcorner` or `xllcenter`,
//! `yllcorner` or `yllcenter`, `cellsize` (or GDAL's `dx` and `dy`) and an optional
//! `NODATA_value`, then `nrows` lines of `ncols` numbers, north row first.
//!
//! The format carries no CRS. Its coordinates are taken as degrees when its cells are finer
//! than 0.01 units and it lies within longitude and latitude bounds (as global DEMs in
//! degrees do), else as metres.

use super::limits::check_header;
use super::raster::{Raster, Values};
use super::{decode_error, LoadError};
use crate::heightfield::georef::{Georef, GeorefError, Georeferencing, MapUnits};
use std::io::BufRead;
use thiserror::Error;

/// The longest token read: a number or key never needs more, and a file of endless digits is
/// refused instead of read through.
const MOST_PER_TOKEN: usize = 256;

/// The most whitespace read before a token: a file of endless spaces is refused too.
const MOST_SPACE: usize = 1 << 20;

/// What is wrong with a grid's header or values.
#[derive(Debug, Error)]
pub enum AscError {
    /// The header has keys but no values follow.
    #[error("the header ends without values")]
    NoValues,
    /// A header key's value is missing or not a number.
    #[error("{key}: {reason}")]
    Value {
        /// The key.
        key: String,
        /// What is wrong with its value.
        reason: Box<AscError>,
    },
    /// A key the format does not have.
    #[error("unknown header key '{0}'")]
    UnknownKey(String),
    /// `ncols` or `nrows` missing or not a whole number.
    #[error("the header has no valid {0}")]
    Size(&'static str),
    /// More values claimed than the file can hold.
    #[error(
        "its header claims {width}x{height} = {} values, more than a file of {len} bytes can \
         hold; the header is wrong or the file is truncated",
        width * height
    )]
    Claims {
        /// Values along x.
        width: u64,
        /// Values along y.
        height: u64,
        /// The file's bytes.
        len: u64,
    },
    /// The values end early.
    #[error("it ends after {read} of {count} values")]
    Ends {
        /// Values read.
        read: usize,
        /// Values the header claims.
        count: usize,
    },
    /// A token that is not a number.
    #[error("'{0}' is not a number")]
    NotANumber(String),
    /// The header ends before a key's value.
    #[error("the header ends early")]
    HeaderEnds,
    /// Endless whitespace.
    #[error("more than {MOST_SPACE} bytes of blank space")]
    Space,
    /// Endless digits.
    #[error("a value longer than {MOST_PER_TOKEN} bytes")]
    LongToken,
    /// Bytes that are not UTF-8.
    #[error("it is not text")]
    NotText,
    /// The header lacks where the grid lies.
    #[error("its header lacks the lower-left corner or the cell size")]
    NoPlace,
    /// The header's corner or cell size make no georeferencing.
    #[error(transparent)]
    Georef(#[from] GeorefError),
    /// Reading the file failed.
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// Whether a file's first bytes start an ESRI ASCII grid header.
pub fn starts_asc(bytes: &[u8]) -> bool {
    bytes.len() >= 5 && bytes[..5].eq_ignore_ascii_case(b"ncols")
}

/// The header keys, as read.
#[derive(Default)]
struct Header {
    ncols: Option<f64>,
    nrows: Option<f64>,
    x: Option<(f64, bool)>,
    y: Option<(f64, bool)>,
    dx: Option<f64>,
    dy: Option<f64>,
    nodata: Option<f64>,
}

/// Parses a grid from the start of `input`; reading stops after its last value.
pub fn decode(input: impl BufRead, len: u64, name: &str) -> Result<Raster, LoadError> {
    let mut tokens = Tokens { input };
    let mut header = Header::default();
    let first_value = loop {
        let key = tokens
            .next()
            .map_err(|e| decode_error(name, e))?
            .ok_or_else(|| decode_error(name, AscError::NoValues))?;
        if key.parse::<f64>().is_ok() {
            break key;
        }
        let value = tokens.number().map_err(|reason| {
            decode_error(
                name,
                AscError::Value {
                    key: key.clone(),
                    reason: Box::new(reason),
                },
            )
        })?;
        let slot = match key.to_ascii_lowercase().as_str() {
            "ncols" => &mut header.ncols,
            "nrows" => &mut header.nrows,
            "cellsize" => {
                header.dy = Some(value);
                &mut header.dx
            }
            "dx" => &mut header.dx,
            "dy" => &mut header.dy,
            "nodata_value" => &mut header.nodata,
            "xllcorner" | "xllcenter" => {
                header.x = Some((value, key.eq_ignore_ascii_case("xllcenter")));
                continue;
            }
            "yllcorner" | "yllcenter" => {
                header.y = Some((value, key.eq_ignore_ascii_case("yllcenter")));
                continue;
            }
            _ => return Err(decode_error(name, AscError::UnknownKey(key))),
        };
        *slot = Some(value);
    };
    let size = |v: Option<f64>, key: &'static str| match v {
        Some(n) if n.fract() == 0.0 && n >= 0.0 && n <= u32::MAX as f64 => Ok(n as u64),
        _ => Err(decode_error(name, AscError::Size(key))),
    };
    let (width, height) = (size(header.ncols, "ncols")?, size(header.nrows, "nrows")?);
    check_header(name, width, height, 8)?;
    let count = (width * height) as usize;
    // Each value takes a digit and a separator: a header claiming more than the file can
    // hold is refused before anything is allocated for them.
    if width * height > len / 2 + 1 {
        return Err(decode_error(name, AscError::Claims { width, height, len }));
    }
    let mut values = Vec::with_capacity(count);
    values.push(parse(&first_value, name)?);
    while values.len() < count {
        let token = tokens
            .next()
            .map_err(|e| decode_error(name, e))?
            .ok_or_else(|| {
                decode_error(
                    name,
                    AscError::Ends {
                        read: values.len(),
                        count,
                    },
                )
            })?;
        values.push(parse(&token, name)?);
    }
    Ok(Raster {
        width: width as usize,
        height: height as usize,
        values: Values::F64(values),
        file_nodata: header.nodata,
        georef: Georeferencing::from_result(georef(&header, height)),
    })
}

fn parse(token: &str, name: &str) -> Result<f64, LoadError> {
    token
        .parse()
        .map_err(|_| decode_error(name, AscError::NotANumber(token.to_owned())))
}

/// Where the samples lie, from the header.
fn georef(header: &Header, height: u64) -> Result<Georef, AscError> {
    let (Some((x, x_centre)), Some((y, y_centre)), Some(dx), Some(dy)) =
        (header.x, header.y, header.dx, header.dy)
    else {
        return Err(AscError::NoPlace);
    };
    // A corner is half a cell from the lower-left sample.
    let origin = [
        if x_centre { x } else { x + 0.5 * dx },
        if y_centre { y } else { y + 0.5 * dy },
    ];
    let top = origin[1] + (height as f64 - 1.0) * dy;
    let in_degrees =
        dx < 0.01 && dy < 0.01 && origin[0].abs() <= 180.0 && origin[1] >= -90.0 && top <= 90.0;
    let units = if in_degrees {
        MapUnits::Degrees
    } else {
        MapUnits::Linear { metres: 1.0 }
    };
    Ok(Georef::new(origin, [dx, dy], units)?)
}

/// Whitespace-separated tokens of a stream.
struct Tokens<R> {
    input: R,
}

impl<R: BufRead> Tokens<R> {
    /// The next token, or `None` at the end of the stream.
    fn next(&mut self) -> Result<Option<String>, AscError> {
        let mut token = Vec::new();
        let mut space = 0;
        loop {
            let buffer = self.input.fill_buf()?;
            let Some(&byte) = buffer.first() else {
                break;
            };
            self.input.consume(1);
            if byte.is_ascii_whitespace() {
                if !token.is_empty() {
                    break;
                }
                space += 1;
                if space > MOST_SPACE {
                    return Err(AscError::Space);
                }
                continue;
            }
            if token.len() == MOST_PER_TOKEN {
                return Err(AscError::LongToken);
            }
            token.push(byte);
        }
        if token.is_empty() {
            return Ok(None);
        }
        String::from_utf8(token)
            .map(Some)
            .map_err(|_| AscError::NotText)
    }

    /// The next token as a number.
    fn number(&mut self) -> Result<f64, AscError> {
        let token = self.next()?.ok_or(AscError::HeaderEnds)?;
        token.parse().map_err(|_| AscError::NotANumber(token))
    }
}
