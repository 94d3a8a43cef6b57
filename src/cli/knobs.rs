//! Numbers a user types that size work: each is range-checked when parsed, so that a digit
//! too many is refused at once instead of running for hours or asking for gigabytes.

use std::ops::RangeInclusive;
use thiserror::Error;

/// A value typed on the command line that the option does not take.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum ValueError {
    /// Not a whole number in the range.
    #[error("expected {what} from {} to {}, got '{got}'", range.start(), range.end())]
    Range {
        /// What the number counts.
        what: &'static str,
        /// The numbers taken.
        range: RangeInclusive<usize>,
        /// The text typed.
        got: String,
    },
    /// Not `WIDTHxHEIGHT` within the limits.
    #[error("expected WIDTHxHEIGHT (1 to 16384 each), got '{0}'")]
    Size(String),
    /// Not three numbers.
    #[error("expected three comma-separated numbers, got '{0}'")]
    Triple(String),
    /// Not four whole numbers.
    #[error("expected X,Y,WIDTH,HEIGHT (four whole numbers), got '{0}'")]
    Window(String),
    /// Not a number.
    #[error("'{0}' is not a number")]
    Number(String),
    /// Not a size in bytes.
    #[error("'{0}' is not a size: give a number above 0, with K, M, G or T after it if wanted (e.g. 4G)")]
    Bytes(String),
    /// Not `HH:MM:SS`.
    #[error("expected HH:MM:SS, got '{0}'")]
    Time(String),
    /// Not a date.
    #[error("'{text}' is not a date such as 2026-03-20 ({reason})")]
    Date {
        /// The text typed.
        text: String,
        /// What the parser said.
        reason: chrono::ParseError,
    },
}

/// The most worker threads asked for on the command line.
pub const MOST_THREADS: usize = 1024;

/// Threads beyond this many per core only add switching, never speed.
const THREADS_PER_CORE: usize = 4;

/// `s` as a whole number in `range`, or a message naming the range.
fn in_range(
    s: &str,
    range: RangeInclusive<usize>,
    what: &'static str,
) -> Result<usize, ValueError> {
    s.trim()
        .parse::<usize>()
        .ok()
        .filter(|n| range.contains(n))
        .ok_or_else(|| ValueError::Range {
            what,
            range,
            got: s.to_owned(),
        })
}

/// A size in bytes: a number, with K, M, G or T (powers of 1024) after it if wanted.
pub fn bytes(s: &str) -> Result<u64, ValueError> {
    let s = s.trim();
    let refused = || ValueError::Bytes(s.to_owned());
    let (number, unit) = s.split_at(s.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(s.len()));
    let scale: u64 = match unit.to_ascii_uppercase().trim_end_matches(['B', 'I']) {
        "" => 1,
        "K" => 1 << 10,
        "M" => 1 << 20,
        "G" => 1 << 30,
        "T" => 1 << 40,
        _ => return Err(refused()),
    };
    number
        .trim()
        .parse::<f64>()
        .ok()
        .filter(|n| n.is_finite() && *n > 0.0)
        .map(|n| (n * scale as f64) as u64)
        .filter(|&b| b > 0)
        .ok_or_else(refused)
}

/// A thread count, 1 to [`MOST_THREADS`].
pub fn threads(s: &str) -> Result<usize, ValueError> {
    in_range(s, 1..=MOST_THREADS, "a number of threads")
}

/// Rays per hard-case set: each is answered exactly too, which takes milliseconds.
pub fn per_set(s: &str) -> Result<usize, ValueError> {
    in_range(s, 1..=1 << 16, "a number of rays per set")
}

/// Samples per side of a generated map made window by window (a million: 10^12 samples).
pub fn generated_map_size(s: &str) -> Result<usize, ValueError> {
    in_range(s, 2..=1_000_000, "samples per side")
}

/// A window `X,Y,WIDTH,HEIGHT` of whole numbers.
pub fn window(s: &str) -> Result<[usize; 4], ValueError> {
    let numbers: Vec<usize> = s
        .split(',')
        .map(|p| p.trim().parse::<usize>())
        .collect::<Result<_, _>>()
        .map_err(|_| ValueError::Window(s.to_owned()))?;
    numbers
        .try_into()
        .map_err(|_| ValueError::Window(s.to_owned()))
}

/// Samples per side of a generated landscape.
pub fn landscape_size(s: &str) -> Result<usize, ValueError> {
    in_range(s, 2..=16385, "samples per side")
}

/// An image's width and height in a benchmark.
pub fn bench_image_size(s: &str) -> Result<u32, ValueError> {
    in_range(s, 1..=4096, "an image width and height").map(|n| n as u32)
}

/// Rounds of a comparison.
pub fn rounds(s: &str) -> Result<usize, ValueError> {
    in_range(s, 1..=1000, "a number of rounds")
}

/// `requested` threads, or at most [`THREADS_PER_CORE`] per core with a note on stderr.
pub fn capped_threads(requested: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let most = THREADS_PER_CORE * cores;
    if requested > most {
        eprintln!(
            "note: {requested} threads asked for on {cores} cores; using {most} \
             ({THREADS_PER_CORE} a core): more only add switching"
        );
        most
    } else {
        requested
    }
}

/// A pool of `threads` workers (default: one a core), capped by [`capped_threads`].
pub fn worker_pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    use anyhow::Context;
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(threads) = threads {
        pool = pool.num_threads(capped_threads(threads));
    }
    pool.build().context("cannot start worker threads")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_outside_their_range_are_refused_with_the_range() {
        assert_eq!(threads("4"), Ok(4));
        let error = threads("10000").unwrap_err().to_string();
        assert!(error.contains("1 to 1024"), "{error}");
        assert!(threads("0").is_err());
        let message = |e: ValueError| e.to_string();
        assert!(message(per_set("100000000").unwrap_err()).contains("65536"));
        assert!(message(landscape_size("0").unwrap_err()).contains("2 to 16385"));
        assert_eq!(window("0, 5000,5000,10"), Ok([0, 5000, 5000, 10]));
        assert!(message(window("1,2,3").unwrap_err()).contains("X,Y,WIDTH,HEIGHT"));
        assert!(window("1,2,-3,4").is_err());
        assert_eq!(bench_image_size("512"), Ok(512));
        assert!(capped_threads(1) == 1);
    }
}
