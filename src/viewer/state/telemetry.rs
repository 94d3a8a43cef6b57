//! What the viewer measures and reports: latencies, a lowered render size, messages.

use super::loads::Progress;
use crate::heightfield::store::residency::{self, ProcessMemory, Residency};
use crate::heightfield::Heightfield;
use crate::viewer::compose::HeatScale;
use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// How often a tile store's figures are measured again while the view redraws: reading the
/// process's status each redraw would cost more than showing it.
const STORE_EVERY: Duration = Duration::from_millis(500);

/// The most pixels a view is rendered at (2048x2048, a 2560x1600 screen's fit): a larger
/// window shows the frame scaled up, and a frame's memory (24 bytes a pixel, up to three
/// frames alive) stays about 300 MB whatever size the window is given.
pub const MOST_VIEW_PIXELS: f64 = (1u64 << 22) as f64;

/// A view rendered at fewer pixels than the window shows it at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capped {
    /// The render size at full resolution.
    pub render: (u32, u32),
    /// The view's size in window pixels.
    pub shown: (u32, u32),
}

impl std::fmt::Display for Capped {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "rendering at {}x{}, shown at {}x{} (at most {:.1} million pixels are rendered)",
            self.render.0,
            self.render.1,
            self.shown.0,
            self.shown.1,
            MOST_VIEW_PIXELS / 1e6
        )
    }
}

/// The tile store the map on screen is mapped from: its size, and the memory its watcher and
/// the kernel count, as last measured.
#[derive(Clone, Copy, Debug)]
pub struct StoreFigures {
    /// Its samples.
    pub samples: u64,
    /// Its file's bytes.
    pub bytes: u64,
    /// Its pages resident, as the watcher saw them.
    pub residency: Residency,
    /// The process's resident memory and page faults.
    pub memory: ProcessMemory,
    /// When they were measured.
    pub at: Instant,
}

/// Times from an input to the first frame on screen that shows its effect.
#[derive(Clone, Debug, Default)]
pub struct Latency {
    recent: VecDeque<f64>,
    pub count: u64,
    pub max_ms: f64,
}

impl Latency {
    const KEEP: usize = 240;

    pub fn record(&mut self, latency: Duration) {
        let ms = latency.as_secs_f64() * 1e3;
        if self.recent.len() == Self::KEEP {
            self.recent.pop_front();
        }
        self.recent.push_back(ms);
        self.count += 1;
        self.max_ms = self.max_ms.max(ms);
    }

    /// The recent samples, oldest first.
    pub fn recent(&self) -> impl Iterator<Item = f64> + '_ {
        self.recent.iter().copied()
    }

    pub fn last_ms(&self) -> Option<f64> {
        self.recent.back().copied()
    }

    /// Median and 95th percentile of the recent samples.
    pub fn percentiles(&self) -> Option<(f64, f64)> {
        let mut sorted: Vec<f64> = self.recent.iter().copied().collect();
        if sorted.is_empty() {
            return None;
        }
        sorted.sort_by(f64::total_cmp);
        let at = |q: f64| sorted[((sorted.len() - 1) as f64 * q).round() as usize];
        Some((at(0.5), at(0.95)))
    }
}

/// A short message shown over the view.
#[derive(Clone, Debug)]
pub struct Notice {
    pub text: String,
    pub at: Instant,
}

impl Notice {
    /// `text`, shown from now.
    pub fn now(text: impl Into<String>) -> Notice {
        Notice {
            text: text.into(),
            at: Instant::now(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latency_percentiles_of_recent_samples() {
        let mut latency = Latency::default();
        assert_eq!(latency.percentiles(), None);
        for ms in 1..=100 {
            latency.record(Duration::from_millis(ms));
        }
        let (median, p95) = latency.percentiles().expect("samples");
        assert!((median - 50.0).abs() <= 1.0 && (p95 - 95.0).abs() <= 1.0);
        assert_eq!(latency.max_ms, 100.0);
        assert_eq!(latency.last_ms(), Some(100.0));
    }
}

/// What the viewer measures as it runs, for the panels and the report.
#[derive(Clone, Debug, Default)]
pub struct Telemetry {
    /// The load under way.
    pub progress: Option<Progress>,
    /// The heat map scale of the frame on screen, with the frame's generation and passes.
    pub heat_scale: Option<(u64, usize, HeatScale)>,
    pub latency: Latency,
    /// Time the window thread spent on each redraw (UI, compositing, presenting).
    pub redraw: Latency,
    /// Set while the view renders at fewer pixels than it shows.
    pub capped: Option<Capped>,
    /// The figures of the tile store on screen, if the map is one.
    pub store: Option<StoreFigures>,
}

impl Telemetry {
    /// Measures the tile store `field` is mapped from again, where it is one and its figures
    /// are older than [`STORE_EVERY`] or another store's.
    pub fn measure_store(&mut self, field: &Heightfield) {
        let Some(bytes) = field.store_bytes() else {
            self.store = None;
            return;
        };
        let samples = (field.width() * field.height()) as u64;
        let fresh = |s: &StoreFigures| {
            (s.bytes, s.samples) == (bytes, samples) && s.at.elapsed() < STORE_EVERY
        };
        if self.store.as_ref().is_some_and(fresh) {
            return;
        }
        self.store = Some(StoreFigures {
            samples,
            bytes,
            residency: residency::residency(),
            memory: residency::process_memory(),
            at: Instant::now(),
        });
    }
}
