//! Time per primary ray, queries per ray, and how far each answer is from exact, per method and
//! the number of answers that differ from exact arithmetic when exact is measured too.

use crate::heightfield::Terrain;
use crate::render::Camera;
use crate::traverse::{trace, Arith, Counters, Hit, Method, TraceOptions};
use std::time::{Duration, Instant};

/// One method and arithmetic measured on every pixel of a view.
#[derive(Clone, Debug)]
pub struct AccuracyRow {
    pub method: Method,
    pub arith: Arith,
    pub rays: u64,
    pub hits: u64,
    pub time: Duration,
    pub counters: Counters,
    /// How the answers differ from exact arithmetic on the same method (if measured).
    pub versus_exact: Option<Disagreement>,
}

/// How a set of answers differs from the exact answers to the same rays.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Disagreement {
    /// A hit where exact misses, or the other way round.
    pub hit_or_miss: u64,
    /// Both hit, but another cell or triangle.
    pub cell_or_triangle: u64,
    /// Same cell and triangle, `t` off by more than a relative 1e-9.
    pub t_error: u64,
    /// The largest relative error of `t` among rays hitting the same triangle.
    pub worst_t_error: f64,
}

impl Disagreement {
    /// Compares answers with the exact answers to the same rays.
    pub fn between(answers: &[Option<Hit>], exact: &[Option<Hit>]) -> Disagreement {
        let mut d = Disagreement::default();
        for (a, e) in answers.iter().zip(exact) {
            match (a, e) {
                (None, None) => {}
                (Some(a), Some(e)) if a.cell == e.cell && a.triangle == e.triangle => {
                    let error = (a.t - e.t).abs() / e.t.abs().max(f64::MIN_POSITIVE);
                    d.worst_t_error = d.worst_t_error.max(error);
                    d.t_error += u64::from(error > 1e-9);
                }
                (Some(_), Some(_)) => d.cell_or_triangle += 1,
                _ => d.hit_or_miss += 1,
            }
        }
        d
    }
}

impl AccuracyRow {
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
pub fn accuracy(
    terrain: &Terrain,
    camera: &Camera,
    methods: &[Method],
    ariths: &[Arith],
) -> Vec<AccuracyRow> {
    let (w, h) = camera.size();
    let rays: Vec<_> = (0..h)
        .flat_map(|py| (0..w).map(move |px| (px, py)))
        .map(|(px, py)| camera.ray(px, py))
        .collect();
    let mut rows = Vec::new();
    for &method in methods {
        let mut answers = Vec::new();
        for &arith in ariths {
            let options = TraceOptions::new(method, arith);
            let start = Instant::now();
            let traces: Vec<_> = rays
                .iter()
                .map(|ray| trace(terrain, ray, &options))
                .collect();
            let time = start.elapsed();
            let mut counters = Counters::default();
            for t in &traces {
                counters += t.counters;
            }
            rows.push(AccuracyRow {
                method,
                arith,
                rays: rays.len() as u64,
                hits: traces.iter().filter(|t| t.hit.is_some()).count() as u64,
                time,
                counters,
                versus_exact: None,
            });
            answers.push(traces.into_iter().map(|t| t.hit).collect::<Vec<_>>());
        }
        // Compare with exact, if it was measured.
        let first = rows.len() - ariths.len();
        if let Some(exact) = ariths.iter().position(|&a| a == Arith::Exact) {
            for (k, row) in rows[first..].iter_mut().enumerate() {
                row.versus_exact = Some(Disagreement::between(&answers[k], &answers[exact]));
            }
        }
    }
    rows
}
