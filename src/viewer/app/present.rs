//! Drawing a frame into the window (terrain first, egui over it), the window grab that
//! `--exit-after-frames` saves, the latency and frame counts after each present, and the keys.
//! The window's parts come in as arguments: this file knows nothing of the application.

use crate::viewer::compose::{self, Canvas, HeatScale, PixelRect};
use crate::viewer::hooks::{self, Counts, Hooks};
use crate::viewer::navigation;
use crate::viewer::orbit::Orbit;
use crate::viewer::settings::HeatMode;
use crate::viewer::state::{Action, Flythrough, Model, Widgets};
use crate::viewer::worker::RenderWorker;
use crate::Terrain;
use egui_software_backend::{BufferMutRef, ColorFieldOrder, EguiSoftwareRender};
use std::collections::VecDeque;
use std::num::NonZeroU32;
use std::path::Path;
use std::rc::Rc;
use std::time::Instant;
use winit::window::Window;

/// Behind the view where nothing is rendered yet.
const BACKGROUND: u32 = 0x0020_2226;

/// What a frame is drawn into: the window's pixels, and egui's renderer for them.
pub struct Screen {
    surface: softbuffer::Surface<Rc<Window>, Rc<Window>>,
    egui_ctx: egui::Context,
    egui_renderer: EguiSoftwareRender,
}

impl Screen {
    /// The window's pixels, drawn with `egui_ctx`'s shapes.
    pub fn new(window: &Rc<Window>, egui_ctx: egui::Context) -> anyhow::Result<Screen> {
        let context = softbuffer::Context::new(window.clone())
            .map_err(|e| anyhow::anyhow!("cannot draw into the window: {e}"))?;
        let surface = softbuffer::Surface::new(&context, window.clone())
            .map_err(|e| anyhow::anyhow!("cannot draw into the window: {e}"))?;
        Ok(Screen {
            surface,
            egui_ctx,
            // Drawn straight into the window's buffer: the cache keeps a canvas the size of the
            // window (256 MB at 8000x8000), and the panel redraws as fast without it.
            egui_renderer: EguiSoftwareRender::new(ColorFieldOrder::Bgra).with_caching(false),
        })
    }

    /// Draws the terrain, then egui over it, and shows the result; saves the window's pixels
    /// to `grab` first, if given, and counts it saved.
    pub fn present(
        &mut self,
        (width, height): (NonZeroU32, NonZeroU32),
        view: PixelRect,
        output: egui::FullOutput,
        model: &Model,
        grab: Option<&Path>,
        counts: &mut Counts,
    ) -> Result<(), PresentError> {
        self.surface.resize(width, height)?;
        let mut buffer = self.surface.buffer_mut()?;
        buffer.fill(BACKGROUND);
        let mut canvas = Canvas {
            pixels: &mut buffer,
            width: width.get(),
            height: height.get(),
        };
        if let Some(latest) = &model.latest {
            let heat = match (model.settings.heat, model.telemetry.heat_scale) {
                (HeatMode::Off, _) => None,
                (_, Some((_, _, scale))) => Some(scale),
                (mode, None) => Some(HeatScale::of(&latest.frame, mode)),
            };
            let look = compose::Look {
                heat,
                differs: model
                    .accuracy
                    .comparison_shown()
                    .map(|c| c.differs.as_slice()),
            };
            compose::blit(&mut canvas, view, &latest.frame, look);
        }
        let ppp = output.pixels_per_point;
        let primitives = self.egui_ctx.tessellate(output.shapes, ppp);
        let mut target = BufferMutRef::new(
            bytemuck::cast_slice_mut(&mut buffer),
            width.get() as usize,
            height.get() as usize,
        );
        self.egui_renderer
            .render(&mut target, &primitives, &output.textures_delta, ppp);
        if let Some(path) = grab {
            hooks::save_png(&buffer, width.get(), height.get(), path)?;
            counts.last_screenshot = Some(path.to_path_buf());
        }
        Ok(buffer.present()?)
    }
}

/// The frames presented: the report's counts, and the inputs whose effect is not on screen
/// yet.
#[derive(Default)]
pub struct Presented {
    pub counts: Counts,
    /// Jobs submitted for input whose effect is not on screen yet: generation, input time.
    pub unreflected: VecDeque<(u64, Instant)>,
    /// The generation of the last converged frame counted.
    pub converged_counted: u64,
}

impl Presented {
    /// Whether this redraw presents the last converged frame `--exit-after-frames` asks for.
    pub fn exiting_now(&self, hooks: &Hooks, model: &Model) -> bool {
        let Some((limit, latest)) = hooks.exit_after_frames.zip(model.latest.as_ref()) else {
            return false;
        };
        let new_converged = latest.frame.complete() && latest.generation != self.converged_counted;
        self.counts.converged_frames + u64::from(new_converged) >= limit
    }

    /// Counts the frame, measures input latency and writes the report. Returns whether to
    /// quit, as `--exit-after-frames` asks.
    pub fn after_present(
        &mut self,
        hooks: &Hooks,
        model: &mut Model,
        worker: &RenderWorker,
    ) -> bool {
        let exiting = self.exiting_now(hooks, model);
        self.counts.frames_presented += 1;
        self.counts.busy = worker.busy();
        if let Some(latest) = model.latest.clone() {
            worker.presented(latest.generation);
            // This frame shows the inputs of its own job and of every earlier one.
            let mut reflected = None;
            while let Some(&(generation, at)) = self.unreflected.front() {
                if generation > latest.generation {
                    break;
                }
                reflected = reflected.or(Some(at));
                self.unreflected.pop_front();
            }
            if let Some(at) = reflected {
                model.telemetry.latency.record(at.elapsed());
            }
            if latest.frame.complete() && latest.generation != self.converged_counted {
                self.converged_counted = latest.generation;
                self.counts.converged_frames += 1;
            }
        }
        if let Some(path) = &hooks.report_state {
            if let Err(message) = hooks::write_report(path, model, &self.counts) {
                eprintln!("heightray: {message}");
            }
        }
        exiting
    }
}

/// Why the window could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PresentError {
    /// The window's buffer.
    #[error("cannot draw the window: {0}")]
    Window(#[from] softbuffer::SoftBufferError),
    /// The window's pixels could not be saved.
    #[error(transparent)]
    Grab(#[from] crate::output_file::SaveError),
}

/// The navigation keys moving `orbit` over `terrain`, S, K (adding the view to `flythrough`),
/// H and F1 (toggling `widgets`' panel and help), unless a text field has the keyboard.
pub fn keys_ui(
    ui: &egui::Ui,
    orbit: &mut Orbit,
    terrain: &Terrain,
    flythrough: &mut Flythrough,
    widgets: &mut Widgets,
) -> Vec<Action> {
    let mut actions = Vec::new();
    if ui.ctx().egui_wants_keyboard_input() {
        return actions;
    }
    // A focused slider or drag value takes the arrow keys itself: the camera leaves them.
    if ui.ctx().memory(|m| m.focused().is_none()) {
        actions.extend(navigation::keys_ui(ui, orbit, terrain));
    }
    let pressed = |key| ui.input(|i| i.key_pressed(key));
    // Every press is one export, even two within one frame; holding the key is one press.
    let exports = ui.input(|i| {
        i.events
            .iter()
            .filter(|e| {
                matches!(
                    e,
                    egui::Event::Key {
                        key: egui::Key::S,
                        pressed: true,
                        repeat: false,
                        ..
                    }
                )
            })
            .count()
    });
    actions.extend((0..exports).map(|_| Action::Screenshot));
    if pressed(egui::Key::K) {
        flythrough.add(*orbit);
    }
    if pressed(egui::Key::H) {
        widgets.panels_visible = !widgets.panels_visible;
    }
    if pressed(egui::Key::F1) {
        widgets.help_open = !widgets.help_open;
    }
    actions
}
