//! Annotations drawn into a finished picture at its output resolution, so text and marks are
//! crisp at any size: a scale bar, a north arrow, a height legend, a title and attribution,
//! and vector layers' places and lines, shown only where the terrain lets the eye see them.
//!
//! They are written as one SVG document of the whole image and rasterised by resvg with the
//! viewer's font; a window of the image (a poster's tile) rasterises its part of the same
//! document, so merged tiles show the whole picture's annotations.

#[cfg(feature = "annotate")]
mod fonts;
mod layout;
mod measure;
mod place_names;
#[cfg(feature = "annotate")]
mod raster;
mod sight;
mod svg;
mod vectors;

#[cfg(feature = "annotate")]
pub use fonts::svg_options;
pub use layout::{north_angle_deg, trimmed, ScaleBar};
pub use measure::TextWidth;
pub use place_names::PlacedName;
pub use sight::Sight;
pub use svg::{escaped, round_marks};
pub use vectors::{
    from_geojson, from_gpx, Coordinates, Place, VectorFile, VectorLayer, VectorSection,
};

use crate::heightfield::Terrain;
#[cfg(feature = "annotate")]
use crate::render::Window;
use crate::render::{Camera, Ramp};
use crate::traverse::{Arith, Method};
use serde::Deserialize;

/// A scene file's `[annotations]` section: which marks are drawn into the picture.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AnnotationsSection {
    /// A scale bar at the depth of the view's target.
    #[serde(default)]
    pub scale_bar: bool,
    /// An arrow to grid north.
    #[serde(default)]
    pub north_arrow: bool,
    /// The height legend: the ramp and its heights.
    #[serde(default)]
    pub legend: bool,
    /// A title in the top-left corner.
    #[serde(default)]
    pub title: Option<String>,
    /// The data's attribution line, bottom right.
    #[serde(default)]
    pub attribution: Option<String>,
}

/// What is drawn over a picture.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Annotations {
    /// A scale bar at the depth of the view's target.
    pub scale_bar: bool,
    /// An arrow to grid north.
    pub north_arrow: bool,
    /// The height legend.
    pub legend: bool,
    /// A title.
    pub title: Option<String>,
    /// The data's attribution.
    pub attribution: Option<String>,
    /// Places and lines from vector files.
    pub vectors: Vec<VectorLayer>,
}

/// The picture annotations are drawn over: its terrain and camera, and how its rays run.
#[derive(Clone, Copy, Debug)]
pub struct Sheet<'a> {
    /// The terrain shown.
    pub terrain: &'a Terrain,
    /// The camera, in world coordinates, of the whole image.
    pub camera: Camera,
    /// The colour ramp the terrain is shown in.
    pub ramp: Ramp,
    /// The method sight lines are walked with.
    pub method: Method,
    /// The arithmetic sight lines are traced in.
    pub arith: Arith,
}

impl Sheet<'_> {
    /// Sight lines from the camera's eye.
    pub fn sight(&self) -> Sight<'_> {
        let grid = self.camera.in_grid(self.terrain.world_from_grid());
        Sight {
            terrain: self.terrain,
            eye: grid.eye(),
            method: self.method,
            arith: self.arith,
        }
    }

    /// Where grid point `point` shows in the whole image, if it lies in front of the eye and
    /// within the image.
    pub fn on_image(&self, point: [f64; 3]) -> Option<[f64; 2]> {
        let [x, y] = self.camera.project(self.terrain.world_point(point))?;
        let (w, h) = self.camera.whole_size();
        (x >= 0.0 && y >= 0.0 && x <= f64::from(w) && y <= f64::from(h)).then_some([x, y])
    }
}

impl Annotations {
    /// The annotations a scene's sections ask for, with its vector layers.
    pub fn new(section: Option<&AnnotationsSection>, vectors: Vec<VectorLayer>) -> Annotations {
        let section = section.cloned().unwrap_or_default();
        Annotations {
            scale_bar: section.scale_bar,
            north_arrow: section.north_arrow,
            legend: section.legend,
            title: section.title.filter(|t| !t.trim().is_empty()),
            attribution: section.attribution.filter(|t| !t.trim().is_empty()),
            vectors,
        }
    }

    /// Whether nothing is to be drawn.
    pub fn is_empty(&self) -> bool {
        *self == Annotations::default()
    }

    /// The places' names drawn over `sheet`'s whole image, where they are.
    pub fn place_names(&self, sheet: &Sheet<'_>) -> Vec<PlacedName> {
        svg::place_names(self, sheet)
    }

    /// The SVG document of these annotations over `sheet`'s whole image.
    pub fn svg(&self, sheet: &Sheet<'_>) -> String {
        svg::compose(self, sheet)
    }

    /// Draws these annotations into `pixels` (0x00RRGGBB, row by row), which hold `window` of
    /// `sheet`'s whole image.
    #[cfg(feature = "annotate")]
    pub fn draw(
        &self,
        sheet: &Sheet<'_>,
        pixels: &mut [u32],
        window: Window,
    ) -> Result<(), String> {
        if self.is_empty() {
            return Ok(());
        }
        raster::draw_over(&self.svg(sheet), pixels, window)
    }
}
