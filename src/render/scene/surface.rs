//! How a scene's surface looks: `[shading]` (normals and the colour ramp) and `[overlay]` (an
//! image draped over the map).

use super::level_z;
use crate::compact::Compact;
use crate::heightfield::Heightfield;
use crate::render::contours::Contours;
use crate::render::ramp::Ramp;
use serde::Deserialize;

/// A scene file's `[overlay]` section: an image (PNG, JPEG or TIFF) draped over the map, and
/// contour lines drawn on it.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OverlaySection {
    /// The image, relative to the scene file (none: the ramp's colours).
    #[serde(default)]
    pub path: Option<String>,
    /// How much of the ramp's colour the image replaces, 0 to 1 (default 1).
    #[serde(default = "super::sections::one")]
    pub opacity: f64,
    /// Contour lines every this much height, in the map's height unit (metres on most DEMs).
    #[serde(default)]
    pub contours: Option<f64>,
    /// Every this many contour lines is a wider index line (default 5; 0 for none).
    #[serde(default = "default_index")]
    pub index_every: u32,
}

fn default_index() -> u32 {
    5
}

impl OverlaySection {
    /// The contour lines `contours` asks for on `field`, the interval in its height unit.
    pub fn contours(&self, field: &Heightfield) -> Result<Option<Contours>, ContoursError> {
        let Some(interval) = self.contours else {
            return Ok(None);
        };
        Contours::new(level_z(field, interval), self.index_every)
            .map(Some)
            .ok_or(ContoursError(interval))
    }
}

/// A contour interval that is not a finite height above 0.
#[derive(Clone, Debug, thiserror::Error, PartialEq)]
#[error(
    "[overlay] contours must be a finite height interval > 0, got {}",
    Compact(*.0)
)]
pub struct ContoursError(pub f64);

/// A scene file's `[shading]` section.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ShadingSection {
    /// Flat or smooth normals (default flat).
    #[serde(default)]
    pub normals: Normals,
    /// Colour by height: `terrain` (the default), `hypsometric`, `gray`, `viridis`, `magma` or
    /// `turbo`; the land ramps show a sea below height 0 (see [`Ramp`]).
    #[serde(default)]
    pub ramp: Ramp,
    /// A solid base under the map: side walls from its edge down to a floor (default off;
    /// a map with holes always shows the floor through them).
    #[serde(default)]
    pub base: bool,
    /// How far the base's floor lies below the lowest sample, in height units (default 5%
    /// of the relief, at least 1).
    #[serde(default)]
    pub base_depth: Option<f64>,
}

/// Surface normals: per triangle, or interpolated from vertex normals.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Normals {
    /// Each triangle's own normal.
    #[default]
    Flat,
    /// Vertex normals (central differences) interpolated across the triangle.
    Smooth,
}
