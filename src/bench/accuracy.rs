//! What accuracy costs in time: per method and arithmetic, time per ray, queries per ray, and
//! how far the answers are from exact arithmetic on the same rays.

use super::ray_sets::RaySet;
use crate::arith::Arith;
use crate::render::timing::{fastest, timed, TIMING_BUDGET};
use crate::render::{view_pixel_differences, PixelRow, Scene, View};
use crate::traverse::{covered_cells, trace, Counters, Hit, Method, TraceOptions};
use crate::Terrain;
use std::collections::HashSet;
use std::time::Duration;

/// One method and arithmetic measured on every ray of a set.
#[derive(Clone, Debug)]
pub struct AccuracyRow {
    /// The ray set's name.
    pub set: String,
    /// The traversal method.
    pub method: Method,
    /// The arithmetic traced in.
    pub arith: Arith,
    /// Rays in the set.
    pub rays: u64,
    /// Rays that hit the terrain.
    pub hits: u64,
    /// All the rays, traced one after the other: the fastest pass.
    pub time: Duration,
    /// The queries of all the rays, summed.
    pub counters: Counters,
    /// How the answers differ from exact arithmetic on the same method (if measured).
    pub versus_exact: Option<Disagreement>,
    /// Cells the exact walk covers that this walk did not (if exact was measured).
    pub skipped_cells: Option<u64>,
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
    /// Answers that differ in any way counted here.
    pub fn total(&self) -> u64 {
        self.hit_or_miss + self.cell_or_triangle + self.t_error
    }

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

/// Traces every ray of `set` with each method and arithmetic, one thread, and compares each
/// with exact arithmetic (if among `ariths`): answers, and cells of the exact walk skipped.
pub fn accuracy(
    set: &RaySet,
    methods: &[Method],
    ariths: &[Arith],
    progress: &mut dyn FnMut(),
) -> Vec<AccuracyRow> {
    let mut rows = Vec::new();
    for &method in methods {
        let mut answers = Vec::new();
        for &arith in ariths {
            let options = TraceOptions::new(method, arith);
            let trace_all = || {
                let traces = set
                    .rays
                    .iter()
                    .map(|ray| trace(&set.terrain, ray, &options));
                traces.collect::<Vec<_>>()
            };
            let measured = fastest(TIMING_BUDGET, || timed(trace_all));
            let (traces, time) = (measured.out, measured.fastest);
            let mut counters = Counters::default();
            for t in &traces {
                counters += t.counters;
            }
            rows.push(AccuracyRow {
                set: set.name.clone(),
                method,
                arith,
                rays: set.rays.len() as u64,
                hits: traces.iter().filter(|t| t.hit.is_some()).count() as u64,
                time,
                counters,
                versus_exact: None,
                skipped_cells: None,
            });
            answers.push(traces.into_iter().map(|t| t.hit).collect::<Vec<_>>());
            progress();
        }
        let first = rows.len() - ariths.len();
        let Some(exact) = ariths.iter().position(|&a| a == Arith::Exact) else {
            continue;
        };
        let exact_cells: Vec<HashSet<[usize; 2]>> = set
            .rays
            .iter()
            .map(|ray| {
                covered_cells(&set.terrain, ray, method, Arith::Exact)
                    .into_iter()
                    .collect()
            })
            .collect();
        for (k, row) in rows[first..].iter_mut().enumerate() {
            row.versus_exact = Some(Disagreement::between(&answers[k], &answers[exact]));
            let skipped = set.rays.iter().zip(&exact_cells).map(|(ray, want)| {
                let got: HashSet<_> = covered_cells(&set.terrain, ray, method, row.arith)
                    .into_iter()
                    .collect();
                want.difference(&got).count() as u64
            });
            row.skipped_cells = Some(skipped.sum());
        }
    }
    rows
}

/// Renders `scene` in each arithmetic and counts pixels that differ from the exact render
/// (which is rendered too, whether or not `ariths` names it).
pub fn pixel_differences(
    scene: &Scene,
    terrain: &Terrain,
    methods: &[Method],
    ariths: &[Arith],
    progress: &mut dyn FnMut(),
) -> Vec<PixelRow> {
    let mut rows = Vec::new();
    for &method in methods {
        let view = View {
            terrain,
            camera: scene.camera,
            lighting: scene.lighting,
            method,
        };
        // Never cancelled, so always complete.
        let measured = view_pixel_differences(&view, ariths, &|| false, &mut |_| progress());
        rows.extend(measured.unwrap_or_default());
    }
    rows
}
