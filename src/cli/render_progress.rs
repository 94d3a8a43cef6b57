//! Progress of long renders on stderr. On a terminal, a bar of pixels done with the time
//! taken and left ([`Progress`]). Otherwise (a log file, a scheduler's output) one line per
//! frame or tile, and a long still says so before it starts: the first pass (one pixel in 64)
//! is timed, the whole frame estimated from it, and a frame that looks to take longer than a
//! minute is traced pass by pass with a line every few seconds. The image is the same either
//! way.

use heightray::render::{Frame, Renderer, PASS_BLOCKS};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Pixels done over a run of frames or tiles: a bar on a terminal, else a line per item.
pub struct Progress {
    /// `None` when stderr is not a terminal.
    bar: Option<ProgressBar>,
    start: Instant,
    items: AtomicU64,
}

impl Progress {
    /// Progress over `pixels` pixels in all.
    pub fn new(pixels: u64) -> Progress {
        let bar = std::io::stderr().is_terminal().then(|| {
            let style = ProgressStyle::with_template(
                "{bar:40} {human_pos}/{human_len} pixels, {elapsed} so far, about {eta} left {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            ProgressBar::with_draw_target(Some(pixels), ProgressDrawTarget::stderr())
                .with_style(style)
        });
        Progress {
            bar,
            start: Instant::now(),
            items: AtomicU64::new(0),
        }
    }

    /// Renders `frame` whole, moving the bar as its tiles are traced.
    pub fn render(&self, renderer: &Renderer, frame: &mut Frame) {
        let Some(bar) = &self.bar else {
            return renderer.render(frame);
        };
        let pixels = u64::from(frame.width) * u64::from(frame.height);
        let ticks = renderer.ticks(frame).max(1);
        let seen = AtomicU64::new(0);
        let before = bar.position();
        renderer.render_watched(frame, &|| {
            let k = seen.fetch_add(1, Ordering::Relaxed) + 1;
            bar.set_position(before + (pixels * k / ticks).min(pixels));
        });
        bar.set_position(before + pixels);
    }

    /// Says that an item (a frame or tile, written to `name`) is done: a line when there is
    /// no bar.
    pub fn finished(&self, name: &str) {
        let n = self.items.fetch_add(1, Ordering::Relaxed) + 1;
        match &self.bar {
            Some(bar) => bar.set_message(name.to_owned()),
            None => eprintln!(
                "{n}: {name} written, {:.1} s so far",
                self.start.elapsed().as_secs_f64()
            ),
        }
    }

    /// Clears the bar and says how long it all took.
    pub fn done(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
        eprintln!(
            "{} written in {:.1} s",
            self.items.load(Ordering::Relaxed),
            self.start.elapsed().as_secs_f64()
        );
    }
}

/// An estimate above this is said up front, and progress shown.
const LONG: Duration = Duration::from_secs(60);

/// How often progress is written.
const EVERY: Duration = Duration::from_secs(5);

/// The share of a frame's pixels each pass traces (pass `k` the pixels of the
/// `PASS_BLOCKS[k]` lattice not on a coarser one).
fn share(pass: usize) -> f64 {
    let block = |k: usize| f64::from(PASS_BLOCKS[k]);
    let mine = 1.0 / (block(pass) * block(pass));
    let coarser = if pass == 0 {
        0.0
    } else {
        1.0 / (block(pass - 1) * block(pass - 1))
    };
    mine - coarser
}

/// Renders all passes of `frame`: with a bar on a terminal; otherwise first timing the first
/// pass to say how long the rest may take.
pub fn render_with_estimate(renderer: &Renderer, frame: &mut Frame) {
    if std::io::stderr().is_terminal() {
        let progress = Progress::new(u64::from(frame.width) * u64::from(frame.height));
        progress.render(renderer, frame);
        if let Some(bar) = &progress.bar {
            bar.finish_and_clear();
        }
        return;
    }
    let effects = &renderer.shader.lighting.effects;
    if effects.adaptive && effects.samples > 1 {
        // Traced in rounds over the whole frame, not in passes.
        return renderer.render(frame);
    }
    let tiles = AtomicU64::new(0);
    let start = Instant::now();
    renderer.render_pass(frame, &|| {
        tiles.fetch_add(1, Ordering::Relaxed);
        false
    });
    let first = start.elapsed();
    let estimate = first.as_secs_f64() / share(0);
    if Duration::from_secs_f64(estimate) <= LONG {
        return renderer.render(frame);
    }
    eprintln!(
        "note: this {}x{} render looks to take about {:.0} min (its first pass, 1 pixel in \
         64, took {:.1} s); progress follows",
        frame.width,
        frame.height,
        estimate / 60.0,
        first.as_secs_f64()
    );
    let tiles_a_pass = tiles.load(Ordering::Relaxed).max(1) as f64;
    let mut done = share(0);
    while !frame.complete() {
        let pass = frame.passes_done;
        let seen = AtomicU64::new(0);
        let last = Mutex::new(Instant::now());
        renderer.render_pass(frame, &|| {
            let tile = seen.fetch_add(1, Ordering::Relaxed) as f64;
            if let Ok(mut last) = last.try_lock() {
                if last.elapsed() >= EVERY {
                    *last = Instant::now();
                    let part = (tile / tiles_a_pass).min(1.0) * share(pass);
                    eprintln!(
                        "{:.0}% of the pixels traced, {:.0} s so far",
                        100.0 * (done + part),
                        start.elapsed().as_secs_f64()
                    );
                }
            }
            false
        });
        done += share(pass);
    }
    eprintln!("traced in {:.0} s", start.elapsed().as_secs_f64());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_passes_share_out_every_pixel_once() {
        assert_eq!(share(0), 1.0 / 64.0);
        assert_eq!(share(3), 0.75);
        let all: f64 = (0..PASS_BLOCKS.len()).map(share).sum();
        assert_eq!(all, 1.0);
    }
}
