//! "Compare with exact": the frame on screen rendered again, at its own size, in exact
//! arithmetic, and the pixels where the two differ (for the overlay and the count).

use crate::render::Frame;
use crate::render::{differing_pixels, largest_difference};
use crate::viewer::background::Step;
use crate::viewer::worker::RenderedFrame;
use crate::Arith;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The frame to compare: complete, as shown.
pub struct CompareJob {
    pub frame: Arc<RenderedFrame>,
}

/// Where a frame differs from its exact render.
pub struct Comparison {
    /// The generation of the frame compared.
    pub generation: u64,
    /// One flag per pixel of the frame, row-major.
    pub differs: Vec<bool>,
    pub differing: u64,
    /// The largest difference of a colour channel, in display bytes.
    pub largest: u8,
    pub pixels: u64,
    pub exact_time: Duration,
}

/// Renders the frame's view exactly (on the background pool, all threads) and compares.
pub fn run(job: CompareJob, step: &Step<'_, CompareJob, Arc<Comparison>>) {
    let shown = &job.frame;
    let (width, height) = shown.job.camera.size();
    let started = Instant::now();
    // A frame rendered exactly is its own exact render.
    let exact = if shown.job.arith == Arith::Exact {
        None
    } else {
        let renderer = shown.job.renderer(Arith::Exact);
        let mut exact = Frame::new(width, height);
        // The scene's samples, adaptive as the frame shown took them.
        step.report(0.0, "exact render".into(), None, false);
        if !renderer.render_cancellable(&mut exact, &|| step.cancelled()) {
            return;
        }
        Some(exact)
    };
    let mut differs = vec![false; shown.frame.pixels.len()];
    if let Some(exact) = &exact {
        for k in differing_pixels(&shown.frame.pixels, &exact.pixels) {
            differs[k] = true;
        }
    }
    let comparison = Comparison {
        generation: shown.generation,
        differing: differs.iter().filter(|&&d| d).count() as u64,
        largest: exact.as_ref().map_or(0, |exact| {
            largest_difference(&shown.frame.pixels, &exact.pixels)
        }),
        pixels: differs.len() as u64,
        differs,
        exact_time: started.elapsed(),
    };
    step.report(1.0, "done".into(), Some(Arc::new(comparison)), true);
}
