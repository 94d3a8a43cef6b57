//! Mosaics: ESRI ASCII tiles written by the test, joined by a scene's `paths` into one field
//! whose samples are the tiles' values where they lie, and no data in the gaps; tiles that
//! are not on one grid are refused with the reason.

use heightray::heightfield::MapUnits;
use heightray::render::Scene;
use std::path::Path;

/// A 3x3 ESRI ASCII grid of 10 m cells, its lower-left corner at `(x, y)`, holding
/// `first, first + 1, ...` in image order.
fn write_tile(dir: &Path, name: &str, (x, y): (f64, f64), cell: f64, first: i32) {
    let rows: Vec<String> = (0..3)
        .map(|r| {
            (0..3)
                .map(|c| (first + 3 * r + c).to_string())
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    let text = format!(
        "ncols 3\nnrows 3\nxllcorner {x}\nyllcorner {y}\ncellsize {cell}\nNODATA_value -9999\n{}\n",
        rows.join("\n")
    );
    std::fs::write(dir.join(name), text).unwrap();
}

fn load(dir: &Path, paths: &[&str]) -> Result<Scene, String> {
    let scene = format!("[heightmap]\npaths = {paths:?}\nz_scale = 1.0\n");
    let path = dir.join("mosaic.toml");
    std::fs::write(&path, scene).unwrap();
    Scene::load(&path).map_err(|e| e.to_string())
}

#[test]
fn adjacent_tiles_join_into_one_field_with_no_data_in_the_gaps() {
    let dir = tempfile::tempdir().unwrap();
    // West (1000..1030, 2000..2030), east beside it, and one north of the east tile, leaving
    // the north-west 3x3 samples uncovered.
    write_tile(dir.path(), "w.asc", (1000.0, 2000.0), 10.0, 100);
    write_tile(dir.path(), "e.asc", (1030.0, 2000.0), 10.0, 200);
    write_tile(dir.path(), "ne.asc", (1030.0, 2030.0), 10.0, 300);
    let field = load(dir.path(), &["w.asc", "e.asc", "ne.asc"])
        .unwrap()
        .field;
    assert_eq!((field.width(), field.height()), (6, 6));
    let georef = field.georef().unwrap();
    // Sample (0, 0) is the west tile's lower-left cell centre.
    assert_eq!(georef.origin, [1005.0, 2005.0]);
    assert_eq!(georef.spacing, [10.0, 10.0]);
    assert_eq!(georef.units, MapUnits::Linear { metres: 1.0 });
    // A tile's row r (from the top) and column c hold first + 3 r + c; sample row j counts
    // from the south.
    let expected = |i: usize, j: usize| -> Option<f64> {
        let (tile_first, c, j_in) = match (i, j) {
            (0..=2, 0..=2) => (100, i, j),
            (3..=5, 0..=2) => (200, i - 3, j),
            (3..=5, 3..=5) => (300, i - 3, j - 3),
            _ => return None,
        };
        let r = 2 - j_in;
        Some(f64::from(tile_first + 3 * r as i32 + c as i32))
    };
    for j in 0..6 {
        for i in 0..6 {
            match expected(i, j) {
                Some(value) => {
                    assert!(!field.is_nodata(i, j), "({i}, {j})");
                    assert_eq!(field.z(i, j), value, "({i}, {j})");
                }
                None => assert!(field.is_nodata(i, j), "({i}, {j}) is a gap"),
            }
        }
    }
}

#[test]
fn tiles_not_on_one_grid_are_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    write_tile(dir.path(), "a.asc", (1000.0, 2000.0), 10.0, 1);
    write_tile(dir.path(), "coarse.asc", (1030.0, 2000.0), 20.0, 1);
    write_tile(dir.path(), "shifted.asc", (1035.0, 2000.0), 10.0, 1);
    let mut pgm = b"P5\n3 3\n255\n".to_vec();
    pgm.extend([0u8; 9]);
    std::fs::write(dir.path().join("plain.pgm"), pgm).unwrap();
    for (other, says) in [
        ("coarse.asc", "different cell sizes"),
        ("shifted.asc", "not on one grid"),
        ("plain.pgm", "not georeferenced"),
    ] {
        let error = load(dir.path(), &["a.asc", other]).expect_err(other);
        assert!(
            error.contains("cannot join") && error.contains(says),
            "{other}: {error}"
        );
    }
    let both = "[heightmap]\npath = \"a.asc\"\npaths = [\"a.asc\"]\n";
    std::fs::write(dir.path().join("both.toml"), both).unwrap();
    let error = Scene::load(&dir.path().join("both.toml"))
        .err()
        .unwrap()
        .to_string();
    assert!(error.contains("not both"), "{error}");
}
