//! A header that promises a 100000x100000 image is refused without allocating for it: every
//! allocation made while loading such files is recorded, and none may be large, nor all of
//! them together.

// (It uses a few of the shared functions; the suite uses the rest.)
#[allow(dead_code, unused_imports)]
mod common;
#[path = "common/recording.rs"]
mod recording;

use common::files::{png_header, tiff_header};
use heightray::heightfield::load_bytes;
use recording::{measure, Recording};

#[global_allocator]
static ALLOCATOR: Recording = Recording;

// The only test in this binary, so no other test's allocations are recorded.
#[test]
fn huge_headers_allocate_nothing_large() {
    let files = [
        ("huge.png", png_header(100_000, 100_000, 16, 0)),
        ("huge.tif", tiff_header(100_000, 100_000)),
        ("huge.pgm", b"P2 100000 100000 65535\n1 2 3\n".to_vec()),
        ("ascii.pgm", b"P2 46000 46000 65535\n1 2 3\n".to_vec()),
    ];
    for (name, bytes) in files {
        let (result, allocated) = measure(|| load_bytes(&bytes, 1.0, name));
        assert!(result.is_err(), "{name} loaded");
        assert!(
            allocated.largest < 1 << 20 && allocated.peak < 1 << 20,
            "{name}: {allocated:?}"
        );
    }
}
