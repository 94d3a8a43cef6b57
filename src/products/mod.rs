//! Map products: rasters made straight down over a height field, one value per pixel of a
//! north-up grid that lies on the map's own ([`OrthoGrid`](crate::products::OrthoGrid)), written as GeoTIFFs a GIS lays on
//! the DEM ([`tiff_out`](crate::products::tiff_out)).
//!
//! - **shaded**: shaded relief with cast shadows, a colour picture ([`shaded`](crate::products::shaded));
//! - **sky-view**: the sky-view factor, 0 to 1 ([`sky_view`](crate::products::sky_view));
//! - **sunlight-hours**: hours of direct sun over a day ([`sunlight`](crate::products::sunlight)).
//!
//! Contour lines with labelled index lines are drawn over the pictures ([`contour_map`](crate::products::contour_map)).

pub mod contour_labels;
pub mod contour_map;
pub mod grid;
pub mod horizon;
pub mod isolines;
#[cfg(feature = "annotate")]
mod overlay;
pub mod shaded;
pub mod sky_view;
pub mod sunlight;
pub mod tiff_out;

pub use contour_labels::Label;
pub use contour_map::{MapContours, MapStyle};
pub use grid::{GeoTransform, GridError, OrthoGrid};
pub use horizon::Horizon;
pub use shaded::Rgba16;
pub use sky_view::{SkyView, SkyViewError};
pub use sunlight::{SunPath, SunPathError, Sunlight};

use crate::render::Shader;
use crate::Arith;
use rayon::prelude::*;

/// What a product's pixels hold.
#[derive(Clone, Debug, PartialEq)]
pub enum Raster {
    /// Colour and coverage, row by row from the north.
    Colour(Vec<Rgba16>),
    /// A quantity, row by row from the north; NaN where there is no surface.
    Values(Vec<f32>),
}

/// How a product's pixel is made.
pub enum Maker<'a> {
    /// Shaded relief by this shader, rays traced in this arithmetic, for a picture of this
    /// depth.
    Shaded(Box<Shader<'a>>, Arith, tiff_out::Depth),
    /// The sky-view factor.
    SkyView(SkyView, Horizon<'a>),
    /// Hours of direct sun.
    Sunlight(Sunlight<'a>),
}

impl Maker<'_> {
    /// Every pixel of `grid`, rows in parallel on rayon's threads; `progress` is told of each
    /// row done.
    pub fn raster(&self, grid: &OrthoGrid, progress: &(dyn Fn() + Sync)) -> Raster {
        let centre = |column, row| grid.point(column, row, (0.5, 0.5));
        let value = |v: Option<f64>| v.map_or(f32::NAN, |v| v as f32);
        match self {
            Maker::Shaded(shader, arith, depth) => {
                Raster::Colour(fill(grid, progress, |column, row| {
                    shaded::pixel(shader, (*arith, *depth), grid, column, row)
                }))
            }
            Maker::SkyView(measure, horizon) => {
                Raster::Values(fill(grid, progress, |column, row| {
                    value(measure.at(horizon, centre(column, row)))
                }))
            }
            Maker::Sunlight(sunlight) => Raster::Values(fill(grid, progress, |column, row| {
                value(sunlight.hours_at(centre(column, row)))
            })),
        }
    }
}

/// The pixels `make(column, row)` of `grid` row by row from the north, rows in parallel.
fn fill<T: Copy + Default + Send>(
    grid: &OrthoGrid,
    progress: &(dyn Fn() + Sync),
    make: impl Fn(u32, u32) -> T + Sync,
) -> Vec<T> {
    let mut pixels = vec![T::default(); grid.pixels()];
    pixels
        .par_chunks_mut(grid.width as usize)
        .enumerate()
        .for_each(|(row, line)| {
            for (column, pixel) in line.iter_mut().enumerate() {
                *pixel = make(column as u32, row as u32);
            }
            progress();
        });
    pixels
}
