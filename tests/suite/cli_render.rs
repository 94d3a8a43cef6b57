//! `heightray render` of a height map alone and of scenes that leave sections out: the map is
//! framed as the viewer frames it (the same image as a scene whose orbit is the framing's),
//! at 1280x720 or at `--size`, which also resizes a scene's own camera.

use heightray::render::framing::{self, DEFAULT_FOV_Y_DEG, DEFAULT_PITCH_DEG, DEFAULT_YAW_DEG};
use heightray::render::{Scene, SceneFile, DEFAULT_SIZE};
use heightray::Terrain;
use std::path::Path;
use std::process::Command;

/// A 9x9 ESRI ASCII grid of 30 m cells with a hill, in `dir`.
fn write_grid(dir: &Path) -> std::path::PathBuf {
    let mut text = String::from("ncols 9\nnrows 9\nxllcorner 0\nyllcorner 0\ncellsize 30\n");
    for r in 0..9i32 {
        let row: Vec<String> = (0..9i32)
            .map(|c| (200 - 8 * ((c - 4).pow(2) + (r - 3).pow(2))).to_string())
            .collect();
        text += &(row.join(" ") + "\n");
    }
    let path = dir.join("hill.asc");
    std::fs::write(&path, text).unwrap();
    path
}

/// `heightray render ARGS`, as the PNG it writes.
fn render(dir: &Path, args: &[&str]) -> image::RgbImage {
    let out = dir.join("out.png");
    let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .arg("render")
        .args(args)
        .arg("-o")
        .arg(&out)
        .output()
        .expect("run heightray render");
    assert!(
        output.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    image::open(&out).expect("the PNG").to_rgb8()
}

#[test]
fn a_map_alone_renders_framed_as_the_viewer_frames_it() {
    let dir = tempfile::tempdir().unwrap();
    let map = write_grid(dir.path());
    let alone = render(dir.path(), &[map.to_str().unwrap(), "--size", "96x54"]);
    assert_eq!(alone.dimensions(), (96, 54));
    // A scene naming only the map: the same image.
    let bare = dir.path().join("bare.toml");
    std::fs::write(&bare, "[heightmap]\npath = \"hill.asc\"\n").unwrap();
    assert_eq!(
        render(dir.path(), &[bare.to_str().unwrap(), "--size", "96x54"]),
        alone
    );
    // A scene whose orbit is the framing of the map at that aspect: the same image.
    let scene = Scene::load(&bare).unwrap();
    assert_eq!(scene.camera.size(), DEFAULT_SIZE);
    let terrain = Terrain::new(scene.field);
    let fit = framing::fit(
        &terrain,
        DEFAULT_YAW_DEG,
        DEFAULT_PITCH_DEG,
        DEFAULT_FOV_Y_DEG,
        96.0 / 54.0,
    );
    let orbit = dir.path().join("orbit.toml");
    std::fs::write(
        &orbit,
        format!(
            "[heightmap]\npath = \"hill.asc\"\n[camera]\norbit = {{ target = {:?}, \
             yaw_deg = {DEFAULT_YAW_DEG:?}, pitch_deg = {DEFAULT_PITCH_DEG:?}, distance = {:?} }}\n\
             fov_y_deg = {DEFAULT_FOV_Y_DEG:?}\nwidth = 96\nheight = 54\n",
            fit.target, fit.distance
        ),
    )
    .unwrap();
    assert_eq!(render(dir.path(), &[orbit.to_str().unwrap()]), alone);
    // Terrain fills the middle; the corners are sky.
    let (middle, corner) = (alone.get_pixel(48, 27), alone.get_pixel(0, 0));
    assert_ne!(middle, corner);
}

#[test]
fn size_replaces_a_scenes_own_image_size() {
    let dir = tempfile::tempdir().unwrap();
    write_grid(dir.path());
    let path = dir.path().join("scene.toml");
    std::fs::write(
        &path,
        "[heightmap]\npath = \"hill.asc\"\n[camera]\neye = [-5.0, -5.0, 12.0]\n\
         target = [4.0, 4.0, 3.0]\nwidth = 20\nheight = 10\n",
    )
    .unwrap();
    assert_eq!(
        render(dir.path(), &[path.to_str().unwrap()]).dimensions(),
        (20, 10)
    );
    let resized = render(dir.path(), &[path.to_str().unwrap(), "--size", "40x20"]);
    assert_eq!(resized.dimensions(), (40, 20));
    let mut file = SceneFile::read(&path).unwrap();
    file.size = Some((40, 20));
    let scene = Scene::from_file(&file, dir.path(), &path).unwrap();
    assert_eq!(scene.camera.size(), (40, 20));
}
