//! Fetching ahead: on a map larger than the processor's caches, a walk waits on memory for each
//! sample and block it reads; asked for early, the reads overlap with the walk's own work.
//!
//! Fetching ahead the samples of blocks larger than 4x4 cells gains nothing more.

/// The samples' size from which the walks fetch ahead. Below it the map stays in the caches
/// (of a machine with a 32 MB last-level cache), and the hints cost more than they save.
pub const FETCH_AHEAD_BYTES: usize = 16 << 20;

/// Part of a row-major array: `rows` rows of `len` values each, the first from index `first` on,
/// each row `stride` values after the one before. A window at the far edge of a grid reaches
/// past it (into the next rows, or past the array's end): it is only ever fetched, and a
/// prefetch cannot fault, so the few wasted hints cost less than clipping every window and
/// checking every index would (a division among them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// Index of the first row's first value.
    pub first: usize,
    /// Values per row.
    pub len: usize,
    /// Rows.
    pub rows: usize,
    /// Values from the start of one row to the start of the next.
    pub stride: usize,
}

impl Window {
    /// Whether index `at` lies in the window.
    #[cfg(test)]
    pub fn contains(&self, at: usize) -> bool {
        (0..self.rows).any(|row| {
            let start = self.first + row * self.stride;
            (start..start + self.len).contains(&at)
        })
    }
    /// Asks the processor to fetch the window's values of `values` into its caches, without
    /// waiting for them: the lines holding each row's first and last value (a row is shorter
    /// than a cache line). (Addresses, not indices: nothing is read, so nothing is checked.)
    #[inline(always)]
    pub fn prefetch<T>(self, values: &[T]) {
        let at = |index: usize| values.as_ptr().wrapping_add(index);
        for row in 0..self.rows {
            let start = self.first + row * self.stride;
            prefetch(at(start));
            prefetch(at(start + self.len - 1));
        }
    }
}

/// A hint to fetch the cache line holding the address `at`; nothing on other processors.
#[inline(always)]
fn prefetch<T>(at: *const T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: SSE is part of every x86-64 processor, and a prefetch reads nothing: it
        // cannot fault, whatever the address.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(at.cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = at;
}
