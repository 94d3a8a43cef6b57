//! Mosaics: georeferenced tiles given together, joined into one height field when they share
//! their units and cell size and lie on one grid. The field spans all of them; samples no tile
//! covers are no data, and where tiles overlap (SRTM tiles share their edge rows) the first
//! tile given wins.

use super::raster::{Raster, Values};
use super::{load_with, LoadError, LoadOptions, NoDataValue, Progress};
use crate::heightfield::georef::{Georef, GeorefError, Georeferencing, MapUnits};
use crate::heightfield::limits::{MAX_DECODED_BYTES, MAX_SAMPLES};
use crate::heightfield::{Heightfield, Quantisation};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// How far (in cells) a tile's origin may lie off the first tile's grid, and how far apart
/// (relatively) two cell sizes may be, and still be one grid: rounding in the files' tags.
const TOLERANCE: f64 = 1e-6;

/// Why tiles cannot be joined into one map.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum MosaicError {
    /// A tile's georeferencing was ignored.
    #[error(
        "{}'s georeferencing cannot be used ({why}), so where it lies beside the others is \
         unknown",
        path.display()
    )]
    Ignored {
        /// The tile.
        path: PathBuf,
        /// Why it was ignored.
        why: String,
    },
    /// A tile without georeferencing.
    #[error(
        "{} is not georeferenced, so where it lies beside the others is unknown",
        .0.display()
    )]
    NotGeoreferenced(PathBuf),
    /// No paths.
    #[error("no tiles given")]
    NoTiles,
    /// A tile off the first tile's grid.
    #[error("{} and {} {why}", first.display(), other.display())]
    OffGrid {
        /// The first tile.
        first: PathBuf,
        /// The tile off its grid.
        other: PathBuf,
        /// How they differ.
        why: GridMismatch,
    },
    /// A tile too far from the first for any joined grid.
    #[error(
        "{} lies {offset:e} cells from the first tile along {axis}, farther than any joined \
         map can span ({MAX_SAMPLES} samples at most); check its corner coordinates",
        path.display()
    )]
    TooFar {
        /// The tile.
        path: PathBuf,
        /// Cells from the first tile.
        offset: f64,
        /// "x" or "y".
        axis: &'static str,
    },
    /// A joined grid beyond the limits.
    #[error(
        "together they span {width}x{height} samples, more than the limits of {MAX_SAMPLES} \
         samples and {} GiB decoded; give fewer or smaller tiles",
        MAX_DECODED_BYTES >> 30
    )]
    TooLarge {
        /// Samples along x.
        width: u64,
        /// Samples along y.
        height: u64,
    },
    /// A large joined grid the tiles cover little of.
    #[error(
        "together they span {width}x{height} samples, of which the tiles cover at most \
         {covered} ({:.3}%): the gaps between them would be stored as no data; give tiles \
         that adjoin",
        100.0 * *covered as f64 / width.saturating_mul(*height) as f64
    )]
    Sparse {
        /// Samples along x.
        width: u64,
        /// Samples along y.
        height: u64,
        /// Samples the tiles hold.
        covered: u64,
    },
    /// No memory for the joined grid.
    #[error("there is not enough memory for their {width}x{height} samples")]
    NoMemory {
        /// Samples along x.
        width: usize,
        /// Samples along y.
        height: usize,
    },
    /// The joined grid's corner makes no georeferencing.
    #[error(transparent)]
    Georef(#[from] GeorefError),
}

/// How a tile differs from the first tile's grid.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum GridMismatch {
    /// Degrees and linear units, or two linear units.
    #[error("are in different units ({0} and {1}); reproject them to one CRS")]
    Units(MapUnits, MapUnits),
    /// Two EPSG codes.
    #[error("are in different coordinate systems ({0} and {1}); reproject them to one CRS")]
    Crs(String, String),
    /// Two cell sizes.
    #[error("have different cell sizes ({0:?} and {1:?}); resample them to one")]
    Spacing([f64; 2], [f64; 2]),
    /// Origins a part of a cell apart.
    #[error("are not on one grid: their samples are offset by part of a cell")]
    Offset,
}

/// Loads the tiles at `paths` and joins them into one field, as `options` say.
pub fn load_mosaic(
    paths: &[PathBuf],
    options: &LoadOptions,
    progress: Progress,
) -> Result<Heightfield, LoadError> {
    let names = paths
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let refuse = |reason: MosaicError| LoadError::Mosaic {
        names: names.clone(),
        reason: Box::new(reason),
    };
    let tile_options = LoadOptions {
        z_scale: 1.0,
        ..*options
    };
    let mut tiles = Vec::with_capacity(paths.len());
    for path in paths {
        let field = load_with(path, &tile_options, progress)?;
        let georef = match field.georeferencing() {
            Georeferencing::Map(georef) => *georef,
            Georeferencing::Ignored(why) => {
                return Err(refuse(MosaicError::Ignored {
                    path: path.clone(),
                    why: why.clone(),
                }))
            }
            Georeferencing::None => {
                return Err(refuse(MosaicError::NotGeoreferenced(path.clone())))
            }
        };
        tiles.push((path.as_path(), field, georef));
    }
    let (first_path, _, first) = tiles.first().ok_or_else(|| refuse(MosaicError::NoTiles))?;
    for (path, _, georef) in &tiles[1..] {
        one_grid(first, georef).map_err(|why| {
            refuse(MosaicError::OffGrid {
                first: first_path.to_path_buf(),
                other: path.to_path_buf(),
                why,
            })
        })?;
    }
    let raster = join(&tiles, *first).map_err(refuse)?;
    raster
        .into_field(&LoadOptions {
            // The tiles' own no-data samples are NaN by now.
            nodata: NoDataValue::Off,
            ..*options
        })
        .map_err(|source| LoadError::Field {
            name: names,
            source,
        })
}

/// Whether tile `b` lies on `a`'s grid, or why not.
pub(in crate::heightfield) fn one_grid(a: &Georef, b: &Georef) -> Result<(), GridMismatch> {
    let same_units = match (a.units, b.units) {
        (MapUnits::Degrees, MapUnits::Degrees) => true,
        (MapUnits::Linear { metres: x }, MapUnits::Linear { metres: y }) => x == y,
        _ => false,
    };
    let same_crs = match (a.crs, b.crs) {
        (Some(x), Some(y)) => x == y,
        _ => true,
    };
    if !same_units {
        return Err(GridMismatch::Units(a.units, b.units));
    }
    if !same_crs {
        return Err(GridMismatch::Crs(a.crs_label(), b.crs_label()));
    }
    for axis in 0..2 {
        let (x, y) = (a.spacing[axis], b.spacing[axis]);
        if (x - y).abs() > TOLERANCE * x.max(y) {
            return Err(GridMismatch::Spacing(a.spacing, b.spacing));
        }
        let offset = (b.origin[axis] - a.origin[axis]) / x;
        if (offset - offset.round()).abs() > TOLERANCE {
            return Err(GridMismatch::Offset);
        }
    }
    Ok(())
}

/// The farthest a tile's origin may lie from the first tile's, in cells: a joined grid
/// spanning more could never stay within the sample limit.
const MOST_CELLS_APART: f64 = (1u64 << 32) as f64;

/// A joined grid larger than this many samples is refused when the tiles cover less than
/// [`LEAST_COVERED`] of it: its gaps would be stored as no data, sample by sample.
const SPARSE_FLOOR: u64 = 1 << 24;

/// The least fraction of a large joined grid its tiles must cover, as 1 / this.
const LEAST_COVERED: u64 = 4;

/// Where each tile's lower-left sample lies on the first tile's grid, in whole cells, or why
/// a tile lies too far off for any joined grid to hold.
pub(in crate::heightfield) fn tile_offsets<'a>(
    tiles: impl Iterator<Item = (&'a Path, &'a Georef)>,
    first: &Georef,
) -> Result<Vec<[i64; 2]>, MosaicError> {
    tiles
        .map(|(path, georef)| {
            let mut cells = [0; 2];
            for (axis, cell) in cells.iter_mut().enumerate() {
                let offset =
                    ((georef.origin[axis] - first.origin[axis]) / first.spacing[axis]).round();
                if !offset.is_finite() || offset.abs() > MOST_CELLS_APART {
                    return Err(MosaicError::TooFar {
                        path: path.to_path_buf(),
                        offset,
                        axis: ["x", "y"][axis],
                    });
                }
                // In range: |offset| is at most 2^32.
                *cell = offset as i64;
            }
            Ok(cells)
        })
        .collect()
}

/// The tiles' values in one raster over their joint extent, NaN where no tile has data.
fn join(tiles: &[(&Path, Heightfield, Georef)], first: Georef) -> Result<Raster, MosaicError> {
    let offsets = tile_offsets(tiles.iter().map(|(p, _, g)| (*p, g)), &first)?;
    let (mut lo, mut hi) = ([i64::MAX; 2], [i64::MIN; 2]);
    let mut covered = 0u64;
    for ((_, field, _), offset) in tiles.iter().zip(&offsets) {
        let size = [field.width() as i64, field.height() as i64];
        covered += (field.width() * field.height()) as u64;
        for axis in 0..2 {
            lo[axis] = lo[axis].min(offset[axis]);
            hi[axis] = hi[axis].max(offset[axis] + size[axis] - 1);
        }
    }
    let (width, height) = ((hi[0] - lo[0] + 1) as u64, (hi[1] - lo[1] + 1) as u64);
    let samples = width.saturating_mul(height);
    if samples > MAX_SAMPLES || samples.saturating_mul(8) > MAX_DECODED_BYTES {
        return Err(MosaicError::TooLarge { width, height });
    }
    if samples > SPARSE_FLOOR && samples > LEAST_COVERED.saturating_mul(covered) {
        return Err(MosaicError::Sparse {
            width,
            height,
            covered,
        });
    }
    let (width, height) = (width as usize, height as usize);
    let mut values = Vec::new();
    values
        .try_reserve_exact(width * height)
        .map_err(|_| MosaicError::NoMemory { width, height })?;
    values.resize(width * height, f64::NAN);
    for ((_, field, _), offset) in tiles.iter().zip(&offsets) {
        let (di, dj) = ((offset[0] - lo[0]) as usize, (offset[1] - lo[1]) as usize);
        for j in 0..field.height() {
            // Image order: row 0 is the northern edge.
            let row = height - 1 - (dj + j);
            for i in 0..field.width() {
                let at = &mut values[row * width + di + i];
                if at.is_nan() && !field.is_nodata(i, j) {
                    *at = value(field, i, j);
                }
            }
        }
    }
    let origin = [
        first.origin[0] + lo[0] as f64 * first.spacing[0],
        first.origin[1] + lo[1] as f64 * first.spacing[1],
    ];
    let georef = Georef::new(origin, first.spacing, first.units)?
        .with_crs(first.crs)
        .with_height_unit(first.height_unit);
    Ok(Raster {
        width,
        height,
        values: Values::F64(values),
        file_nodata: None,
        georef: Georeferencing::Map(georef),
    })
}

/// A tile's raster value at sample `(i, j)` (loaded at z scale 1): a height in its own units,
/// or an unsigned integer sample as it is (a DEM of whole metres).
pub(in crate::heightfield) fn value(field: &Heightfield, i: usize, j: usize) -> f64 {
    match field.quantisation() {
        Quantisation::Offset { .. } => field.z(i, j),
        Quantisation::Maxval(_) => f64::from(field.sample(i, j)),
    }
}
