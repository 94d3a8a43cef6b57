//! The viewer's state that the panels and the 3D view read and edit, and the actions they ask
//! the application to carry out. Nothing here draws: the panels import these types, never the
//! other way round.

mod camera;
mod exports;
mod flythrough;
mod loads;
mod sun;
mod telemetry;
mod widgets;

pub use camera::{Framed, Home};
pub use exports::{ExportError, Exported, Exports, Rendering};
pub use flythrough::{Flythrough, KeysError, Playing};
pub use loads::{
    Decoding, LoadEvent, LoadFailure, LoadRequest, Loaded, OverlayChange, Progress, SceneClock,
    SceneSetup, Source, Stage,
};
pub use sun::{clock_text, default_local, SunClock};
pub use telemetry::{Capped, Notice, StoreFigures, Telemetry, MOST_VIEW_PIXELS};
pub use widgets::{ContourControls, DropLoads, OverlayControls, Widgets};

use super::accuracy::AccuracyState;
use super::orbit::Orbit;
use super::probe::Probe;
use super::settings::Settings;
use super::worker::RenderedFrame;
use crate::Terrain;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How a notice of the sun below the horizon ends, so that sunrise can clear it.
const NIGHT: &str = ": night";

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
    /// Place the sun where the Light panel's date, time and place put it.
    ApplyClock,
    /// Start previewing the flythrough's keys.
    PlayFlythrough,
    /// End the preview, restoring the render scale and the view it started from.
    StopFlythrough,
    /// Show this notice.
    Notify(String),
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
    pub flythrough: Flythrough,
    pub settings: Settings,
    /// The Light panel's date and time.
    pub sun_clock: SunClock,
    /// The panels' fields and toggles.
    pub widgets: Widgets,
    /// Latencies, load progress and the render size, as the panels report them.
    pub telemetry: Telemetry,
    /// Files dropped onto the window and not yet loaded (a drop delivers them one by one).
    pub dropped: Vec<PathBuf>,
    /// The window is too narrow for the panel beside the view.
    pub narrow_window: bool,
    /// Where the pointer came to rest over the view, and when (the probe waits for it).
    pub pointer_rest: Option<(egui::Pos2, Instant)>,
    /// A file is being dragged over the window.
    pub drop_hover: bool,
    /// Why the last file could not be used (stays until dismissed or a load succeeds).
    pub error: Option<String>,
    pub notice: Option<Notice>,
    pub latest: Option<Arc<RenderedFrame>>,
    pub probe: Option<Probe>,
    /// Window scale factor and the physical size of the window.
    pub scale_factor: f32,
    pub pixels_per_point: f32,
    pub window_size: (u32, u32),
    /// A mouse button is held on the 3D view (a drag in progress).
    pub view_held: bool,
    /// Measuring every arithmetic, and comparing with exact.
    pub accuracy: AccuracyState,
}

impl Model {
    /// Shows a scene file's camera as written (R returns to it), with its light, method and
    /// arithmetic.
    pub fn adopt_scene(&mut self, scene: &SceneSetup) {
        self.orbit = scene.orbit;
        self.home = Home::Scene(scene.orbit);
        self.framed = None;
        self.settings
            .adopt_scene(&scene.lighting, scene.method, scene.arith);
        self.export.adopt(&scene.annotations);
        self.widgets.contours.adopt(scene.contours);
        self.sun_clock.on = false;
        if let Some(flythrough) = &scene.flythrough {
            self.flythrough = flythrough.clone();
        }
        if let Some(clock) = scene.clock {
            self.sun_clock.set(clock);
            // Placed again by the clock, as the scene was: the same sun to the last bit.
            self.apply_clock();
        }
    }

    /// A model showing the whole of `shown` (framed again for the view's shape once it is
    /// known).
    pub fn new(shown: Shown, settings: Settings) -> Model {
        let orbit = Orbit::framing(&shown.terrain);
        Model {
            widgets: Widgets {
                z_scale: shown.terrain.field().z_scale(),
                decoding: shown.decoding,
                path_text: String::new(),
                path_source: None,
                overlay: OverlayControls::default(),
                contours: ContourControls::default(),
                panels_visible: true,
                panel_auto_hidden: false,
                show_probe: false,
                help_open: false,
                rects: BTreeMap::new(),
            },
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
            flythrough: Flythrough::default(),
            settings,
            sun_clock: SunClock::default(),
            telemetry: Telemetry::default(),
            dropped: Vec::new(),
            narrow_window: false,
            pointer_rest: None,
            drop_hover: false,
            error: None,
            notice: None,
            latest: None,
            probe: None,
            scale_factor: 1.0,
            pixels_per_point: 1.0,
            window_size: (0, 0),
            view_held: false,
            accuracy: AccuracyState::default(),
        }
    }

    /// Places the sun at the clock's date and time, or says why it cannot.
    pub fn apply_clock(&mut self) {
        let place = self.sun_clock.place(self.shown.terrain.field());
        match self.sun_clock.sun_at(place) {
            Ok(sun) => {
                self.settings.sun_azimuth_deg = sun.azimuth_deg;
                self.settings.sun_elevation_deg = sun.elevation_deg;
                let night = self
                    .notice
                    .as_ref()
                    .is_some_and(|n| n.text.ends_with(NIGHT));
                if !sun.is_up() {
                    self.notify(format!(
                        "The sun is {:.1}° below the horizon{NIGHT}",
                        -sun.elevation_deg
                    ));
                } else if night {
                    self.notice = None;
                }
            }
            Err(message) => self.error = Some(message.to_string()),
        }
    }

    /// Shows a short message for a few seconds.
    pub fn notify(&mut self, text: impl Into<String>) {
        self.notice = Some(Notice::now(text));
    }
}
