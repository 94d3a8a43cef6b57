//! Exporting the rendered image: the view's converged frame, or a new render at a chosen size
//! with the same camera, light and effects, saved as a PNG under a name no other file has, in
//! the export folder. Never the window's pixels: no panels, overlays or messages. Scene files
//! of the view are saved there too (see `save_scene`).

use super::state::{ExportError, Exported, Exports, Model, Rendering};
use super::user_event::UserEvent;
use super::worker::{RenderJob, RenderedFrame};
use crate::output_file;
use crate::render::annotate::{Annotations, Sheet};
use crate::render::{Frame, Window};
use std::fs::{File, OpenOptions};
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::sync::Arc;
use winit::event_loop::EventLoopProxy;

/// Numbers past this are not tried: a folder with that many exports of one map is full.
const LAST_NUMBER: u32 = 99_999;

/// Records a finished export and says where it went (`None`: cancelled).
pub fn finished(model: &mut Model, result: Result<Option<Exported>, ExportError>) {
    model.export.running = model.export.running.saturating_sub(1);
    model
        .export
        .rendering
        .retain(|r| !r.finished.load(Ordering::Relaxed));
    match result {
        Ok(None) => model.notify("Export cancelled"),
        Ok(Some(exported)) => {
            let (w, h) = exported.size;
            model.notify(format!("Saved {} ({w} x {h})", exported.path.display()));
            model.export.saved += 1;
            model.export.last = Some(exported.path);
        }
        Err(refused) => model.error = Some(refused.to_string()),
    }
}

/// Starts exporting `job`'s view: `ready` is its converged frame when that has the size to
/// export, otherwise the view is rendered anew at the job camera's size, off the window's
/// thread. The result comes back as [`UserEvent::Exported`].
pub fn start(
    model: &mut Model,
    job: RenderJob,
    ready: Option<Arc<RenderedFrame>>,
    proxy: EventLoopProxy<UserEvent>,
) {
    let size = job.camera.size();
    let folder = model.export.folder();
    let stem = stem(model);
    let fresh = ready.is_none();
    let rendering = Arc::new(Rendering {
        size,
        ..Rendering::default()
    });
    let progress = Arc::clone(&rendering);
    let annotations = model.export.annotations();
    let spawned = std::thread::Builder::new()
        .name("heightray-export".into())
        .spawn(move || {
            let pixels = match ready {
                Some(frame) => Some(frame.frame.pixels.clone()),
                None => render_fresh(&job, size, &progress),
            };
            let saved = pixels
                .map(|mut pixels| {
                    annotate(&job, &annotations, &mut pixels)?;
                    save_numbered(&folder, &stem, &pixels, size)
                })
                .transpose();
            progress.finished.store(true, Ordering::Relaxed);
            // The window may be gone at exit; then nobody needs the news.
            let _ = proxy.send_event(UserEvent::Exported(
                saved.map(|path| path.map(|path| Exported { path, size })),
            ));
        });
    match spawned {
        Ok(_) => {
            model.export.running += 1;
            if fresh {
                model.export.rendering.push(rendering);
                model.notify(format!("Rendering {} x {} to export…", size.0, size.1));
            }
        }
        Err(e) => model.error = Some(format!("cannot start exporting: {e}")),
    }
}

/// Renders `job` at `size`, counting its progress in `rendering`; `None` if cancelled.
fn render_fresh(job: &RenderJob, size: (u32, u32), rendering: &Rendering) -> Option<Vec<u32>> {
    let mut frame = Frame::new(size.0, size.1);
    let renderer = job.renderer(job.arith);
    rendering
        .total
        .store(renderer.ticks(&frame), Ordering::Relaxed);
    let finished = renderer.render_cancellable(&mut frame, &|| {
        rendering.done.fetch_add(1, Ordering::Relaxed);
        rendering.cancelled.load(Ordering::Relaxed)
    });
    finished.then_some(frame.pixels)
}

/// Draws `annotations` into `pixels`, the whole image of `job`'s camera.
fn annotate(
    job: &RenderJob,
    annotations: &Annotations,
    pixels: &mut [u32],
) -> Result<(), ExportError> {
    let (width, height) = job.camera.size();
    let sheet = Sheet {
        terrain: &job.terrain,
        camera: job.camera,
        ramp: job.lighting.ramp,
        method: job.method,
        arith: job.arith,
    };
    let whole = Window {
        x: 0,
        y: 0,
        width,
        height,
    };
    Ok(annotations.draw(&sheet, pixels, whole)?)
}

/// The exports rendering anew: a bar for each, and a button that cancels it.
pub fn progress_ui(ui: &mut egui::Ui, exports: &Exports) {
    for rendering in &exports.rendering {
        let (w, h) = rendering.size;
        let fraction = rendering.fraction();
        ui.horizontal(|ui| {
            let bar = egui::ProgressBar::new(fraction)
                .desired_width(ui.available_width() - 70.0)
                .text(format!("{w} x {h}: {:.0}%", 100.0 * fraction));
            ui.add(bar);
            let stopping = rendering.cancelled.load(Ordering::Relaxed);
            if ui
                .add_enabled(!stopping, egui::Button::new("Cancel"))
                .clicked()
            {
                rendering.cancelled.store(true, Ordering::Relaxed);
            }
        });
    }
    if !exports.rendering.is_empty() {
        // The render's threads do not wake the window: the bar asks to be drawn again.
        ui.ctx()
            .request_repaint_after(std::time::Duration::from_millis(200));
    }
}

/// Whether `frame` is the image `job` asks for: the same terrain, camera, light, contour
/// lines and traversal.
pub fn shows(frame: &RenderedFrame, job: &RenderJob) -> bool {
    let done = &frame.job;
    frame.frame.complete()
        && Arc::ptr_eq(&done.terrain, &job.terrain)
        && done.camera == job.camera
        && done.lighting == job.lighting
        && done.contours == job.contours
        && (done.method, done.arith) == (job.method, job.arith)
}

/// The name of the exports of the map on screen, before their number.
pub fn stem(model: &Model) -> String {
    format!("heightray-{}", file_stem(&model.shown.source.label()))
}

/// A file name part from a map's label: its first word (a built-in's name, or a file name
/// without its extension), with anything but letters, digits, `-` and `_` replaced.
pub fn file_stem(label: &str) -> String {
    let word = label.split(" (").next().unwrap_or(label);
    let word = Path::new(word)
        .file_stem()
        .map_or(word.into(), |s| s.to_string_lossy());
    let stem: String = word
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if stem.is_empty() {
        "map".into()
    } else {
        stem
    }
}

/// Writes 0x00RRGGBB pixels as `folder/stem-NNN.png` with the first number no file has yet
/// (the file is created only if it does not exist, so no export ever replaces another).
pub fn save_numbered(
    folder: &Path,
    stem: &str,
    pixels: &[u32],
    (width, height): (u32, u32),
) -> Result<PathBuf, ExportError> {
    // The empty file holds the number; the image replaces it whole once written.
    let (_, path) = create_numbered(folder, stem, "png")?;
    output_file::save_rgb(&path, pixels, (width, height)).inspect_err(|_| {
        // An empty file left behind is worse than none.
        let _ = std::fs::remove_file(&path);
    })?;
    Ok(path)
}

/// Creates `folder/stem-NNN.extension` with the first number no file has yet (only if it
/// does not exist, so that nothing saved ever replaces another file).
pub fn create_numbered(
    folder: &Path,
    stem: &str,
    extension: &str,
) -> Result<(File, PathBuf), ExportError> {
    std::fs::create_dir_all(folder).map_err(|reason| ExportError::Folder {
        folder: folder.to_owned(),
        reason,
    })?;
    for number in 1..=LAST_NUMBER {
        let path = folder.join(format!("{stem}-{number:03}.{extension}"));
        match OpenOptions::new().write(true).create_new(true).open(&path) {
            Ok(file) => return Ok((file, path)),
            Err(e) if e.kind() == ErrorKind::AlreadyExists => continue,
            Err(reason) => return Err(ExportError::Create { path, reason }),
        }
    }
    Err(ExportError::Full {
        folder: folder.to_owned(),
        stem: stem.to_owned(),
        extension: extension.to_owned(),
        last: LAST_NUMBER,
    })
}

/// The export folder and size, for the side panel.
pub fn settings_ui(ui: &mut egui::Ui, exports: &mut Exports, render_size: Option<(u32, u32)>) {
    // Wrapped rows and a field as wide as the panel: the panel narrows in small windows.
    ui.label("export folder");
    ui.add(
        egui::TextEdit::singleline(&mut exports.dir)
            .hint_text("current directory")
            .desired_width(ui.available_width()),
    );
    ui.weak(format!("saves to {}", exports.folder().display()));
    ui.horizontal_wrapped(|ui| {
        let render = match render_size {
            Some((w, h)) => format!("view ({w} x {h})"),
            None => "view".into(),
        };
        ui.radio_value(&mut exports.custom, false, render);
        ui.radio_value(&mut exports.custom, true, "size");
        if exports.size == (0, 0) {
            exports.size = render_size.unwrap_or((1920, 1080));
        }
        ui.add_enabled(
            exports.custom,
            egui::DragValue::new(&mut exports.size.0).range(1..=16384),
        );
        ui.add_enabled(
            exports.custom,
            egui::DragValue::new(&mut exports.size.1).range(1..=16384),
        );
    });
    // Drawn into the exported image at its size, not into the view.
    ui.label("drawn into the image");
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut exports.marks.scale_bar, "scale bar");
        ui.checkbox(&mut exports.marks.north_arrow, "north arrow");
        ui.checkbox(&mut exports.marks.legend, "legend");
    });
    for (text, hint) in [
        (&mut exports.title, "title"),
        (&mut exports.attribution, "attribution"),
    ] {
        ui.add(
            egui::TextEdit::singleline(text)
                .hint_text(hint)
                .desired_width(ui.available_width()),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_come_from_the_map_and_numbers_never_repeat() {
        assert_eq!(file_stem("valley513 (built-in)"), "valley513");
        assert_eq!(file_stem("my hill.pgm"), "my_hill");
        assert_eq!(file_stem(""), "map");
        let dir = tempfile::tempdir().expect("a temporary directory");
        let folder = dir.path().join("new folder");
        let pixels = [0x00ff_0000, 0x0000_ff00, 0x0000_00ff, 0x00ff_ffff];
        let first = save_numbered(&folder, "x", &pixels, (2, 2)).expect("saved");
        // A file the user put there keeps its number and its contents.
        std::fs::write(folder.join("x-002.png"), "mine").expect("write");
        let third = save_numbered(&folder, "x", &pixels, (2, 2)).expect("saved");
        assert_eq!(first, folder.join("x-001.png"));
        assert_eq!(third, folder.join("x-003.png"));
        assert_eq!(
            std::fs::read_to_string(folder.join("x-002.png")).ok(),
            Some("mine".into())
        );
        let image = image::open(&third).expect("a PNG").to_rgb8();
        assert_eq!(image.get_pixel(1, 0).0, [0, 255, 0]);
        assert_eq!(image.get_pixel(1, 1).0, [255, 255, 255]);
    }
}
