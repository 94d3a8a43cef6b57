//! Orthophotos as GIS tools deliver them, made here by GDAL (`gdal_translate`, which `.ci/run`
//! installs; these tests fail, never skip, without it): a JPEG-compressed YCbCr GeoTIFF
//! decodes to its RGB twin's pixels within JPEG's error, a ZSTD DEM to the samples of its
//! uncompressed twin, a LERC one is refused naming LERC and the command that converts it; a
//! JPEG or RGB TIFF given as a height map is named a picture; an overlay in UTM lands on the
//! cells of a geographic DEM worked out by hand.

use crate::common::files::{tagged_tiff, tiff, TagData};
use heightray::heightfield::{load, load_bytes, Drape};
use std::process::Command;
use tempfile::TempDir;
use tiff::encoder::colortype::{Gray32Float, RGB8};
use tiff::tags::Tag;

/// Runs `gdal_translate ARGS`, failing the test with GDAL's words if it cannot.
fn gdal_translate(args: &[&str]) {
    let output = Command::new("gdal_translate")
        .args(args)
        .output()
        .expect("gdal_translate runs (apt-get install gdal-bin; .ci/run installs it)");
    assert!(
        output.status.success(),
        "gdal_translate {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// A smooth 64x48 RGB picture (JPEG keeps smooth gradients within a few levels).
fn picture() -> Vec<u8> {
    (0..48u32)
        .flat_map(|r| (0..64u32).flat_map(move |c| [(c * 4) as u8, (r * 5) as u8, 128]))
        .collect()
}

/// A 3x3 flat DEM in metres, for overlays to lie on.
fn flat_field(dir: &TempDir) -> heightray::Heightfield {
    let path = dir.path().join("flat.tif");
    std::fs::write(&path, tiff::<Gray32Float>(3, 3, &[1.0; 9], None)).unwrap();
    load(&path, 1.0).unwrap()
}

#[test]
fn a_ycbcr_jpeg_tiff_decodes_to_its_rgb_twin_within_jpeg_error() {
    let dir = TempDir::new().unwrap();
    let rgb = dir.path().join("rgb.tif");
    std::fs::write(&rgb, tiff::<RGB8>(64, 48, &picture(), None)).unwrap();
    let jpeg = dir.path().join("ycbcr.tif");
    let (rgb_s, jpeg_s) = (rgb.to_str().unwrap(), jpeg.to_str().unwrap());
    gdal_translate(&[
        "-q",
        "-co",
        "COMPRESS=JPEG",
        "-co",
        "PHOTOMETRIC=YCBCR",
        "-co",
        "JPEG_QUALITY=95",
        rgb_s,
        jpeg_s,
    ]);
    let field = flat_field(&dir);
    let twin = Drape::load(&rgb, &field, 1.0).expect("the RGB TIFF drapes");
    let decoded = Drape::load(&jpeg, &field, 1.0).expect("the YCbCr JPEG TIFF drapes");
    let (mut worst, mut sum, mut count) = (0.0f64, 0.0, 0);
    for k in 0..=20 {
        for l in 0..=20 {
            let (x, y) = (0.1 * k as f64, 0.1 * l as f64);
            let (a, _) = twin.colour(x, y).unwrap();
            let (b, _) = decoded.colour(x, y).unwrap();
            for c in 0..3 {
                // In display levels (0..255), by the gamma the drape reads with.
                let level = |v: f64| 255.0 * v.powf(1.0 / 2.2);
                let error = (level(a[c]) - level(b[c])).abs();
                worst = worst.max(error);
                sum += error;
                count += 1;
            }
        }
    }
    // Quality 95 with 2x2 chroma subsampling on smooth gradients: a few levels at most.
    assert!(worst < 8.0, "worst {worst:.2} levels");
    assert!(
        sum / count as f64 <= 2.0,
        "mean {:.2} levels",
        sum / count as f64
    );
}

#[test]
fn zstd_dems_load_and_lerc_is_named_with_the_command_that_converts_it() {
    let dir = TempDir::new().unwrap();
    let plain = dir.path().join("dem.tif");
    let heights: Vec<f32> = (0..20 * 16).map(|k| 100.0 + (k % 7) as f32 * 3.5).collect();
    std::fs::write(&plain, tiff::<Gray32Float>(20, 16, &heights, None)).unwrap();
    let zstd = dir.path().join("zstd.tif");
    let lerc = dir.path().join("lerc.tif");
    let p = plain.to_str().unwrap();
    gdal_translate(&[
        "-q",
        "-co",
        "COMPRESS=ZSTD",
        "-co",
        "PREDICTOR=3",
        p,
        zstd.to_str().unwrap(),
    ]);
    gdal_translate(&["-q", "-co", "COMPRESS=LERC", p, lerc.to_str().unwrap()]);
    let a = load(&plain, 1.0).unwrap();
    let b = load(&zstd, 1.0).expect("ZSTD is read");
    assert_eq!(a.samples(), b.samples());
    assert_eq!(a.step(), b.step());
    let error = load(&lerc, 1.0).unwrap_err().to_string();
    assert!(error.contains("LERC"), "{error}");
    assert!(
        error.contains("gdal_translate -co COMPRESS=DEFLATE"),
        "{error}"
    );
    assert!(!error.contains("corrupt"), "{error}");
}

#[test]
fn pictures_given_as_height_maps_are_named_as_pictures_in_readable_words() {
    let dir = TempDir::new().unwrap();
    let rgb = dir.path().join("photo.tif");
    std::fs::write(&rgb, tiff::<RGB8>(64, 48, &picture(), None)).unwrap();
    let jpeg = dir.path().join("photo.jpg");
    gdal_translate(&[
        "-q",
        "-of",
        "JPEG",
        rgb.to_str().unwrap(),
        jpeg.to_str().unwrap(),
    ]);
    for (path, what) in [(&rgb, "an RGB TIFF"), (&jpeg, "a JPEG image")] {
        let error = load(path, 1.0).unwrap_err().to_string();
        assert!(error.contains(what) && error.contains("overlay"), "{error}");
        assert_eq!(
            heightray::heightfield::picture_kind(path).as_deref(),
            Some(what)
        );
    }
    // Unprintable first bytes are written in hex.
    let error = load_bytes(
        &[0x00, 0x10, 0x4a, 0x46, 0xfe, 0x01, 0x02, 0x03],
        1.0,
        "x.bin",
    )
    .unwrap_err()
    .to_string();
    assert!(error.contains("00 10 4a 46 fe 01 02 03 in hex"), "{error}");
}

/// GeoKeys of a UTM zone 32 N map (EPSG:32632).
fn utm32_keys() -> Vec<u16> {
    vec![1, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, 32632]
}

#[test]
fn an_overlay_in_utm_lands_on_the_cells_of_a_geographic_dem() {
    let dir = TempDir::new().unwrap();
    // A geographic DEM of 11x11 samples 0.001° apart around 45 N, 9 E (zone 32's central
    // meridian): its grid point (i, j) is at 9 + (i - 5) / 1000 E, 45 + (j - 5) / 1000 N.
    let keys = [1u16, 1, 0, 2, 1024, 0, 1, 2, 2048, 0, 1, 4326];
    let step = 0.001;
    let corner = [9.0 - 5.5 * step, 45.0 + 5.5 * step];
    let dem = tagged_tiff::<Gray32Float>(
        11,
        11,
        &[10.0; 121],
        &[
            (Tag::GeoKeyDirectoryTag, TagData::Shorts(&keys)),
            (
                Tag::ModelPixelScaleTag,
                TagData::Doubles(&[step, step, 0.0]),
            ),
            (
                Tag::ModelTiepointTag,
                TagData::Doubles(&[0.0, 0.0, 0.0, corner[0], corner[1], 0.0]),
            ),
        ],
    );
    let field = load_bytes(&dem, 1.0, "geo.tif").unwrap();
    // The overlay: 10 m pixels in UTM 32 N over the same ground; west of the central
    // meridian's easting (500 000 m) red, east of it blue.
    // On the central meridian, transverse Mercator's northing is k0 times the meridian arc:
    // at 45 N the WGS 84 arc is 4 984 944.378 m (Snyder 3-21), so the northing is 4 982 950.4 m.
    let north = 0.9996 * 4_984_944.378;
    let (w, h) = (200u32, 200u32);
    let pixels: Vec<u8> = (0..h)
        .flat_map(|_| (0..w).flat_map(|c| if c < w / 2 { [255, 0, 0] } else { [0, 0, 255] }))
        .collect();
    let utm = utm32_keys();
    let photo = tagged_tiff::<RGB8>(
        w,
        h,
        &pixels,
        &[
            (Tag::GeoKeyDirectoryTag, TagData::Shorts(&utm)),
            (
                Tag::ModelPixelScaleTag,
                TagData::Doubles(&[10.0, 10.0, 0.0]),
            ),
            (
                Tag::ModelTiepointTag,
                TagData::Doubles(&[0.0, 0.0, 0.0, 499_000.0, north + 1000.0, 0.0]),
            ),
        ],
    );
    let path = dir.path().join("utm_photo.tif");
    std::fs::write(&path, photo).unwrap();
    let drape = Drape::load(&path, &field, 1.0).expect("reprojected onto the map");
    assert!(drape.georeferenced());
    // Column 4 (9.000 - 0.001 E, 79 m west of the meridian) is red, column 6 blue, on
    // every row: the UTM pixels land on the geographic cells they cover.
    for j in [1.0, 5.0, 9.0] {
        let (west, _) = drape.colour(4.0, j).unwrap();
        let (east, _) = drape.colour(6.0, j).unwrap();
        assert!(west[0] > 0.9 && west[2] < 0.1, "row {j}: {west:?}");
        assert!(east[2] > 0.9 && east[0] < 0.1, "row {j}: {east:?}");
    }
    // The overlay covers northings within 1000 m of 45 N (about 0.009°): row 10, 0.005°
    // north of 45 N, lies under it.
    assert!(drape
        .colour(5.0, 10.0)
        .is_some_and(|(_, alpha)| alpha > 0.9));
}
