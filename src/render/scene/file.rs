//! A scene as written in its file: read, parsed, and made for a map on its own.

use super::error::{SceneError, MOST_SCENE_BYTES};
use super::heightmap::HeightmapSection;
use super::sections::{EffectsSection, RenderSection, SunSection};
use super::surface::{OverlaySection, ShadingSection};
use super::view::CameraSection;
use super::water::WaterSection;
use crate::regular_file::{self, OpenError};
use crate::render::animation::AnimationSection;
use crate::render::annotate::{AnnotationsSection, VectorSection};
use serde::Deserialize;
use std::io::Read;
use std::path::Path;

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
    ("valley513", include_str!("../../../assets/valley513.toml")),
    ("small49", include_str!("../../../assets/small49.toml")),
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

impl SceneFile {
    /// Whether `path` names a scene file (`.toml`) rather than a height map.
    pub fn is_scene_path(path: &Path) -> bool {
        path.extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
    }

    /// The scene of a height map on its own: what the viewer first shows of it, the whole map
    /// framed, at its default relief, with shadows on and every other section's defaults. Its
    /// path is relative to the map's folder ([`Scene::base`](super::Scene::base)).
    pub fn for_map(path: &Path) -> SceneFile {
        let name = path.file_name().unwrap_or(path.as_os_str());
        SceneFile {
            heightmap: HeightmapSection {
                path: name.to_string_lossy().into_owned(),
                paths: Vec::new(),
                z_scale: None,
                exaggeration: None,
                rgb: None,
                nodata: None,
                height_unit: None,
            },
            camera: None,
            sun: Default::default(),
            effects: EffectsSection {
                shadows: true,
                ..Default::default()
            },
            shading: Default::default(),
            render: Default::default(),
            overlay: None,
            water: None,
            animation: None,
            annotations: None,
            vector: Vec::new(),
            size: None,
        }
    }
}
