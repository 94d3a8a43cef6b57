//! Fetching ahead: on a map larger than the processor's caches, a walk waits on memory for each
//! sample and block it reads; asked for early, the reads overlap with the walk's own work.

/// The samples' size from which the walks fetch ahead. Below it the map stays in the caches of
/// the machines this is measured on (32 MB last-level cache), and the hints bought nothing:
/// with them on at every size, frames with shadows were 3% slower at 513² and 1% slower at
/// 2049², 2% faster at 4097² and 7% faster at 8193².
pub const FETCH_AHEAD_BYTES: usize = 16 << 20;

/// Part of a row-major array: `rows` rows of `len` values each, the first from index `first`
/// on, each row `stride` values after the one before.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    pub first: usize,
    pub len: usize,
    pub rows: usize,
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
    /// One past the window's last index.
    #[cfg(test)]
    pub fn end(&self) -> usize {
        self.first + (self.rows - 1) * self.stride + self.len
    }
    /// Asks the processor to fetch the window's values of `values` into its caches, without
    /// waiting for them: the lines holding each row's first and last value (a row is shorter
    /// than a cache line).
    #[inline(always)]
    pub fn prefetch<T>(self, values: &[T]) {
        for row in 0..self.rows {
            let start = self.first + row * self.stride;
            prefetch(&values[start]);
            prefetch(&values[start + self.len - 1]);
        }
    }
}

/// A hint to fetch the cache line holding `value`; nothing on other processors.
#[inline(always)]
fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: SSE is part of every x86-64 processor, and a prefetch reads nothing: it
        // cannot fault, whatever the address.
        unsafe { _mm_prefetch::<_MM_HINT_T0>((value as *const T).cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}
