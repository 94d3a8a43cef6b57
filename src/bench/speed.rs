//! Rays per second of whole frames: primary and shadow rays, per scene, method, arithmetic
//! and thread count, measured in one run so the rows compare as ratios.

use crate::arith::Arith;
use crate::render::timing::{fastest, timed};
use crate::render::{Culling, Frame, FrameStats, Renderer, Scene, Shader};
use crate::traverse::{Counters, Method};
use crate::Terrain;
use std::time::Duration;

/// What traces a configuration's frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tracer {
    /// One of heightray's methods in one arithmetic.
    Heightray(Method, Arith),
    /// One of the [`Reference`] tracers, by its index among them (Embree's, in the
    /// comparison).
    Reference(usize),
}

/// A tracer other than heightray's that renders the same frames: the same pixels, shading and
/// shadow rays, traced its own way (Embree, with the `embree` feature).
pub trait Reference: Sync {
    /// Its name in the tables.
    fn name(&self) -> String;
    /// Renders every pixel of `renderer`'s view into `frame` on the current rayon pool.
    fn render(&self, renderer: &Renderer<'_>, frame: &mut Frame);
}

/// One configuration measured.
#[derive(Clone, Debug)]
pub struct ThroughputRow {
    /// What traced the frames.
    pub tracer: Tracer,
    /// Threads of the rayon pool the frames were rendered on.
    pub threads: usize,
    /// Primary rays of a frame (one per pixel).
    pub primary_rays: u64,
    /// Shadow rays of a frame with shadows.
    pub shadow_rays: u64,
    /// The queries of the primary rays (frame without shadows).
    pub primary_queries: Counters,
    /// The frame without shadows.
    pub primary_time: Duration,
    /// The frame with shadows.
    pub total_time: Duration,
}

impl ThroughputRow {
    /// Primary rays per second (frame without shadows).
    pub fn primary_per_second(&self) -> f64 {
        self.primary_rays as f64 / self.primary_time.as_secs_f64()
    }
    /// Shadow rays per second: the extra time shadows took, per shadow ray; `None` where
    /// there were none, or the frame with shadows was not the slower one (shadows were lost
    /// in the noise of the two times).
    pub fn shadow_per_second(&self) -> Option<f64> {
        let extra = self
            .total_time
            .saturating_sub(self.primary_time)
            .as_secs_f64();
        (self.shadow_rays > 0 && extra > 0.0).then(|| self.shadow_rays as f64 / extra)
    }
}

/// Rounds over all configurations: each time is the fastest frame of any round. On a shared
/// machine a disturbance can last seconds; spread over rounds, a configuration's frames are
/// not all taken inside one, not even a configuration whose one frame takes seconds (the run
/// walk and the DDA on the large maps).
pub const ROUNDS: usize = 3;

/// Frames per configuration and round: as many as fit in this time, at least one.
const ROUND_TIME: Duration = Duration::from_millis(500);

/// Renders the scene's view with and without shadows for each configuration (each method in
/// each arithmetic, then each of `references`, each on every thread count), in [`ROUNDS`]
/// rounds; `progress` is told after each configuration's round.
pub fn throughput(
    scene: &Scene,
    terrain: &Terrain,
    methods: &[Method],
    ariths: &[Arith],
    threads: &[usize],
    references: &[&dyn Reference],
    progress: &mut dyn FnMut(),
) -> anyhow::Result<Vec<ThroughputRow>> {
    let mut pools = Vec::new();
    for &count in threads {
        pools.push(rayon::ThreadPoolBuilder::new().num_threads(count).build()?);
    }
    let ours = methods.iter().flat_map(|&method| {
        ariths
            .iter()
            .map(move |&arith| Tracer::Heightray(method, arith))
    });
    let tracers = ours.chain((0..references.len()).map(Tracer::Reference));
    let mut configs = Vec::new();
    for tracer in tracers {
        for (&count, pool) in threads.iter().zip(&pools) {
            configs.push((tracer, count, pool, [Timing::new(), Timing::new()]));
        }
    }
    for _ in 0..ROUNDS {
        for (tracer, _, pool, timings) in &mut configs {
            for (shadows, timing) in [false, true].into_iter().zip(timings) {
                let renderer = view(scene, terrain, *tracer, shadows);
                let render = |frame: &mut Frame| render_as(*tracer, &renderer, references, frame);
                timing.round(renderer.camera.size(), render, pool);
            }
            progress();
        }
    }
    let rows = configs
        .into_iter()
        .map(|(tracer, threads, _, [plain, shadowed])| ThroughputRow {
            tracer,
            threads,
            primary_rays: plain.totals.primary_rays,
            shadow_rays: shadowed.totals.shadow_rays,
            primary_queries: plain.totals.primary,
            primary_time: plain.best,
            total_time: shadowed.best,
        });
    Ok(rows.collect())
}

/// Renders `renderer`'s view into `frame` as `tracer` traces it (a reference tracer being
/// one of `references`).
pub fn render_as(
    tracer: Tracer,
    renderer: &Renderer<'_>,
    references: &[&dyn Reference],
    frame: &mut Frame,
) {
    match tracer {
        Tracer::Heightray(..) => renderer.render(frame),
        Tracer::Reference(k) => references[k].render(renderer, frame),
    }
}

/// The scene's view as `tracer` renders it, with or without shadows (a reference tracer
/// takes only the camera and shading from it).
pub fn view<'a>(
    scene: &Scene,
    terrain: &'a Terrain,
    tracer: Tracer,
    shadows: bool,
) -> Renderer<'a> {
    let (method, arith) = match tracer {
        Tracer::Heightray(method, arith) => (method, arith),
        Tracer::Reference(_) => (Method::Mipmap, Arith::F64),
    };
    let mut lighting = scene.lighting;
    lighting.shadows = shadows;
    Renderer {
        shader: Shader::new(terrain, lighting, method, Culling::default()),
        camera: scene.camera,
        arith,
    }
}

/// The frames of one configuration so far.
struct Timing {
    best: Duration,
    /// The statistics of a frame (every frame's are the same).
    totals: FrameStats,
}

impl Timing {
    fn new() -> Self {
        Timing {
            best: Duration::MAX,
            totals: FrameStats::default(),
        }
    }

    /// Renders as many frames of `(w, h)` pixels as fit in [`ROUND_TIME`] (at least one).
    fn round(
        &mut self,
        (w, h): (u32, u32),
        render: impl Fn(&mut Frame) + Sync,
        pool: &rayon::ThreadPool,
    ) {
        let round = fastest(ROUND_TIME, || {
            let mut frame = Frame::new(w, h);
            let ((), time) = timed(|| pool.install(|| render(&mut frame)));
            (frame.totals, time)
        });
        (self.best, self.totals) = (self.best.min(round.fastest), round.out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(shadow_rays: u64, primary_ms: u64, total_ms: u64) -> ThroughputRow {
        ThroughputRow {
            tracer: Tracer::Heightray(Method::Mipmap, Arith::F64),
            threads: 1,
            primary_rays: 1000,
            shadow_rays,
            primary_queries: Counters::default(),
            primary_time: Duration::from_millis(primary_ms),
            total_time: Duration::from_millis(total_ms),
        }
    }

    #[test]
    fn shadow_rays_per_second_come_from_the_extra_time_or_are_not_given() {
        // 500 shadow rays in the 250 ms shadows added: 2000 per second.
        assert_eq!(row(500, 1000, 1250).shadow_per_second(), Some(2000.0));
        // Shadows lost in the noise: the frame with them was no slower.
        assert_eq!(row(500, 1000, 1000).shadow_per_second(), None);
        assert_eq!(row(500, 1000, 900).shadow_per_second(), None);
        // No shadow rays at all.
        assert_eq!(row(0, 1000, 1250).shadow_per_second(), None);
        assert_eq!(row(0, 1000, 1000).primary_per_second(), 1000.0);
    }
}
