//! An overlay in another coordinate system than the map's, resampled onto the map's grid:
//! each pixel of the new image, a grid point of the map, is taken to longitude and latitude
//! by the map's CRS, into the overlay's CRS by its own, and sampled there bilinearly in linear
//! light (the overlay's own [`Drape::colour`]).

use super::error::{ReprojectError, MOST_OVERLAY_PIXELS};
use super::read::Image;
use super::{Drape, Placement};
use crate::heightfield::crs::Crs;
use crate::heightfield::georef::{Georef, MapUnits};
use rayon::prelude::*;

/// The most new pixels per map cell along a side: finer than the overlay's pixels gains
/// nothing, and a map of few cells still gets a sharp picture.
const MOST_PIXELS_PER_CELL: usize = 8;

/// The CRS of a georeferencing: its EPSG code, or WGS 84 for longitude and latitude.
fn crs_of(georef: &Georef) -> Option<Crs> {
    match (georef.crs, georef.units) {
        (Some(crs), _) => Some(crs),
        (None, MapUnits::Degrees) => Crs::from_epsg(4326),
        (None, MapUnits::Linear { .. }) => None,
    }
}

/// Whether two georeferencings are in one coordinate system (as far as their codes and
/// units tell).
pub fn same_crs(a: &Georef, b: &Georef) -> bool {
    match (crs_of(a), crs_of(b)) {
        (Some(x), Some(y)) => x == y,
        _ => a.units == b.units,
    }
}

/// `image`, placed by `own` in its coordinate system, resampled onto the grid of a map of
/// `field` samples placed by `map`: the new image's size and RGBA bytes, stretched over the
/// map; or why it cannot be (a CRS without an EPSG code).
pub fn onto_map(
    image: Image,
    own: &Georef,
    map: &Georef,
    field: (usize, usize),
) -> Result<(usize, usize, Vec<u8>), ReprojectError> {
    let unknown = |g: &Georef| ReprojectError::NoCode(g.crs_label());
    let own_crs = crs_of(own).ok_or_else(|| unknown(own))?;
    let map_crs = crs_of(map).ok_or_else(|| unknown(map))?;
    let (to_lonlat, from_lonlat) = (map_crs.to_lonlat()?, own_crs.to_lonlat()?);
    let (w, h) = (image.width, image.height);
    let source = Drape::from_pixels(w, h, image.pixels, 1.0, Placement::IDENTITY);
    // The overlay's pixel position of map grid point (x, y).
    let pixel_of = |x: f64, y: f64| -> Option<(f64, f64)> {
        let lonlat = to_lonlat.lonlat(map.map_point(x, y))?;
        let [ox, oy] = from_lonlat.map_point(lonlat)?;
        let u = (ox - own.origin[0]) / own.spacing[0];
        let v = (h - 1) as f64 - (oy - own.origin[1]) / own.spacing[1];
        Some((u, v))
    };
    let per_cell = pixels_per_cell(&pixel_of, field);
    let (ow, oh) = ((field.0 - 1) * per_cell, (field.1 - 1) * per_cell);
    let placement = Placement::stretched((ow, oh), field);
    let mut pixels = vec![0u8; 4 * ow * oh];
    pixels
        .par_chunks_mut(4 * ow)
        .enumerate()
        .for_each(|(row, out)| {
            // Pixel centres as grid points, by the stretched placement's inverse.
            let y = (row as f64 - placement.v0) / placement.dv;
            for (column, rgba) in out.chunks_exact_mut(4).enumerate() {
                let x = (column as f64 - placement.u0) / placement.du;
                let colour = pixel_of(x, y).and_then(|(u, v)| source.colour(u, v));
                if let Some((rgb, alpha)) = colour {
                    // Back to display bytes by the gamma the overlay was read with.
                    let [r, g, b] =
                        rgb.map(|c| (c.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8);
                    rgba.copy_from_slice(&[r, g, b, (alpha * 255.0).round() as u8]);
                }
            }
        });
    Ok((ow, oh, pixels))
}

/// New pixels per map cell: about as many as the overlay has there, within the limits.
fn pixels_per_cell(
    pixel_of: &impl Fn(f64, f64) -> Option<(f64, f64)>,
    (width, height): (usize, usize),
) -> usize {
    let (cx, cy) = (0.5 * (width - 1) as f64, 0.5 * (height - 1) as f64);
    let across = match (pixel_of(cx, cy), pixel_of(cx + 1.0, cy)) {
        (Some((u0, v0)), Some((u1, v1))) => (u1 - u0).hypot(v1 - v0),
        _ => 1.0,
    };
    let cells = ((width - 1) * (height - 1)) as f64;
    let most = (MOST_OVERLAY_PIXELS as f64 / cells).sqrt().floor().max(1.0) as usize;
    (across.ceil() as usize).clamp(1, MOST_PIXELS_PER_CELL.min(most))
}
