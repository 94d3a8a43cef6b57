//! Georeferenced height maps: GeoTIFFs written with known tags (projected in metres and feet,
//! geographic at 60 N, a north-up ModelTransformation), SRTM `.hgt` tiles and ESRI ASCII grids
//! read back as written, each sample's place and each cell's size checked against the tags by
//! hand; a rotated transform or an unknown unit falls back to a plain image with the reason.

use crate::common::files::{tagged_tiff, TagData};
use heightray::heightfield::{load_bytes, Georef, Georeferencing, MapUnits};
use heightray::Heightfield;
use tiff::encoder::colortype::Gray32Float;
use tiff::tags::Tag;

/// GeoKeyDirectory header then (id, 0, 1, value) per key.
fn geo_keys(keys: &[(u16, u16)]) -> Vec<u16> {
    let mut directory = vec![1, 1, 0, keys.len() as u16];
    for &(id, value) in keys {
        directory.extend([id, 0, 1, value]);
    }
    directory
}

const MODEL_TYPE: u16 = 1024;
const RASTER_TYPE: u16 = 1025;
const LINEAR_UNITS: u16 = 3076;

/// A 4x3 float DEM (heights 100 + 10 * index, image order) with these georeferencing tags.
fn dem(
    scale: Option<&[f64]>,
    tiepoint: Option<&[f64]>,
    transform: Option<&[f64]>,
    keys: &[(u16, u16)],
) -> Heightfield {
    let heights: Vec<f32> = (0..12).map(|k| 100.0 + 10.0 * k as f32).collect();
    let keys = geo_keys(keys);
    let mut tags = vec![(Tag::GeoKeyDirectoryTag, TagData::Shorts(&keys))];
    for (tag, values) in [
        (Tag::ModelPixelScaleTag, scale),
        (Tag::ModelTiepointTag, tiepoint),
        (Tag::ModelTransformationTag, transform),
    ] {
        if let Some(values) = values {
            tags.push((tag, TagData::Doubles(values)));
        }
    }
    let bytes = tagged_tiff::<Gray32Float>(4, 3, &heights, &tags);
    load_bytes(&bytes, 1.0, "dem.tif").expect("loads")
}

fn georef(field: &Heightfield) -> Georef {
    match field.georeferencing() {
        Georeferencing::Map(georef) => *georef,
        other => panic!("not georeferenced: {other:?}"),
    }
}

#[test]
fn a_projected_geotiff_in_metres_places_its_samples_at_pixel_centres() {
    // Pixel (0, 0)'s top-left corner at (500000, 4600000), 30 m east and 20 m south per pixel.
    let field = dem(
        Some(&[30.0, 20.0, 0.0]),
        Some(&[0.0, 0.0, 0.0, 500_000.0, 4_600_000.0, 0.0]),
        None,
        &[(MODEL_TYPE, 1)],
    );
    let g = georef(&field);
    assert_eq!(g.units, MapUnits::Linear { metres: 1.0 });
    // Sample (0, 0) is the bottom-left pixel (row 2), its centre 2.5 pixels below the top.
    assert_eq!(g.origin, [500_015.0, 4_600_000.0 - 2.5 * 20.0]);
    assert_eq!(
        g.map_point(3.0, 2.0),
        [500_000.0 + 3.5 * 30.0, 4_600_000.0 - 0.5 * 20.0]
    );
    assert_eq!(field.cell_metres(), Some([30.0, 20.0]));
    // Heights are the file's: the top-left pixel (value 100) is sample (0, 2).
    assert_eq!(field.z(0, 2), 100.0);
    assert_eq!(field.z(3, 0), 100.0 + 10.0 * 11.0);
}

#[test]
fn a_tiepoint_off_the_first_pixel_and_pixel_is_point_move_the_origin() {
    // Tiepoint at raster (1, 1) -> (1000, 2000); PixelIsPoint: samples sit on the tiepoints.
    let field = dem(
        Some(&[2.0, 4.0, 0.0]),
        Some(&[1.0, 1.0, 0.0, 1000.0, 2000.0, 0.0]),
        None,
        &[(MODEL_TYPE, 1), (RASTER_TYPE, 2)],
    );
    let g = georef(&field);
    // Image column 0 is 1 pixel west of the tiepoint, row 2 (field row 0) one pixel south.
    assert_eq!(g.origin, [998.0, 1996.0]);
}

#[test]
fn feet_become_metres() {
    for (unit, metres) in [(9002, 0.3048), (9003, 1200.0 / 3937.0)] {
        let field = dem(
            Some(&[10.0, 10.0, 0.0]),
            Some(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
            None,
            &[(MODEL_TYPE, 1), (LINEAR_UNITS, unit)],
        );
        assert_eq!(
            field.cell_metres(),
            Some([10.0 * metres, 10.0 * metres]),
            "unit {unit}"
        );
    }
}

#[test]
fn a_geographic_tile_at_60_north_has_cells_half_as_wide_as_high() {
    // 3 rows of 1-second pixels whose middle row is centred on 60 N.
    let second = 1.0 / 3600.0;
    let field = dem(
        Some(&[second, second, 0.0]),
        Some(&[0.0, 0.0, 0.0, 10.0, 60.0 + 1.5 * second, 0.0]),
        None,
        &[(MODEL_TYPE, 2)],
    );
    assert_eq!(georef(&field).units, MapUnits::Degrees);
    let [x, y] = field.cell_metres().unwrap();
    // On the WGS 84 ellipsoid a degree of longitude spans N cos(phi) where one of latitude
    // spans M: the ratio is cos(phi) (1 - e^2 sin^2 phi) / (1 - e^2) = 0.50084 at 60 N.
    let e2 = 0.006_694_379_990_141_317_f64;
    let ratio = 0.5 * (1.0 - e2 * 0.75) / (1.0 - e2);
    assert!((x / y - ratio).abs() < 1e-6, "{x} / {y}");
    // About 30.95 m: a second of latitude at 60 N (a degree spans 111.41 km there).
    assert!((y - 30.948).abs() < 1e-3, "{y}");
}

#[test]
fn a_north_up_transformation_equals_scale_and_tiepoint() {
    let by_tiepoint = dem(
        Some(&[30.0, 20.0, 0.0]),
        Some(&[0.0, 0.0, 0.0, 500_000.0, 4_600_000.0, 0.0]),
        None,
        &[(MODEL_TYPE, 1)],
    );
    #[rustfmt::skip]
    let matrix = [
        30.0, 0.0, 0.0, 500_000.0,
        0.0, -20.0, 0.0, 4_600_000.0,
        0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
    ];
    let by_matrix = dem(None, None, Some(&matrix), &[(MODEL_TYPE, 1)]);
    assert_eq!(georef(&by_matrix), georef(&by_tiepoint));
}

#[test]
fn rotated_transforms_and_unknown_units_fall_back_to_a_plain_image_with_the_reason() {
    #[rustfmt::skip]
    let rotated = [
        30.0, 5.0, 0.0, 500_000.0,
        5.0, -20.0, 0.0, 4_600_000.0,
        0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
    ];
    let scale = [1.0, 1.0, 0.0];
    let tie = [0.0; 6];
    let cases: [(Heightfield, &str); 4] = [
        (
            dem(None, None, Some(&rotated), &[(MODEL_TYPE, 1)]),
            "rotated",
        ),
        (
            dem(
                Some(&scale),
                Some(&tie),
                None,
                &[(MODEL_TYPE, 1), (LINEAR_UNITS, 9036)],
            ),
            "unknown",
        ),
        (
            dem(Some(&scale), Some(&tie), None, &[(MODEL_TYPE, 3)]),
            "neither projected",
        ),
        (dem(Some(&scale), None, None, &[(MODEL_TYPE, 1)]), "without"),
    ];
    for (field, reason) in cases {
        match field.georeferencing() {
            Georeferencing::Ignored(why) => assert!(why.contains(reason), "{why}"),
            other => panic!("expected '{reason}', got {other:?}"),
        }
        assert_eq!(field.cell_metres(), None);
        assert_eq!(field.z(0, 2), 100.0);
    }
}

#[test]
fn an_hgt_tile_reads_back_as_written_and_is_placed_by_its_name() {
    // 3x3 big-endian heights, north row first, one of them SRTM's void.
    let heights: [i16; 9] = [10, 20, 30, -5, -32768, 1500, 7, 8, 9];
    let bytes: Vec<u8> = heights.iter().flat_map(|h| h.to_be_bytes()).collect();
    let field = load_bytes(&bytes, 1.0, "tiles/N45W123.hgt").expect("loads");
    assert_eq!((field.width(), field.height()), (3, 3));
    for (k, &h) in heights.iter().enumerate() {
        let (i, j) = (k % 3, 2 - k / 3);
        if h == -32768 {
            assert!(field.is_nodata(i, j));
        } else {
            assert_eq!(field.z(i, j), f64::from(h), "sample ({i}, {j})");
        }
    }
    let g = georef(&field);
    assert_eq!(
        (g.origin, g.spacing, g.units),
        ([-123.0, 45.0], [0.5, 0.5], MapUnits::Degrees)
    );
}

#[test]
fn an_hgt_tile_of_no_square_size_or_place_is_explained() {
    let error = load_bytes(&[0u8; 10], 1.0, "N45W123.hgt")
        .unwrap_err()
        .to_string();
    assert!(error.contains("2 n^2 bytes"), "{error}");
    let field = load_bytes(&[0u8; 8], 1.0, "dem.hgt").expect("loads");
    match field.georeferencing() {
        Georeferencing::Ignored(why) => assert!(why.contains("N45W123"), "{why}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn an_ascii_grid_reads_back_as_written_with_its_corner_and_cells() {
    let text =
        "ncols 3\nNROWS 2\nxllcorner 1000.0\nyllcorner 2000\ncellsize 10\nNODATA_value -9999\n\
                1.5 2 3\n-9999 5 6.25\n";
    let field = load_bytes(text.as_bytes(), 1.0, "grid.asc").expect("loads");
    assert_eq!((field.width(), field.height()), (3, 2));
    // The top row is field row 1.
    assert!(field.is_nodata(0, 0));
    for (i, j, h) in [
        (0, 1, 1.5),
        (1, 1, 2.0),
        (2, 1, 3.0),
        (1, 0, 5.0),
        (2, 0, 6.25),
    ] {
        assert!(
            (field.z(i, j) - h).abs() <= 0.5 * field.step(),
            "({i}, {j})"
        );
    }
    let g = georef(&field);
    assert_eq!((g.origin, g.spacing), ([1005.0, 2005.0], [10.0, 10.0]));
    assert_eq!(g.units, MapUnits::Linear { metres: 1.0 });
    // Centre coordinates name the sample itself; tiny cells within lon/lat bounds are degrees.
    let text = "ncols 2\nnrows 2\nxllcenter 10\nyllcenter 60\ncellsize 0.001\n1 2\n3 4\n";
    let g = georef(&load_bytes(text.as_bytes(), 1.0, "grid.asc").expect("loads"));
    assert_eq!((g.origin, g.units), ([10.0, 60.0], MapUnits::Degrees));
}

#[test]
fn a_broken_ascii_grid_is_explained() {
    for (text, says) in [
        (
            "ncols 3\nnrows 2\ncellsize 1\n1 2 3\n4\n",
            "ends after 4 of 6",
        ),
        (
            "ncols 3\nnrows 2\ncolour 1\n1 2 3\n",
            "unknown header key 'colour'",
        ),
        ("ncols 3\nnrows x\n", "'x' is not a number"),
        ("ncols 2\nnrows 2\n1 2 abc 4\n", "'abc' is not a number"),
        ("ncols 1\nnrows 2\n1 2\n", "at least 2x2"),
        (
            &format!("ncols 2\nnrows 2\n1 2{}", " ".repeat(1 << 21)),
            "blank space",
        ),
        (
            &format!("ncols 2\nnrows 2\n1 2 {}", "9".repeat(300)),
            "longer than 256 bytes",
        ),
    ] {
        let error = load_bytes(text.as_bytes(), 1.0, "grid.asc")
            .unwrap_err()
            .to_string();
        assert!(
            error.contains(says) && error.contains("grid.asc"),
            "{error}"
        );
    }
}
