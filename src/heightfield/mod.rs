// (The summary line of this module's docs is its `pub mod` line in lib.rs; the empty line
// below starts the rest as a paragraph of its own.)
//!
//! A field's samples lie on a grid with their height mapping
//! ([`Heightfield`](crate::heightfield::Heightfield)); loading reads them from files; the
//! per-cell maxima, range maxima and min-max mipmap are what the traversals skip empty space
//! with ([`Terrain`](crate::heightfield::Terrain)).

mod builtin;
pub mod crs;
mod drape;
mod error;
mod fetch;
mod generate;
pub mod geokeys;
mod georef;
pub mod ground;
mod limits;
mod load;
mod maxima;
mod mipmap;
mod near_rise;
mod nodata;
pub mod place;
mod preview;
pub mod relief;
mod sky_bounds;
pub mod store;
mod strips;
mod summary;
mod terrain;
mod values;

pub use builtin::{Builtin, BUILTINS};
pub use drape::{Drape, DrapeError, Placement};
pub use error::HeightfieldError;
pub use fetch::Window;
pub use generate::{landscape, landscape_window};
pub use georef::{Georef, GeorefError, Georeferencing, HeightUnit, HeightUnitSource, MapUnits};
pub use limits::{MAX_DECODED_BYTES, MAX_SAMPLES};
pub use load::{
    load, load_bytes, load_bytes_with, load_mosaic, load_with, picture_kind, ColourEncoding,
    LoadError, LoadOptions, NoDataValue, OptionError, Progress,
};
pub use maxima::{CellMaxima, LineMaxima};
pub use mipmap::Mipmap;
pub use near_rise::{ConeRises, NearStart};
pub use nodata::NoDataMask;
pub use preview::Preview;
pub use sky_bounds::{SkyBounds, Unsettled, SKY_SECTORS};
pub use strips::{StripBounds, BLOCK as STRIP_BLOCK, STRIP};
pub(crate) use terrain::world_from_grid;
pub use terrain::{Lines, Terrain};
pub use values::Values;

use std::sync::Arc;

/// How a sample value becomes a height.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Quantisation {
    /// An unsigned integer raster (PNG, PGM, unsigned TIFF): `z = sample / maxval * z_scale`.
    Maxval(u16),
    /// A raster of heights in their own units (floats, signed integers, decoded terrain-RGB),
    /// stored as `value = lowest + sample * step`: `z = value * z_scale`.
    Offset {
        /// The raster value of sample 0.
        lowest: f64,
        /// The raster value of one sample step.
        step: f64,
    },
}

/// A grid of height samples, the input of the surface contract ([`crate::geometry`]).
///
/// Sample `(i, j)` sits at `x = i`, `y = j` (y grows north; image row `r` is `j = H-1-r`), and
/// its height is `base + sample * unit`, computed in `f64` (`base` is 0 for integer rasters,
/// so their heights are `sample * (z_scale / maxval)`). Those `f64` heights are the
/// exact inputs of exact mode. No-data samples hold the field's lowest valid sample, so
/// maxima over samples stay conservative without knowing about holes; cells with a no-data
/// corner are holes (`is_hole_cell`).
#[derive(Clone, Debug)]
pub struct Heightfield {
    width: usize,
    height: usize,
    /// Samples by `j * width + i` (y up).
    samples: Values<u16>,
    quantisation: Quantisation,
    z_scale: f64,
    /// Height of sample value 0.
    base: f64,
    /// Height of one sample step.
    unit: f64,
    /// No-data samples; `None` when there are none.
    nodata: Option<NoDataMask>,
    /// Where the samples lie on the Earth, if the file said.
    georef: Georeferencing,
    /// The ground size of the cells, for a georeferenced field.
    ground: Option<Arc<ground::GroundScale>>,
    /// An image colouring the surface, if one is laid over it.
    drape: Option<Arc<Drape>>,
    /// The acceleration data a tile store holds ready, if the field was read from one.
    prebuilt: Option<Arc<store::Prebuilt>>,
}

impl Heightfield {
    /// Builds a field from samples in image order (row 0 is the top, the northern edge).
    pub fn from_image_rows(
        width: usize,
        height: usize,
        rows: &[u16],
        maxval: u32,
        z_scale: f64,
    ) -> Result<Self, HeightfieldError> {
        check_size(width, height)?;
        if rows.len() != width * height {
            return Err(HeightfieldError::SampleCount {
                expected: width * height,
                got: rows.len(),
            });
        }
        Self::from_fn(width, height, maxval, z_scale, |i, j| {
            rows[(height - 1 - j) * width + i]
        })
    }

    /// Builds a field from a function of the sample position `(x, y)` (y up).
    pub fn from_fn(
        width: usize,
        height: usize,
        maxval: u32,
        z_scale: f64,
        sample: impl Fn(usize, usize) -> u16,
    ) -> Result<Self, HeightfieldError> {
        check_size(width, height)?;
        let maxval = u16::try_from(maxval)
            .ok()
            .filter(|&m| m > 0)
            .ok_or(HeightfieldError::BadMaxval(maxval))?;
        let samples = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| sample(x, y))
            .collect();
        Self::new(
            width,
            height,
            samples,
            Quantisation::Maxval(maxval),
            z_scale,
            None,
        )
    }

    /// Builds a field from samples by `j * width + i` (y up) and their no-data samples,
    /// whose values are replaced by the lowest valid sample.
    pub fn new(
        width: usize,
        height: usize,
        mut samples: Vec<u16>,
        quantisation: Quantisation,
        z_scale: f64,
        nodata: Option<NoDataMask>,
    ) -> Result<Self, HeightfieldError> {
        check_size(width, height)?;
        if samples.len() != width * height {
            return Err(HeightfieldError::SampleCount {
                expected: width * height,
                got: samples.len(),
            });
        }
        // (A bad z scale is refused before the samples are looked at.)
        mapping(quantisation, z_scale)?;
        if let Quantisation::Maxval(maxval) = quantisation {
            if let Some(k) = samples.iter().position(|&s| s > maxval) {
                return Err(HeightfieldError::SampleAboveMaxval {
                    sample: samples[k],
                    x: k % width,
                    y: k / width,
                    maxval,
                });
            }
        }
        let nodata = nodata.filter(|mask| mask.count() > 0);
        if let Some(mask) = &nodata {
            let lowest = (0..samples.len())
                .filter(|&k| !mask.contains(k))
                .map(|k| samples[k])
                .min()
                .ok_or(HeightfieldError::AllNoData)?;
            for (k, s) in samples.iter_mut().enumerate() {
                if mask.contains(k) {
                    *s = lowest;
                }
            }
        }
        let samples = Values::owned(samples);
        Heightfield::of_parts(
            (width, height),
            samples,
            quantisation,
            z_scale,
            nodata,
            None,
        )
    }

    /// A field of `samples` whose heights `quantisation` and `z_scale` give, not yet placed on
    /// the Earth, with the acceleration data held ready for it if any.
    fn of_parts(
        (width, height): (usize, usize),
        samples: Values<u16>,
        quantisation: Quantisation,
        z_scale: f64,
        nodata: Option<NoDataMask>,
        prebuilt: Option<Arc<store::Prebuilt>>,
    ) -> Result<Self, HeightfieldError> {
        let (base, unit) = mapping(quantisation, z_scale)?;
        Ok(Heightfield {
            width,
            height,
            samples,
            quantisation,
            z_scale,
            base,
            unit,
            nodata,
            georef: Georeferencing::None,
            ground: None,
            drape: None,
            prebuilt,
        })
    }

    /// The same field, placed on the Earth.
    pub fn with_georeferencing(self, georef: Georeferencing) -> Self {
        let ground = georef
            .georef()
            .map(|g| Arc::new(ground::GroundScale::of(g, self.width, self.height)));
        Heightfield {
            georef,
            ground,
            ..self
        }
    }

    /// The ground size of the cells and what it rests on, for a georeferenced field.
    pub fn ground(&self) -> Option<&ground::GroundScale> {
        self.ground.as_deref()
    }

    /// The same field with `drape` colouring its surface (or none).
    pub fn with_drape(self, drape: Option<Arc<Drape>>) -> Self {
        Heightfield { drape, ..self }
    }

    /// The image colouring the surface, if any.
    pub fn drape(&self) -> Option<&Drape> {
        self.drape.as_deref()
    }

    /// What the file said about where the samples lie.
    pub fn georeferencing(&self) -> &Georeferencing {
        &self.georef
    }

    /// Where the samples lie, if the file said so usably.
    pub fn georef(&self) -> Option<&Georef> {
        self.georef.georef()
    }

    /// The size of a cell in metres along x and y, for a georeferenced field.
    pub fn cell_metres(&self) -> Option<[f64; 2]> {
        self.ground().map(|g| g.cell_metres)
    }

    /// The same samples and holes with another z scale.
    pub fn with_z_scale(&self, z_scale: f64) -> Result<Self, HeightfieldError> {
        let (base, unit) = mapping(self.quantisation, z_scale)?;
        Ok(Heightfield {
            z_scale,
            base,
            unit,
            ..self.clone()
        })
    }

    /// The surface height at `(i + fx, j + fy)`, on the triangle of cell `(i, j)` that holds
    /// it (the cell split along the diagonal from `P00` to `P11`).
    pub fn surface_z(&self, (i, j): (usize, usize), (fx, fy): (f64, f64)) -> f64 {
        let [z00, z10, z01, z11] = [
            self.z(i, j),
            self.z(i + 1, j),
            self.z(i, j + 1),
            self.z(i + 1, j + 1),
        ];
        if fx >= fy {
            // Triangle P00, P10, P11.
            z00 + fx * (z10 - z00) + fy * (z11 - z10)
        } else {
            // Triangle P00, P11, P01.
            z00 + fy * (z01 - z00) + fx * (z11 - z01)
        }
    }

    /// Samples along x.
    pub fn width(&self) -> usize {
        self.width
    }
    /// Samples along y.
    pub fn height(&self) -> usize {
        self.height
    }
    /// The largest sample value: an integer raster's maxval, 65535 for a quantised one.
    pub fn maxval(&self) -> u16 {
        match self.quantisation {
            Quantisation::Maxval(maxval) => maxval,
            Quantisation::Offset { .. } => u16::MAX,
        }
    }
    /// How samples map to the raster's values.
    pub fn quantisation(&self) -> Quantisation {
        self.quantisation
    }
    /// The z scale: the height of `maxval` for integer rasters, the factor applied to the
    /// raster's own units otherwise.
    pub fn z_scale(&self) -> f64 {
        self.z_scale
    }
    /// The height between consecutive sample values (the quantisation step).
    pub fn step(&self) -> f64 {
        self.unit
    }
    /// The raw sample at `(i, j)` (the lowest valid sample where there is no data).
    pub fn sample(&self, i: usize, j: usize) -> u16 {
        self.samples[j * self.width + i]
    }
    /// The height a sample value maps to.
    pub fn height_of(&self, sample: u16) -> f64 {
        self.base + f64::from(sample) * self.unit
    }
    /// The height at sample `(i, j)`.
    pub fn z(&self, i: usize, j: usize) -> f64 {
        self.height_of(self.sample(i, j))
    }
    /// The samples of the `n x n` cells from cell `(i, j)` on (reaching past the grid's far
    /// edges where the cells do, see [`Window`]).
    #[inline]
    pub fn cells_window(&self, i: usize, j: usize, n: usize) -> Window {
        Window {
            first: j * self.width + i,
            len: n + 1,
            rows: n + 1,
            stride: self.width,
        }
    }
    /// All samples, by `j * width + i`.
    pub fn samples(&self) -> &[u16] {
        &self.samples
    }
    /// Whether the samples are mapped from a tile store rather than held in memory.
    pub fn is_mapped(&self) -> bool {
        self.samples.is_mapped()
    }
    /// The bytes of the tile store the samples are mapped from, if they are.
    pub fn store_bytes(&self) -> Option<u64> {
        self.samples.mapping_len()
    }
    /// How many samples hold no data.
    pub fn nodata_count(&self) -> usize {
        self.nodata.as_ref().map_or(0, NoDataMask::count)
    }
    /// Whether sample `(i, j)` holds no data.
    pub fn is_nodata(&self, i: usize, j: usize) -> bool {
        self.nodata
            .as_ref()
            .is_some_and(|mask| mask.contains(j * self.width + i))
    }
    /// Whether cell `(i, j)` is a hole (a corner holds no data): rays pass through it.
    #[inline]
    pub fn is_hole_cell(&self, i: usize, j: usize) -> bool {
        let Some(mask) = &self.nodata else {
            return false;
        };
        let k = j * self.width + i;
        let above = k + self.width;
        mask.contains(k) || mask.contains(k + 1) || mask.contains(above) || mask.contains(above + 1)
    }
    /// Bytes of samples and no-data mask.
    pub fn bytes(&self) -> usize {
        self.samples.len() * 2 + self.nodata.as_ref().map_or(0, NoDataMask::bytes)
    }
}

/// The largest height magnitude a field may have: far beyond any terrain in any unit, and
/// small enough that a camera framing it stays in range.
pub const MOST_HEIGHT: f64 = 1e12;

/// `(base, unit)`: the height of sample 0 and of one sample step.
fn mapping(quantisation: Quantisation, z_scale: f64) -> Result<(f64, f64), HeightfieldError> {
    if !(z_scale.is_finite() && z_scale >= 0.0) {
        return Err(HeightfieldError::BadZScale(z_scale));
    }
    let (base, unit) = scaled(quantisation, z_scale)?;
    let highest = base + f64::from(u16::MAX) * unit;
    if !(base.abs() <= MOST_HEIGHT && highest.abs() <= MOST_HEIGHT) {
        return Err(HeightfieldError::HeightsOutOfRange(z_scale));
    }
    Ok((base, unit))
}

/// `(base, unit)` before their range is checked.
fn scaled(quantisation: Quantisation, z_scale: f64) -> Result<(f64, f64), HeightfieldError> {
    match quantisation {
        Quantisation::Maxval(0) => Err(HeightfieldError::BadMaxval(0)),
        Quantisation::Maxval(maxval) => Ok((0.0, z_scale / f64::from(maxval))),
        Quantisation::Offset { lowest, step } => {
            let (base, unit) = (lowest * z_scale, step * z_scale);
            if lowest.is_finite() && step >= 0.0 && base.is_finite() && unit.is_finite() {
                Ok((base, unit))
            } else {
                Err(HeightfieldError::BadOffset { lowest, step })
            }
        }
    }
}

fn check_size(width: usize, height: usize) -> Result<(), HeightfieldError> {
    if width < 2 || height < 2 {
        return Err(HeightfieldError::TooSmall { width, height });
    }
    if width as u64 * height as u64 > MAX_SAMPLES {
        return Err(HeightfieldError::TooLarge { width, height });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cells_window_holds_every_corner_sample_of_its_cells() {
        for (w, h) in [(2, 2), (3, 2), (13, 6), (17, 33), (70, 37)] {
            let field = Heightfield::from_fn(w, h, 255, 1.0, |_, _| 0).unwrap();
            for (j, i) in (0..h - 1)
                .step_by(4)
                .flat_map(|j| (0..w - 1).step_by(4).map(move |i| (j, i)))
            {
                let window = field.cells_window(i, j, 4);
                let corners = (j..=(j + 4).min(h - 1))
                    .flat_map(|y| (i..=(i + 4).min(w - 1)).map(move |x| y * w + x));
                for at in corners {
                    assert!(window.contains(at), "{w}x{h} ({i},{j}): {at} in {window:?}");
                }
                assert_eq!(
                    window.len * window.rows,
                    25,
                    "{w}x{h} ({i},{j}): nothing more"
                );
            }
        }
    }

    #[test]
    fn image_rows_map_to_y_up() {
        // 2x3 image: top row 1 2, middle 3 4, bottom 5 6.
        let f = Heightfield::from_image_rows(2, 3, &[1, 2, 3, 4, 5, 6], 255, 255.0).unwrap();
        assert_eq!(f.sample(0, 0), 5);
        assert_eq!(f.sample(1, 2), 2);
        assert_eq!(f.z(1, 1), 4.0);
    }

    #[test]
    fn rejects_bad_sizes_and_scales() {
        assert_eq!(
            Heightfield::from_fn(1, 5, 255, 1.0, |_, _| 0).unwrap_err(),
            HeightfieldError::TooSmall {
                width: 1,
                height: 5
            }
        );
        assert!(matches!(
            Heightfield::from_fn(2, 2, 255, f64::NAN, |_, _| 0),
            Err(HeightfieldError::BadZScale(_))
        ));
        assert!(matches!(
            Heightfield::from_fn(2, 2, 10, 1.0, |_, _| 11),
            Err(HeightfieldError::SampleAboveMaxval { .. })
        ));
    }
}
