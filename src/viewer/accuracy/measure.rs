//! "Measure all arithmetics": the view on screen rendered small in every arithmetic on one
//! thread, timed, and compared pixel by pixel with its exact render. The rendering and the
//! comparison are the renderer's ([`view_pixel_differences`]), as `bench accuracy` uses them;
//! this adds the choice of size and arithmetics, cancelling, and progress.

use crate::render::CameraError;
use crate::render::Lighting;
use crate::render::{view_pixel_differences, PixelRow, View};
use crate::viewer::background::Step;
use crate::viewer::orbit::Orbit;
use crate::viewer::worker::{RenderJob, RenderedFrame};
use crate::{Arith, Method};
use std::sync::Arc;
use std::time::Instant;

/// The rational bounds measured, as `bench accuracy` has them: 2^4, 2^8, 2^12, 2^16, 2^24.
pub const BOUNDS: [u32; 5] = [1 << 4, 1 << 8, 1 << 12, 1 << 16, 1 << 24];

/// Pixels of the measured frame offered: a full view in bounded rationals would take minutes
/// (a ray costs them 0.1 to 2 ms), so the view is measured at a reduced resolution.
pub const PIXEL_BUDGETS: [u32; 3] = [2_304, 9_216, 36_864];

/// What a measurement depends on: the camera, the terrain, the method and the light. The
/// arithmetic on screen is not part of it: every arithmetic is measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Subject {
    orbit: Orbit,
    /// The terrain's identity: a new load, or a new z scale, is a new allocation.
    terrain: usize,
    method: Method,
    lighting: Lighting,
}

impl Subject {
    pub fn of(job: &RenderJob) -> Subject {
        Subject {
            orbit: job.orbit,
            terrain: Arc::as_ptr(&job.terrain) as usize,
            method: job.method,
            lighting: job.lighting,
        }
    }
}

/// The view to measure and in which arithmetics.
pub struct MeasureJob {
    /// The converged frame whose view is measured.
    pub frame: Arc<RenderedFrame>,
    pub size: (u32, u32),
    /// Besides the exact reference, which is always rendered (first).
    pub ariths: Vec<Arith>,
}

/// What a measurement found so far: one row per arithmetic rendered, the exact one first.
#[derive(Clone, Debug)]
pub struct Measurement {
    pub size: (u32, u32),
    pub rows: Vec<PixelRow>,
    /// Rows there will be when it is done.
    pub planned: usize,
}

impl Measurement {
    /// The row of `arith`, if measured.
    pub fn row(&self, arith: Arith) -> Option<&PixelRow> {
        self.rows.iter().find(|r| r.arith == arith)
    }
}

/// Nanoseconds per pixel of a row: its primary ray and, with shadows on, its shadow ray.
pub fn ns_per_ray(row: &PixelRow) -> f64 {
    row.time.as_secs_f64() * 1e9 / row.pixels.max(1) as f64
}

/// A short name: f32, f64, `rational 2^k` (or `rational N` for other bounds), exact.
pub fn label(arith: Arith) -> String {
    match arith {
        Arith::Rational { bound } if bound.is_power_of_two() => {
            format!("rational 2^{}", bound.trailing_zeros())
        }
        Arith::Rational { bound } => format!("rational {bound}"),
        other => other.to_string(),
    }
}

/// The arithmetics to measure besides exact: f32, f64, the bench's rational bounds, and the
/// bound on screen if it is another one.
pub fn ariths(shown: Arith) -> Vec<Arith> {
    let mut bounds = BOUNDS.to_vec();
    if let Arith::Rational { bound } = shown {
        if !bounds.contains(&bound) {
            bounds.push(bound);
            bounds.sort_unstable();
        }
    }
    let rationals = bounds.into_iter().map(|bound| Arith::Rational { bound });
    [Arith::F32, Arith::F64]
        .into_iter()
        .chain(rationals)
        .collect()
}

/// The size of a frame of about `budget` pixels with the aspect ratio of `view` (never larger
/// than the view).
pub fn reduced_size((width, height): (u32, u32), budget: u32) -> (u32, u32) {
    let pixels = f64::from(width.max(1)) * f64::from(height.max(1));
    let scale = (f64::from(budget) / pixels).sqrt().min(1.0);
    let side = |v: u32| ((f64::from(v.max(1)) * scale).round() as u32).max(1);
    (side(width), side(height))
}

impl MeasureJob {
    /// Measures the view of `frame` at about `budget` pixels.
    pub fn new(frame: Arc<RenderedFrame>, budget: u32) -> MeasureJob {
        let size = reduced_size(frame.job.camera.size(), budget);
        let ariths = ariths(frame.job.arith);
        MeasureJob {
            frame,
            size,
            ariths,
        }
    }
}

/// Runs a measurement (on the background pool it is given: one thread), reporting each row.
pub fn run(job: MeasureJob, step: &Step<'_, MeasureJob, Measurement>) {
    let render_job = &job.frame.job;
    let camera = match render_job.orbit.camera(job.size) {
        Ok(camera) => camera,
        Err(error) => return fail(step, &error),
    };
    let view = View {
        terrain: &render_job.terrain,
        camera,
        lighting: render_job.lighting,
        method: render_job.method,
    };
    let mut measurement = Measurement {
        size: job.size,
        rows: Vec::new(),
        planned: job.ariths.len() + 1,
    };
    let started = Instant::now();
    let status = |done: usize| match [Arith::Exact].iter().chain(&job.ariths).nth(done) {
        Some(next) => format!(
            "rendering in {next} ({} of {})",
            done + 1,
            job.ariths.len() + 1
        ),
        None => format!("done in {:.1} s", started.elapsed().as_secs_f64()),
    };
    step.report(0.0, status(0), None, false);
    let finished = view_pixel_differences(&view, &job.ariths, &|| step.cancelled(), &mut |row| {
        measurement.rows.push(row.clone());
        let done = measurement.rows.len();
        let fraction = done as f32 / measurement.planned as f32;
        step.report(fraction, status(done), Some(measurement.clone()), false);
    });
    if finished.is_some() {
        let done = measurement.rows.len();
        step.report(1.0, status(done), Some(measurement), true);
    }
}

fn fail(step: &Step<'_, MeasureJob, Measurement>, error: &CameraError) {
    step.report(
        1.0,
        format!("cannot measure this view: {error}"),
        None,
        true,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_measurement_is_of_the_same_view_whatever_arithmetic_is_on_screen() {
        let field = crate::heightfield::Builtin::named("small49")
            .and_then(|b| b.load().ok())
            .expect("decodes");
        let terrain = Arc::new(crate::Terrain::new(field));
        let orbit = Orbit::framing(&terrain);
        let job = |orbit: Orbit, method, arith| RenderJob {
            terrain: Arc::clone(&terrain),
            orbit,
            camera: orbit.camera((16, 16)).expect("a camera"),
            lighting: crate::viewer::settings::Settings::default().lighting(),
            method,
            arith,
            contours: None,
            view_id: 0,
        };
        let measured = Subject::of(&job(orbit, Method::Runs, Arith::F64));
        let exact = Subject::of(&job(orbit, Method::Runs, Arith::Exact));
        assert_eq!(measured, exact, "only the arithmetic changed");
        let turned = Orbit {
            yaw_deg: orbit.yaw_deg + 5.0,
            ..orbit
        };
        assert_ne!(
            measured,
            Subject::of(&job(turned, Method::Runs, Arith::F64))
        );
        assert_ne!(measured, Subject::of(&job(orbit, Method::Dda, Arith::F64)));
    }

    #[test]
    fn reduced_size_keeps_the_aspect_and_the_budget() {
        assert_eq!(reduced_size((1280, 720), 2_304), (64, 36));
        assert_eq!(reduced_size((40, 30), 2_304), (40, 30));
        assert_eq!(reduced_size((10_000, 1), 100), (1000, 1));
    }

    #[test]
    fn every_arithmetic_once_with_the_shown_bound() {
        let names = |a: Vec<Arith>| a.iter().map(ToString::to_string).collect::<Vec<_>>();
        assert_eq!(ariths(Arith::F64).len(), 2 + BOUNDS.len());
        let with_shown = names(ariths(Arith::Rational { bound: 1000 }));
        assert_eq!(with_shown[2..4], ["rational:16", "rational:256"]);
        assert_eq!(with_shown[4], "rational:1000");
        assert_eq!(
            ariths(Arith::Rational { bound: 256 }).len(),
            2 + BOUNDS.len()
        );
    }
}
