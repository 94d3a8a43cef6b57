//! The viewer's state that the panels and the 3D view read and edit, and the actions they ask
//! the application to carry out.

use super::accuracy::AccuracyState;
use super::compose::HeatScale;
use super::contours_ui::ContourControls;
use super::decoding::Decoding;
use super::export::Exports;
use super::loader::{LoadRequest, Progress, Source};
use super::navigation::{Framed, Home};
use super::orbit::Orbit;
use super::overlay_ui::OverlayControls;
use super::probe::Probe;
use super::quality::Capped;
use super::settings::Settings;
use super::sun_clock::SunClock;
use super::worker::RenderedFrame;
use crate::Terrain;
use std::collections::{BTreeMap, VecDeque};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The terrain on screen.
pub struct Shown {
    pub source: Source,
    /// How its file was decoded, if it is an image.
    pub decoding: Decoding,
    pub terrain: Arc<Terrain>,
    /// Reading and decoding time of its file.
    pub decode_time: Duration,
}

/// Something the UI asks for that the application does.
#[derive(Debug)]
pub enum Action {
    Load(LoadRequest),
    ResetView,
    /// Fit the whole map in the view, from the current direction.
    FrameMap,
    /// Save the rendered image, without the window's panels and overlays.
    Screenshot,
    /// Save the view as a scene file.
    SaveScene,
    /// Measure every arithmetic on the view, or cancel the measurement under way.
    MeasureArithmetics,
}

/// Times from an input to the first frame on screen that shows its effect.
#[derive(Clone, Debug, Default)]
pub struct Latency {
    recent: VecDeque<f64>,
    pub count: u64,
    pub max_ms: f64,
}

impl Latency {
    const KEEP: usize = 240;

    pub fn record(&mut self, latency: Duration) {
        let ms = latency.as_secs_f64() * 1e3;
        if self.recent.len() == Self::KEEP {
            self.recent.pop_front();
        }
        self.recent.push_back(ms);
        self.count += 1;
        self.max_ms = self.max_ms.max(ms);
    }

    /// The recent samples, oldest first.
    pub fn recent(&self) -> impl Iterator<Item = f64> + '_ {
        self.recent.iter().copied()
    }

    pub fn last_ms(&self) -> Option<f64> {
        self.recent.back().copied()
    }

    /// Median and 95th percentile of the recent samples.
    pub fn percentiles(&self) -> Option<(f64, f64)> {
        let mut sorted: Vec<f64> = self.recent.iter().copied().collect();
        if sorted.is_empty() {
            return None;
        }
        sorted.sort_by(f64::total_cmp);
        let at = |q: f64| sorted[((sorted.len() - 1) as f64 * q).round() as usize];
        Some((at(0.5), at(0.95)))
    }
}

/// A short message shown over the view.
#[derive(Clone, Debug)]
pub struct Notice {
    pub text: String,
    pub at: Instant,
}

/// Everything the UI shows and edits.
pub struct Model {
    pub shown: Shown,
    pub orbit: Orbit,
    /// Where R returns to.
    pub home: Home,
    /// Set while the camera shows the whole map as framed, and not moved since.
    pub framed: Option<Framed>,
    /// The 3D view's width over its height.
    pub view_aspect: f64,
    /// Where and how large images are exported.
    pub export: Exports,
    /// The flythrough's keys, and its preview.
    pub flythrough: super::flythrough::Flythrough,
    pub settings: Settings,
    /// The Light panel's date and time.
    pub sun_clock: SunClock,
    /// The z scale field of the heightmap panel (applied when editing ends).
    pub z_scale: f64,
    /// The path field of the heightmap panel.
    pub path_text: String,
    /// The terrain the path field was last filled in for (it shows what is loaded).
    pub path_source: Option<Source>,
    /// How images opened or dropped from now on are decoded.
    pub decoding: Decoding,
    /// The overlay path, opacity and what a drop loads.
    pub overlay: OverlayControls,
    /// Contour lines on the map.
    pub contours: ContourControls,
    /// Files dropped onto the window and not yet loaded (a drop delivers them one by one).
    pub dropped: Vec<PathBuf>,
    pub panels_visible: bool,
    /// The panel was hidden because the window became too narrow for it.
    pub panel_auto_hidden: bool,
    /// The window is too narrow for the panel beside the view.
    pub narrow_window: bool,
    /// Show the ray of the pixel under a resting pointer.
    pub show_probe: bool,
    /// Where the pointer came to rest over the view, and when (the probe waits for it).
    pub pointer_rest: Option<(egui::Pos2, Instant)>,
    pub help_open: bool,
    /// A file is being dragged over the window.
    pub drop_hover: bool,
    /// Why the last file could not be used (stays until dismissed or a load succeeds).
    pub error: Option<String>,
    pub notice: Option<Notice>,
    pub progress: Option<Progress>,
    pub latest: Option<Arc<RenderedFrame>>,
    pub probe: Option<Probe>,
    /// The heat map scale of the frame on screen, with the frame's generation and passes.
    pub heat_scale: Option<(u64, usize, HeatScale)>,
    pub latency: Latency,
    /// Time the window thread spent on each redraw (UI, compositing, presenting).
    pub redraw: Latency,
    /// Window scale factor and the physical size of the window.
    pub scale_factor: f32,
    pub pixels_per_point: f32,
    pub window_size: (u32, u32),
    /// Set while the view renders at fewer pixels than it shows.
    pub capped: Option<Capped>,
    /// A mouse button is held on the 3D view (a drag in progress).
    pub view_held: bool,
    /// Where named widgets were drawn last frame, in points (for scripted tests).
    pub widget_rects: BTreeMap<&'static str, egui::Rect>,
    /// Measuring every arithmetic, and comparing with exact.
    pub accuracy: AccuracyState,
}

impl Model {
    /// Shows a scene file's camera as written (R returns to it), with its light, method and
    /// arithmetic.
    pub fn adopt_scene(&mut self, scene: &super::loader::SceneSetup) {
        self.orbit = scene.orbit;
        self.home = Home::Scene(scene.orbit);
        self.framed = None;
        self.settings
            .adopt_scene(&scene.lighting, scene.method, scene.arith);
        self.export.adopt(&scene.annotations);
        self.contours.adopt(scene.contours);
        self.sun_clock.on = false;
        if let Some(flythrough) = &scene.flythrough {
            self.flythrough = flythrough.clone();
        }
        if let Some(clock) = scene.clock {
            self.sun_clock.set(clock);
            // Placed again by the clock, as the scene was: the same sun to the last bit.
            super::sun_clock::apply_clock(self);
        }
    }

    /// A model showing the whole of `shown` (framed again for the view's shape once it is
    /// known).
    pub fn new(shown: Shown, settings: Settings) -> Model {
        let orbit = Orbit::framing(&shown.terrain);
        Model {
            z_scale: shown.terrain.field().z_scale(),
            decoding: shown.decoding,
            shown,
            orbit,
            home: Home::WholeMap,
            framed: Some(Framed {
                yaw_deg: orbit.yaw_deg,
                pitch_deg: orbit.pitch_deg,
                aspect: 0.0,
                orbit,
                terrain: 0,
            }),
            view_aspect: 16.0 / 9.0,
            export: Exports::default(),
            flythrough: Default::default(),
            settings,
            sun_clock: SunClock::default(),
            path_text: String::new(),
            path_source: None,
            overlay: OverlayControls::default(),
            contours: ContourControls::default(),
            dropped: Vec::new(),
            panels_visible: true,
            panel_auto_hidden: false,
            narrow_window: false,
            show_probe: false,
            pointer_rest: None,
            help_open: false,
            drop_hover: false,
            error: None,
            notice: None,
            progress: None,
            latest: None,
            probe: None,
            heat_scale: None,
            latency: Latency::default(),
            redraw: Latency::default(),
            scale_factor: 1.0,
            pixels_per_point: 1.0,
            window_size: (0, 0),
            capped: None,
            view_held: false,
            widget_rects: BTreeMap::new(),
            accuracy: AccuracyState::default(),
        }
    }

    /// Shows a short message for a few seconds.
    pub fn notify(&mut self, text: impl Into<String>) {
        self.notice = Some(Notice {
            text: text.into(),
            at: Instant::now(),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latency_percentiles_of_recent_samples() {
        let mut latency = Latency::default();
        assert_eq!(latency.percentiles(), None);
        for ms in 1..=100 {
            latency.record(Duration::from_millis(ms));
        }
        let (median, p95) = latency.percentiles().expect("samples");
        assert!((median - 50.0).abs() <= 1.0 && (p95 - 95.0).abs() <= 1.0);
        assert_eq!(latency.max_ms, 100.0);
        assert_eq!(latency.last_ms(), Some(100.0));
    }
}
