//! A header that promises a 100000x100000 image is refused without allocating for it: every
//! allocation made while loading such files is recorded, and none may be large.

// (It uses a few of the shared functions; the suite uses the rest.)
#[allow(dead_code)]
mod common;

use common::files::{png_header, tiff_header};
use heightray::heightfield::load_bytes;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, remembering the largest single allocation.
struct Recording;

static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Recording {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::SeqCst);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::SeqCst);
        System.realloc(ptr, layout, new_size)
    }
}

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
        LARGEST.store(0, Ordering::SeqCst);
        let result = load_bytes(&bytes, 1.0, name);
        let largest = LARGEST.load(Ordering::SeqCst);
        assert!(result.is_err(), "{name} loaded");
        assert!(
            largest < 1 << 20,
            "{name}: an allocation of {largest} bytes"
        );
    }
}
