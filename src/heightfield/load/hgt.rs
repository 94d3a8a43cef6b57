//! SRTM `.hgt` tiles: `n x n` big-endian signed 16-bit heights in metres, north row first,
//! -32768 for no data. The file holds nothing else: its size is `2 n^2` bytes (1201 for 3
//! arc-seconds, 3601 for 1), and its place is its name: `N45W123.hgt` has its south-west
//! sample at 45 N, 123 W, and its samples span one degree each way, edges shared with the
//! neighbouring tiles.

use super::limits::check_header;
use super::raster::{Raster, Values};
use super::{decode_error, DecodeFailure, LoadError};
use crate::heightfield::crs::Crs;
use crate::heightfield::georef::{Georef, GeorefError, Georeferencing, MapUnits};
use std::io::Read;
use std::path::Path;
use thiserror::Error;

/// Why a tile's name does not place it.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum PlaceError {
    /// The name is not of the form `N45W123`.
    #[error("its name '{0}' does not say where it lies (as N45W123 does)")]
    Name(String),
    /// The corner and spacing make no georeferencing.
    #[error(transparent)]
    Georef(#[from] GeorefError),
}

/// Whether `name` names an `.hgt` file.
pub fn is_hgt(name: &str) -> bool {
    Path::new(name)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("hgt"))
}

/// Reads a tile of `len` bytes named `name`.
pub fn decode(mut input: impl Read, len: u64, name: &str) -> Result<Raster, LoadError> {
    let n = (len / 2).isqrt();
    if 2 * n * n != len {
        return Err(decode_error(name, DecodeFailure::HgtSize(len)));
    }
    check_header(name, n, n, 2)?;
    let n = n as usize;
    let mut heights = Vec::with_capacity(n * n);
    let mut row = vec![0u8; 2 * n];
    for _ in 0..n {
        input
            .read_exact(&mut row)
            .map_err(|e| decode_error(name, e))?;
        heights.extend(
            row.chunks_exact(2)
                .map(|b| i16::from_be_bytes([b[0], b[1]])),
        );
    }
    Ok(Raster {
        width: n,
        height: n,
        values: Values::I16(heights),
        file_nodata: None,
        georef: Georeferencing::from_result(place(name, n)),
    })
}

/// The georeferencing of a tile of `n x n` samples from its name.
fn place(name: &str, n: usize) -> Result<Georef, PlaceError> {
    let stem = Path::new(name)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or_default();
    let (lat, lon) = corner_from_name(stem).ok_or_else(|| PlaceError::Name(stem.to_owned()))?;
    let spacing = 1.0 / (n - 1) as f64;
    // SRTM tiles are WGS 84 longitude and latitude.
    Ok(
        Georef::new([lon, lat], [spacing, spacing], MapUnits::Degrees)?
            .with_crs(Crs::from_epsg(4326)),
    )
}

/// Latitude and longitude of a tile's south-west corner from a name such as `N45W123` or
/// `s01e009` (any case).
fn corner_from_name(stem: &str) -> Option<(f64, f64)> {
    let s = stem.get(..7).filter(|s| s.is_ascii())?.to_ascii_uppercase();
    let degrees = |sign: u8, digits: &str, positive: u8, negative: u8| -> Option<f64> {
        let value: u16 = digits
            .parse()
            .ok()
            .filter(|_| digits.bytes().all(|b| b.is_ascii_digit()))?;
        match sign {
            s if s == positive => Some(f64::from(value)),
            s if s == negative => Some(-f64::from(value)),
            _ => None,
        }
    };
    let b = s.as_bytes();
    let lat = degrees(b[0], &s[1..3], b'N', b'S').filter(|l| l.abs() <= 90.0)?;
    let lon = degrees(b[3], &s[4..7], b'E', b'W').filter(|l| l.abs() <= 180.0)?;
    Some((lat, lon))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tile_names_give_their_south_west_corner() {
        assert_eq!(corner_from_name("N45W123"), Some((45.0, -123.0)));
        assert_eq!(corner_from_name("s01e009"), Some((-1.0, 9.0)));
        assert_eq!(corner_from_name("N91E000"), None);
        assert_eq!(corner_from_name("X45W123"), None);
        assert_eq!(corner_from_name("N4+W123"), None);
        assert_eq!(corner_from_name("dem"), None);
    }
}
