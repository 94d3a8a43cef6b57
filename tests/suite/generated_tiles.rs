//! `heightray generate --window`: a generated map written window by window as GeoTIFF tiles
//! and prepared into a store holds the samples of the map written at once, and those are the
//! generator's own landscape under a normalisation fixed by the seed.

use heightray::heightfield::store;
use heightray::heightfield::{landscape, load_with, LoadOptions};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::process::Command;

fn generate(args: &[&str], output: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_heightray"))
        .arg("generate")
        .args(args)
        .arg("-o")
        .arg(output)
        .output()
        .unwrap()
}

#[test]
fn tiles_of_a_generated_map_join_into_the_map_written_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let (size, seed) = (65, 5);
    let map = ["--size", "65", "--seed", "5"];
    // Uneven windows, so that no tile is like another.
    let (columns, rows) = ([(0, 20), (20, 27), (47, 18)], [(0, 40), (40, 25)]);
    let mut tiles: Vec<PathBuf> = Vec::new();
    for (y, h) in rows {
        for (x, w) in columns {
            let path = dir.path().join(format!("tile_{x}_{y}.tif"));
            let window = format!("{x},{y},{w},{h}");
            let output = generate(&[&map[..], &["--window", &window]].concat(), &path);
            assert!(output.status.success(), "{output:?}");
            tiles.push(path);
        }
    }
    let whole_path = dir.path().join("whole.tif");
    assert!(generate(&map, &whole_path).status.success());
    let hrt = dir.path().join("map.hrt");
    let keep_going = |_, _| ControlFlow::Continue(());
    store::prepare(&tiles, &hrt, &LoadOptions::new(1.0), &keep_going).unwrap();

    let quiet = |_| ControlFlow::Continue(());
    let stored = load_with(&hrt, &LoadOptions::new(1.0), &quiet).unwrap();
    // The 16-bit samples as heights: the whole map's file with a z scale of its maxval.
    let whole = load_with(&whole_path, &LoadOptions::new(65535.0), &quiet).unwrap();
    assert!(stored.is_mapped());
    assert_eq!((stored.width(), stored.height()), (size, size));
    assert_eq!(stored.nodata_count(), 0);
    let (a, b) = (stored.georef().unwrap(), whole.georef().unwrap());
    assert_eq!((a.origin, a.spacing), (b.origin, b.spacing));
    for j in 0..size {
        for i in 0..size {
            assert_eq!(stored.z(i, j), whole.z(i, j), "({i}, {j})");
        }
    }

    // The generator's landscape, normalised over its own range: the same heights, mapped
    // onto 0..65535 by another affine map, so each sample within the two roundings.
    let reference = landscape(size, seed, 1.0).unwrap();
    let at = |value: u16| {
        let k = reference
            .samples()
            .iter()
            .position(|&s| s == value)
            .unwrap();
        whole.z(k % size, k / size)
    };
    let (lo, hi) = (at(0), at(65535));
    assert!(hi - lo > 60000.0, "the fixed range is too wide: {lo}..{hi}");
    for j in 0..size {
        for i in 0..size {
            let expected = lo + f64::from(reference.sample(i, j)) / 65535.0 * (hi - lo);
            let got = whole.z(i, j);
            assert!(
                (got - expected).abs() <= 2.0,
                "({i}, {j}): {got} for {expected}"
            );
        }
    }
}

#[test]
fn a_window_off_the_map_or_into_a_png_is_refused_with_a_reason() {
    let dir = tempfile::tempdir().unwrap();
    let tif = dir.path().join("t.tif");
    let off = generate(&["--size", "100", "--window", "90,0,20,20"], &tif);
    let message = String::from_utf8_lossy(&off.stderr);
    assert!(!off.status.success() && message.contains("not inside the 100x100 map"));
    let png = generate(&["--window", "0,0,20,20"], &dir.path().join("t.png"));
    let message = String::from_utf8_lossy(&png.stderr);
    assert!(!png.status.success() && message.contains("name the output .tif"));
    let big = generate(&["--size", "20000"], &dir.path().join("big.png"));
    let message = String::from_utf8_lossy(&big.stderr);
    assert!(!big.status.success() && message.contains("window by window"));
    assert!(!tif.exists());
}
