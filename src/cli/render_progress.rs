//! A long render says so before it starts: the first pass (one pixel in 64) is timed, the
//! whole frame estimated from it, and a frame that looks to take longer than a minute is
//! traced pass by pass with its progress on stderr. A short one runs its remaining passes
//! in one go, as it always did; the image is the same either way.

use heightray::render::{Frame, Renderer, PASS_BLOCKS};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

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

/// Renders all passes of `frame`, first timing the first to say how long the rest may take.
pub fn render_with_estimate(renderer: &Renderer, frame: &mut Frame) {
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
