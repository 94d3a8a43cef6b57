//! Refused input gives an error with a clear message, never a panic; good files load with
//! the sizes and heights that were written.

use crate::common::files::{png_header, tiff, tiff_header};
use heightray::heightfield::{load, load_with, ColourEncoding, LoadOptions};
use heightray::Ray;
use image::{GrayImage, ImageBuffer, Luma, Rgb};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use tempfile::TempDir;
use tiff::encoder::colortype::{Gray16, Gray32Float, RGB8};

/// The error message of `result`, which must be an error.
fn message<T: std::fmt::Debug, E: std::fmt::Display>(result: Result<T, E>) -> String {
    match result {
        Ok(value) => panic!("expected an error, got {value:?}"),
        Err(error) => error.to_string(),
    }
}

fn assert_mentions(message: &str, words: &[&str]) {
    let lower = message.to_lowercase();
    for word in words {
        assert!(
            lower.contains(&word.to_lowercase()),
            "message {message:?} does not mention {word:?}"
        );
    }
}

#[test]
fn nan_and_infinite_ray_components_are_refused() {
    let cases = [
        (
            [f64::NAN, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            ["origin", "x", "nan"],
        ),
        (
            [0.0, 0.0, f64::INFINITY],
            [1.0, 0.0, 0.0],
            ["origin", "z", "inf"],
        ),
        (
            [0.0, 0.0, 0.0],
            [0.0, f64::NAN, 1.0],
            ["direction", "y", "nan"],
        ),
        (
            [0.0, 0.0, 0.0],
            [f64::NEG_INFINITY, 0.0, 1.0],
            ["direction", "x", "inf"],
        ),
    ];
    for (o, d, words) in cases {
        let text = message(Ray::new(o, d));
        assert_mentions(&text, &words);
        assert_mentions(&text, &["finite"]);
    }
}

#[test]
fn zero_direction_is_refused() {
    for d in [[0.0, 0.0, 0.0], [-0.0, 0.0, -0.0], [-0.0, -0.0, -0.0]] {
        let text = message(Ray::new([1.0, 2.0, 3.0], d));
        assert_mentions(&text, &["direction", "zero"]);
    }
    // Subnormal components are not zero.
    assert!(Ray::new([0.0; 3], [0.0, 0.0, 5e-324]).is_ok());
}

fn write(dir: &TempDir, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).expect("write test file");
    path
}

fn load_error(path: &Path) -> String {
    message(load(path, 10.0))
}

/// A valid 3x2 8-bit grayscale PNG.
fn small_png(dir: &TempDir) -> PathBuf {
    let path = dir.path().join("small.png");
    GrayImage::from_fn(3, 2, |x, y| Luma([(x * 10 + y) as u8]))
        .save(&path)
        .expect("write PNG");
    path
}

#[test]
fn one_by_one_images_are_too_small() {
    let dir = TempDir::new().unwrap();
    let png = dir.path().join("one.png");
    GrayImage::from_pixel(1, 1, Luma([7])).save(&png).unwrap();
    let pgm = write(&dir, "one.pgm", b"P2\n1 1\n255\n7\n");
    let wide = write(&dir, "wide.pgm", b"P5 5 1 255\n\x01\x02\x03\x04\x05");
    for path in [png, pgm, wide] {
        assert_mentions(&load_error(&path), &["2x2"]);
    }
}

#[test]
fn an_empty_file_is_refused() {
    let dir = TempDir::new().unwrap();
    let path = write(&dir, "empty.png", b"");
    let text = load_error(&path);
    assert_mentions(&text, &["empty.png", "empty"]);
}

#[test]
fn files_that_are_not_images_are_refused() {
    let dir = TempDir::new().unwrap();
    // Bytes of a fixed pseudo-random sequence (not starting with a known magic number).
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let random: Vec<u8> = (0..4096)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 24) as u8
        })
        .collect();
    assert!(!random.starts_with(b"P") && !random.starts_with(b"\x89PNG"));
    let noise = write(&dir, "noise.png", &random);
    let text = write(
        &dir,
        "notes.txt",
        b"this is a text file,\nnot a height map\n",
    );
    for path in [noise, text] {
        let msg = load_error(&path);
        assert_mentions(
            &msg,
            &[
                path.file_name().unwrap().to_str().unwrap(),
                "not a png, pgm or tiff",
            ],
        );
    }
}

#[test]
fn a_truncated_png_is_refused() {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("big.png");
    GrayImage::from_fn(64, 64, |x, y| Luma([(x ^ y) as u8]))
        .save(&path)
        .unwrap();
    let bytes = std::fs::read(&path).unwrap();
    for keep in [bytes.len() / 2, 40, 12] {
        let cut = write(&dir, "cut.png", &bytes[..keep]);
        let msg = load_error(&cut);
        assert_mentions(&msg, &["cut.png"]);
        assert!(
            msg.contains("decode") || msg.contains("not a PNG"),
            "truncated to {keep} bytes: {msg}"
        );
    }
}

#[test]
fn truncated_and_malformed_pgms_are_refused() {
    let dir = TempDir::new().unwrap();
    let cases: [(&[u8], &[&str]); 5] = [
        (b"P5 4 4 255\n\x01\x02", &["truncated"]),
        (b"P2\n3 2\n1000\n0 500 1000\n250\n", &["raster"]),
        (b"P2\n3 2\n0\n0 0 0\n0 0 0\n", &["maxval"]),
        (b"P2\n3\n", &["height"]),
        (b"P2\n2 2\n10\n0 11 0 0\n", &["exceeds maxval"]),
    ];
    for (n, (bytes, words)) in cases.iter().enumerate() {
        let path = write(&dir, &format!("bad{n}.pgm"), bytes);
        assert_mentions(&load_error(&path), words);
    }
}

#[test]
fn a_directory_is_refused() {
    let dir = TempDir::new().unwrap();
    let msg = load_error(dir.path());
    assert_mentions(&msg, &["is a directory", &dir.path().display().to_string()]);
    let missing = dir.path().join("missing.png");
    assert_mentions(&load_error(&missing), &["cannot read", "missing.png"]);
}

#[test]
fn bad_z_scales_are_refused() {
    let dir = TempDir::new().unwrap();
    let png = small_png(&dir);
    for z in [f64::NAN, f64::INFINITY, -1.0] {
        assert_mentions(&message(load(&png, z)), &["z scale"]);
    }
}

#[test]
fn huge_headers_are_refused_before_decoding() {
    let dir = TempDir::new().unwrap();
    let cases = [
        ("huge.png", png_header(100_000, 100_000, 8, 0)),
        ("huge.tif", tiff_header(100_000, 100_000)),
        ("huge.pgm", b"P5 100000 100000 65535\n\x01\x02".to_vec()),
    ];
    for (name, bytes) in cases {
        let msg = load_error(&write(&dir, name, &bytes));
        assert_mentions(
            &msg,
            &[name, "100000x100000", "more than the limit", "downsample"],
        );
    }
}

#[test]
fn an_image_too_big_to_decode_is_refused_from_its_header() {
    // 40000x40000 is under the sample limit, but RGBA at 16 bits would take 11.9 GiB.
    let dir = TempDir::new().unwrap();
    let path = write(&dir, "bomb.png", &png_header(40_000, 40_000, 16, 6));
    assert_mentions(
        &load_error(&path),
        &["bomb.png", "11.9 GiB", "limit of 8 GiB"],
    );
}

#[test]
fn truncated_and_corrupt_tiffs_are_refused() {
    let dir = TempDir::new().unwrap();
    let samples: Vec<u16> = (0..64 * 64).map(|k| k as u16).collect();
    let whole = tiff::<Gray16>(64, 64, &samples, None);
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut noise: Vec<u8> = b"II*\0".to_vec();
    noise.extend((0..2048).map(|_| {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 33) as u8
    }));
    for (name, bytes) in [
        ("half.tif", &whole[..whole.len() / 2]),
        ("header.tif", &whole[..6]),
        ("noise.tif", &noise[..]),
    ] {
        let msg = load_error(&write(&dir, name, bytes));
        assert_mentions(&msg, &[name, "truncated or corrupt"]);
    }
}

#[test]
fn a_tiff_of_only_nan_has_no_terrain() {
    let dir = TempDir::new().unwrap();
    let path = write(
        &dir,
        "nan.tif",
        &tiff::<Gray32Float>(4, 3, &[f32::NAN; 12], None),
    );
    assert_mentions(&load_error(&path), &["nan.tif", "every sample is no-data"]);
}

#[test]
fn a_one_by_one_tiff_is_too_small() {
    let dir = TempDir::new().unwrap();
    let path = write(&dir, "one.tif", &tiff::<Gray16>(1, 1, &[7], None));
    assert_mentions(&load_error(&path), &["one.tif", "2x2"]);
}

#[test]
fn colour_images_that_are_not_height_maps_are_refused() {
    let dir = TempDir::new().unwrap();
    let rgb_tiff = write(&dir, "rgb.tif", &tiff::<RGB8>(2, 2, &[9; 12], None));
    assert_mentions(
        &load_error(&rgb_tiff),
        &["rgb.tif", "rgb", "single-band tiff"],
    );
    // Terrain-RGB encodings are 8-bit: a 16-bit RGB PNG cannot be one.
    let rgb16 = dir.path().join("rgb16.png");
    ImageBuffer::<Rgb<u16>, Vec<u16>>::from_pixel(3, 3, Rgb([1, 2, 3]))
        .save(&rgb16)
        .unwrap();
    let options = LoadOptions {
        colour: ColourEncoding::Mapbox,
        ..LoadOptions::new(1.0)
    };
    let msg = message(load_with(&rgb16, &options, &|_| ControlFlow::Continue(())));
    assert_mentions(&msg, &["rgb16.png", "mapbox", "not a height map"]);
}

#[test]
fn an_unreadable_path_is_refused() {
    let dir = TempDir::new().unwrap();
    let link = dir.path().join("dangling.png");
    std::os::unix::fs::symlink(dir.path().join("gone.png"), &link).unwrap();
    assert_mentions(&load_error(&link), &["cannot read", "dangling.png"]);
}

#[test]
fn a_cancelled_load_says_so() {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("big.png");
    GrayImage::from_fn(256, 256, |x, y| Luma([(x * 7 + y * 13) as u8]))
        .save(&path)
        .unwrap();
    // Cancel once a tenth of the file has been decoded.
    let cancel = |fraction: f64| {
        if fraction > 0.1 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let msg = message(load_with(&path, &LoadOptions::new(1.0), &cancel));
    assert_mentions(&msg, &["loading", "big.png", "cancelled"]);
}
