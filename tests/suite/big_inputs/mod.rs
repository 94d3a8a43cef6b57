//! GeoTIFF inputs read by strips or tiles (`heightray prepare`): a tiled GeoTIFF of more than
//! 2^31 samples, small on disk (most tiles point at one compressed tile of zeros), is prepared
//! in little memory and holds the tiles' samples; small GeoTIFFs, tiled and stripped, with
//! holes, make stores that hold what the whole-file load makes of them and render the same
//! pixels; damaged ones are refused with a message.

use heightray::heightfield::store::{self, Stage};
use heightray::heightfield::{load, load_mosaic, load_with, Heightfield, LoadOptions};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

mod tiff_writer;

use tiff_writer::{deflate, Chunks, Sample, Spec};

fn keep_going(_: Stage, _: f64) -> ControlFlow<()> {
    ControlFlow::Continue(())
}

fn prepare(inputs: &[PathBuf], output: &Path) -> Result<store::Header, String> {
    store::prepare(inputs, output, &LoadOptions::new(1.0), &keep_going).map_err(|e| e.to_string())
}

fn heightray(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args(args)
        .output()
        .unwrap()
}

/// The PNG `heightray render` makes of `map`.
fn render(map: &Path, out: &Path) -> Vec<u8> {
    let output = heightray(&[
        "render",
        map.to_str().unwrap(),
        "--size",
        "64x48",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    std::fs::read(out).unwrap()
}

/// The height of a hill tile's pixel: never zero.
fn hill(c: u32, r: u32) -> f64 {
    f64::from(1000 + (c * 7 + r * 13) % 500 + (c / 3 + r / 5) % 40)
}

/// The side of the big map, its tiles' side and the tiles (column, row) that hold the hill;
/// every other tile is the one tile of zeros. 46400^2 is over 2^31 samples.
const SIDE: u32 = 46400;
const TILE: u32 = 256;
const HILLS: [[u32; 2]; 3] = [[3, 5], [100, 90], [181, 181]];

fn big_spec() -> Spec<'static> {
    Spec {
        size: [SIDE, SIDE],
        chunks: Chunks::Tiles(TILE, TILE),
        sample: Sample::U16,
        nodata: None,
    }
}

/// The big map's value at pixel (column, row).
fn big_z(c: u32, r: u32) -> f64 {
    match HILLS.contains(&[c / TILE, r / TILE]) {
        true => hill(c, r),
        false => 0.0,
    }
}

/// The big GeoTIFF's compressed tiles (blob 0 the tile of zeros, then the hills') and which
/// each tile is.
fn big_blobs() -> (Vec<Vec<u8>>, Vec<usize>) {
    let spec = big_spec();
    let [across, down] = spec.grid();
    let mut blobs = vec![deflate(&vec![0u8; (2 * TILE * TILE) as usize])];
    let mut which = vec![0usize; (across * down) as usize];
    for [ci, cj] in HILLS {
        let k = cj * across + ci;
        which[k as usize] = blobs.len();
        blobs.push(spec.chunk(k, &big_z));
    }
    (blobs, which)
}

fn big_tiff() -> Vec<u8> {
    let (blobs, which) = big_blobs();
    big_spec().file(&blobs, &which)
}

/// Runs `heightray` with `args`, returning whether it succeeded, its error output and the
/// most memory it held resident, in bytes.
fn peak_memory(args: &[&str], dir: &Path) -> (bool, String, u64) {
    let log = dir.join("stderr.txt");
    // wait4 below reaps it, with what it used.
    #[allow(clippy::zombie_processes)]
    let child = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::from(std::fs::File::create(&log).unwrap()))
        .spawn()
        .unwrap();
    let mut status = 0;
    // SAFETY: `rusage` is plain data, and the child's id is waited for once, here.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let pid = unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    assert_eq!(pid, child.id() as i32);
    let ok = libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0;
    let message = std::fs::read_to_string(&log).unwrap();
    (ok, message, usage.ru_maxrss as u64 * 1024)
}

#[test]
fn a_tiled_geotiff_over_two_to_the_31_samples_is_prepared_in_little_memory() {
    let dir = tempfile::tempdir().unwrap();
    let tif = dir.path().join("big.tif");
    std::fs::write(&tif, big_tiff()).unwrap();
    assert!(std::fs::metadata(&tif).unwrap().len() < 2_000_000);
    let hrt = dir.path().join("big.hrt");
    let args = [
        "prepare",
        tif.to_str().unwrap(),
        "-o",
        hrt.to_str().unwrap(),
    ];
    let (ok, message, peak) = peak_memory(&args, dir.path());
    assert!(ok, "{message}");
    // The samples alone take 4.3 GB.
    assert!(peak < 300_000_000, "{peak} bytes resident at most");
    eprintln!("prepare of {SIDE}x{SIDE}: {message} peak resident {peak} bytes");
    use std::os::unix::fs::MetadataExt;
    let on_disk = std::fs::metadata(&hrt).unwrap().blocks() * 512;
    assert!(on_disk < 100_000_000, "{on_disk} bytes on disk");

    let stored = load(&hrt, 1.0).unwrap();
    assert_eq!(
        (stored.width(), stored.height()),
        (SIDE as usize, SIDE as usize)
    );
    assert!(stored.width() as u64 * stored.height() as u64 > 1 << 31);
    assert_eq!(stored.nodata_count(), 0);
    let at = |c: u32, r: u32| stored.sample(c as usize, (SIDE - 1 - r) as usize);
    for [ci, cj] in HILLS {
        for r in cj * TILE..((cj + 1) * TILE).min(SIDE) {
            for c in ci * TILE..((ci + 1) * TILE).min(SIDE) {
                assert_eq!(f64::from(at(c, r)), hill(c, r), "({c}, {r})");
            }
        }
    }
    for k in 0..4000u32 {
        let (c, r) = ((k * 7919) % SIDE, (k * 104_729 + 17) % SIDE);
        assert_eq!(f64::from(at(c, r)), big_z(c, r), "({c}, {r})");
    }
    let georef = stored.georef().unwrap();
    assert_eq!(georef.spacing, [30.0, 30.0]);
    assert_eq!(
        georef.origin,
        [500015.0, 4000000.0 - 30.0 * f64::from(SIDE) + 15.0]
    );

    let png = render(&hrt, &dir.path().join("big.png"));
    assert!(png.starts_with(b"\x89PNG"));
}

/// A map with relief and a hole (its value `hole`), in whole numbers for 16-bit samples.
fn small_z(sample: Sample) -> impl Fn(u32, u32) -> f64 {
    move |c, r| {
        let hole = (40..52).contains(&c) && (30..37).contains(&r);
        let (x, y) = (f64::from(c), f64::from(r));
        let v = 200.0 + 80.0 * (x / 19.0).sin() * (y / 11.0).cos() + (x * y) % 5.0;
        match (sample, hole) {
            (Sample::U16, true) => 0.0,
            (Sample::U16, false) => v.round(),
            (Sample::F32, true) => -9999.0,
            (Sample::F32, false) => f64::from((v * 1.37) as f32),
        }
    }
}

/// Checks that the store `hrt` holds what the whole-file load makes of `field`.
fn assert_same(stored: &Heightfield, field: &Heightfield, what: &str) {
    assert!(stored.is_mapped() && !field.is_mapped());
    assert_eq!(
        (stored.width(), stored.height()),
        (field.width(), field.height())
    );
    assert_eq!(stored.samples(), field.samples(), "{what}");
    assert_eq!(stored.quantisation(), field.quantisation(), "{what}");
    assert_eq!(stored.georef(), field.georef(), "{what}");
    assert_eq!(stored.nodata_count(), field.nodata_count(), "{what}");
    let holes = |f: &Heightfield| -> Vec<(usize, usize)> {
        let (w, h) = (f.width(), f.height());
        let all = (0..h).flat_map(|j| (0..w).map(move |i| (i, j)));
        all.filter(|&(i, j)| f.is_nodata(i, j)).collect()
    };
    assert_eq!(holes(stored), holes(field), "{what}");
}

#[test]
fn small_geotiffs_by_strips_and_tiles_make_the_stores_of_their_whole_file_loads() {
    let dir = tempfile::tempdir().unwrap();
    let options = LoadOptions::new(1.0);
    let whole = |path: &Path| load_with(path, &options, &|_| ControlFlow::Continue(())).unwrap();
    let variants = [
        (
            "tiled-u16",
            Chunks::Tiles(48, 32),
            Sample::U16,
            Some("-9999"),
        ),
        ("striped-u16", Chunks::Strips(7), Sample::U16, None),
        (
            "tiled-f32",
            Chunks::Tiles(32, 16),
            Sample::F32,
            Some("-9999"),
        ),
        ("striped-f32", Chunks::Strips(5), Sample::F32, Some("-9999")),
    ];
    for (k, (name, chunks, sample, nodata)) in variants.into_iter().enumerate() {
        // Unsigned samples: the hole holds 0 (no data where the file says 0).
        let nodata = match sample {
            Sample::U16 => nodata.map(|_| "0"),
            Sample::F32 => nodata,
        };
        let spec = Spec {
            size: [131, 77],
            chunks,
            sample,
            nodata,
        };
        let z = small_z(sample);
        let tif = dir.path().join(format!("{name}.tif"));
        std::fs::write(&tif, spec.of(&z)).unwrap();
        let hrt = dir.path().join(format!("{name}.hrt"));
        let header = prepare(std::slice::from_ref(&tif), &hrt).unwrap();
        let (field, stored) = (whole(&tif), whole(&hrt));
        assert_same(&stored, &field, name);
        assert_eq!(
            header.holes,
            (field.nodata_count() > 0).then_some(field.nodata_count() as u64)
        );
        if nodata.is_some() {
            assert!(field.nodata_count() > 0, "{name}");
        }
        if k % 2 == 0 {
            let a = render(&tif, &dir.path().join(format!("{name}-tif.png")));
            let b = render(&hrt, &dir.path().join(format!("{name}-hrt.png")));
            assert!(a == b, "{name}: the store renders other pixels");
        }
    }

    // The float map as a mosaic of a tiled west half and a stripped east half, overlapping
    // by a column: the store holds what the mosaic loaded in memory holds.
    let z = small_z(Sample::F32);
    let half = |name: &str, x0: u32, w: u32, chunks| {
        let spec = Spec {
            size: [w, 77],
            chunks,
            sample: Sample::F32,
            nodata: Some("-9999"),
        };
        let mut bytes = spec.of(&|c, r| z(c + x0, r));
        // The east half's corner lies x0 cells east: its tiepoint's x.
        let at = bytes
            .windows(8)
            .position(|w| w == 500000.0f64.to_le_bytes())
            .unwrap();
        bytes[at..at + 8].copy_from_slice(&(500000.0 + 30.0 * f64::from(x0)).to_le_bytes());
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    };
    let tiles = [
        half("west.tif", 0, 70, Chunks::Tiles(32, 16)),
        half("east.tif", 69, 62, Chunks::Strips(9)),
    ];
    let hrt = dir.path().join("mosaic.hrt");
    prepare(&tiles, &hrt).unwrap();
    let in_memory = load_mosaic(&tiles, &options, &|_| ControlFlow::Continue(())).unwrap();
    assert_same(&whole(&hrt), &in_memory, "mosaic");

    // Stopped while writing and run again, it is the store made in one go.
    let part = dir.path().join("part.hrt");
    let stop = |stage, f: f64| match stage == Stage::Writing && f > 0.2 {
        true => ControlFlow::Break(()),
        false => ControlFlow::Continue(()),
    };
    let stopped = store::prepare(&tiles, &part, &options, &stop);
    assert!(stopped.unwrap_err().to_string().contains("cancelled"));
    prepare(&tiles, &part).unwrap();
    assert!(std::fs::read(&part).unwrap() == std::fs::read(&hrt).unwrap());
}

#[test]
fn a_damaged_big_geotiff_is_refused_with_a_message() {
    let dir = tempfile::tempdir().unwrap();
    let (blobs, which) = big_blobs();
    let bytes = big_spec().file(&blobs, &which);
    // The tiles' offsets, then their byte counts, follow the tiles (at an even offset).
    let offsets = (8 + blobs.iter().map(Vec::len).sum::<usize>()).next_multiple_of(2);
    let counts = offsets + 4 * which.len();
    let refused = |name: &str, bytes: &[u8]| {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        let message = prepare(
            std::slice::from_ref(&path),
            &dir.path().join(format!("{name}.hrt")),
        )
        .expect_err(name);
        assert!(message.contains(path.to_str().unwrap()), "{message}");
        message
    };
    // The first hill's tile is blob 1, right after the tile of zeros.
    let hill_at = 8 + blobs[0].len();
    let mut garbled = bytes.clone();
    garbled[hill_at + 2..hill_at + 40].fill(0xa5);
    let message = refused("garbled.tif", &garbled);
    assert!(message.contains("truncated or corrupt"), "{message}");

    // A tile offset past the end of the file.
    let mut past = bytes.clone();
    let at = offsets + 4 * 1000;
    past[at..at + 4].copy_from_slice(&4_000_000_000u32.to_le_bytes());
    let message = refused("past.tif", &past);
    assert!(message.contains("past the end of the file"), "{message}");

    // A hill tile's byte count reaching past the end of the file.
    let mut long = bytes.clone();
    let first_hill = which.iter().position(|&b| b == 1).unwrap();
    let at = counts + 4 * first_hill;
    long[at..at + 4].copy_from_slice(&3_000_000u32.to_le_bytes());
    let message = refused("long.tif", &long);
    assert!(message.contains("past the end of the file"), "{message}");

    // Cut in the middle: the directory at its end is gone.
    let message = refused("cut.tif", &bytes[..bytes.len() / 2]);
    assert!(message.contains("truncated or corrupt"), "{message}");
}
