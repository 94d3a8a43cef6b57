//! Hostile input reaching the library and the commands: each is refused with a message that
//! names its real cause, within seconds and before any work is done for it.

use super::cli_paths::{assert_fails, heightray_within_ten_seconds};
use crate::common::scenes::{load_scene_text, SMALL_SCENE};
use heightray::heightfield::{load, Georeferencing};
use std::path::Path;
use tempfile::TempDir;

/// A small height map in its own folder, as a path string.
fn small_map() -> (TempDir, String) {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("map.png");
    image::GrayImage::from_fn(17, 17, |x, y| image::Luma([(x * 9 + y * 5) as u8]))
        .save(&path)
        .unwrap();
    (dir, path.to_str().unwrap().to_owned())
}

fn assert_mentions(message: &str, words: &[&str]) {
    for word in words {
        assert!(
            message.contains(word),
            "{message:?} does not mention {word:?}"
        );
    }
}

/// SMALL_SCENE with the line starting `key =` replaced by `line`.
fn with_line(key: &str, line: &str) -> String {
    SMALL_SCENE
        .lines()
        .map(|l| if l.starts_with(key) { line } else { l })
        .collect::<Vec<_>>()
        .join("\n")
}

fn scene_error(text: &str) -> String {
    match load_scene_text("hostile.toml", text) {
        Ok(_) => panic!("expected an error for {text}"),
        Err(message) => message,
    }
}

#[test]
fn arrays_of_three_take_exactly_three_numbers() {
    for (key, line) in [
        ("eye", "eye = [1.0, 2.0, 3.0, 4.0]"),
        ("eye", "eye = [1.0, 2.0]"),
        ("target", "target = \"24, 24, 0\""),
        ("target", "target = [24.0, \"24\", 0.0]"),
    ] {
        let message = scene_error(&with_line(key, line));
        assert_mentions(&message, &["hostile.toml", line]);
    }
    let up = SMALL_SCENE.replace("width = 16", "up = { x = 1.0 }\nwidth = 16");
    assert_mentions(&scene_error(&up), &["up = { x = 1.0 }"]);
    let zero = SMALL_SCENE.replace("width = 16", "up = [0.0, 0.0, 0.0]\nwidth = 16");
    assert_mentions(
        &scene_error(&zero),
        &["camera up vector is zero or parallel"],
    );
    let sun = format!("{SMALL_SCENE}[sun]\ndirection = [1.0, 1.0, 1.0, 1.0]\n");
    assert_mentions(&scene_error(&sun), &["direction", "three numbers"]);
}

#[test]
fn colours_are_six_hex_digits_and_nothing_else() {
    for colour in ["#+fffff", "#-00000", "# fffff", "#fffffff"] {
        let text = format!("{SMALL_SCENE}[water]\nlevel = 1.0\ncolour = \"{colour}\"\n");
        assert_mentions(&scene_error(&text), &["[water] colour", colour]);
    }
}

#[test]
fn cameras_and_heights_beyond_any_map_are_out_of_range() {
    let eye = with_line("eye", "eye = [1e308, 0.0, 30.0]");
    assert_mentions(&scene_error(&eye), &["camera eye is out of range", "1e308"]);
    let orbit = SMALL_SCENE
        .replace("eye = [-10.0, -10.0, 30.0]\n", "")
        .replace(
            "target = [24.0, 24.0, 0.0]",
            "orbit = { target = [24.0, 24.0, 0.0], yaw_deg = 0.0, pitch_deg = 30.0, \
             distance = 1e308 }",
        );
    assert_mentions(&scene_error(&orbit), &["orbit distance is out of range"]);
    let tall = "[heightmap]\npath = \"builtin:small49\"\nz_scale = 1e200\n";
    assert_mentions(&scene_error(tall), &["z scale 1e200 is out of range"]);
    let dir = TempDir::new().unwrap();
    let rows = "1 2 3 4\n".repeat(4);
    let grid = format!("ncols 4\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 30\n{rows}");
    std::fs::write(dir.path().join("grid.asc"), grid).unwrap();
    let scene = dir.path().join("tall.toml");
    std::fs::write(
        &scene,
        "[heightmap]\npath = \"grid.asc\"\nexaggeration = 1e300\n",
    )
    .unwrap();
    let message = heightray::render::Scene::load(&scene)
        .map(|_| ())
        .expect_err("refused")
        .to_string();
    assert_mentions(&message, &["out of range"]);
}

#[test]
fn a_geographic_map_beyond_the_poles_is_not_placed() {
    // A 17x17 DEM of 0.1 degree cells whose top-left corner is at latitude 200.
    let bytes = crate::common::files::dem_bytes(0.1, [10.0, 200.0], 2);
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("pole.tif");
    std::fs::write(&path, bytes).unwrap();
    let field = load(&path, 1.0).expect("the samples load");
    match field.georeferencing() {
        Georeferencing::Ignored(why) => assert_mentions(why, &["outside -90..90"]),
        other => panic!("placed: {other:?}"),
    }
}

/// Cells finer than a micrometre (down to subnormal sizes, whose true-scale z scale is not
/// even finite) or coarser than 10 000 km leave a map unplaced, saying why, instead of
/// failing on a z scale nobody gave.
#[test]
fn a_map_of_absurd_cell_sizes_is_not_placed() {
    let dir = TempDir::new().unwrap();
    for (scale, shown) in [(1e-310, "1.000e-310 x 1.000e-310 m"), (1e10, "1.000e10")] {
        let path = dir.path().join("cells.tif");
        let bytes = crate::common::files::dem_bytes(scale, [500_000.0, 4_000_000.0], 1);
        std::fs::write(&path, bytes).unwrap();
        let field = load(&path, 1.0).expect("the samples load");
        match field.georeferencing() {
            Georeferencing::Ignored(why) => assert_mentions(why, &[shown, "outside 1e-6 to 1e7 m"]),
            other => panic!("placed: {other:?}"),
        }
        let output = heightray_within_ten_seconds(&[
            "render",
            path.to_str().unwrap(),
            "-o",
            dir.path().join("out.png").to_str().unwrap(),
            "--size",
            "16x16",
        ]);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{stderr}");
        assert_mentions(&stderr, &["georeferencing not used (its cells are"]);
    }
}

#[test]
fn tiles_in_metres_and_degrees_name_their_units() {
    let dir = TempDir::new().unwrap();
    let rows = "1 2 3 4\n".repeat(4);
    let mut paths = Vec::new();
    for (name, cell) in [("metres.asc", 1.0), ("degrees.asc", 0.001)] {
        let path = dir.path().join(name);
        let header = format!("ncols 4\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize {cell}\n");
        std::fs::write(&path, header + &rows).unwrap();
        paths.push(path);
    }
    let message = heightray::heightfield::load_mosaic(
        &paths,
        &heightray::heightfield::LoadOptions::new(1.0),
        &|_| std::ops::ControlFlow::Continue(()),
    )
    .map(|_| ())
    .expect_err("refused")
    .to_string();
    assert_mentions(&message, &["are in different units (metres and degrees)"]);
}

#[test]
fn kernel_pseudo_files_are_not_image_files() {
    let message = load(Path::new("/proc/self/status"), 1.0)
        .map(|_| ())
        .expect_err("refused")
        .to_string();
    assert_mentions(
        &message,
        &["/proc/self/status", "kernel pseudo-file", "not a file"],
    );
}

#[test]
fn an_overlong_world_file_is_too_large() {
    let dir = TempDir::new().unwrap();
    let map = dir.path().join("map.png");
    image::GrayImage::from_fn(8, 8, |x, _| image::Luma([x as u8]))
        .save(&map)
        .unwrap();
    let overlay = dir.path().join("photo.png");
    image::RgbImage::from_pixel(4, 4, image::Rgb([1, 2, 3]))
        .save(&overlay)
        .unwrap();
    std::fs::write(dir.path().join("photo.pgw"), "1 0 0 -1 0 8\n".repeat(400)).unwrap();
    let field = load(&map, 1.0).unwrap();
    let message = heightray::heightfield::Drape::load(&overlay, &field, 1.0)
        .map(|_| ())
        .expect_err("refused")
        .to_string();
    assert_mentions(&message, &["photo.pgw is too large (5200 bytes"]);
}

#[test]
fn outputs_that_cannot_be_written_are_refused_before_rendering() {
    let (_map_dir, map) = small_map();
    let dir = TempDir::new().unwrap();
    let shown = dir.path().display().to_string();

    for (out, words) in [
        (
            "/dev/full".to_owned(),
            vec!["/dev/full is a character device"],
        ),
        (shown.clone(), vec!["is a directory"]),
        (format!("{shown}/no/such/out.png"), vec!["does not exist"]),
        (
            format!("{shown}/out.xyz"),
            vec!["extension names no image format"],
        ),
    ] {
        assert_fails(&["render", &map, "-o", &out], &words);
    }
    // A statistics file named by its folder: the suggestion is a JSON file, not an image.
    let stats_folder = [
        "render",
        &map,
        "-o",
        &format!("{shown}/out.png"),
        "--stats",
        &shown,
    ];
    let suggestion = format!("such as {}", dir.path().join("stats.json").display());
    assert_fails(&stats_folder, &["is a directory", &suggestion]);
    let generate = ["generate", "--size", "33", "-o", "/dev/full"];
    assert_fails(&generate, &["/dev/full is a character device"]);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn a_completed_output_replaces_the_old_file_and_leaves_nothing_else() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("map.png");
    std::fs::write(&out, "old").unwrap();
    let output =
        heightray_within_ten_seconds(&["generate", "--size", "33", "-o", out.to_str().unwrap()]);
    assert!(output.status.success(), "{output:?}");
    let field = load(&out, 1.0).expect("the new map");
    assert_eq!((field.width(), field.height()), (33, 33));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn knobs_beyond_their_range_are_refused() {
    let (dir, map) = small_map();
    let map = map.as_str();
    let out = dir.path().join("out.png");
    let out = out.to_str().unwrap();
    assert_fails(
        &["render", map, "-o", out, "--threads", "10000"],
        &["1 to 1024"],
    );
    assert_fails(
        &["render", map, "-o", out, "--size", "16384x16384"],
        &["image size 16384x16384 is more than the limit of 33554432 pixels"],
    );
    assert_fails(
        &["bench", "textbook", "--per-set", "100000000"],
        &["expected a number of rays per set from 1 to 65536"],
    );
    assert_fails(
        &["bench", "speed", "--sizes", "0"],
        &["expected samples per side from 2 to 16385"],
    );
    assert_fails(
        &["view", "--export-size", "16384x16384", map],
        &["--export-size 16384x16384 is more than the limit"],
    );
    let missing = dir.path().join("exports");
    assert_fails(
        &["view", "--export-dir", missing.to_str().unwrap(), map],
        &["does not exist; make it first"],
    );
    assert_fails(
        &["view", "--export-dir", map, map],
        &["is not a folder; choose a folder for the exports"],
    );
    // Many threads are capped to 4 a core, with a note.
    let output = heightray_within_ten_seconds(&["render", map, "-o", out, "--threads", "1000"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert_mentions(&stderr, &["note: 1000 threads asked for"]);
}

/// A smooth picture of `width` x `height` pixels as RGBA bytes, and as a JPEG an encoder
/// writes of it.
fn picture_and_jpeg(width: u32, height: u32) -> (Vec<u8>, Vec<u8>) {
    let picture = image::RgbaImage::from_fn(width, height, |x, y| {
        image::Rgba([(x * 255 / width) as u8, 120, (y * 255 / height) as u8, 255])
    });
    let mut jpeg = Vec::new();
    image::DynamicImage::ImageRgba8(picture.clone())
        .to_rgb8()
        .write_to(
            &mut std::io::Cursor::new(&mut jpeg),
            image::ImageFormat::Jpeg,
        )
        .unwrap();
    (picture.into_raw(), jpeg)
}

#[test]
fn a_truncated_jpeg_overlay_is_refused_and_whole_ones_load() {
    use heightray::heightfield::{Drape, Heightfield, Placement};
    let dir = TempDir::new().unwrap();
    let field = Heightfield::from_fn(8, 8, 255, 1.0, |i, j| (i + j) as u16).unwrap();
    let (width, height) = (640, 480);
    let (picture, jpeg) = picture_and_jpeg(width, height);

    // Whole, it drapes the picture within JPEG's error.
    let whole = dir.path().join("whole.jpg");
    std::fs::write(&whole, &jpeg).unwrap();
    let drape = Drape::load(&whole, &field, 1.0).expect("a whole JPEG loads");
    assert_eq!(drape.size(), (640, 480));
    let size = (width as usize, height as usize);
    let source = Drape::from_pixels(
        size.0,
        size.1,
        picture,
        1.0,
        Placement::stretched(size, (8, 8)),
    );
    for (x, y) in [(0.0, 0.0), (7.0, 0.0), (0.0, 7.0), (3.5, 2.25), (7.0, 7.0)] {
        let (got, expected) = (drape.colour(x, y).unwrap(), source.colour(x, y).unwrap());
        for (a, b) in got.0.iter().zip(expected.0) {
            assert!(
                (a - b).abs() < 0.03,
                "at ({x}, {y}): {got:?} against {expected:?}"
            );
        }
    }

    // Cut short, within its entropy-coded data: refused, not filled with grey.
    let cut = dir.path().join("cut.jpg");
    std::fs::write(&cut, &jpeg[..jpeg.len() * 3 / 5]).unwrap();
    let message = Drape::load(&cut, &field, 1.0)
        .map(|_| ())
        .expect_err("a truncated JPEG is refused")
        .to_string();
    assert_mentions(&message, &["cut.jpg", "cannot be decoded"]);

    // One flat colour, the least data an encoder writes a block in, 4096x4096: it loads.
    let flat = image::RgbImage::from_pixel(4096, 4096, image::Rgb([90, 140, 60]));
    let path = dir.path().join("flat.jpg");
    flat.save(&path).unwrap();
    let flat_bytes = std::fs::metadata(&path).unwrap().len();
    let drape = Drape::load(&path, &field, 1.0).expect("a flat JPEG loads");
    assert_eq!(drape.size(), (4096, 4096), "{flat_bytes} bytes");
}

/// Whether `message` holds a run of `n` digits.
fn has_digit_run(message: &str, n: usize) -> bool {
    message
        .split(|c: char| !c.is_ascii_digit())
        .any(|run| run.len() >= n)
}

#[test]
fn huge_and_tiny_numbers_are_echoed_compactly() {
    let scene = |extra: &str| format!("{SMALL_SCENE}{extra}\n");
    for (text, echoed) in [
        (
            SMALL_SCENE.replace("width = 16", "fov_y_deg = 1e300\nwidth = 16"),
            "got 1e300",
        ),
        (
            SMALL_SCENE.replace("width = 16", "fov_y_deg = -2.5e-300\nwidth = 16"),
            "got -2.5e-300",
        ),
        (scene("[sun]\nangle_deg = 1e300"), "got 1e300"),
        (scene("[sun]\nintensity = -1e300"), "got -1e300"),
        (
            scene("[sun]\nazimuth_deg = 10.0\nelevation_deg = 1e300"),
            "got 10 and 1e300",
        ),
        (
            scene("[sun]\ntime = \"2024-06-21T10:00:00Z\"\nlat = 1e300\nlon = 9.5"),
            "got 1e300 and 9.5",
        ),
        (scene("[effects]\nfog = -1e300"), "got -1e300"),
        (
            scene("[effects]\nsky_light = true\nsky_distance = -1e300"),
            "got -1e300",
        ),
        (
            scene("[overlay]\npath = \"ortho.png\"\nopacity = 1e300"),
            "got 1e300",
        ),
        (
            SMALL_SCENE.replace("z_scale = 12.0", "z_scale = -1e300"),
            "got -1e300",
        ),
    ] {
        let message = scene_error(&text);
        assert_mentions(&message, &[echoed]);
        assert!(!has_digit_run(&message, 20), "{message}");
    }
    let (_dir, map) = small_map();
    let output = heightray_within_ten_seconds(&["view", &map, "--render-scale", "1e30"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert_mentions(&stderr, &["--render-scale", "got 1e30"]);
    assert!(!has_digit_run(&stderr, 20), "{stderr}");
}
