//! Why a scene could not be used.

use super::effects::EffectsError;
use super::lighting::BaseDepthError;
use super::sun::PlaceSunError;
use super::surface::ContoursError;
use super::water::WaterError;
use crate::heightfield::{DrapeError, LoadError};
use crate::render::animation::AnimationError;
use crate::render::annotate::VectorError;
use crate::render::camera::CameraError;
use std::path::PathBuf;
use thiserror::Error;

/// The longest scene file read: a scene is a few hundred bytes of TOML.
pub(super) const MOST_SCENE_BYTES: u64 = 1 << 20;

/// Why a scene could not be used.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene {path}: {source}")]
    Io {
        /// The scene file.
        path: PathBuf,
        /// Why it could not be read.
        source: std::io::Error,
    },
    /// Not text, as a height map given where a scene was asked for.
    #[error(
        "scene {path} is not a text file: a scene is written in TOML (see README, Formats); \
         to look at a height map, open it with `heightray view {path}`"
    )]
    NotText {
        /// The file given as a scene.
        path: PathBuf,
    },
    /// The path names a directory, a device, a FIFO or a socket.
    #[error("scene {path} is {what}, not a file; choose a scene file (.toml) instead")]
    NotAFile {
        /// The path given as a scene.
        path: PathBuf,
        /// What it names instead ("a directory", ...).
        what: &'static str,
    },
    /// Longer than any scene file: most likely not the file meant.
    #[error(
        "scene {path} is longer than {MOST_SCENE_BYTES} bytes, far more than a scene file's \
         few lines of TOML; check that it is the scene you meant"
    )]
    TooLong {
        /// The file given as a scene.
        path: PathBuf,
    },
    /// Not valid TOML, or keys and values the scene format does not have.
    #[error("scene {path}: {message}")]
    Parse {
        /// The scene file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// Well-formed, but a value is out of range or names nothing known.
    #[error("scene {path}: {message}")]
    Invalid {
        /// The scene file.
        path: PathBuf,
        /// Which key, and what is wrong with it.
        message: String,
    },
    /// A section's keys are out of range or name nothing known.
    #[error("scene {path}: {source}")]
    Section {
        /// The scene file.
        path: PathBuf,
        /// Which section, and what is wrong with it.
        source: SectionError,
    },
    /// The `[camera]` section describes no valid camera.
    #[error("scene {path}: [camera] {source}")]
    Camera {
        /// The scene file.
        path: PathBuf,
        /// Why the camera was refused.
        source: CameraError,
    },
    /// The `[overlay]` section's image could not be laid over the map.
    #[error("scene {path}: [overlay] {source}")]
    Overlay {
        /// The scene file.
        path: PathBuf,
        /// Why the image was refused.
        source: DrapeError,
    },
    /// The `[heightmap]` section's map could not be loaded.
    #[error("scene {path}: [heightmap] {source}")]
    Heightmap {
        /// The scene file.
        path: PathBuf,
        /// Why the map could not be loaded.
        source: LoadError,
    },
}

/// Which section of a scene is wrong, and how.
#[derive(Debug, Error)]
pub enum SectionError {
    /// `[shading]`.
    #[error(transparent)]
    Shading(#[from] BaseDepthError),
    /// `[sun]`'s direction, bearing or time.
    #[error(transparent)]
    Sun(#[from] PlaceSunError),
    /// `[sun]`, `[effects]` and `[render]` effect keys.
    #[error(transparent)]
    Effects(#[from] EffectsError),
    /// `[water]`.
    #[error(transparent)]
    Water(#[from] WaterError),
    /// `[animation]`.
    #[error(transparent)]
    Animation(#[from] AnimationError),
    /// `[overlay]` contours.
    #[error(transparent)]
    Contours(#[from] ContoursError),
    /// `[[vector]]`.
    #[error(transparent)]
    Vector(#[from] VectorError),
}
