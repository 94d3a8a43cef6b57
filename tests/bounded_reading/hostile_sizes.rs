//! Files whose headers or layouts claim far more than they hold, or than a height map needs:
//! each is refused (or its excess skipped) before memory is allocated for the claim, with a
//! message naming the cause; and a TIFF of millions of strips is read in one pass.

use super::files::tiff_directory;
use super::recording::{alone, measure, Allocated};
use super::{error_of, load, sparse, MIB};
use heightray::heightfield::{load_mosaic, Drape, LoadOptions};
use heightray::Heightfield;
use std::borrow::Cow;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use tempfile::TempDir;

#[test]
fn an_asc_claiming_a_billion_values_in_300_bytes_is_refused_before_allocating() {
    let dir = TempDir::new().unwrap();
    // 2 x 5e8 = 1e9 values: within the sample limit, 8 GB as f64.
    let mut text = String::from("ncols 2\nnrows 5e8\nxllcorner 0\nyllcorner 0\ncellsize 1\n");
    while text.len() < 300 {
        text += "1 2\n";
    }
    text.truncate(300);
    let path = dir.path().join("tall.asc");
    std::fs::write(&path, &text).unwrap();
    let outcome = load(&path);
    let message = error_of(&outcome);
    assert!(
        message.contains("tall.asc") && message.contains("claims 2x500000000"),
        "{message}"
    );
    assert!(
        message.contains("more than a file of 300 bytes"),
        "{message}"
    );
    assert!(outcome.allocated.peak < MIB, "{:?}", outcome.allocated);
}

#[test]
fn a_134_byte_tiff_claiming_40000_squared_floats_is_refused_before_allocating() {
    let dir = TempDir::new().unwrap();
    // 40000 x 40000 32-bit floats (6.4 GB) in one strip of 12 bytes.
    let mut tiff = tiff_directory(&[
        (256, 4, 1, 40000), // ImageWidth
        (257, 4, 1, 40000), // ImageLength
        (258, 3, 1, 32),    // BitsPerSample
        (259, 3, 1, 1),     // Compression: none
        (262, 3, 1, 1),     // PhotometricInterpretation
        (273, 4, 1, 122),   // StripOffsets
        (279, 4, 1, 12),    // StripByteCounts
        (339, 3, 1, 3),     // SampleFormat: float
    ]);
    tiff.resize(134, 0);
    let path = dir.path().join("claims.tif");
    std::fs::write(&path, &tiff).unwrap();
    let outcome = load(&path);
    let message = error_of(&outcome);
    assert!(
        message.contains("claims.tif")
            && message.contains("truncated or corrupt")
            && message.contains("its strips hold 12 bytes, which cannot decode to the 6400000000"),
        "{message}"
    );
    assert!(outcome.allocated.peak < MIB, "{:?}", outcome.allocated);
}

#[test]
fn a_strip_past_the_end_of_the_file_is_corrupt() {
    let dir = TempDir::new().unwrap();
    let mut tiff = tiff_directory(&[
        (256, 4, 1, 4),
        (257, 4, 1, 4),
        (258, 3, 1, 16),
        (259, 3, 1, 1),
        (262, 3, 1, 1),
        (273, 4, 1, 1 << 30), // StripOffsets: a GiB into a file of 200 bytes
        (279, 4, 1, 32),
    ]);
    tiff.resize(200, 0);
    let path = sparse(&dir, "far-strip.tif", &tiff, 200);
    let message = error_of(&load(&path));
    assert!(
        message.contains("truncated or corrupt")
            && message.contains("strip 0 lies past the end of the file"),
        "{message}"
    );
}

/// A 64x64 gray PNG with a zTXt chunk and an ICC profile that each inflate to `inflated`
/// bytes.
fn png_with_bombs(inflated: usize) -> Vec<u8> {
    let mut info = png::Info::with_size(64, 64);
    info.color_type = png::ColorType::Grayscale;
    info.bit_depth = png::BitDepth::Eight;
    info.icc_profile = Some(Cow::Owned(vec![0; inflated]));
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::with_info(&mut bytes, info).unwrap();
    encoder
        .add_ztxt_chunk("Comment".into(), "a".repeat(inflated))
        .unwrap();
    let mut writer = encoder.write_header().unwrap();
    let pixels: Vec<u8> = (0..64 * 64).map(|k| (k % 251) as u8).collect();
    writer.write_image_data(&pixels).unwrap();
    writer.finish().unwrap();
    bytes
}

#[test]
fn png_text_and_profile_chunks_are_skipped_unread() {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("bombs.png");
    alone(|| std::fs::write(&path, png_with_bombs(64 * MIB)).unwrap());
    let outcome = load(&path);
    let field = outcome.result.as_ref().expect("the map loads");
    assert_eq!((field.width(), field.height()), (64, 64));
    // Image row 0 is the field's top row.
    assert_eq!(field.sample(5, 63), 5);
    // The chunks inflate to 128 MiB between them; the map needs 4 KiB of pixels.
    assert!(outcome.allocated.peak < 4 * MIB, "{:?}", outcome.allocated);
}

#[test]
fn an_overlay_png_s_text_and_profile_chunks_are_skipped_unread() {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("bombs.png");
    alone(|| std::fs::write(&path, png_with_bombs(64 * MIB)).unwrap());
    let field = Heightfield::from_fn(8, 8, 255, 1.0, |i, j| (i + j) as u16).unwrap();
    let (drape, allocated) = measure(|| Drape::load(&path, &field, 1.0));
    let drape = drape.expect("the overlay loads");
    assert_eq!(drape.size(), (64, 64));
    // The chunks inflate to 128 MiB between them; the overlay needs 16 KiB of pixels.
    assert!(allocated.peak < 4 * MIB, "{allocated:?}");
}

/// A small JPEG whose frame header is rewritten to declare `width` x `height` pixels.
fn jpeg_declaring(width: u16, height: u16) -> Vec<u8> {
    let image = image::RgbImage::from_fn(16, 16, |x, y| image::Rgb([x as u8 * 16, y as u8, 9]));
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Jpeg,
        )
        .unwrap();
    let sof = bytes
        .windows(2)
        .position(|w| w == [0xff, 0xc0])
        .expect("a baseline frame header");
    // FFC0, length (2), precision (1), then height and width.
    bytes[sof + 5..sof + 7].copy_from_slice(&height.to_be_bytes());
    bytes[sof + 7..sof + 9].copy_from_slice(&width.to_be_bytes());
    bytes
}

#[test]
fn an_overlay_declaring_46000_squared_pixels_is_refused_before_decoding() {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("huge.jpg");
    std::fs::write(&path, jpeg_declaring(46000, 46000)).unwrap();
    let field = Heightfield::from_fn(8, 8, 255, 1.0, |i, j| (i + j) as u16).unwrap();
    let (result, allocated) = measure(|| Drape::load(&path, &field, 1.0).map(|_| ()));
    let message = result.expect_err("refused").to_string();
    assert!(
        message.contains("huge.jpg")
            && message.contains("46000x46000")
            && message.contains("more than the limit of 67108864 (8192x8192) for an overlay"),
        "{message}"
    );
    assert!(allocated.peak < 4 * MIB, "{allocated:?}");
}

/// The 16x16 JPEG's few hundred bytes cannot hold the coded blocks of 8000x8000 pixels (a
/// 4:2:0 frame of 250,000 units of 6 blocks, at least a bit each): refused before its 256 MB
/// of pixels are allocated, where a lenient decoder fills them with grey.
#[test]
fn an_overlay_of_a_few_hundred_bytes_declaring_8000_squared_pixels_is_corrupt() {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("claims.jpg");
    let bytes = jpeg_declaring(8000, 8000);
    assert!(bytes.len() < 1000, "{} bytes", bytes.len());
    std::fs::write(&path, &bytes).unwrap();
    let field = Heightfield::from_fn(8, 8, 255, 1.0, |i, j| (i + j) as u16).unwrap();
    let (result, allocated) = measure(|| Drape::load(&path, &field, 1.0).map(|_| ()));
    let message = result.expect_err("refused").to_string();
    assert!(
        message.contains("claims.jpg")
            && message.contains("truncated or corrupt")
            && message.contains("8000x8000"),
        "{message}"
    );
    assert!(allocated.peak < 4 * MIB, "{allocated:?}");
}

/// A 4x4 ESRI ASCII tile of 1 m cells with its lower-left corner at `(x, 0)`.
fn tile(dir: &Path, name: &str, x: f64) -> PathBuf {
    let path = dir.join(name);
    let rows = "1 2 3 4\n".repeat(4);
    let text = format!("ncols 4\nnrows 4\nxllcorner {x:e}\nyllcorner 0\ncellsize 1\n{rows}");
    std::fs::write(&path, text).unwrap();
    path
}

fn join(paths: &[PathBuf]) -> (String, Allocated) {
    let (result, allocated) = measure(|| {
        load_mosaic(
            paths,
            &LoadOptions::new(1.0),
            &|_| ControlFlow::Continue(()),
        )
        .map(|_| ())
    });
    (result.expect_err("refused").to_string(), allocated)
}

#[test]
fn tiles_far_off_or_far_apart_are_refused_with_the_reason() {
    let dir = TempDir::new().unwrap();
    let near = tile(dir.path(), "a.asc", 0.0);
    let far = tile(dir.path(), "far.asc", 1e300);
    let (message, allocated) = join(&[near.clone(), far]);
    assert!(
        message.contains("far.asc lies 1e300 cells from the first tile along x"),
        "{message}"
    );
    assert!(allocated.peak < MIB, "{allocated:?}");
    // 23000 cells apart: a joined grid of 23004 x 4 samples would do, so they are joined
    // diagonally to span 23004 x 23004, 529 million samples of which 32 hold data.
    let apart = dir.path().join("apart.asc");
    let rows = "1 2 3 4\n".repeat(4);
    std::fs::write(
        &apart,
        format!("ncols 4\nnrows 4\nxllcorner 23000\nyllcorner 23000\ncellsize 1\n{rows}"),
    )
    .unwrap();
    let (message, allocated) = join(&[near, apart]);
    assert!(
        message.contains("23004x23004 samples, of which the tiles cover at most 32")
            && message.contains("gaps between them would be stored as no data"),
        "{message}"
    );
    assert!(allocated.peak < MIB, "{allocated:?}");
}

/// A TIFF of `rows` rows of two 16-bit samples, one row a strip: row `r` holds `r % 65536`
/// and `7 r % 65536`, and is stored `slot(r)` strips into the file's data.
fn many_strips(rows: u32, slot: impl Fn(u32) -> u32) -> Vec<u8> {
    let data_at = 8u32;
    let offsets_at = data_at + 4 * rows;
    let counts_at = offsets_at + 4 * rows;
    let directory_at = counts_at + 4 * rows;
    let mut bytes = b"II*\0".to_vec();
    bytes.extend(directory_at.to_le_bytes());
    let mut data = vec![0u8; 4 * rows as usize];
    for r in 0..rows {
        let at = 4 * slot(r) as usize;
        data[at..at + 2].copy_from_slice(&((r % 65536) as u16).to_le_bytes());
        data[at + 2..at + 4].copy_from_slice(&((r.wrapping_mul(7) % 65536) as u16).to_le_bytes());
    }
    bytes.extend(data);
    bytes.extend((0..rows).flat_map(|r| (data_at + 4 * slot(r)).to_le_bytes()));
    bytes.extend((0..rows).flat_map(|_| 4u32.to_le_bytes()));
    let directory = tiff_directory(&[
        (256, 4, 1, 2),
        (257, 4, 1, rows),
        (258, 3, 1, 16),
        (259, 3, 1, 1),
        (262, 3, 1, 1),
        (273, 4, rows, offsets_at),
        (277, 3, 1, 1),
        (278, 4, 1, 1),
        (279, 4, rows, counts_at),
    ]);
    // The directory without its own 8-byte header.
    bytes.extend(&directory[8..]);
    bytes
}

#[test]
fn a_tiff_of_two_million_strips_is_read_in_one_pass() {
    let dir = TempDir::new().unwrap();
    let rows = 2_000_000;
    let path = dir.path().join("strips.tif");
    let len = alone(|| {
        let bytes = many_strips(rows, |r| r);
        std::fs::write(&path, &bytes).unwrap();
        bytes.len() as u64
    });
    let outcome = load(&path);
    let field = outcome.result.as_ref().expect("the map loads");
    assert_eq!((field.width(), field.height()), (2, rows as usize));
    // Sample row j is image row rows - 1 - j.
    let r = rows - 1 - 12345;
    assert_eq!(field.sample(0, 12345), (r % 65536) as u16);
    assert_eq!(field.sample(1, 12345), (r * 7 % 65536) as u16);
    // Each byte once, give or take the buffer: a seek to the next strip keeps the buffer.
    assert!(
        outcome.read < 2 * len,
        "read {} bytes of {len}",
        outcome.read
    );
    // The strip tables (2 million offsets and counts, as the decoder's tag values and as
    // the numbers checked against the file) and the samples.
    assert!(
        outcome.allocated.peak < 384 * MIB,
        "{:?}",
        outcome.allocated
    );
}

/// Loads `path`, a TIFF of `rows` strips made by [`many_strips`], and checks two of its rows.
fn assert_strips_load(path: &Path, rows: u32) -> super::Outcome {
    let outcome = load(path);
    let field = outcome.result.as_ref().expect("the map loads");
    assert_eq!((field.width(), field.height()), (2, rows as usize));
    for j in [0, 12345, rows as usize - 1] {
        // Sample row j is image row rows - 1 - j.
        let r = rows - 1 - j as u32;
        assert_eq!(field.sample(0, j), (r % 65536) as u16, "row {r}");
        assert_eq!(field.sample(1, j), (r * 7 % 65536) as u16, "row {r}");
    }
    outcome
}

#[test]
fn a_tiff_of_two_million_strips_in_any_order_is_read_once() {
    let dir = TempDir::new().unwrap();
    let rows = 2_000_000;
    // Backwards, and scattered (7919 is prime to 2 million, so each row has its own slot).
    let orders: [(&str, &dyn Fn(u32) -> u32); 2] = [
        ("backwards.tif", &|r| rows - 1 - r),
        ("scattered.tif", &|r| {
            ((u64::from(r) * 7919) % u64::from(rows)) as u32
        }),
    ];
    for (name, slot) in orders {
        let path = dir.path().join(name);
        alone(|| std::fs::write(&path, many_strips(rows, slot)).unwrap());
        let len = std::fs::metadata(&path).unwrap().len();
        let outcome = assert_strips_load(&path, rows);
        // Each byte once: jumping between strips reads nothing again.
        assert!(
            outcome.read < len + MIB as u64,
            "{name}: read {} bytes of {len}",
            outcome.read
        );
        assert!(
            outcome.time.as_secs_f64() < 5.0,
            "{name}: {:?}",
            outcome.time
        );
        assert!(
            outcome.allocated.peak < 384 * MIB,
            "{name}: {:?}",
            outcome.allocated
        );
    }
}
