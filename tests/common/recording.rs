//! A global allocator that records what a piece of work allocates: its largest single
//! allocation, and the peak of memory in use above what was in use when it started. A test
//! binary installs it with `#[global_allocator]`; its tests measure one at a time.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

/// The system allocator, counting.
pub struct Recording;

static LARGEST: AtomicUsize = AtomicUsize::new(0);
static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn grew(by: usize) {
    let now = IN_USE.fetch_add(by, Ordering::SeqCst) + by;
    PEAK.fetch_max(now, Ordering::SeqCst);
}

unsafe impl GlobalAlloc for Recording {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::SeqCst);
        let ptr = System.alloc(layout);
        if !ptr.is_null() {
            grew(layout.size());
        }
        ptr
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        IN_USE.fetch_sub(layout.size(), Ordering::SeqCst);
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::SeqCst);
        let moved = System.realloc(ptr, layout, new_size);
        if !moved.is_null() {
            // Counted as the new block in use before the old one is freed, as a move is.
            grew(new_size);
            IN_USE.fetch_sub(layout.size(), Ordering::SeqCst);
        }
        moved
    }
}

/// What a piece of work allocated, in bytes.
#[derive(Clone, Copy, Debug)]
pub struct Allocated {
    pub largest: usize,
    pub peak: usize,
}

/// Runs `work` alone (other measurements wait) and returns what it allocated.
pub fn measure<T>(work: impl FnOnce() -> T) -> (T, Allocated) {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(PoisonError::into_inner);
    let before = IN_USE.load(Ordering::SeqCst);
    LARGEST.store(0, Ordering::SeqCst);
    PEAK.store(before, Ordering::SeqCst);
    let result = work();
    let allocated = Allocated {
        largest: LARGEST.load(Ordering::SeqCst),
        peak: PEAK.load(Ordering::SeqCst).saturating_sub(before),
    };
    (result, allocated)
}

/// Runs `work` while no measurement runs: preparing a large input (a file of millions of
/// strips) must not count in another test's peak.
#[allow(dead_code)] // (Not every test binary prepares large inputs.)
pub fn alone<T>(work: impl FnOnce() -> T) -> T {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(PoisonError::into_inner);
    work()
}
