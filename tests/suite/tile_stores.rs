//! Tile stores (`heightray prepare`): a store of a mosaic holds the mosaic's samples and holes,
//! and renders and traces exactly as the mosaic loaded in memory does, in every arithmetic and
//! with a budget that lets go of pages all the time; a store larger than 2^31 samples, sparse
//! on disk, traces as its tile alone does; an unfinished, truncated or damaged store is
//! refused with a message.

use crate::common::options;
use heightray::heightfield::store::{self, residency};
use heightray::heightfield::{load, LoadOptions};
use heightray::{trace, Arith, Method, Ray, Terrain};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::process::Command;

/// An ESRI ASCII grid of `w x h` 30 m cells with its lower-left cell at cell `(i0, j0)` of a
/// grid from (1000, 5000), holding `z(i, j)` (whole metres), no data where `z` is `None`.
fn write_tile(
    path: &Path,
    (i0, j0): (usize, usize),
    (w, h): (usize, usize),
    z: impl Fn(usize, usize) -> Option<i32>,
) {
    let mut text = format!(
        "ncols {w}\nnrows {h}\nxllcorner {}\nyllcorner {}\ncellsize 30\nNODATA_value -9999\n",
        1000 + 30 * i0,
        5000 + 30 * j0
    );
    for r in 0..h {
        let j = j0 + h - 1 - r;
        let row: Vec<String> = (i0..i0 + w)
            .map(|i| z(i, j).unwrap_or(-9999).to_string())
            .collect();
        text += &row.join(" ");
        text.push('\n');
    }
    std::fs::write(path, text).unwrap();
}

/// Rolling hills with a hole in the north-east tile.
fn hills(i: usize, j: usize) -> Option<i32> {
    let (x, y) = (i as f64, j as f64);
    let hole = (170..180).contains(&i) && (115..125).contains(&j);
    (!hole).then(|| (100.0 + 40.0 * (x / 17.0).sin() * (y / 13.0).cos() + (x * y) % 7.0) as i32)
}

/// Four tiles of 151x103 samples overlapping by a column and a row (where the first given
/// wins), with a gap in the north-west corner; the paths in the order given.
fn mosaic(dir: &Path) -> Vec<PathBuf> {
    let tiles = [(0, 0), (150, 0), (0, 102), (150, 102)];
    tiles
        .iter()
        .enumerate()
        .map(|(k, &at)| {
            let path = dir.join(format!("t{k}.asc"));
            // A later tile's overlap holds other heights: the first tile's must win.
            write_tile(&path, at, (151, 103), |i, j| {
                let gap = k == 2 && i < 20 && j > 180;
                (!gap).then_some(())?;
                hills(i, j).map(|z| z + 3 * k as i32)
            });
            path
        })
        .collect()
}

fn prepare(inputs: &[PathBuf], output: &Path) -> store::Header {
    let keep_going = |_, _| ControlFlow::Continue(());
    store::prepare(inputs, output, &LoadOptions::new(1.0), &keep_going).unwrap()
}

fn heightray(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn a_store_of_a_mosaic_holds_its_samples_and_renders_its_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let tiles = mosaic(dir.path());
    let hrt = dir.path().join("map.hrt");
    let header = prepare(&tiles, &hrt);
    let options = LoadOptions::new(2.0);
    let in_memory =
        heightray::heightfield::load_mosaic(&tiles, &options, &|_| ControlFlow::Continue(()))
            .unwrap();
    let stored =
        heightray::heightfield::load_with(&hrt, &options, &|_| ControlFlow::Continue(())).unwrap();
    assert!(stored.is_mapped() && !in_memory.is_mapped());
    assert_eq!(
        (stored.width(), stored.height()),
        (in_memory.width(), in_memory.height())
    );
    assert_eq!(stored.samples(), in_memory.samples());
    assert_eq!(stored.quantisation(), in_memory.quantisation());
    assert_eq!(stored.georef(), in_memory.georef());
    assert_eq!(stored.nodata_count(), in_memory.nodata_count());
    assert_eq!(header.holes, Some(in_memory.nodata_count() as u64));
    for j in 0..stored.height() {
        for i in 0..stored.width() {
            assert_eq!(
                stored.is_nodata(i, j),
                in_memory.is_nodata(i, j),
                "({i}, {j})"
            );
        }
    }
    let (a, b) = (Terrain::new(in_memory), Terrain::new(stored));
    assert_eq!(a.max_slope(), b.max_slope());
    assert_eq!(a.z_range(), b.z_range());

    // The same pictures, pixel for pixel, from the scene on the tiles and on the store, with
    // a budget so small that the watcher lets go of the store's pages as the rays read them.
    let scene = |map: &str| {
        format!(
            "[heightmap]\n{map}\nexaggeration = 3.0\n[sun]\ndirection = [0.5, 0.2, 0.4]\n\
             [effects]\nshadows = true\n"
        )
    };
    let names: Vec<String> = tiles
        .iter()
        .map(|t| format!("{:?}", t.display().to_string()))
        .collect();
    std::fs::write(
        dir.path().join("tiles.toml"),
        scene(&format!("paths = [{}]", names.join(", "))),
    )
    .unwrap();
    std::fs::write(dir.path().join("store.toml"), scene("path = \"map.hrt\"")).unwrap();
    for arith in ["f32", "f64", "exact"] {
        let render = |name: &str, memory: &str| {
            let out = dir.path().join(format!("{name}-{arith}.png"));
            let scene = dir.path().join(format!("{name}.toml"));
            let output = heightray(&[
                "render",
                scene.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--size",
                "160x100",
                "--arith",
                arith,
                "--memory",
                memory,
            ]);
            assert!(
                output.status.success(),
                "{}",
                String::from_utf8_lossy(&output.stderr)
            );
            std::fs::read(out).unwrap()
        };
        assert_eq!(render("tiles", "4G"), render("store", "4K"), "{arith}");
    }
}

#[test]
fn a_store_larger_than_two_to_the_31_samples_is_sparse_and_traces_as_its_tile() {
    let dir = tempfile::tempdir().unwrap();
    // Two 65x65 tiles at opposite corners of a 50001x50001 grid: 2.5e9 samples, almost all
    // gaps.
    let (near, far) = (dir.path().join("near.asc"), dir.path().join("far.asc"));
    let z = |i: usize, j: usize| Some(((i * 37 + j * 91) % 53) as i32 + 10 * (i % 5) as i32);
    write_tile(&near, (0, 0), (65, 65), z);
    write_tile(&far, (49936, 49936), (65, 65), |i, j| {
        z(i - 49936, j - 49936)
    });
    let hrt = dir.path().join("big.hrt");
    prepare(&[near.clone(), far], &hrt);
    let stored = load(&hrt, 1.0).unwrap();
    assert_eq!((stored.width(), stored.height()), (50001, 50001));
    assert!(stored.width() as u64 * stored.height() as u64 > 1 << 31);
    let metadata = std::fs::metadata(&hrt).unwrap();
    use std::os::unix::fs::MetadataExt;
    assert!(metadata.len() > 7_000_000_000, "{}", metadata.len());
    assert!(
        metadata.blocks() * 512 < 200_000_000,
        "{} bytes on disk",
        metadata.blocks() * 512
    );

    // Rays from above the near tile, in exact arithmetic: the same hits as on the tile alone
    // (whole metres, step 1, so the same heights).
    let (big, alone) = (
        Terrain::new(stored),
        Terrain::new(load(&near, 1.0).unwrap()),
    );
    let mut hits = 0;
    for k in 0..200 {
        let (x, y) = (2.0 + (k % 20) as f64 * 3.1, 2.0 + (k / 20) as f64 * 6.1);
        let ray = Ray::new([x, y, 150.0], [0.05, -0.03, -1.0]).unwrap();
        for arith in [Arith::Exact, Arith::F64] {
            let on = |terrain: &Terrain| trace(terrain, &ray, &options(Method::Mipmap, arith)).hit;
            let (a, b) = (on(&big), on(&alone));
            assert_eq!(
                a.as_ref().map(|h| (h.t, h.cell)),
                b.as_ref().map(|h| (h.t, h.cell)),
                "{arith:?} {ray:?}"
            );
            hits += usize::from(a.is_some());
        }
    }
    assert!(hits > 300, "{hits} hits");
    assert!(residency::budget() > 0);
}

#[test]
fn unfinished_truncated_and_damaged_stores_are_refused_with_a_message() {
    let dir = tempfile::tempdir().unwrap();
    let tiles = mosaic(dir.path());
    let hrt = dir.path().join("map.hrt");
    prepare(&tiles, &hrt);
    let bytes = std::fs::read(&hrt).unwrap();
    let refused = |name: &str, bytes: &[u8]| {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        load(&path, 1.0).unwrap_err().to_string()
    };
    let cut = refused("cut.hrt", &bytes[..bytes.len() / 2]);
    assert!(
        cut.contains("is truncated") && cut.contains("heightray prepare"),
        "{cut}"
    );
    let mut garbled = bytes.clone();
    garbled[40..60].fill(b'#');
    let damaged = refused("garbled.hrt", &garbled);
    assert!(damaged.contains("damaged tile store"), "{damaged}");
    let header = refused("header.hrt", &bytes[..100]);
    assert!(header.contains("damaged tile store"), "{header}");

    // A preparation cancelled part way is refused until it is run again, which finishes it.
    let part = dir.path().join("part.hrt");
    let stop_writing = |stage, _| match stage {
        store::Stage::Building => ControlFlow::Break(()),
        _ => ControlFlow::Continue(()),
    };
    let stopped = store::prepare(&tiles, &part, &LoadOptions::new(1.0), &stop_writing);
    assert!(stopped.unwrap_err().to_string().contains("cancelled"));
    let unfinished = load(&part, 1.0).unwrap_err().to_string();
    assert!(
        unfinished.contains("not prepared to the end"),
        "{unfinished}"
    );
    prepare(&tiles, &part);
    assert_eq!(
        std::fs::read(&part).unwrap(),
        bytes,
        "finished as if never stopped"
    );

    // An output that is not a store, an input say, is refused and left as it was.
    let input = std::fs::read(&tiles[0]).unwrap();
    let keep_going = |_, _| ControlFlow::Continue(());
    let onto_input = store::prepare(&tiles, &tiles[0], &LoadOptions::new(1.0), &keep_going);
    let message = onto_input.unwrap_err().to_string();
    assert!(message.contains("is not a tile store"), "{message}");
    assert_eq!(
        std::fs::read(&tiles[0]).unwrap(),
        input,
        "the input is untouched"
    );

    let output = heightray(&[
        "render",
        dir.path().join("cut.hrt").to_str().unwrap(),
        "-o",
        dir.path().join("cut.png").to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("is truncated"), "{message}");
}

#[test]
fn a_store_let_go_of_while_four_threads_trace_answers_as_the_map_in_memory() {
    let dir = tempfile::tempdir().unwrap();
    let field = heightray::heightfield::landscape(1025, 3, 60.0).unwrap();
    let hrt = dir.path().join("land.hrt");
    store::save(&field, &hrt).unwrap();
    // Every look of the watcher (each 20 ms while over half the budget) lets go of every page
    // not pinned.
    residency::set_budget(4096);
    let stored =
        heightray::heightfield::load_with(&hrt, &LoadOptions::new(field.z_scale()), &|_| {
            ControlFlow::Continue(())
        })
        .unwrap();
    let (memory, mapped) = (Terrain::new(field), Terrain::new(stored));
    let released = residency::residency().released;
    std::thread::scope(|scope| {
        for seed in 0..4u64 {
            let (memory, mapped) = (&memory, &mapped);
            scope.spawn(move || {
                let mut random = crate::common::random::Rng(0x9e37_79b9 + seed);
                for _ in 0..4000 {
                    let o = [
                        random.within(-50.0, 1100.0),
                        random.within(-50.0, 1100.0),
                        random.within(70.0, 200.0),
                    ];
                    let d = [
                        random.within(-1.0, 1.0),
                        random.within(-1.0, 1.0),
                        random.within(-1.0, -0.05),
                    ];
                    let ray = Ray::new(o, d).unwrap();
                    for arith in [Arith::F64, Arith::F32] {
                        let on = |t: &Terrain| trace(t, &ray, &options(Method::Mipmap, arith)).hit;
                        let (a, b) = (on(memory), on(mapped));
                        let key = |h: Option<heightray::Hit>| h.map(|h| (h.t, h.cell));
                        assert_eq!(key(a), key(b), "{ray:?}");
                    }
                }
            });
        }
    });
    assert!(
        residency::residency().released > released,
        "pages were let go of meanwhile"
    );
}
