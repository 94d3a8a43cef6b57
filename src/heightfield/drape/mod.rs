//! A drape: an image (an orthophoto, a map) that colours the surface instead of the height
//! ramp. It is stretched over the field's extent, or placed by its own georeferencing where
//! both it and the field have one, and sampled bilinearly between pixel centres in linear
//! light. Outside the image the surface keeps the ramp's colour.

mod error;
mod jpeg;
mod png;
mod read;
mod reproject;
mod tiff_rgba;

pub use error::DrapeError;

use read::OwnPlace;

use super::georef::{Georef, MapUnits};
use super::Heightfield;
use std::path::{Path, PathBuf};
use std::sync::LazyLock;

/// An image laid over a height field.
#[derive(Clone, Debug, PartialEq)]
pub struct Drape {
    /// The file it was read from.
    path: PathBuf,
    width: usize,
    height: usize,
    /// RGBA bytes by rows, the top (northern) row first.
    pixels: Vec<u8>,
    /// How much of the ramp's colour the image replaces where it is opaque, 0 to 1.
    opacity: f64,
    /// Image coordinates of grid points.
    placement: Placement,
    /// Whether the image was placed by its own georeferencing (else stretched).
    georeferenced: bool,
}

/// Grid point `(x, y)` lands at image position `(column, row) = (u0 + x * du, v0 + y * dv)`,
/// in pixel-centre units (pixel `(c, r)`'s centre is at `(c, r)`, its edges half a pixel
/// away).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Column of grid point `x = 0`.
    pub u0: f64,
    /// Columns per grid unit along x.
    pub du: f64,
    /// Row of grid point `y = 0`.
    pub v0: f64,
    /// Rows per grid unit along y (negative: rows go south).
    pub dv: f64,
}

impl Placement {
    /// Grid coordinates are image coordinates.
    pub const IDENTITY: Placement = Placement {
        u0: 0.0,
        du: 1.0,
        v0: 0.0,
        dv: 1.0,
    };

    /// An image of `width` x `height` pixels stretched over a field of `field` samples: the
    /// image's outer edges on the first and last samples.
    pub fn stretched((width, height): (usize, usize), field: (usize, usize)) -> Placement {
        let across = |pixels: usize, samples: usize| pixels as f64 / (samples - 1) as f64;
        Placement {
            u0: -0.5,
            du: across(width, field.0),
            v0: height as f64 - 0.5,
            dv: -across(height, field.1),
        }
    }

    /// An image of `height` rows whose pixel centres lie at `image`'s map coordinates, over a
    /// field whose samples lie at `field`'s (the same coordinate system).
    pub fn by_map(image: &Georef, height: usize, field: &Georef) -> Placement {
        let (sx, sy) = (image.spacing[0], image.spacing[1]);
        Placement {
            u0: (field.origin[0] - image.origin[0]) / sx,
            du: field.spacing[0] / sx,
            // `image.origin` is the bottom row's centre, row `height - 1`.
            v0: (height - 1) as f64 - (field.origin[1] - image.origin[1]) / sy,
            dv: -field.spacing[1] / sy,
        }
    }

    /// The image position of grid point `(x, y)`.
    pub fn image_point(&self, x: f64, y: f64) -> (f64, f64) {
        (self.u0 + x * self.du, self.v0 + y * self.dv)
    }
}

/// The linear light of each display byte (gamma 2.2, as the renderer writes bytes).
static LINEAR: LazyLock<[f64; 256]> =
    LazyLock::new(|| std::array::from_fn(|b| (b as f64 / 255.0).powf(2.2)));

impl Drape {
    /// Reads an image file (PNG, JPEG or TIFF) and lays it over `field` with `opacity`:
    /// placed by its georeferencing (a GeoTIFF's tags, or a world file beside it) where the
    /// field has one too, else stretched over the field.
    pub fn load(path: &Path, field: &Heightfield, opacity: f64) -> Result<Drape, DrapeError> {
        if !(opacity.is_finite() && (0.0..=1.0).contains(&opacity)) {
            return Err(DrapeError::Opacity(opacity));
        }
        let image = read::read(path)?;
        let field_size = (field.width(), field.height());
        let own = match (image.place.as_ref(), field.georef()) {
            (Some(OwnPlace::Map(own)), Some(_)) => Some(*own),
            (Some(OwnPlace::WorldFile { origin, spacing }), Some(map)) => {
                Some(world_file_place(*origin, *spacing, map))
            }
            _ => None,
        };
        if let (Some(own), Some(map)) = (&own, field.georef()) {
            if !reproject::same_crs(own, map) {
                let (width, height, pixels) = reproject::onto_map(image, own, map, field_size)
                    .map_err(|why| DrapeError::Crs {
                        path: path.to_owned(),
                        own: own.crs_label(),
                        map: map.crs_label(),
                        why: Box::new(why),
                    })?;
                let drape = Drape {
                    path: path.to_owned(),
                    placement: Placement::stretched((width, height), field_size),
                    georeferenced: true,
                    ..Drape::from_pixels(width, height, pixels, opacity, Placement::IDENTITY)
                };
                return drape.covering(field_size);
            }
        }
        let size = (image.width, image.height);
        let placement = match (&own, field.georef()) {
            (Some(own), Some(map)) => Placement::by_map(own, image.height, map),
            _ => Placement::stretched(size, field_size),
        };
        let georeferenced = own.is_some();
        let drape = Drape {
            path: path.to_owned(),
            width: image.width,
            height: image.height,
            pixels: image.pixels,
            opacity,
            placement,
            georeferenced,
        };
        drape.covering(field_size)
    }

    /// The drape, if it covers any of a field of `field_size` samples.
    fn covering(self, field_size: (usize, usize)) -> Result<Drape, DrapeError> {
        if self.overlaps(field_size) {
            Ok(self)
        } else {
            Err(DrapeError::Outside { path: self.path })
        }
    }

    /// An image of `width` x `height` pixels, RGBA bytes by rows from the top, placed by
    /// `placement`.
    pub fn from_pixels(
        width: usize,
        height: usize,
        pixels: Vec<u8>,
        opacity: f64,
        placement: Placement,
    ) -> Drape {
        assert_eq!(pixels.len(), 4 * width * height, "four bytes per pixel");
        Drape {
            path: PathBuf::new(),
            width,
            height,
            pixels,
            opacity,
            placement,
            georeferenced: false,
        }
    }

    /// The file the image was read from.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The image's size in pixels.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// How much of the ramp's colour the image replaces where it is opaque.
    pub fn opacity(&self) -> f64 {
        self.opacity
    }

    /// Whether the image was placed by its own georeferencing rather than stretched.
    pub fn georeferenced(&self) -> bool {
        self.georeferenced
    }

    /// The image's colour at grid point `(x, y)` in linear light, and how much of the ramp's
    /// colour it replaces there (its alpha times the opacity); `None` outside the image.
    pub fn colour(&self, x: f64, y: f64) -> Option<([f64; 3], f64)> {
        let (u, v) = self.placement.image_point(x, y);
        let (w, h) = (self.width as f64, self.height as f64);
        if !(u >= -0.5 && u <= w - 0.5 && v >= -0.5 && v <= h - 0.5) {
            return None;
        }
        // Between pixel centres; within half a pixel of an edge, the edge pixel's colour.
        let (u, v) = (u.clamp(0.0, w - 1.0), v.clamp(0.0, h - 1.0));
        let (c0, r0) = (u.floor() as usize, v.floor() as usize);
        let (c1, r1) = ((c0 + 1).min(self.width - 1), (r0 + 1).min(self.height - 1));
        let (fu, fv) = (u - c0 as f64, v - r0 as f64);
        let weights = [
            ((c0, r0), (1.0 - fu) * (1.0 - fv)),
            ((c1, r0), fu * (1.0 - fv)),
            ((c0, r1), (1.0 - fu) * fv),
            ((c1, r1), fu * fv),
        ];
        let (mut rgb, mut alpha) = ([0.0; 3], 0.0);
        for ((c, r), weight) in weights {
            let at = 4 * (r * self.width + c);
            let [red, green, blue, a] = [0, 1, 2, 3].map(|k| self.pixels[at + k]);
            // Colours weighted by their alpha, so a transparent pixel lends no colour.
            let a = weight * f64::from(a) / 255.0;
            for (sum, byte) in rgb.iter_mut().zip([red, green, blue]) {
                *sum += a * LINEAR[usize::from(byte)];
            }
            alpha += a;
        }
        if alpha <= 0.0 {
            return Some(([0.0; 3], 0.0));
        }
        Some((rgb.map(|c| c / alpha), alpha * self.opacity))
    }

    /// Whether any of the field's cells, `field` samples, lies under the image.
    fn overlaps(&self, (width, height): (usize, usize)) -> bool {
        let (u_a, v_a) = self.placement.image_point(0.0, 0.0);
        let (u_b, v_b) = self
            .placement
            .image_point((width - 1) as f64, (height - 1) as f64);
        let (w, h) = (self.width as f64, self.height as f64);
        u_a.min(u_b) < w - 0.5
            && u_a.max(u_b) > -0.5
            && v_a.min(v_b) < h - 0.5
            && v_a.max(v_b) > -0.5
    }
}

/// Where a world file places an image over `map`: in the map's coordinate system, unless its
/// numbers can only be longitude and latitude on a map in metres or feet (a world file does
/// not say its CRS).
fn world_file_place(origin: [f64; 2], spacing: [f64; 2], map: &Georef) -> Georef {
    let looks_like_degrees =
        spacing.iter().all(|s| *s < 0.01) && origin[0].abs() <= 180.0 && origin[1].abs() <= 90.0;
    let units = match map.units {
        MapUnits::Linear { .. } if looks_like_degrees => MapUnits::Degrees,
        units => units,
    };
    let crs = if units == map.units { map.crs } else { None };
    Georef {
        origin,
        spacing,
        units,
        crs,
        height_unit: map.height_unit,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2x2 image: red, green over blue, white (top row first), all opaque.
    fn four() -> Vec<u8> {
        [
            [255, 0, 0, 255],
            [0, 255, 0, 255],
            [0, 0, 255, 255],
            [255; 4],
        ]
        .concat()
    }

    #[test]
    fn a_stretched_image_puts_its_corner_pixels_on_the_corner_samples() {
        // 2x2 pixels over 5x5 samples: grid x in [0, 4] spans columns -0.5..1.5.
        let placement = Placement::stretched((2, 2), (5, 5));
        assert_eq!(placement.image_point(0.0, 0.0), (-0.5, 1.5));
        assert_eq!(placement.image_point(4.0, 4.0), (1.5, -0.5));
        // Grid x = 1 is column -0.5 + 1 * 0.5 = 0: the centre of the left pixels.
        assert_eq!(placement.image_point(1.0, 3.0), (0.0, 0.0));
        let drape = Drape::from_pixels(2, 2, four(), 1.0, placement);
        // South-west quarter: the bottom-left pixel, blue.
        let (rgb, alpha) = drape.colour(0.5, 0.5).unwrap();
        assert_eq!((rgb, alpha), ([0.0, 0.0, 1.0], 1.0));
        // The middle: a quarter of each, in linear light.
        let (rgb, _) = drape.colour(2.0, 2.0).unwrap();
        assert_eq!(rgb, [0.5, 0.5, 0.5]);
        assert_eq!(drape.colour(-0.1, 2.0), None);
    }

    #[test]
    fn a_georeferenced_image_lands_where_its_map_coordinates_say() {
        let metres = MapUnits::Linear { metres: 1.0 };
        // Field samples 10 m apart from (1000, 2000); image pixels 5 m apart, its bottom-left
        // centre at (1002.5, 2002.5), 4 rows high.
        let field = Georef::new([1000.0, 2000.0], [10.0, 10.0], metres).unwrap();
        let image = Georef::new([1002.5, 2002.5], [5.0, 5.0], metres).unwrap();
        let placement = Placement::by_map(&image, 4, &field);
        // Sample (0, 0) at (1000, 2000) is half a pixel west and south of that centre:
        // column -0.5, row 3.5.
        assert_eq!(placement.image_point(0.0, 0.0), (-0.5, 3.5));
        // Sample (1, 1) at (1010, 2010): 1.5 pixels east and north of it.
        assert_eq!(placement.image_point(1.0, 1.0), (1.5, 1.5));
    }

    #[test]
    fn opacity_and_alpha_scale_how_much_of_the_ramp_is_replaced() {
        let mut pixels = four();
        pixels[11] = 0; // blue, transparent
        let placement = Placement::stretched((2, 2), (5, 5));
        let drape = Drape::from_pixels(2, 2, pixels, 0.5, placement);
        assert_eq!(drape.colour(0.5, 0.5), Some(([0.0; 3], 0.0)));
        // Red is opaque: half the ramp is replaced at opacity 0.5.
        assert_eq!(drape.colour(0.5, 3.5), Some(([1.0, 0.0, 0.0], 0.5)));
    }
}
