//! The raster a product is made on, and where it lies on the map.
//!
//! A DEM of `W x H` samples is, to GDAL and QGIS, `W x H` pixels whose areas are centred on the
//! samples (PixelIsArea): its top-left corner lies half a sample spacing west and north of
//! sample `(0, H-1)`. One pixel per cell of that grid is the DEM's own raster, so a product at
//! the default cell size has the DEM's size and geotransform and lays on it pixel for pixel,
//! each value computed at its pixel's centre, the sample. A chosen cell size keeps that top-left
//! corner and covers the same extent with pixels of the size asked for (the last row and
//! column reach past it where the extent is not a whole number of them).

use crate::heightfield::{Georef, Heightfield};
use thiserror::Error;

/// Pixels a product may have (a quarter of the largest DEM heightray reads, in 4-byte values).
pub const MAX_PRODUCT_PIXELS: u64 = 1 << 30;

/// Why a product's raster cannot be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum GridError {
    /// A cell size that is not a positive number.
    #[error("--cell must be a positive size, got {0}")]
    Cell(f64),
    /// More pixels than a product may have.
    #[error(
        "the product would have {width} x {height} pixels, more than the {MAX_PRODUCT_PIXELS} \
         allowed: choose a larger --cell"
    )]
    TooLarge {
        /// Pixels along x.
        width: f64,
        /// Pixels along y.
        height: f64,
    },
}

/// A north-up raster over a height field: its size, and its pixels' places in grid coordinates
/// (sample `(i, j)` at `x = i`, `y = j`, `y` north).
#[derive(Clone, Debug, PartialEq)]
pub struct OrthoGrid {
    /// Pixels along x.
    pub width: u32,
    /// Pixels along y (rows, the first the northernmost).
    pub height: u32,
    /// Grid coordinates of the top-left corner of pixel `(0, 0)`.
    corner: [f64; 2],
    /// Grid units a pixel spans along x and y.
    step: [f64; 2],
    /// The map's georeferencing, if any.
    georef: Option<Georef>,
}

/// A GDAL geotransform: `X = t[0] + column * t[1] + row * t[2]`, `Y = t[3] + column * t[4] +
/// row * t[5]`, for pixel corners.
pub type GeoTransform = [f64; 6];

impl OrthoGrid {
    /// The raster of `field` with pixels `cell` map units wide (grid units on a map without
    /// georeferencing), the field's own spacing by default; or why there is none.
    pub fn over(field: &Heightfield, cell: Option<f64>) -> Result<OrthoGrid, GridError> {
        let georef = field.georef().copied();
        let spacing = georef.map_or([1.0, 1.0], |g| g.spacing);
        let (w, h) = (field.width() as f64, field.height() as f64);
        let step = match cell {
            None => [1.0, 1.0],
            Some(size) if size.is_finite() && size > 0.0 => [size / spacing[0], size / spacing[1]],
            Some(size) => return Err(GridError::Cell(size)),
        };
        // (A whole number of pixels within rounding is not rounded up to one more.)
        let count = |extent: f64, step: f64| (extent / step - 1e-9).ceil().max(1.0);
        let (width, height) = (count(w, step[0]), count(h, step[1]));
        if width * height > MAX_PRODUCT_PIXELS as f64 {
            return Err(GridError::TooLarge { width, height });
        }
        Ok(OrthoGrid {
            width: width as u32,
            height: height as u32,
            corner: [-0.5, h - 0.5],
            step,
            georef,
        })
    }

    /// Grid coordinates of the point `(u, v)` of pixel `(column, row)`, `(0.5, 0.5)` its
    /// centre.
    pub fn point(&self, column: u32, row: u32, (u, v): (f64, f64)) -> [f64; 2] {
        [
            self.corner[0] + (f64::from(column) + u) * self.step[0],
            self.corner[1] - (f64::from(row) + v) * self.step[1],
        ]
    }

    /// Where grid point `[x, y]` lies in the raster, in pixels from its top-left corner (pixel
    /// `(column, row)` spans `column..column + 1` and `row..row + 1`): the inverse of
    /// [`OrthoGrid::point`].
    pub fn image_point(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [
            (x - self.corner[0]) / self.step[0],
            (self.corner[1] - y) / self.step[1],
        ]
    }

    /// Grid units a pixel spans along x and y.
    pub fn step(&self) -> [f64; 2] {
        self.step
    }

    /// The map's georeferencing, if any.
    pub fn georef(&self) -> Option<&Georef> {
        self.georef.as_ref()
    }

    /// The geotransform of the raster on the map, if the map is georeferenced.
    pub fn geotransform(&self) -> Option<GeoTransform> {
        let georef = self.georef.as_ref()?;
        let [x0, y0] = georef.map_point(self.corner[0], self.corner[1]);
        let [sx, sy] = georef.spacing;
        Some([x0, self.step[0] * sx, 0.0, y0, 0.0, -self.step[1] * sy])
    }

    /// Pixels in the raster.
    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::{Georeferencing, MapUnits};

    fn field(width: usize, height: usize) -> Heightfield {
        let georef = Georef::new(
            [1000.0, 2000.0],
            [10.0, 20.0],
            MapUnits::Linear { metres: 1.0 },
        );
        Heightfield::from_fn(width, height, 1, 1.0, |_, _| 1)
            .unwrap()
            .with_georeferencing(Georeferencing::Map(georef.unwrap()))
    }

    #[test]
    fn one_pixel_per_sample_centres_pixels_on_samples() {
        let grid = OrthoGrid::over(&field(5, 4), None).unwrap();
        assert_eq!((grid.width, grid.height), (5, 4));
        // Row 0 is the northernmost samples, row y = 3.
        assert_eq!(grid.point(0, 0, (0.5, 0.5)), [0.0, 3.0]);
        assert_eq!(grid.point(4, 3, (0.5, 0.5)), [4.0, 0.0]);
        // Sample (0, 3) lies at (1000, 2060); the corner half a spacing west and north.
        assert_eq!(
            grid.geotransform(),
            Some([995.0, 10.0, 0.0, 2070.0, 0.0, -20.0])
        );
    }

    #[test]
    fn a_chosen_cell_covers_the_same_extent_from_the_same_corner() {
        // 5 x 4 pixels of 10 x 20 m: 50 x 80 m; in 25 m pixels, 2 x 4 (80 / 25 = 3.2).
        let grid = OrthoGrid::over(&field(5, 4), Some(25.0)).unwrap();
        assert_eq!((grid.width, grid.height), (2, 4));
        assert_eq!(
            grid.geotransform(),
            Some([995.0, 25.0, 0.0, 2070.0, 0.0, -25.0])
        );
        assert_eq!(grid.point(0, 0, (0.5, 0.5)), [-0.5 + 1.25, 3.5 - 0.625]);
        assert!(OrthoGrid::over(&field(5, 4), Some(-1.0)).is_err());
        assert!(OrthoGrid::over(&field(5, 4), Some(f64::NAN)).is_err());
    }
}
