// (The summary line of this module's docs is its `pub mod` line in lib.rs; the empty line
// below starts the rest as a paragraph of its own.)
//!
//! The renderer fills the view progressively on worker threads; the window thread never waits
//! for a frame.
//!
//! This module wires winit's events to `app::App`, which draws; what the panels show and edit
//! lives in `state`, which imports no panel.

mod accuracy;
mod annotations;
mod app;
mod background;
mod compose;
mod contours_ui;
mod decoding;
mod drops;
mod export;
mod flythrough;
mod ground;
mod hooks;
mod legend;
mod loader;
mod mailbox;
mod navigation;
mod orbit;
mod overlay_ui;
mod panels;
mod probe;
mod probe_ui;
mod quality;
mod relief_ui;
mod save_scene;
mod settings;
mod sources;
mod state;
mod stats_ui;
mod store_view;
mod sun_clock;
mod user_event;
mod view;
mod water_ui;
mod widgets;
mod worker;

pub use orbit::Orbit;
pub use state::{Decoding, Source};

use app::App;
use state::{LoadRequest, Loaded};
use std::path::PathBuf;
use std::rc::Rc;
use user_event::UserEvent;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop, EventLoopProxy};
use winit::window::{Window, WindowId};

/// How to start the viewer.
#[derive(Clone, Debug)]
pub struct ViewerOptions {
    /// A height map or `.toml` scene, or tiles to join into one map; none shows the built-in
    /// default terrain.
    pub sources: Vec<PathBuf>,
    /// z scale for a height map (default: its own, or a quarter of the larger side).
    pub z_scale: Option<f64>,
    /// How height map images are decoded (the panel can change it).
    pub decoding: Decoding,
    /// Window size in logical pixels.
    pub size: (u32, u32),
    /// Rays per physical pixel along each axis (default: one per logical pixel).
    pub render_scale: Option<f32>,
    /// Quit after this many fully refined frames were shown (for tests).
    pub exit_after_frames: Option<u64>,
    /// With `exit_after_frames`: where the window's last frame is saved on exit.
    pub screenshot: Option<PathBuf>,
    /// Where S exports rendered images (None: the current directory).
    pub export_dir: Option<PathBuf>,
    /// The size S exports at (None: the view's render size).
    pub export_size: Option<(u32, u32)>,
    /// Write the window's state as JSON here after every frame (for tests).
    pub report_state: Option<PathBuf>,
}

impl Default for ViewerOptions {
    fn default() -> Self {
        ViewerOptions {
            sources: Vec::new(),
            z_scale: None,
            decoding: Decoding::default(),
            size: (1280, 720),
            render_scale: None,
            exit_after_frames: None,
            screenshot: None,
            export_dir: None,
            export_size: None,
            report_state: None,
        }
    }
}

/// Opens the window and runs until it is closed.
pub fn run(options: ViewerOptions) -> anyhow::Result<()> {
    // Load first: a file named on the command line that cannot be used is an error there.
    let request = LoadRequest {
        source: Source::of_paths(options.sources.clone()).unwrap_or_else(Source::default_builtin),
        z_scale: options.z_scale,
        reframe: true,
        from_memory: None,
        decoding: options.decoding,
        overlay: None,
    };
    let loaded = loader::load_now(request).map_err(anyhow::Error::msg)?;
    let event_loop = EventLoop::<UserEvent>::with_user_event()
        .build()
        .map_err(|e| {
            anyhow::anyhow!(
                "cannot open a window ({e}); is DISPLAY set? `heightray render` works without one"
            )
        })?;
    let mut shell = Shell {
        options,
        proxy: event_loop.create_proxy(),
        loaded: Some(loaded),
        app: None,
        error: None,
    };
    event_loop.run_app(&mut shell)?;
    match shell.error {
        Some(error) => Err(error),
        None => Ok(()),
    }
}

/// Creates the application when the event loop is ready and hands it the events.
struct Shell {
    options: ViewerOptions,
    proxy: EventLoopProxy<UserEvent>,
    loaded: Option<Loaded>,
    app: Option<App>,
    error: Option<anyhow::Error>,
}

impl Shell {
    fn start(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<App> {
        let (width, height) = self.options.size;
        let attributes = Window::default_attributes()
            .with_title("heightray")
            .with_inner_size(winit::dpi::LogicalSize::new(width, height));
        let window = Rc::new(event_loop.create_window(attributes)?);
        let loaded = self
            .loaded
            .take()
            .ok_or_else(|| anyhow::anyhow!("the viewer was started twice"))?;
        let hooks = hooks::Hooks {
            exit_after_frames: self.options.exit_after_frames,
            screenshot: self.options.screenshot.clone(),
            report_state: self.options.report_state.clone(),
        };
        let mut app = App::new(
            window,
            self.proxy.clone(),
            loaded,
            self.options.render_scale,
            hooks,
        )?;
        app.set_export(self.options.export_dir.as_deref(), self.options.export_size);
        Ok(app)
    }
}

impl ApplicationHandler<UserEvent> for Shell {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.app.is_some() || self.error.is_some() {
            return;
        }
        match self.start(event_loop) {
            Ok(app) => self.app = Some(app),
            Err(error) => {
                self.error = Some(error);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        if let Some(app) = &mut self.app {
            app.window_event(event_loop, event);
        }
    }

    fn user_event(&mut self, _: &ActiveEventLoop, event: UserEvent) {
        if let Some(app) = &mut self.app {
            app.user_event(event);
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(app) = &mut self.app {
            app.about_to_wait(event_loop);
        }
    }

    fn exiting(&mut self, _: &ActiveEventLoop) {
        // Stops the render thread before the window goes.
        self.app = None;
    }
}
