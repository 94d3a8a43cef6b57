//! A georeferenced map opened in the viewer is shown at true scale: an SRTM tile at 60 N has
//! cells half as wide as high, its heights are not exaggerated, and the framing holds the
//! whole of its stretched extent.

use super::app::num;
use super::Session;

/// Writes a 5x5 SRTM tile named for 60 N, 10 E: a 1 km hill in the middle.
fn write_tile(path: &std::path::Path) {
    let heights: Vec<i16> = (0..25).map(|k| if k == 12 { 1000 } else { 100 }).collect();
    let bytes: Vec<u8> = heights.iter().flat_map(|h| h.to_be_bytes()).collect();
    std::fs::write(path, bytes).expect("write the tile");
}

#[test]
fn an_srtm_tile_opens_at_true_scale_with_cells_in_metres() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let tile = dir.path().join("N60E010.hgt");
    write_tile(&tile);
    let session = Session::start(&[tile.to_str().expect("a UTF-8 path")]);
    let state = session.state();
    assert_eq!(state["error"], serde_json::Value::Null);
    // Cells a quarter degree apart; the tile's centre is at 60.5 N.
    let (x, y) = (
        num(&state, "/terrain/cell_metres/0"),
        num(&state, "/terrain/cell_metres/1"),
    );
    // On the WGS 84 ellipsoid: a quarter degree of the meridian's radius of curvature M at
    // 60.5 N along y, of the prime vertical's N times cos(latitude) along x.
    let (a, e2) = (6_378_137.0, 0.006_694_379_990_141_317_f64);
    let phi = 60.5f64.to_radians();
    let w = 1.0 - e2 * phi.sin().powi(2);
    let quarter_degree = 0.25f64.to_radians() * a * (1.0 - e2) / w.powf(1.5);
    assert!((y / quarter_degree - 1.0).abs() < 1e-9, "{y}");
    let ratio = phi.cos() * w / (1.0 - e2);
    assert!((x / y - ratio).abs() < 1e-9, "{x} / {y}");
    assert!((num(&state, "/terrain/exaggeration") - 1.0).abs() < 1e-12);
    // One world unit is a cell's height: 900 m of hill over 27.8 km cells.
    assert!((num(&state, "/terrain/z_scale") * y - 1.0).abs() < 1e-12);
}
