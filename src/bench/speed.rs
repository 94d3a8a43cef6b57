//! Time per primary ray and queries per ray, per method and arithmetic, on one view; with
//! the number of answers that differ from exact arithmetic when exact is measured too.

use crate::heightfield::Terrain;
use crate::render::Camera;
use crate::traverse::{trace, Arith, Counters, Hit, Method, TraceOptions};
use std::time::{Duration, Instant};

/// One method and arithmetic measured on every pixel of a view.
#[derive(Clone, Debug)]
pub struct SpeedRow {
    pub method: Method,
    pub arith: Arith,
    pub rays: u64,
    pub hits: u64,
    pub time: Duration,
    pub counters: Counters,
    /// Answers that differ from exact arithmetic on the same method (if measured).
    pub differ_from_exact: Option<u64>,
}

impl SpeedRow {
    /// Nanoseconds per ray.
    pub fn ns_per_ray(&self) -> f64 {
        self.time.as_secs_f64() * 1e9 / self.rays.max(1) as f64
    }
    /// Queries per ray of a counter.
    pub fn per_ray(&self, total: u64) -> f64 {
        total as f64 / self.rays.max(1) as f64
    }
}

/// Traces every pixel's primary ray of `camera` with each method and arithmetic, one thread.
pub fn measure(terrain: &Terrain, camera: &Camera, methods: &[Method], ariths: &[Arith]) -> Vec<SpeedRow> {
    let (w, h) = camera.size();
    let rays: Vec<_> = (0..h).flat_map(|py| (0..w).map(move |px| (px, py))).map(|(px, py)| camera.ray(px, py)).collect();
    let mut rows = Vec::new();
    for &method in methods {
        let mut answers = Vec::new();
        for &arith in ariths {
            let options = TraceOptions::new(method, arith);
            let start = Instant::now();
            let traces: Vec<_> = rays.iter().map(|ray| trace(terrain, ray, &options)).collect();
            let time = start.elapsed();
            let mut counters = Counters::default();
            for t in &traces {
                counters += t.counters;
            }
            rows.push(SpeedRow {
                method,
                arith,
                rays: rays.len() as u64,
                hits: traces.iter().filter(|t| t.hit.is_some()).count() as u64,
                time,
                counters,
                differ_from_exact: None,
            });
            answers.push(traces.into_iter().map(|t| t.hit).collect::<Vec<_>>());
        }
        // Compare with exact, if it was measured.
        let first = rows.len() - ariths.len();
        if let Some(exact) = ariths.iter().position(|&a| a == Arith::Exact) {
            for (k, row) in rows[first..].iter_mut().enumerate() {
                let differ = answers[k].iter().zip(&answers[exact]).filter(|(a, b)| !same_answer(a, b)).count();
                row.differ_from_exact = Some(differ as u64);
            }
        }
    }
    rows
}

/// Same hit or miss, same cell and triangle, and `t` within a relative 1e-9.
pub fn same_answer(a: &Option<Hit>, b: &Option<Hit>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            a.cell == b.cell && a.triangle == b.triangle && (a.t - b.t).abs() <= 1e-9 * b.t.abs().max(1e-300)
        }
        _ => false,
    }
}
