//! Paths that are not ordinary image files: devices, FIFOs and directories are refused before
//! they are read; an image followed by gigabytes (sparse files) is decoded from its first
//! bytes; a file that only starts like an image is refused as corrupt. Each finishes within a
//! few seconds (a guard fails the test after ten instead of letting it hang), and the memory
//! it allocates, recorded by this binary's allocator, stays far below the file's length.

#[allow(dead_code)]
#[path = "common/files.rs"]
mod files;
#[path = "bounded_reading/hostile_sizes.rs"]
mod hostile_sizes;
#[path = "common/recording.rs"]
mod recording;

use heightray::heightfield::{load_with, LoadOptions};
use heightray::{Heightfield, LoadError};
use image::{GrayImage, Luma};
use recording::{measure, Allocated, Recording};
use std::fs::OpenOptions;
use std::io::Write;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};
use tempfile::TempDir;
use tiff::encoder::colortype::Gray16;

#[global_allocator]
static ALLOCATOR: Recording = Recording;

const GB: u64 = 1_000_000_000;
const MIB: usize = 1 << 20;

/// A load, timed and measured.
struct Outcome {
    result: Result<Heightfield, LoadError>,
    /// Bytes the loading thread read from files (the kernel's count).
    read: u64,
    allocated: Allocated,
    time: Duration,
}

/// Bytes this thread has read from files so far (Linux's `rchar`).
fn bytes_read_by_this_thread() -> u64 {
    let io = std::fs::read_to_string("/proc/thread-self/io").expect("/proc/thread-self/io");
    io.lines()
        .find_map(|line| line.strip_prefix("rchar:"))
        .and_then(|n| n.trim().parse().ok())
        .expect("an rchar line")
}

/// Loads `path`, cancelling once more than `cancel_after` of it has been read; fails the test
/// if that takes more than ten seconds.
fn load_watched(path: &Path, cancel_after: f64) -> Outcome {
    let len = std::fs::metadata(path).map_or(0, |m| m.len());
    let (send, receive) = mpsc::channel();
    let owned = path.to_owned();
    let start = Instant::now();
    // On its own thread, so that a load that hangs fails the test instead of hanging it.
    std::thread::spawn(move || {
        let before = bytes_read_by_this_thread();
        let (result, allocated) = measure(|| {
            let progress = |fraction: f64| {
                if fraction > cancel_after {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            };
            load_with(&owned, &LoadOptions::new(1.0), &progress)
        });
        let read = bytes_read_by_this_thread() - before;
        let _ = send.send((result, read, allocated));
    });
    let (result, read, allocated) = receive
        .recv_timeout(Duration::from_secs(10))
        .unwrap_or_else(|_| panic!("loading {} took more than 10 s", path.display()));
    let outcome = Outcome {
        result,
        read,
        allocated,
        time: start.elapsed(),
    };
    eprintln!(
        "{}: {len} bytes long, {read} bytes read in {:.3} s, peak {} bytes allocated",
        path.display(),
        outcome.time.as_secs_f64(),
        outcome.allocated.peak
    );
    outcome
}

fn load(path: &Path) -> Outcome {
    load_watched(path, f64::INFINITY)
}

/// A file of `head` followed by zeros up to `len` bytes, which take no disk space.
fn sparse(dir: &TempDir, name: &str, head: &[u8], len: u64) -> PathBuf {
    let path = dir.path().join(name);
    let mut file = OpenOptions::new()
        .create(true)
        .truncate(true)
        .write(true)
        .open(&path)
        .expect("create the file");
    file.write_all(head).expect("write its start");
    file.set_len(len).expect("make it sparse");
    path
}

fn error_of(outcome: &Outcome) -> String {
    match &outcome.result {
        Ok(field) => panic!(
            "expected an error, got a {}x{} field",
            field.width(),
            field.height()
        ),
        Err(error) => error.to_string(),
    }
}

/// A 49x49 pattern, as in the image files below.
fn pattern(x: u32, y: u32) -> u16 {
    ((x * 5 + y * 3) % 251) as u16
}

/// Checks that `field` holds the pattern (image row 0 is the field's top row) at `scale`.
fn assert_pattern(field: &Heightfield, scale: u16) {
    assert_eq!((field.width(), field.height()), (49, 49));
    for y in 0..49 {
        for x in 0..49 {
            let expected = pattern(x, y) * scale;
            let got = field.sample(x as usize, 48 - y as usize);
            assert_eq!(got, expected, "sample ({x}, {y}) of the image");
        }
    }
}

/// Asserts that a whole image loaded while only its first bytes were read, in little memory.
fn assert_read_only_the_image(outcome: &Outcome, scale: u16) {
    match &outcome.result {
        Ok(field) => assert_pattern(field, scale),
        Err(error) => panic!("{error}"),
    }
    assert!(outcome.read < MIB as u64, "read {} bytes", outcome.read);
    assert!(
        outcome.allocated.peak < 4 * MIB,
        "{} bytes allocated",
        outcome.allocated.peak
    );
}

#[test]
fn a_png_followed_by_20_gb_loads_from_its_first_bytes() {
    let dir = TempDir::new().unwrap();
    let image = GrayImage::from_fn(49, 49, |x, y| Luma([pattern(x, y) as u8]));
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let path = sparse(&dir, "trailing.png", &png, 20 * GB);
    assert_read_only_the_image(&load(&path), 1);
}

#[test]
fn a_pgm_and_a_tiff_followed_by_20_gb_load_from_their_first_bytes() {
    let dir = TempDir::new().unwrap();
    let mut pgm = b"P5 49 49 255\n".to_vec();
    pgm.extend((0..49 * 49).map(|k| pattern(k % 49, k / 49) as u8));
    let path = sparse(&dir, "trailing.pgm", &pgm, 20 * GB);
    assert_read_only_the_image(&load(&path), 1);

    let samples: Vec<u16> = (0..49 * 49)
        .map(|k| pattern(k % 49, k / 49) * 256)
        .collect();
    let tiff = files::tiff::<Gray16>(49, 49, &samples, None);
    let path = sparse(&dir, "trailing.tif", &tiff, 20 * GB);
    assert_read_only_the_image(&load(&path), 256);
}

/// Each format's signature, or a PNG's whole header, followed by 30 GB of zeros: refused as
/// corrupt, not as too large for memory.
#[test]
fn a_30_gb_file_that_only_starts_like_an_image_is_refused_as_corrupt() {
    let dir = TempDir::new().unwrap();
    let ihdr = files::png_header(49, 49, 8, 0);
    // The signature and IHDR chunk: 8 + 25 bytes.
    let heads: [(&str, &[u8]); 4] = [
        ("signature.png", b"\x89PNG\r\n\x1a\n"),
        ("header.png", &ihdr[..33]),
        ("signature.tif", b"II*\0"),
        ("signature.pgm", b"P5"),
    ];
    for (name, head) in heads {
        let path = sparse(&dir, name, head, 30 * GB);
        let outcome = load(&path);
        let message = error_of(&outcome);
        assert!(
            message.contains(name) && message.contains("truncated or corrupt"),
            "{message}"
        );
        assert!(!message.contains("memory"), "{message}");
        assert!(
            outcome.allocated.peak < 4 * MIB,
            "{name}: {:?}",
            outcome.allocated
        );
    }
}

#[test]
fn a_pgm_promising_more_than_its_file_holds_is_refused_before_allocating() {
    let dir = TempDir::new().unwrap();
    // 900 million samples promised, 10 MB present.
    let path = sparse(&dir, "short.pgm", b"P5 30000 30000 255\n", 10_000_000);
    let outcome = load(&path);
    let message = error_of(&outcome);
    assert!(
        message.contains("short.pgm") && message.contains("truncated: 9999981 of 900000000 bytes"),
        "{message}"
    );
    assert!(outcome.allocated.largest < MIB, "{:?}", outcome.allocated);
}

#[test]
fn a_load_cancelled_while_reading_stops_reading() {
    let dir = TempDir::new().unwrap();
    // 400 MB of samples; the load is cancelled after 1% of the file.
    let head = b"P5 20000 20000 255\n";
    let path = sparse(&dir, "big.pgm", head, head.len() as u64 + 400_000_000);
    let outcome = load_watched(&path, 0.01);
    let message = error_of(&outcome);
    assert!(
        message.contains("big.pgm") && message.contains("cancelled"),
        "{message}"
    );
    // Reading stops at the first read after the 1%: a MiB later at most.
    assert!(
        outcome.read < 4_000_000 + 2 * MIB as u64,
        "read {} bytes",
        outcome.read
    );
    assert!(outcome.read > 4_000_000, "read {} bytes", outcome.read);
}

/// What a path names, for the messages about it.
fn assert_refused(path: &Path, what: &str) {
    let outcome = load(path);
    let message = error_of(&outcome);
    assert!(
        message.contains(&path.display().to_string())
            && message.contains(what)
            && message.contains("not a file")
            && message.contains("choose a height map file"),
        "{message}"
    );
    // (The few bytes read are the kernel's own files: /proc.)
    assert!(
        outcome.read < 4096,
        "{}: {} bytes read",
        path.display(),
        outcome.read
    );
    assert!(outcome.allocated.peak < MIB, "{:?}", outcome.allocated);
}

#[test]
fn devices_fifos_and_directories_are_refused_before_reading() {
    let dir = TempDir::new().unwrap();
    assert_refused(Path::new("/dev/zero"), "is a character device");
    let link = dir.path().join("zeros.png");
    std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
    assert_refused(&link, "is a character device");
    assert_refused(dir.path(), "is a directory");
    // Opening a FIFO for reading would wait for a writer that never comes.
    let fifo = dir.path().join("pipe.png");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("run mkfifo");
    assert!(made.success(), "mkfifo failed");
    assert_refused(&fifo, "is a FIFO (named pipe)");
}
