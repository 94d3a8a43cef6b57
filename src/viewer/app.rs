//! The application: one window, its egui state, the render worker and the loader. Window
//! events come in through `window_event`, worker and loader news through `user_event`; each
//! redraw runs the UI, submits a render job if the view changed, and presents.

use super::accuracy::Accuracy;
use super::annotations::{annotations_ui, Overlaid};
use super::compose::{self, PixelRect};
use super::hooks::{Counts, Hooks};
use super::loader::Loader;
use super::navigation;
use super::quality::{detail, JobKey, Quality, ViewKey};
use super::state::{Action, Capped, Home, LoadRequest, Loaded, Model, Shown};
use super::user_event::UserEvent;
use super::view::ViewParts;
use super::worker::{RenderWorker, RenderedFrame};
use super::{contours_ui, drops, export, flythrough, overlay_ui, panels, view, water_ui};

mod jobs;
mod present;

use present::{keys_ui, Presented, Screen};
use std::num::NonZeroU32;
use std::rc::Rc;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoopProxy};
use winit::window::Window;

/// Shortest time between redraws that egui asks for: its animations (a spinner while a file
/// loads) need no more than 60 a second, and the loader needs the CPU more.
const MIN_FRAME: Duration = Duration::from_millis(16);

/// The viewer's window and everything it shows.
pub struct App {
    window: Rc<Window>,
    screen: Screen,
    egui_ctx: egui::Context,
    egui_state: egui_winit::State,
    proxy: EventLoopProxy<UserEvent>,
    worker: RenderWorker,
    loader: Loader,
    accuracy: Accuracy,
    model: Model,
    hooks: Hooks,
    presented: Presented,
    quality: Quality,
    /// The inputs of the job last submitted.
    submitted: Option<JobKey>,
    /// The earliest input event since the last redraw.
    input_since_redraw: Option<Instant>,
    next_repaint: Option<Instant>,
}

impl App {
    pub fn new(
        window: Rc<Window>,
        proxy: EventLoopProxy<UserEvent>,
        loaded: Loaded,
        render_scale: Option<f32>,
        hooks: Hooks,
    ) -> anyhow::Result<App> {
        let egui_ctx = egui::Context::default();
        let screen = Screen::new(&window, egui_ctx.clone())?;
        let egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            None,
        );
        let (worker, loader, accuracy) = background_threads(&proxy)?;
        // Rays cost the square of the scale factor: by default trace one ray per logical pixel.
        let settings = super::settings::Settings {
            render_scale: render_scale.unwrap_or(1.0 / window.scale_factor().max(1.0) as f32),
            ..Default::default()
        };
        let model = initial_model(loaded, settings);
        let counts = Counts {
            x11_window: x11_window_id(&window),
            ..Counts::default()
        };
        window.set_title(&format!("heightray: {}", model.shown.source.label()));
        Ok(App {
            window,
            screen,
            egui_ctx,
            egui_state,
            proxy,
            worker,
            loader,
            accuracy,
            model,
            hooks,
            presented: Presented {
                counts,
                ..Presented::default()
            },
            quality: Quality::default(),
            submitted: None,
            input_since_redraw: None,
            next_repaint: None,
        })
    }

    pub fn window_event(&mut self, event_loop: &ActiveEventLoop, event: WindowEvent) {
        let response = self.egui_state.on_window_event(&self.window, &event);
        // egui asks for a repaint in answer to the redraw itself: obeying would spin.
        if response.repaint && !matches!(event, WindowEvent::RedrawRequested) {
            self.window.request_redraw();
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            WindowEvent::CursorMoved { .. }
            | WindowEvent::MouseInput { .. }
            | WindowEvent::MouseWheel { .. }
            | WindowEvent::KeyboardInput { .. } => {
                self.input_since_redraw.get_or_insert_with(Instant::now);
            }
            WindowEvent::HoveredFile(_) => {
                self.model.drop_hover = true;
                self.window.request_redraw();
            }
            WindowEvent::HoveredFileCancelled => {
                self.model.drop_hover = false;
                self.window.request_redraw();
            }
            WindowEvent::DroppedFile(path) => {
                self.model.drop_hover = false;
                self.model.dropped.push(path);
            }
            WindowEvent::Resized(_) | WindowEvent::ScaleFactorChanged { .. } => {
                self.window.request_redraw();
            }
            _ => {}
        }
    }

    pub fn user_event(&mut self, event: UserEvent) {
        match event {
            UserEvent::FrameReady => {
                // Taken now, not at the redraw: the worker waits for the window to let go
                // of the frame before, to refine the next pass in its buffers.
                self.pick_frame();
                self.worker.taken();
            }
            UserEvent::Accuracy => {}
            UserEvent::Load(event) => match self.loader.accept(event) {
                Some((_, Ok(loaded))) => self.show(loaded),
                Some((what, Err(message))) => {
                    self.model.widgets.overlay.dropped_picture = None;
                    self.model.error = Some(format!(
                        "Could not open {what}: {message}. Still showing {}.",
                        self.model.shown.source.label()
                    ));
                }
                None => {}
            },
            UserEvent::Exported(result) => export::finished(&mut self.model, result),
        }
        self.window.request_redraw();
    }

    /// Sleeps until the next thing to draw: a frame from the worker, input, egui's own
    /// repaint time, or the moment the camera comes to rest (to refine at full resolution).
    pub fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(request) = drops::take(&mut self.model) {
            self.start_load(request);
        }
        let wake = [self.next_repaint, self.quality.rest_deadline()]
            .into_iter()
            .flatten()
            .min();
        match wake {
            Some(at) if at <= Instant::now() => {
                self.next_repaint = None;
                self.window.request_redraw();
                event_loop.set_control_flow(ControlFlow::Wait);
            }
            Some(at) => event_loop.set_control_flow(ControlFlow::WaitUntil(at)),
            None => event_loop.set_control_flow(ControlFlow::Wait),
        }
    }

    fn start_load(&mut self, request: LoadRequest) {
        // A new load supersedes the last one's error.
        self.model.error = None;
        self.loader.start(request);
        self.model.telemetry.progress = self.loader.progress().cloned();
        self.window.request_redraw();
    }

    /// Puts a loaded terrain on screen.
    fn show(&mut self, loaded: Loaded) {
        let terrain = loaded.terrain;
        let model = &mut self.model;
        let was = model.shown.terrain.clone();
        model.shown = Shown {
            source: loaded.request.source.clone(),
            decoding: loaded.request.decoding,
            terrain: terrain.clone(),
            decode_time: loaded.decode_time,
        };
        model.error = None;
        overlay_ui::shown(model, loaded.request.overlay.as_ref());
        if !loaded.request.reframe {
            water_ui::follow_relief(model, was.field().z_scale());
        }
        contours_ui::follow_map(model, was.field(), loaded.request.reframe);
        // A rescale keeps the z scale field as the user has it (they may still be dragging).
        if loaded.request.reframe {
            model.widgets.z_scale = terrain.field().z_scale();
            match loaded.scene {
                Some(scene) => model.adopt_scene(&scene),
                None => {
                    model.home = Home::WholeMap;
                    navigation::reset(model);
                }
            }
            let field = terrain.field();
            let store = field.store_bytes().map_or(String::new(), |bytes| {
                format!(" (a tile store of {:.2} GB)", bytes as f64 / 1e9)
            });
            model.notify(format!(
                "Opened {}: {} x {} samples{store}, acceleration data built in {:.1} ms",
                model.shown.source.label(),
                field.width(),
                field.height(),
                terrain.build_time().as_secs_f64() * 1e3
            ));
        }
        self.window
            .set_title(&format!("heightray: {}", model.shown.source.label()));
    }

    fn apply(&mut self, action: Action) {
        match action {
            Action::Load(request) => self.start_load(request),
            Action::ResetView => navigation::reset(&mut self.model),
            Action::FrameMap => navigation::frame_from_here(&mut self.model),
            Action::Screenshot => self.export(),
            Action::SaveScene => self.save_scene(),
            Action::MeasureArithmetics => self.accuracy.toggle_measure(&mut self.model.accuracy),
            Action::ApplyClock => self.model.apply_clock(),
            Action::PlayFlythrough => flythrough::play(&mut self.model),
            Action::StopFlythrough => flythrough::stop(&mut self.model),
            Action::Notify(text) => self.model.notify(text),
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let size = self.window.inner_size();
        // Minimised or not yet laid out: nothing to draw into.
        let (Some(width), Some(height)) =
            (NonZeroU32::new(size.width), NonZeroU32::new(size.height))
        else {
            return;
        };
        let started = Instant::now();
        self.model.window_size = (size.width, size.height);
        self.model.scale_factor = self.window.scale_factor() as f32;
        self.model.telemetry.progress = self.loader.progress().cloned();
        self.pick_frame();
        // Collect the accuracy threads' news before the panel shows them.
        self.update_accuracy();
        let input_at = self.input_since_redraw.take();
        let (output, view_rect, actions) = self.run_ui();
        for action in actions {
            self.apply(action);
        }
        self.model.pixels_per_point = output.pixels_per_point;
        let view = compose::physical_rect(view_rect, output.pixels_per_point);
        self.presented.counts.view_rect = Some(view);
        self.submit(view, input_at);
        // Start, or cancel for a changed view, what the panel has just asked for.
        self.update_accuracy();
        let delay = output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map_or(Duration::MAX, |v| v.repaint_delay);
        let exiting = self.presented.exiting_now(&self.hooks, &self.model);
        let grab = self.hooks.screenshot.as_deref().filter(|_| exiting);
        let counts = &mut self.presented.counts;
        let drawn = self
            .screen
            .present((width, height), view, output, &self.model, grab, counts);
        if let Err(refused) = drawn {
            self.model.error = Some(refused.to_string());
        }
        self.model.telemetry.redraw.record(started.elapsed());
        let model = &mut self.model;
        model.telemetry.measure_store(model.shown.terrain.field());
        if self
            .presented
            .after_present(&self.hooks, &mut self.model, &self.worker)
        {
            event_loop.exit();
        }
        if delay < Duration::from_secs(3600) {
            self.next_repaint = Some(Instant::now() + delay.max(MIN_FRAME));
        }
    }

    /// Runs egui: the panels, the 3D view and the keys. Returns the view's rectangle.
    fn run_ui(&mut self) -> (egui::FullOutput, egui::Rect, Vec<Action>) {
        let input = self.egui_state.take_egui_input(&self.window);
        let ctx = self.egui_ctx.clone();
        let model = &mut self.model;
        let mut actions = Vec::new();
        let mut view_rect = egui::Rect::NOTHING;
        let output = ctx.run_ui(input, |ui| {
            // egui may run this twice in one frame; act on the last run only.
            actions.clear();
            model.widgets.rects.clear();
            actions.extend(keys_ui(
                ui,
                &mut model.orbit,
                &model.shown.terrain,
                &mut model.flythrough,
                &mut model.widgets,
            ));
            actions.extend(flythrough::play_ui(
                ui,
                &mut model.flythrough,
                &mut model.orbit,
                &model.shown.terrain,
                model.latest.as_deref(),
            ));
            let fit = panels::fit_to_window(ui, &mut model.widgets, &mut model.narrow_window);
            actions.extend(fit);
            if model.widgets.panels_visible {
                panels::side_panel_ui(ui, model, &mut actions);
            }
            egui::CentralPanel::no_frame().show_inside(ui, |ui| {
                view_rect = view::view_ui(ui, ViewParts::of(model));
                annotations_ui(ui, Overlaid::of(model), view_rect);
            });
        });
        self.egui_state
            .handle_platform_output(&self.window, output.platform_output.clone());
        (output, view_rect, actions)
    }

    /// Chooses the frame to show: the newest, unless it is a coarser render of the view on
    /// screen (coming to rest restarts at full resolution from coarse blocks).
    fn pick_frame(&mut self) {
        let Some(latest) = self.worker.latest() else {
            return;
        };
        let replace = match &self.model.latest {
            None => true,
            // Taken already (when the worker said it was ready).
            Some(shown) if Arc::ptr_eq(shown, &latest) => false,
            Some(shown) => {
                shown.generation == latest.generation
                    || shown.job.view_id != latest.job.view_id
                    || detail(&latest) >= detail(shown)
            }
        };
        if replace {
            if latest.pass_times.len() == 1 {
                self.quality.first_pass(&latest);
            }
            self.model.latest = Some(latest);
        }
    }

    fn update_accuracy(&mut self) {
        let converged = self.converged();
        self.accuracy.update(
            &mut self.model.accuracy,
            converged.as_ref(),
            self.model.latest.as_ref(),
        );
    }

    /// The frame on screen if it is complete and shows the current view at the size last
    /// asked for (not a lowered resolution while moving).
    fn converged(&self) -> Option<Arc<RenderedFrame>> {
        let latest = self.model.latest.as_ref()?;
        let submitted = self.submitted.as_ref()?;
        let current = latest.job.view_id == self.quality.view_id()
            && (latest.frame.width, latest.frame.height) == submitted.size
            && latest.finished();
        current.then(|| Arc::clone(latest))
    }

    /// Sends the worker a job when what the view shows, or its resolution, has changed.
    fn submit(&mut self, view: PixelRect, input_at: Option<Instant>) {
        if view.width == 0 || view.height == 0 {
            return;
        }
        let model = &self.model;
        self.quality.settle(model.view_held);
        let view_key = ViewKey::new(model, view);
        let mut caused_by = None;
        if self.submitted.as_ref().is_none_or(|s| s.view != view_key) {
            self.quality.changed(model.view_held, &view_key);
            // Latency is measured from input that changed a view already on screen.
            caused_by = input_at.filter(|_| self.submitted.is_some());
        }
        self.model.telemetry.capped = view_key.capped().then(|| Capped {
            render: view_key.full_size(),
            shown: (view.width, view.height),
        });
        let size = self.quality.render_size(&view_key);
        let key = JobKey {
            view: view_key,
            size,
        };
        if self.submitted.as_ref() == Some(&key) {
            return;
        }
        let Ok(job) = self.job(size) else {
            return;
        };
        let generation = self.worker.submit(job);
        if let Some(at) = caused_by {
            self.presented.unreflected.push_back((generation, at));
        }
        self.presented.counts.submitted_generation = generation;
        self.submitted = Some(key);
    }
}

/// The render worker, the loader and the accuracy threads, all reporting to the window
/// through `proxy`.
fn background_threads(
    proxy: &EventLoopProxy<UserEvent>,
) -> std::io::Result<(RenderWorker, Loader, Accuracy)> {
    let frame_proxy = proxy.clone();
    let worker = RenderWorker::start(move || {
        // The window may be gone at exit; then nobody needs the news.
        let _ = frame_proxy.send_event(UserEvent::FrameReady);
    })?;
    let load_proxy = proxy.clone();
    let loader = Loader::new(move |event| {
        let _ = load_proxy.send_event(UserEvent::Load(event));
    })?;
    let accuracy_proxy = proxy.clone();
    let accuracy = Accuracy::start(move || {
        let _ = accuracy_proxy.send_event(UserEvent::Accuracy);
    })?;
    Ok((worker, loader, accuracy))
}

/// The model for the terrain named on the command line (with a scene's view and lighting).
fn initial_model(loaded: Loaded, settings: super::settings::Settings) -> Model {
    let shown = Shown {
        source: loaded.request.source.clone(),
        decoding: loaded.request.decoding,
        terrain: loaded.terrain.clone(),
        decode_time: loaded.decode_time,
    };
    let mut model = Model::new(shown, settings);
    if let Some(scene) = loaded.scene {
        model.adopt_scene(&scene);
    }
    model
}

/// The X11 window id, for scripted tests that drive the window.
fn x11_window_id(window: &Window) -> Option<u64> {
    use winit::raw_window_handle::{HasWindowHandle, RawWindowHandle};
    match window.window_handle().ok()?.as_raw() {
        RawWindowHandle::Xlib(handle) => Some(handle.window),
        RawWindowHandle::Xcb(handle) => Some(u64::from(handle.window.get())),
        _ => None,
    }
}
