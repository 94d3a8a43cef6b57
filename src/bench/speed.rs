//! Rays per second of whole frames: primary and shadow rays, per scene, method, arithmetic
//! and thread count, measured in one run so the rows compare as ratios.

use crate::render::{Culling, Frame, FrameStats, Renderer, Scene, Shader};
use crate::traverse::{Arith, Counters, Method};
use crate::Terrain;
use std::time::{Duration, Instant};

/// One configuration measured.
#[derive(Clone, Debug)]
pub struct ThroughputRow {
    pub method: Method,
    pub arith: Arith,
    pub threads: usize,
    pub primary_rays: u64,
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

/// Renders the scene's view with and without shadows for each configuration; `progress` is
/// told after each one.
pub fn throughput(
    scene: &Scene,
    terrain: &Terrain,
    methods: &[Method],
    ariths: &[Arith],
    threads: &[usize],
    progress: &mut dyn FnMut(),
) -> anyhow::Result<Vec<ThroughputRow>> {
    let mut rows = Vec::new();
    for &method in methods {
        for &arith in ariths {
            for &count in threads {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(count).build()?;
                // The fastest of as many frames as fit in 1.5 s (at least one): the least
                // disturbed by whatever else the machine does (on a shared machine a
                // disturbance can last a second).
                let time = |shadows: bool| {
                    let mut lighting = scene.lighting;
                    lighting.shadows = shadows;
                    let renderer = Renderer {
                        shader: Shader {
                            terrain,
                            lighting,
                            method,
                            culling: Culling::default(),
                        },
                        camera: scene.camera,
                        arith,
                    };
                    let (w, h) = scene.camera.size();
                    let (mut best, mut spent, mut runs) = (Duration::MAX, Duration::ZERO, 0);
                    let mut totals = FrameStats::default();
                    while runs == 0 || spent < Duration::from_millis(1500) {
                        let mut frame = Frame::new(w, h);
                        let start = Instant::now();
                        pool.install(|| renderer.render(&mut frame));
                        let elapsed = start.elapsed();
                        (best, spent, runs, totals) =
                            (best.min(elapsed), spent + elapsed, runs + 1, frame.totals);
                    }
                    (best, totals)
                };
                let (primary_time, plain) = time(false);
                let (total_time, shadowed) = time(true);
                rows.push(ThroughputRow {
                    method,
                    arith,
                    threads: count,
                    primary_rays: plain.primary_rays,
                    shadow_rays: shadowed.shadow_rays,
                    primary_queries: plain.primary,
                    primary_time,
                    total_time,
                });
                progress();
            }
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(shadow_rays: u64, primary_ms: u64, total_ms: u64) -> ThroughputRow {
        ThroughputRow {
            method: Method::Mipmap,
            arith: Arith::F64,
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
