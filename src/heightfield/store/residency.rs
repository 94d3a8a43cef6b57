//! How much of the open stores stays in memory: the pages the walks touch are read in on
//! demand (the kernel's page cache is the tile cache), and a watcher keeps the process's
//! resident memory within a budget, letting go of the longest-held megabytes of a store first
//! when it nears it. The mipmap's upper levels, which every walk reads, stay pinned. A page
//! let go of is read again, from the page cache or the disk, when a walk next touches it: the
//! answers never change, only the time.

use memmap2::{Mmap, UncheckedAdvice};
use std::ops::Range;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Weak};
use std::time::Duration;

/// The process's resident bytes at most; 0 for the default.
static BUDGET: AtomicU64 = AtomicU64::new(0);

/// The most bytes of mapped files resident at once, as the watchers saw them.
static PEAK: AtomicU64 = AtomicU64::new(0);

/// Bytes of mapped files resident when the watchers last looked.
static RESIDENT: AtomicU64 = AtomicU64::new(0);

/// Bytes of mapped files let go of to stay within the budget.
static RELEASED: AtomicU64 = AtomicU64::new(0);

/// How often a watcher looks while the process is under half the budget.
const EVERY: Duration = Duration::from_millis(250);

/// How often it looks above that: walks touch pages fast, and between two looks the process
/// may grow past the budget.
const CLOSELY: Duration = Duration::from_millis(20);

/// Pages are let go of in chunks of this many bytes.
const CHUNK: usize = 1 << 20;

/// Chunks let go of before the process's memory is looked at again.
const RELEASE_BATCH: usize = 64;

/// Sets the budget of the process's resident memory, in bytes (0: the default, half the
/// machine's memory).
pub fn set_budget(bytes: u64) {
    BUDGET.store(bytes, Ordering::Relaxed);
}

/// The budget of the process's resident memory, in bytes.
pub fn budget() -> u64 {
    match BUDGET.load(Ordering::Relaxed) {
        0 => machine_memory() / 2,
        bytes => bytes,
    }
}

/// What the watchers saw: bytes of mapped files (the stores' pages, and the program's own)
/// resident now, at most, and let go of.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Residency {
    /// Resident when last looked.
    pub resident: u64,
    /// The most resident at once.
    pub peak: u64,
    /// Let go of to stay within the budget.
    pub released: u64,
}

/// What the watchers saw so far.
pub fn residency() -> Residency {
    Residency {
        resident: RESIDENT.load(Ordering::Relaxed),
        peak: PEAK.load(Ordering::Relaxed),
        released: RELEASED.load(Ordering::Relaxed),
    }
}

/// The whole process's memory as the kernel counts it: its resident bytes now and at most,
/// and its page faults served from memory (the page cache) and from the disk.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ProcessMemory {
    /// Bytes resident now (VmRSS), 0 where unknown.
    pub resident: u64,
    /// Bytes of mapped files resident now (RssFile: the stores' pages, and the program's
    /// own), 0 where unknown.
    pub file_resident: u64,
    /// The most bytes resident at once (VmHWM), 0 where unknown.
    pub peak_resident: u64,
    /// Faults on pages already in memory.
    pub minor_faults: u64,
    /// Faults that read a page from the disk.
    pub major_faults: u64,
}

impl ProcessMemory {
    /// The fraction of page faults served from memory: how often a page a walk asked for was
    /// in the page cache (the tile cache) rather than read from the disk; `None` before any.
    pub fn hit_rate(&self) -> Option<f64> {
        let all = self.minor_faults + self.major_faults;
        (all > 0).then(|| self.minor_faults as f64 / all as f64)
    }
}

/// This process's memory so far.
pub fn process_memory() -> ProcessMemory {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let kb = |key: &str| {
        status
            .lines()
            .find_map(|line| line.strip_prefix(key))
            .and_then(|rest| {
                rest.trim()
                    .trim_end_matches("kB")
                    .trim()
                    .parse::<u64>()
                    .ok()
            })
    };
    // SAFETY: getrusage fills the struct it is given; a zeroed `rusage` is a valid one.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: as above, for this process.
    let ok = unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut usage) } == 0;
    let count = |n: libc::c_long| if ok { u64::try_from(n).unwrap_or(0) } else { 0 };
    ProcessMemory {
        resident: kb("VmRSS:").unwrap_or(0) * 1024,
        file_resident: kb("RssFile:").unwrap_or(0) * 1024,
        peak_resident: kb("VmHWM:").unwrap_or(0) * 1024,
        minor_faults: count(usage.ru_minflt),
        major_faults: count(usage.ru_majflt),
    }
}

/// Watches `map` on a thread of its own until it is dropped, keeping the process's resident
/// memory within the budget by letting go of the map's pages, never those in `pinned` (byte
/// ranges of the map).
pub fn watch(map: &Arc<Mmap>, pinned: Vec<Range<usize>>) {
    let map = Arc::downgrade(map);
    let spawned = std::thread::Builder::new()
        .name("store residency".into())
        .spawn(move || Watcher::new(map, &pinned).run());
    // Without a watcher the map still works; only its memory is not held to the budget.
    drop(spawned);
}

/// A map's watcher: for each chunk, the look at which its pages were first seen resident
/// ([`PINNED`] for chunks never let go of).
struct Watcher {
    map: Weak<Mmap>,
    since: Vec<u64>,
    looks: u64,
    /// Per page, what `mincore` said at the last look (kept: a large map's is megabytes).
    pages: Vec<u8>,
}

/// The mark of a pinned chunk.
const PINNED: u64 = u64::MAX - 1;

impl Watcher {
    fn new(map: Weak<Mmap>, pinned: &[Range<usize>]) -> Self {
        let chunks = map.upgrade().map_or(0, |m| m.len().div_ceil(CHUNK));
        let mut since = vec![u64::MAX; chunks];
        for range in pinned {
            let end = range.end.div_ceil(CHUNK).min(chunks);
            since[(range.start / CHUNK).min(end)..end].fill(PINNED);
        }
        Watcher {
            map,
            since,
            looks: 0,
            pages: Vec::new(),
        }
    }

    fn run(mut self) {
        let len = self.map.upgrade().map_or(0, |m| m.len() as u64);
        let mut wait = if len > budget() / 2 { CLOSELY } else { EVERY };
        loop {
            std::thread::sleep(wait);
            let Some(map) = self.map.upgrade() else {
                return;
            };
            let process = self.look(&map);
            wait = if process > budget() / 2 {
                CLOSELY
            } else {
                EVERY
            };
        }
    }

    /// With the process over three quarters of the budget, lets go of the map's chunks held
    /// longest (pinned chunks stay) until the process is at half the budget; returns the
    /// process's bytes resident then. (`mincore` sees the page cache, a superset of the pages
    /// mapped here: chunks are let go of a batch at a time, and the process's own count says
    /// when enough were.)
    fn look(&mut self, map: &Mmap) -> u64 {
        self.looks += 1;
        resident_pages(map, &mut self.pages);
        let per_chunk = CHUNK / page_size();
        let mut held = Vec::new();
        for (k, chunk) in self.pages.chunks(per_chunk).enumerate() {
            match self.since[k] {
                PINNED => {}
                _ if !chunk.iter().any(|&p| p & 1 != 0) => self.since[k] = u64::MAX,
                u64::MAX => {
                    self.since[k] = self.looks;
                    held.push(k);
                }
                _ => held.push(k),
            }
        }
        let budget = budget();
        let mut memory = process_memory();
        if memory.resident > budget / 4 * 3 {
            held.sort_by_key(|&k| self.since[k]);
            for batch in held.chunks(RELEASE_BATCH) {
                for &k in batch {
                    let (at, len) = (k * CHUNK, CHUNK.min(map.len() - k * CHUNK));
                    // SAFETY: the map is a read-only shared mapping of a file: pages let go
                    // of are read again from the file, unchanged, when next touched.
                    let _ =
                        unsafe { map.unchecked_advise_range(UncheckedAdvice::DontNeed, at, len) };
                    self.since[k] = u64::MAX;
                }
                let after = process_memory();
                RELEASED.fetch_add(
                    memory.file_resident.saturating_sub(after.file_resident),
                    Ordering::Relaxed,
                );
                memory = after;
                if memory.resident <= budget / 2 {
                    break;
                }
            }
        }
        RESIDENT.store(memory.file_resident, Ordering::Relaxed);
        PEAK.fetch_max(memory.file_resident, Ordering::Relaxed);
        memory.resident
    }
}

/// Per page of `map`, whether it is resident (bit 0), as `mincore` says, into `pages`; none
/// where it fails.
fn resident_pages(map: &Mmap, pages: &mut Vec<u8>) {
    pages.resize(map.len().div_ceil(page_size()), 0);
    // SAFETY: the range is the whole mapping, page-aligned at its start, and the vector holds
    // one byte per page of it, as mincore writes.
    let ok = unsafe {
        libc::mincore(
            map.as_ptr() as *mut libc::c_void,
            map.len(),
            pages.as_mut_ptr(),
        )
    };
    if ok != 0 {
        pages.clear();
    }
}

/// The machine's page size.
fn page_size() -> usize {
    // SAFETY: sysconf reads a constant of the system.
    let size = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    usize::try_from(size)
        .ok()
        .filter(|&s| s > 0)
        .unwrap_or(4096)
}

/// The machine's memory, in bytes.
fn machine_memory() -> u64 {
    // SAFETY: sysconf reads constants of the system.
    let pages = unsafe { libc::sysconf(libc::_SC_PHYS_PAGES) };
    u64::try_from(pages).unwrap_or(0) * page_size() as u64
}
