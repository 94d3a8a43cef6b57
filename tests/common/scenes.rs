//! Scene files written by the tests: a small valid scene to vary, and loading a scene's text
//! the way `heightray render` loads a file.

use heightray::render::Scene;

/// A valid scene on the built-in small49 map, 16x16 pixels.
pub const SMALL_SCENE: &str = r#"
[heightmap]
path = "builtin:small49"
z_scale = 12.0
[camera]
eye = [-10.0, -10.0, 30.0]
target = [24.0, 24.0, 0.0]
width = 16
height = 16
"#;

/// Writes `text` as a scene file named `name` and loads it; an error as its message.
pub fn load_scene_text(name: &str, text: &str) -> Result<Scene, String> {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let path = dir.path().join(name);
    std::fs::write(&path, text).expect("the scene written");
    Scene::load(&path).map_err(|e| e.to_string())
}
