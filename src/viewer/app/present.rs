//! Drawing a frame into the window (terrain first, egui over it), the window grab that
//! `--exit-after-frames` saves, the latency and frame counts after each present, and the keys.

use super::{App, BACKGROUND};
use crate::viewer::compose::{self, Canvas, HeatScale, PixelRect};
use crate::viewer::hooks;
use crate::viewer::model::{Action, Model};
use crate::viewer::navigation;
use crate::viewer::settings::HeatMode;
use egui_software_backend::BufferMutRef;
use std::num::NonZeroU32;
use winit::event_loop::ActiveEventLoop;

impl App {
    /// Draws the terrain, then egui over it, and shows the result.
    pub(super) fn present(
        &mut self,
        (width, height): (NonZeroU32, NonZeroU32),
        view: PixelRect,
        output: egui::FullOutput,
    ) -> Result<(), String> {
        let fail = |e: softbuffer::SoftBufferError| format!("cannot draw the window: {e}");
        let exiting = self.exiting_now();
        self.surface.resize(width, height).map_err(fail)?;
        let mut buffer = self.surface.buffer_mut().map_err(fail)?;
        buffer.fill(BACKGROUND);
        let mut canvas = Canvas {
            pixels: &mut buffer,
            width: width.get(),
            height: height.get(),
        };
        if let Some(latest) = &self.model.latest {
            let heat = match (self.model.settings.heat, self.model.heat_scale) {
                (HeatMode::Off, _) => None,
                (_, Some((_, _, scale))) => Some(scale),
                (mode, None) => Some(HeatScale::of(&latest.frame, mode)),
            };
            let look = compose::Look {
                heat,
                differs: self
                    .model
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
        let size = (width.get(), height.get());
        if let (true, Some(path)) = (exiting, &self.hooks.screenshot) {
            hooks::save_png(&buffer, size.0, size.1, path)?;
            self.counts.last_screenshot = Some(path.clone());
        }
        buffer.present().map_err(fail)
    }

    /// Whether this redraw presents the last converged frame `--exit-after-frames` asks for.
    fn exiting_now(&self) -> bool {
        let Some((limit, latest)) = self.hooks.exit_after_frames.zip(self.model.latest.as_ref())
        else {
            return false;
        };
        let new_converged = latest.frame.complete() && latest.generation != self.converged_counted;
        self.counts.converged_frames + u64::from(new_converged) >= limit
    }

    /// Counts the frame, measures input latency, writes the report, and quits if asked to.
    pub(super) fn after_present(&mut self, event_loop: &ActiveEventLoop) {
        let exiting = self.exiting_now();
        self.counts.frames_presented += 1;
        self.counts.busy = self.worker.busy();
        if let Some(latest) = self.model.latest.clone() {
            self.worker.presented(latest.generation);
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
                self.model.latency.record(at.elapsed());
            }
            if latest.frame.complete() && latest.generation != self.converged_counted {
                self.converged_counted = latest.generation;
                self.counts.converged_frames += 1;
            }
        }
        if let Some(path) = &self.hooks.report_state {
            if let Err(message) = hooks::write_report(path, &self.model, &self.counts) {
                eprintln!("heightray: {message}");
            }
        }
        if exiting {
            event_loop.exit();
        }
    }
}

/// The navigation keys, S, K, H and F1, unless a text field has the keyboard.
pub(super) fn keys_ui(ui: &egui::Ui, model: &mut Model, actions: &mut Vec<Action>) {
    if ui.ctx().egui_wants_keyboard_input() {
        return;
    }
    // A focused slider or drag value takes the arrow keys itself: the camera leaves them.
    if ui.ctx().memory(|m| m.focused().is_none()) {
        navigation::keys_ui(ui, model, actions);
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
        let orbit = model.orbit;
        model.flythrough.add(orbit);
    }
    if pressed(egui::Key::H) {
        model.panels_visible = !model.panels_visible;
    }
    if pressed(egui::Key::F1) {
        model.help_open = !model.help_open;
    }
}
