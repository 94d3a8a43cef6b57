//! The jobs the window hands on: the render of the view at a size, and its exports and saved
//! scenes at the export size.

use super::App;
use crate::viewer::export;
use crate::viewer::save_scene;
use crate::viewer::worker::RenderJob;

impl App {
    /// Where exports go and at which size (the panel can change both).
    pub fn set_export(&mut self, dir: Option<&std::path::Path>, size: Option<(u32, u32)>) {
        let export = &mut self.model.export;
        if let Some(dir) = dir {
            export.dir = dir.display().to_string();
        }
        if let Some(size) = size {
            (export.custom, export.size) = (true, size);
        }
    }

    /// A render of the current view at `size` pixels.
    pub(super) fn job(&self, size: (u32, u32)) -> Result<RenderJob, crate::render::CameraError> {
        let model = &self.model;
        Ok(RenderJob {
            terrain: model.shown.terrain.clone(),
            orbit: model.orbit,
            camera: model.orbit.camera(size)?,
            lighting: model.settings.lighting(),
            method: model.settings.method,
            arith: model.settings.arith(),
            contours: model.widgets.contours.lines(model.shown.terrain.field()),
            view_id: self.quality.view_id(),
        })
    }

    /// The size the view is exported at: its render size, or the one the panel asks for.
    fn export_size(&mut self) -> Option<(u32, u32)> {
        let Some(submitted) = &self.submitted else {
            self.model
                .notify("Nothing to export yet: the view is not rendered");
            return None;
        };
        let exports = &self.model.export;
        Some(if exports.custom {
            exports.size
        } else {
            submitted.view.full_size()
        })
    }

    /// Saves the view as a scene file at the export size.
    pub(super) fn save_scene(&mut self) {
        if let Some(size) = self.export_size() {
            save_scene::save(&mut self.model, size);
        }
    }

    /// Exports the view at its render size (the converged frame, if it is on screen) or at
    /// the size the panel asks for.
    pub(super) fn export(&mut self) {
        let Some(size) = self.export_size() else {
            return;
        };
        let job = match self.job(size) {
            Ok(job) => job,
            Err(e) => {
                self.model.error = Some(format!("cannot export at {} x {}: {e}", size.0, size.1));
                return;
            }
        };
        let ready = self.converged().filter(|frame| export::shows(frame, &job));
        export::start(&mut self.model, job, ready, self.proxy.clone());
    }
}
