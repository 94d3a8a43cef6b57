//! Refused input gives an error with a clear message, never a panic; good files load with
//! the sizes and heights that were written.

use heightray::heightfield::{load, Heightfield};
use heightray::Ray;
use image::{GrayImage, ImageBuffer, Luma, RgbImage};
use std::path::{Path, PathBuf};
use tempfile::TempDir;

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
                "not a png or pgm",
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
    assert_mentions(&msg, &["cannot read", &dir.path().display().to_string()]);
    let missing = dir.path().join("missing.png");
    assert_mentions(&load_error(&missing), &["cannot read", "missing.png"]);
}

#[test]
fn color_images_are_refused() {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("rgb.png");
    RgbImage::from_pixel(4, 4, image::Rgb([1, 2, 3]))
        .save(&path)
        .unwrap();
    assert_mentions(&load_error(&path), &["grayscale"]);
}

#[test]
fn bad_z_scales_are_refused() {
    let dir = TempDir::new().unwrap();
    let png = small_png(&dir);
    for z in [f64::NAN, f64::INFINITY, -1.0] {
        assert_mentions(&message(load(&png, z)), &["z scale"]);
    }
}

/// Checks size, maxval and every height: `rows[r][c]` is image row `r` (top first), so
/// sample `(c, H-1-r)`.
fn assert_field(field: &Heightfield, rows: &[Vec<u32>], maxval: u32, z_scale: f64) {
    let (w, h) = (rows[0].len(), rows.len());
    assert_eq!((field.width(), field.height()), (w, h));
    assert_eq!(u32::from(field.maxval()), maxval);
    for (r, row) in rows.iter().enumerate() {
        for (c, &s) in row.iter().enumerate() {
            let j = h - 1 - r;
            assert_eq!(u32::from(field.sample(c, j)), s, "sample ({c}, {j})");
            let expected = f64::from(s) * (z_scale / f64::from(maxval));
            assert_eq!(
                field.z(c, j).to_bits(),
                expected.to_bits(),
                "height ({c}, {j})"
            );
        }
    }
}

/// 5 columns x 3 rows of distinct samples up to `maxval`.
fn test_rows(maxval: u32) -> Vec<Vec<u32>> {
    (0..3)
        .map(|r| (0..5).map(|c| (r * 5 + c) * maxval / 14).collect())
        .collect()
}

#[test]
fn eight_bit_png_loads_with_its_heights() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(255);
    let path = dir.path().join("eight.png");
    GrayImage::from_fn(5, 3, |x, y| Luma([rows[y as usize][x as usize] as u8]))
        .save(&path)
        .unwrap();
    let field = load(&path, 12.5).unwrap();
    assert_field(&field, &rows, 255, 12.5);
}

#[test]
fn sixteen_bit_png_loads_with_its_heights() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(65535);
    let path = dir.path().join("sixteen.png");
    ImageBuffer::<Luma<u16>, Vec<u16>>::from_fn(5, 3, |x, y| {
        Luma([rows[y as usize][x as usize] as u16])
    })
    .save(&path)
    .unwrap();
    let field = load(&path, 3000.0).unwrap();
    assert_field(&field, &rows, 65535, 3000.0);
}

#[test]
fn ascii_pgm_with_maxval_1000_loads_with_its_heights() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(1000);
    let mut text = String::from("P2\n# written by bad_input.rs\n5 3\n1000\n");
    for row in &rows {
        text += &row.iter().map(u32::to_string).collect::<Vec<_>>().join(" ");
        text += "\n";
    }
    let path = write(&dir, "ascii.pgm", text.as_bytes());
    let field = load(&path, 0.7).unwrap();
    assert_field(&field, &rows, 1000, 0.7);
}

#[test]
fn binary_pgm_with_maxval_1000_loads_with_its_heights() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(1000);
    let mut bytes = b"P5\n5 3\n1000\n".to_vec();
    for &s in rows.iter().flatten() {
        bytes.extend((s as u16).to_be_bytes());
    }
    let path = write(&dir, "binary.pgm", &bytes);
    let field = load(&path, 25.0).unwrap();
    assert_field(&field, &rows, 1000, 25.0);
}
