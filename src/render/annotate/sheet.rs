//! What annotations are asked for and the picture they are drawn over.

use super::sight::Sight;
use super::vectors::VectorLayer;
use crate::arith::Arith;
use crate::heightfield::Terrain;
use crate::render::{Camera, Ramp};
use crate::traverse::Method;
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
}
