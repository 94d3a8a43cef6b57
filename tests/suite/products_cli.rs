//! `heightray render MAP --ortho`: the GeoTIFF a product is written as lies where its DEM lies
//! (its tags are the DEM's transform as GDAL reads it, and `gdalinfo` agrees; these fail
//! without GDAL only when HEIGHTRAY_REQUIRE_GDAL=1, as `.ci/run` sets it); bad requests are
//! refused with a reason. (16-bit TIFFs: [`crate::deep_tiffs`].)

use crate::common::files::{tagged_tiff, TagData};
use heightray::heightfield::load;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use tiff::decoder::Decoder;
use tiff::encoder::colortype::Gray32Float;
use tiff::tags::Tag;

/// Samples of the test DEMs along x and y.
const SIZE: (u32, u32) = (33, 25);

/// A DEM of a hill in UTM zone 32 N (EPSG:32632), 30 m samples, its tiepoint at
/// (500000, 5200000): the corner of the first pixel (PixelIsArea, `raster_type` 1) or its
/// sample (PixelIsPoint, 2).
pub(crate) fn dem(dir: &Path, raster_type: u16) -> PathBuf {
    let (w, h) = SIZE;
    let heights: Vec<f32> = (0..h)
        .flat_map(|r| {
            (0..w).map(move |c| {
                let (dx, dy) = (c as f32 - 14.0, r as f32 - 10.0);
                400.0 + 200.0 * (-(dx * dx + dy * dy) / 40.0).exp()
            })
        })
        .collect();
    let keys = [
        1,
        1,
        0,
        3,
        1024,
        0,
        1,
        1,
        1025,
        0,
        1,
        raster_type,
        3072,
        0,
        1,
        32632,
    ];
    let tags = [
        (Tag::GeoKeyDirectoryTag, TagData::Shorts(&keys)),
        (
            Tag::ModelPixelScaleTag,
            TagData::Doubles(&[30.0, 30.0, 0.0]),
        ),
        (
            Tag::ModelTiepointTag,
            TagData::Doubles(&[0.0, 0.0, 0.0, 500000.0, 5200000.0, 0.0]),
        ),
    ];
    let path = dir.join(format!("dem{raster_type}.tif"));
    std::fs::write(&path, tagged_tiff::<Gray32Float>(w, h, &heights, &tags)).unwrap();
    path
}

/// `heightray render ARGS`.
pub(crate) fn heightray(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_heightray"))
        .arg("render")
        .args(args)
        .output()
        .expect("run heightray render")
}

/// `heightray render ARGS`, which must succeed.
pub(crate) fn render(args: &[&str]) {
    let output = heightray(args);
    assert!(
        output.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// A tag's doubles.
fn doubles(decoder: &mut Decoder<std::fs::File>, tag: Tag) -> Vec<f64> {
    decoder.get_tag_f64_vec(tag).expect("the tag")
}

/// The GeoTIFF tags of `path`: pixel scale, tiepoint, and the GeoKey directory.
fn geo_tags(path: &Path) -> (Vec<f64>, Vec<f64>, Vec<u16>) {
    let mut decoder = Decoder::new(std::fs::File::open(path).unwrap()).unwrap();
    let scale = doubles(&mut decoder, Tag::ModelPixelScaleTag);
    let tiepoint = doubles(&mut decoder, Tag::ModelTiepointTag);
    let keys = decoder.get_tag_u16_vec(Tag::GeoKeyDirectoryTag).unwrap();
    (scale, tiepoint, keys)
}

/// The value of GeoKey `id` in a directory.
fn key(keys: &[u16], id: u16) -> Option<u16> {
    keys[4..].chunks_exact(4).find(|k| k[0] == id).map(|k| k[3])
}

#[test]
fn a_products_tags_are_the_dems_transform_as_gdal_reads_it() {
    let dir = tempfile::tempdir().unwrap();
    // GDAL's corner of pixel (0, 0): the tiepoint of a PixelIsArea DEM; half a pixel west and
    // north of a PixelIsPoint DEM's, whose tiepoint is a sample.
    for (raster_type, corner) in [(1, [500000.0, 5200000.0]), (2, [499985.0, 5200015.0])] {
        let dem = dem(dir.path(), raster_type);
        for product in ["shaded", "sky-view"] {
            let out = dir.path().join(format!("{product}{raster_type}.tif"));
            let (d, o) = (dem.to_str().unwrap(), out.to_str().unwrap());
            render(&[d, "--ortho", "--product", product, "-o", o]);
            let (scale, tiepoint, keys) = geo_tags(&out);
            assert_eq!(scale, [30.0, 30.0, 0.0]);
            assert_eq!(tiepoint, [0.0, 0.0, 0.0, corner[0], corner[1], 0.0]);
            assert_eq!(key(&keys, 1024), Some(1), "projected");
            assert_eq!(key(&keys, 1025), Some(1), "PixelIsArea");
            assert_eq!(key(&keys, 3072), Some(32632));
            let decoder = Decoder::new(std::fs::File::open(&out).unwrap());
            assert_eq!(decoder.unwrap().dimensions().unwrap(), SIZE);
        }
        // Read back by heightray, the sky-view raster's samples lie on the DEM's.
        let product = load(&dir.path().join(format!("sky-view{raster_type}.tif")), 1.0).unwrap();
        let source = load(&dem, 1.0).unwrap();
        let (made, own) = (product.georef().unwrap(), source.georef().unwrap());
        assert_eq!(
            (made.origin, made.spacing, made.units, made.crs),
            (own.origin, own.spacing, own.units, own.crs)
        );
    }
}

/// Whether `gdalinfo` runs here; when it does not, the test fails if HEIGHTRAY_REQUIRE_GDAL=1
/// (as `.ci/run` sets it), else says it skips the comparison.
pub(crate) fn gdal_present() -> bool {
    let present = Command::new("gdalinfo").arg("--version").output().is_ok();
    if !present {
        assert!(
            std::env::var("HEIGHTRAY_REQUIRE_GDAL").as_deref() != Ok("1"),
            "gdalinfo is missing and HEIGHTRAY_REQUIRE_GDAL=1: apt-get install gdal-bin"
        );
        eprintln!("gdalinfo is missing: not compared with GDAL");
    }
    present
}

/// What `gdalinfo -json` says of `path`.
pub(crate) fn gdal_info(path: &Path) -> serde_json::Value {
    let output = Command::new("gdalinfo")
        .arg("-json")
        .arg(path)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).unwrap()
}

#[test]
fn gdalinfo_reads_each_product_on_its_dems_grid() {
    if !gdal_present() {
        return;
    }
    let info = gdal_info;
    let dir = tempfile::tempdir().unwrap();
    for raster_type in [1, 2] {
        let dem = dem(dir.path(), raster_type);
        let source = info(&dem);
        let cases = [
            ("shaded", &[][..], "Byte", 4),
            ("sky-view", &[][..], "Float32", 1),
            (
                "sunlight-hours",
                &["--date", "2026-06-21", "--sun-step", "30"][..],
                "Float32",
                1,
            ),
        ];
        for (product, more, kind, bands) in cases {
            let out = dir.path().join(format!("{product}.tif"));
            let mut args = vec![dem.to_str().unwrap(), "--ortho", "--product", product];
            args.extend(more);
            args.extend(["-o", out.to_str().unwrap()]);
            render(&args);
            let made = info(&out);
            assert_eq!(made["geoTransform"], source["geoTransform"], "{product}");
            assert_eq!(made["size"], source["size"], "{product}");
            assert_eq!(
                made["coordinateSystem"]["wkt"], source["coordinateSystem"]["wkt"],
                "{product}"
            );
            assert_eq!(made["metadata"][""]["AREA_OR_POINT"], "Area", "{product}");
            let found = made["bands"].as_array().unwrap();
            assert_eq!(found.len(), bands, "{product}");
            assert_eq!(found[0]["type"], kind, "{product}");
            if bands == 4 {
                assert_eq!(found[3]["colorInterpretation"], "Alpha");
            } else {
                assert!(
                    found[0]["noDataValue"].is_string(),
                    "{product}: NaN is no data"
                );
            }
        }
    }
}

#[test]
fn bad_product_requests_are_refused_with_a_reason() {
    let dir = tempfile::tempdir().unwrap();
    let dem = dem(dir.path(), 1);
    let plain = dir.path().join("plain.pgm");
    std::fs::write(&plain, b"P2 3 3 9 1 2 3 4 5 6 7 8 9\n").unwrap();
    let (d, p) = (dem.to_str().unwrap(), plain.to_str().unwrap());
    let out = dir.path().join("out.tif");
    let o = out.to_str().unwrap();
    let png = dir.path().join("out.png");
    let cases: [(&[&str], &str); 7] = [
        (
            &[d, "--ortho", "--product", "sunlight-hours", "-o", o],
            "--date",
        ),
        (
            &[
                p,
                "--ortho",
                "--product",
                "sunlight-hours",
                "--date",
                "2026-06-21",
                "-o",
                o,
            ],
            "not georeferenced",
        ),
        (
            &[
                d,
                "--ortho",
                "--product",
                "sunlight-hours",
                "--date",
                "21/6/2026",
                "-o",
                o,
            ],
            "not a date",
        ),
        (
            &[
                d,
                "--ortho",
                "--product",
                "sunlight-hours",
                "--date",
                "2026-06-21",
                "--sun-step",
                "7",
                "-o",
                o,
            ],
            "divide an hour",
        ),
        (&[d, "--ortho", "--cell", "-5", "-o", o], "--cell"),
        (
            &[
                d,
                "--ortho",
                "--product",
                "sky-view",
                "--svf-radius",
                "nan",
                "-o",
                o,
            ],
            "radius",
        ),
        (&[d, "--depth", "16", "-o", png.to_str().unwrap()], ".tif"),
    ];
    for (args, reason) in cases {
        let output = heightray(args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args:?} succeeded");
        assert!(stderr.contains(reason), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
    assert!(!out.exists());
}
