//! Scene files (README, 'Formats'): TOML, paths relative to the file, unknown keys refused by
//! name.

use super::animation::{Animation, AnimationSection};
use super::annotate::{Annotations, AnnotationsSection, VectorLayer, VectorSection};
use super::camera::{Camera, CameraError};
use super::contours::Contours;
use super::effects::Effects;
use crate::arith::Arith;
use crate::heightfield::{Drape, DrapeError, Heightfield, LoadError};
use crate::regular_file::{self, OpenError};
use crate::traverse::Method;
use serde::Deserialize;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use thiserror::Error;

mod heightmap;
mod lighting;
mod sun;
mod surface;
mod triple;
mod view;
mod water;

use crate::compact::Compact;
use heightmap::HeightmapError;
pub use heightmap::{HeightmapSection, NoDataKey};
pub use lighting::{BaseStyle, Lighting};
pub use surface::{Normals, OverlaySection, ShadingSection};
pub use view::{CameraSection, Orbit, DEFAULT_SIZE};
pub use water::{
    bytes_from_hex, bytes_from_linear, level_in_map_units, level_z, linear_from_bytes,
    WaterSection, DEFAULT_WATER_COLOUR,
};

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

/// The longest scene file read: a scene is a few hundred bytes of TOML.
const MOST_SCENE_BYTES: u64 = 1 << 20;

/// A scene as written in its file.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// `[heightmap]`: the map and how to read it.
    pub heightmap: HeightmapSection,
    /// `[camera]`: where the view is from and its image size; left out, the whole map is
    /// framed as the viewer first shows it.
    #[serde(default)]
    pub camera: Option<CameraSection>,
    /// `[sun]`: the light.
    #[serde(default)]
    pub sun: SunSection,
    /// `[effects]`: shadows and fog.
    #[serde(default)]
    pub effects: EffectsSection,
    /// `[shading]`: normals and the colour ramp.
    #[serde(default)]
    pub shading: ShadingSection,
    /// `[render]`: traversal method and arithmetic.
    #[serde(default)]
    pub render: RenderSection,
    /// `[overlay]`: an image colouring the surface instead of the ramp.
    #[serde(default)]
    pub overlay: Option<OverlaySection>,
    /// `[water]`: a water surface at a level.
    #[serde(default)]
    pub water: Option<WaterSection>,
    /// `[animation]`: a camera path, rendered as frames.
    #[serde(default)]
    pub animation: Option<AnimationSection>,
    /// `[annotations]`: marks drawn into the picture.
    #[serde(default)]
    pub annotations: Option<AnnotationsSection>,
    /// `[[vector]]`: places and lines drawn over the picture.
    #[serde(default)]
    pub vector: Vec<VectorSection>,
    /// An image size replacing the scene's (`render --size`); not a key of the file.
    #[serde(skip)]
    pub size: Option<(u32, u32)>,
}

/// The scene files of the built-in terrains (`assets/NAME.toml`), embedded like their maps, so
/// that the benchmarks' default scenes work from any directory.
const BUILTIN_SCENES: [(&str, &str); 2] = [
    ("valley513", include_str!("../../assets/valley513.toml")),
    ("small49", include_str!("../../assets/small49.toml")),
];

impl SceneFile {
    /// Reads and parses a scene file, without checking or loading what it names.
    pub fn read(path: &Path) -> Result<SceneFile, SceneError> {
        let io = |source| SceneError::Io {
            path: path.to_owned(),
            source,
        };
        let (file, _) = regular_file::open(path).map_err(|error| match error {
            OpenError::NotAFile(what) => SceneError::NotAFile {
                path: path.to_owned(),
                what,
            },
            OpenError::Io(source) => io(source),
        })?;
        // One byte more than the limit tells a file that is too long.
        let mut bytes = Vec::new();
        file.take(MOST_SCENE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(io)?;
        let too_long = bytes.len() as u64 > MOST_SCENE_BYTES;
        // Text whose last character the limit cut in two is still text.
        let cut = |e: &std::string::FromUtf8Error| e.utf8_error().error_len().is_none();
        match String::from_utf8(bytes) {
            text if too_long && text.as_ref().err().is_none_or(cut) => Err(SceneError::TooLong {
                path: path.to_owned(),
            }),
            Ok(text) => SceneFile::parse(&text, path),
            Err(_) => Err(SceneError::NotText {
                path: path.to_owned(),
            }),
        }
    }

    /// The built-in terrains' scene files, by name, each on its embedded map.
    pub fn builtins() -> Result<Vec<(&'static str, SceneFile)>, SceneError> {
        let scene = |(name, text): (&'static str, &str)| {
            let mut file = SceneFile::parse(text, Path::new(name))?;
            file.heightmap.path = format!("builtin:{name}");
            Ok((name, file))
        };
        BUILTIN_SCENES.into_iter().map(scene).collect()
    }

    /// Parses a scene file's text; `path` names it in errors.
    fn parse(text: &str, path: &Path) -> Result<SceneFile, SceneError> {
        toml::from_str(text).map_err(|e| SceneError::Parse {
            path: path.to_owned(),
            // Kept on its lines, so that the `^` marker stands under the bad key.
            message: e.to_string().trim_end().to_owned(),
        })
    }
}

/// A scene file's `[sun]` section.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SunSection {
    /// Towards the sun; normalised on load.
    #[serde(default = "default_sun", deserialize_with = "triple::three")]
    pub direction: [f64; 3],
    /// Instead of `direction`: the sun's compass bearing (0 north, 90 east) and its
    /// elevation above the horizon, in degrees.
    #[serde(default)]
    pub azimuth_deg: Option<f64>,
    /// With `azimuth_deg`: degrees above the horizon.
    #[serde(default)]
    pub elevation_deg: Option<f64>,
    /// Instead of `direction`: where the sun stands at this time over the map's centre, or
    /// over `lat` and `lon`: an instant (`2026-12-21T08:00:00Z`) or a local time
    /// (`2026-06-21T09:30`) in `zone`.
    #[serde(default)]
    pub time: Option<String>,
    /// The IANA time zone of a local `time` (default: the zone at the place).
    #[serde(default)]
    pub zone: Option<String>,
    /// Latitude in degrees for `time`.
    #[serde(default)]
    pub lat: Option<f64>,
    /// Longitude in degrees for `time`.
    #[serde(default)]
    pub lon: Option<f64>,
    /// Direct light at full facing (default 1).
    #[serde(default = "one")]
    pub intensity: f64,
    /// Light everywhere, facing the sun or not (default 0.25).
    #[serde(default = "default_ambient")]
    pub ambient: f64,
    /// The sun's angular diameter in degrees (default 0: hard shadows).
    #[serde(default)]
    pub angle_deg: f64,
    /// Directions towards the sun's disc per point, for soft shadows (default 16).
    #[serde(default)]
    pub rays: Option<u32>,
}

/// A scene file's `[effects]` section.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct EffectsSection {
    /// Cast shadow rays towards the sun (default off).
    #[serde(default)]
    pub shadows: bool,
    /// Fog density per unit of distance; 0 is off.
    #[serde(default)]
    pub fog: f64,
    /// Light from the sky dome instead of the constant ambient term (default off).
    #[serde(default)]
    pub sky_light: bool,
    /// Sky-light rays per pixel, shared out among its samples (default 16).
    #[serde(default)]
    pub sky_rays: Option<u32>,
    /// How far sky-light rays look for terrain, in world units (default 64).
    #[serde(default)]
    pub sky_distance: Option<f64>,
}

/// A scene file's `[render]` section, as written (parsed when the scene is validated).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RenderSection {
    /// Traversal method, as `--method` takes it (default `auto`).
    #[serde(default = "default_method")]
    pub method: String,
    /// Arithmetic, as `--arith` takes it (default `f64`).
    #[serde(default = "default_arith")]
    pub arith: String,
    /// Camera rays per pixel (default 1).
    #[serde(default = "one_sample")]
    pub samples: u32,
    /// Stop a pixel's samples once they agree (default off).
    #[serde(default)]
    pub adaptive: bool,
}

impl Default for SunSection {
    fn default() -> Self {
        SunSection {
            direction: default_sun(),
            azimuth_deg: None,
            elevation_deg: None,
            time: None,
            zone: None,
            lat: None,
            lon: None,
            intensity: 1.0,
            ambient: default_ambient(),
            angle_deg: 0.0,
            rays: None,
        }
    }
}

impl Default for RenderSection {
    fn default() -> Self {
        RenderSection {
            method: default_method(),
            arith: default_arith(),
            samples: 1,
            adaptive: false,
        }
    }
}

fn default_sun() -> [f64; 3] {
    [0.4, 0.3, 0.8]
}
fn one() -> f64 {
    1.0
}
fn one_sample() -> u32 {
    1
}
fn default_ambient() -> f64 {
    0.25
}
fn default_method() -> String {
    "auto".into()
}
fn default_arith() -> String {
    "f64".into()
}

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The loaded height map.
    pub field: Heightfield,
    /// The validated camera.
    pub camera: Camera,
    /// Sun, shading and effects.
    pub lighting: Lighting,
    /// The traversal method.
    pub method: Method,
    /// The arithmetic.
    pub arith: Arith,
    /// The camera path, if the scene has one.
    pub animation: Option<Animation>,
    /// What is drawn over the picture.
    pub annotations: Annotations,
    /// Contour lines on the terrain (not yet seen by a camera, see [`Contours::seen_by`]).
    pub contours: Option<Contours>,
}

impl Scene {
    /// Reads and validates a scene file, loading its height map.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        Scene::from_file(&SceneFile::read(path)?, Scene::base(path), path)
    }

    /// The folder a scene file's relative paths start from.
    pub fn base(path: &Path) -> &Path {
        path.parent().unwrap_or(Path::new("."))
    }

    /// Validates a parsed scene; `base` resolves relative paths, `path` names the file in errors.
    pub fn from_file(file: &SceneFile, base: &Path, path: &Path) -> Result<Scene, SceneError> {
        let invalid = |message: String| SceneError::Invalid {
            path: path.to_owned(),
            message,
        };
        let field = file.heightmap.load(base).map_err(|error| match error {
            HeightmapError::Invalid(message) => invalid(message),
            HeightmapError::Load(source) => SceneError::Heightmap {
                path: path.to_owned(),
                source,
            },
        })?;
        let drape_path = file
            .overlay
            .as_ref()
            .and_then(|o| Some((o.path.as_ref()?, o)));
        let field = match drape_path {
            Some((drape_path, overlay)) => {
                let drape = Drape::load(&base.join(drape_path), &field, overlay.opacity).map_err(
                    |source| SceneError::Overlay {
                        path: path.to_owned(),
                        source,
                    },
                )?;
                field.with_drape(Some(Arc::new(drape)))
            }
            None => field,
        };
        let (field, camera) = view::camera(file.camera.as_ref(), file.size, field, path)?;
        let sun = &file.sun;
        let length = sun.direction.iter().map(|c| c * c).sum::<f64>().sqrt();
        if !(length.is_finite() && length > 0.0) {
            return Err(invalid(
                "[sun] direction must be a finite non-zero vector".into(),
            ));
        }
        for (key, value) in [
            ("[sun] intensity", sun.intensity),
            ("[sun] ambient", sun.ambient),
            ("[effects] fog", file.effects.fog),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(format!(
                    "{key} must be a finite number >= 0, got {}",
                    Compact(value)
                )));
            }
        }
        let method = file
            .render
            .method
            .parse()
            .map_err(|e| invalid(format!("[render] method: {e}")))?;
        let arith = file
            .render
            .arith
            .parse()
            .map_err(|e| invalid(format!("[render] arith: {e}")))?;
        let mut lighting = Lighting::from_sections(sun, &file.effects, &file.shading);
        lighting.base = BaseStyle::from_section(&file.shading).map_err(invalid)?;
        let mut lighting = sun::place_sun(sun, &field, lighting).map_err(invalid)?;
        lighting.effects =
            Effects::from_sections(sun, &file.effects, &file.render).map_err(invalid)?;
        lighting.effects.water = file
            .water
            .as_ref()
            .map(|water| water.validate(&field))
            .transpose()
            .map_err(invalid)?;
        let lighting = lighting.after_dark();
        let animation = file
            .animation
            .as_ref()
            .map(|section| {
                let camera = file.camera.as_ref();
                let fov = camera.map_or(45.0, |c| c.fov_y_deg);
                let up = camera.map_or([0.0, 0.0, 1.0], |c| c.up);
                let map = Some((base, &field));
                Animation::new(section, camera.and_then(|c| c.orbit), fov, up, map)
            })
            .transpose()
            .map_err(invalid)?;
        let contours = file
            .overlay
            .as_ref()
            .map(|overlay| overlay.contours(&field))
            .transpose()
            .map_err(invalid)?
            .flatten();
        let vectors = file
            .vector
            .iter()
            .map(|section| VectorLayer::load(section, base, &field))
            .collect::<Result<_, _>>()
            .map_err(invalid)?;
        let annotations = Annotations::new(file.annotations.as_ref(), vectors);
        Ok(Scene {
            field,
            camera,
            lighting,
            method,
            arith,
            animation,
            annotations,
            contours,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::BUILTINS;

    /// Every built-in terrain has its scene, and the embedded scene is the one in `assets/`
    /// with the map embedded: the same samples, camera and lighting.
    #[test]
    fn builtin_scenes_are_the_asset_files_on_the_embedded_maps() {
        let builtins = SceneFile::builtins().unwrap();
        let names: Vec<&str> = builtins.iter().map(|(name, _)| *name).collect();
        assert_eq!(names, BUILTINS.map(|b| b.name));
        for (name, file) in builtins {
            let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("assets/{name}.toml"));
            let on_disk = Scene::load(&path).unwrap();
            let embedded = Scene::from_file(&file, Path::new(""), Path::new(name)).unwrap();
            assert_eq!(embedded.field.samples(), on_disk.field.samples(), "{name}");
            assert_eq!(embedded.field.step(), on_disk.field.step(), "{name}");
            assert_eq!(embedded.camera.size(), on_disk.camera.size(), "{name}");
            assert_eq!(
                embedded.camera.ray(7, 9),
                on_disk.camera.ray(7, 9),
                "{name}"
            );
            assert_eq!(embedded.lighting, on_disk.lighting, "{name}");
        }
    }
}
