//! What to load and where it comes from: sources, requests, a scene's setup, how images are
//! decoded, and a load's progress as the window shows it.

use super::flythrough::Flythrough;
use crate::heightfield::{
    ColourEncoding, DrapeError, HeightUnit, HeightfieldError, LoadError, NoDataValue, BUILTINS,
};
use crate::render::{Lighting, SceneError, SceneFile};
use crate::viewer::orbit::Orbit;
use crate::{Arith, Method, Terrain};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use thiserror::Error;

/// Why a terrain could not be loaded.
#[derive(Debug, Error)]
pub enum LoadFailure {
    /// A built-in name not known.
    #[error("no built-in terrain '{0}'")]
    NoBuiltin(String),
    /// The height map could not be read.
    #[error(transparent)]
    Map(#[from] LoadError),
    /// The scene could not be read or used.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The overlay could not be laid over the map.
    #[error(transparent)]
    Overlay(#[from] DrapeError),
    /// The z scale makes no height field.
    #[error(transparent)]
    Rescale(#[from] HeightfieldError),
    /// Loading panicked.
    #[error("loading {label} failed on an internal error ({message}); other files still load")]
    Internal {
        /// What was loaded.
        label: String,
        /// What the panic said.
        message: String,
    },
}

/// The decoding choices for height map images.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Decoding {
    /// How RGB images become heights.
    pub colour: ColourEncoding,
    /// Which raster value means no data.
    pub nodata: NoDataValue,
    /// A georeferenced map's height unit, instead of the one its file implies.
    pub height_unit: Option<HeightUnit>,
}

/// Where a terrain comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// A built-in terrain, by name.
    Builtin(&'static str),
    /// A height map image, or a `.toml` scene file.
    File(PathBuf),
    /// Georeferenced tiles joined into one map.
    Tiles(Vec<PathBuf>),
}

impl Source {
    /// The name shown to the user.
    pub fn label(&self) -> String {
        match self {
            Source::Builtin(name) => format!("{name} (built-in)"),
            Source::File(path) => file_name(path),
            Source::Tiles(paths) => match paths.split_first() {
                Some((first, rest)) => format!("{} (+{} tiles)", file_name(first), rest.len()),
                None => "no tiles".into(),
            },
        }
    }

    /// The default terrain.
    pub fn default_builtin() -> Source {
        Source::Builtin(BUILTINS[0].name)
    }

    /// The source of the files given on the command line or dropped together: one file, or
    /// tiles to join; `None` for none.
    pub fn of_paths(mut paths: Vec<PathBuf>) -> Option<Source> {
        match paths.len() {
            0 => None,
            1 => paths.pop().map(Source::File),
            _ => Some(Source::Tiles(paths)),
        }
    }

    /// Whether it is a scene file rather than a height map.
    pub fn is_scene(&self) -> bool {
        matches!(self, Source::File(p) if SceneFile::is_scene_path(p))
    }
}

/// A path's file name, for labels.
fn file_name(path: &std::path::Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into(),
    )
}

/// What to load.
#[derive(Clone, Debug)]
pub struct LoadRequest {
    pub source: Source,
    /// Height of the largest sample; None picks the source's own (a built-in's or a scene's)
    /// or, for a plain image, a quarter of its larger side.
    pub z_scale: Option<f64>,
    /// Frame the camera on the new terrain (and take a scene's camera and lighting); false
    /// keeps the view, for a changed z scale.
    pub reframe: bool,
    /// Rescale these samples instead of reading the source again (a z scale change).
    pub from_memory: Option<Arc<Terrain>>,
    /// How a height map image is decoded (a scene file says so itself).
    pub decoding: Decoding,
    /// An image to lay over the map, or to take off it; `None` keeps what the source gives
    /// (a scene's `[overlay]`, the drape of samples rescaled in memory, none on a new map).
    pub overlay: Option<OverlayChange>,
}

/// A change to the image draped over the map.
#[derive(Clone, Debug, PartialEq)]
pub enum OverlayChange {
    /// Drape this image, replacing any other.
    Lay {
        /// The image file.
        path: PathBuf,
        /// How much of the ramp's colour it replaces, 0 to 1.
        opacity: f64,
    },
    /// Show the ramp again.
    Remove,
}

impl LoadRequest {
    /// What the load is of, for its progress and its error message.
    pub fn label(&self) -> String {
        match &self.overlay {
            Some(OverlayChange::Lay { path, .. }) => format!("the overlay {}", path.display()),
            _ => self.source.label(),
        }
    }
}

/// A scene file's camera, lighting and traversal.
#[derive(Clone, Debug)]
pub struct SceneSetup {
    pub orbit: Orbit,
    pub lighting: Lighting,
    pub method: Method,
    pub arith: Arith,
    /// What the scene draws over its pictures: exports draw it too.
    pub annotations: crate::render::annotate::Annotations,
    /// Its `[overlay]` contour interval in the map's height unit, and index line count.
    pub contours: Option<(f64, u32)>,
    /// The local date and time that placed the sun, if the scene gave one.
    pub clock: Option<SceneClock>,
    /// The scene's `[animation]` keys, to play and edit.
    pub flythrough: Option<Flythrough>,
}

/// A scene's `[sun]` local time, its zone (none: the place's own) and place (none: the
/// map's centre).
#[derive(Clone, Copy, Debug)]
pub struct SceneClock {
    pub local: chrono::NaiveDateTime,
    pub zone: Option<chrono_tz::Tz>,
    pub place: Option<(f64, f64)>,
}

/// A terrain ready to render.
pub struct Loaded {
    pub request: LoadRequest,
    pub terrain: Arc<Terrain>,
    pub scene: Option<SceneSetup>,
    /// Reading and decoding, before the acceleration data was built.
    pub decode_time: Duration,
}

/// The steps of a load, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    Reading,
    Building,
}

impl Stage {
    pub fn label(self) -> &'static str {
        match self {
            Stage::Reading => "reading and decoding",
            Stage::Building => "building acceleration data",
        }
    }
    /// Rough share of the work done when this stage starts (for a progress bar).
    pub fn fraction(self) -> f32 {
        match self {
            Stage::Reading => 0.1,
            Stage::Building => 0.6,
        }
    }
}

/// Sent from a loading thread to the window.
pub enum LoadEvent {
    Stage {
        generation: u64,
        stage: Stage,
    },
    Done {
        generation: u64,
        result: Box<Result<Loaded, LoadFailure>>,
    },
}

/// A load in progress, as the window shows it.
#[derive(Clone, Debug)]
pub struct Progress {
    pub label: String,
    pub stage: Stage,
    pub started: Instant,
}
