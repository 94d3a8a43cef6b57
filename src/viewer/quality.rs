//! Resolution while the view moves: the first pass after a camera move must land within a
//! frame or two, so while the view changes continuously the render size drops to what the
//! last first passes say fits the budget; when the view rests it renders at full resolution.

use super::compose::PixelRect;
use super::orbit::Orbit;
use super::state::{Model, MOST_VIEW_PIXELS};
use super::worker::RenderedFrame;
use crate::render::Lighting;
use crate::{Arith, Method};
use std::time::{Duration, Instant};

/// Time the first pass of a moving view should take.
const BUDGET_MS: f64 = 8.0;
/// Changes closer together than this make a continuous move.
const REST: Duration = Duration::from_millis(150);
/// Lowest resolution factor while moving.
const MIN_FACTOR: f64 = 0.3;
/// What a render shows, apart from a resolution lowered while moving.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewKey {
    /// The full-resolution render size (the window's view area times the render scale, at
    /// most [`MOST_VIEW_PIXELS`]).
    full_size: (u32, u32),
    /// Whether the render size was lowered to [`MOST_VIEW_PIXELS`].
    capped: bool,
    terrain: usize,
    orbit: Orbit,
    lighting: Lighting,
    method: Method,
    arith: Arith,
    contours: Option<crate::render::Contours>,
}

impl ViewKey {
    pub fn new(model: &Model, view: PixelRect) -> ViewKey {
        let (w, h) = Quality::full_size(view, model.settings.render_scale);
        let (full_size, capped) = capped_size(w, h);
        ViewKey {
            full_size,
            capped,
            // The terrain's identity: a new load is a new allocation.
            terrain: std::sync::Arc::as_ptr(&model.shown.terrain) as usize,
            orbit: model.orbit,
            lighting: model.settings.lighting(),
            method: model.settings.method,
            arith: model.settings.arith(),
            contours: model.widgets.contours.lines(model.shown.terrain.field()),
        }
    }

    /// The full-resolution render size.
    pub fn full_size(&self) -> (u32, u32) {
        self.full_size
    }

    /// Whether the view renders at fewer pixels than it shows, to stay within
    /// [`MOST_VIEW_PIXELS`].
    pub fn capped(&self) -> bool {
        self.capped
    }
}

/// A render size of `w` x `h` pixels, scaled down (keeping its shape) to at most
/// [`MOST_VIEW_PIXELS`]; and whether it was.
fn capped_size(w: f64, h: f64) -> ((u32, u32), bool) {
    let cap = (MOST_VIEW_PIXELS / (w * h).max(1.0)).sqrt().min(1.0);
    // Rounded up as ever; down when capped, so that the limit holds.
    let size = |v: f64| {
        let scaled = v * cap;
        (if cap < 1.0 {
            scaled.floor()
        } else {
            scaled.ceil()
        } as u32)
            .max(1)
    };
    ((size(w), size(h)), cap < 1.0)
}

/// What a render shows, at which size.
#[derive(Clone, Debug, PartialEq)]
pub struct JobKey {
    pub view: ViewKey,
    pub size: (u32, u32),
}

/// Decides the render size from how the view is changing.
#[derive(Clone, Debug)]
pub struct Quality {
    /// First-pass milliseconds per million pixels, smoothed.
    ms_per_mpixel: Option<f64>,
    last_change: Option<Instant>,
    /// The resolution factor, chosen when the view changes and kept until the next change:
    /// recomputing it as estimates move would restart the render for nothing.
    factor: f64,
    view_id: u64,
}

impl Default for Quality {
    fn default() -> Self {
        Quality {
            ms_per_mpixel: None,
            last_change: None,
            factor: 1.0,
            view_id: 0,
        }
    }
}

impl Quality {
    /// The view changed; `held` says a drag is in progress.
    pub fn changed(&mut self, held: bool, view: &ViewKey) {
        let pixels = f64::from(view.full_size.0) * f64::from(view.full_size.1);
        let now = Instant::now();
        let moving = held || self.last_change.is_some_and(|t| now - t < REST);
        self.factor = match (moving, self.ms_per_mpixel) {
            (true, Some(ms)) => {
                let predicted = ms * pixels / 1e6;
                (BUDGET_MS / predicted.max(1e-9))
                    .sqrt()
                    .clamp(MIN_FACTOR, 1.0)
            }
            _ => 1.0,
        };
        self.last_change = Some(now);
        self.view_id += 1;
    }

    /// Returns to full resolution once the view has rested and no drag is held.
    pub fn settle(&mut self, held: bool) {
        if !held && self.rest_deadline().is_some_and(|t| Instant::now() >= t) {
            self.factor = 1.0;
        }
    }

    /// When to look again whether the view has come to rest.
    pub fn rest_deadline(&self) -> Option<Instant> {
        self.last_change
            .filter(|_| self.factor < 1.0)
            .map(|t| t + REST)
    }

    pub fn view_id(&self) -> u64 {
        self.view_id
    }

    /// Learns from a first pass how long the next ones will take.
    pub fn first_pass(&mut self, rendered: &RenderedFrame) {
        let pixels = f64::from(rendered.frame.width) * f64::from(rendered.frame.height);
        let (Some(time), true) = (rendered.pass_times.first(), pixels > 0.0) else {
            return;
        };
        let sample = time.as_secs_f64() * 1e3 / (pixels / 1e6);
        self.ms_per_mpixel = Some(match self.ms_per_mpixel {
            Some(old) => 0.7 * old + 0.3 * sample,
            None => sample,
        });
    }

    /// The full-resolution render size of a view of `view` window pixels.
    fn full_size(view: PixelRect, render_scale: f32) -> (f64, f64) {
        let scale = f64::from(render_scale.clamp(0.05, 4.0));
        (
            f64::from(view.width) * scale,
            f64::from(view.height) * scale,
        )
    }

    /// The render size of a view now.
    pub fn render_size(&self, view: &ViewKey) -> (u32, u32) {
        let size = |v: u32| ((f64::from(v) * self.factor).ceil() as u32).max(1);
        (size(view.full_size.0), size(view.full_size.1))
    }
}

/// How finely a frame resolves the view: traced pixels along a row.
pub fn detail(rendered: &RenderedFrame) -> f64 {
    let passes = rendered.frame.passes_done;
    let block = crate::render::PASS_BLOCKS[passes.clamp(1, crate::render::PASS_BLOCKS.len()) - 1];
    f64::from(rendered.frame.width) / f64::from(block)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::state::Capped;

    #[test]
    fn a_huge_window_renders_at_most_the_pixel_limit_in_its_shape() {
        let ((w, h), capped) = capped_size(8000.0, 8000.0);
        assert!(capped);
        // 2^22 pixels: 2048 on each side of a square, 4096x1024 at 4:1.
        assert_eq!((w, h), (2048, 2048));
        assert_eq!(capped_size(16000.0, 4000.0), ((4096, 1024), true));
        assert!(f64::from(w) * f64::from(h) <= MOST_VIEW_PIXELS);
        let capped = Capped {
            render: (w, h),
            shown: (8000, 8000),
        };
        assert!(capped
            .to_string()
            .starts_with("rendering at 2048x2048, shown at 8000x8000"));
        assert_eq!(capped_size(1280.0, 720.0), ((1280, 720), false));
        assert_eq!(capped_size(1280.5, 720.2), ((1281, 721), false));
    }

    #[test]
    fn a_fast_move_lowers_the_resolution_and_rest_restores_it() {
        let mut quality = Quality {
            ms_per_mpixel: Some(32.0),
            ..Quality::default()
        };
        let view = ViewKey {
            full_size: (1000, 500),
            capped: false,
            terrain: 0,
            orbit: Orbit {
                target: [0.0; 3],
                yaw_deg: 0.0,
                pitch_deg: 30.0,
                distance: 10.0,
                fov_y_deg: 45.0,
                scale: 10.0,
            },
            lighting: crate::viewer::settings::Settings::default().lighting(),
            method: Method::Runs,
            arith: Arith::F64,
            contours: None,
        };
        assert_eq!(quality.render_size(&view), (1000, 500));
        quality.changed(true, &view);
        // 16 ms predicted against an 8 ms budget: sqrt(1/2) of each side.
        assert_eq!(quality.render_size(&view), (708, 354));
        quality.last_change = Some(Instant::now() - REST);
        quality.settle(false);
        assert_eq!(quality.render_size(&view), (1000, 500));
        assert_eq!(quality.rest_deadline(), None);
    }
}
