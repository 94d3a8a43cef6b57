//! Where and how large images are exported, and how exports went.

use crate::output_file::{FileError, SaveError};
use crate::render::annotate::{Annotations, DrawError};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use thiserror::Error;

/// Why an image or a scene file could not be saved in the export folder.
#[derive(Debug, Error)]
pub enum ExportError {
    /// The folder could not be made.
    #[error("cannot make the export folder {}: {reason}", folder.display())]
    Folder {
        /// The export folder.
        folder: PathBuf,
        /// Why not.
        reason: std::io::Error,
    },
    /// A numbered file could not be created.
    #[error("cannot write {}: {reason}", path.display())]
    Create {
        /// The file.
        path: PathBuf,
        /// Why not.
        reason: std::io::Error,
    },
    /// Every number is taken.
    #[error(
        "cannot save: {} already holds {stem}-001.{extension} to {stem}-{last}.{extension}",
        folder.display()
    )]
    Full {
        /// The export folder.
        folder: PathBuf,
        /// The names' start.
        stem: String,
        /// Their extension.
        extension: String,
        /// The last number tried.
        last: u32,
    },
    /// The marks could not be drawn into the image.
    #[error(transparent)]
    Draw(#[from] DrawError),
    /// The image could not be written.
    #[error(transparent)]
    Image(#[from] SaveError),
    /// The scene file could not be written.
    #[error(transparent)]
    File(#[from] FileError),
}

/// Where and how large images are exported, and how exports went.
#[derive(Clone, Debug, Default)]
pub struct Exports {
    /// The export folder as typed; empty means the current directory.
    pub dir: String,
    /// Export at `size` instead of the view's render size.
    pub custom: bool,
    pub size: (u32, u32),
    /// Exports rendering or being written.
    pub running: usize,
    /// Images written so far, and the last one.
    pub saved: u64,
    pub last: Option<PathBuf>,
    /// The last scene file saved.
    pub last_scene: Option<PathBuf>,
    /// Exports rendering anew, with their progress.
    pub rendering: Vec<Arc<Rendering>>,
    /// Marks drawn into exported images: scale bar, north arrow, legend.
    pub marks: Annotations,
    /// The title and attribution as typed (empty: none).
    pub title: String,
    pub attribution: String,
}

/// An export rendering anew, off the window's thread: how far it is, and whether the user
/// asked it to stop.
#[derive(Debug, Default)]
pub struct Rendering {
    pub size: (u32, u32),
    /// Tiles (or rows of a batch of samples) traced, of `total`.
    pub done: AtomicU64,
    pub total: AtomicU64,
    pub cancelled: AtomicBool,
    pub finished: AtomicBool,
}

impl Rendering {
    /// The fraction done, 0 to 1.
    pub fn fraction(&self) -> f32 {
        let total = self.total.load(Ordering::Relaxed).max(1);
        (self.done.load(Ordering::Relaxed) as f64 / total as f64).min(1.0) as f32
    }
}

/// An image written.
#[derive(Clone, Debug)]
pub struct Exported {
    pub path: PathBuf,
    pub size: (u32, u32),
}

impl Exports {
    /// What the Export section's header says: the size an export is made at.
    pub fn summary(&self) -> String {
        if self.custom {
            format!("{} x {}", self.size.0, self.size.1)
        } else {
            "view size".into()
        }
    }

    /// What is drawn into an exported image.
    pub fn annotations(&self) -> Annotations {
        let typed = |text: &str| Some(text.trim().to_owned()).filter(|t| !t.is_empty());
        Annotations {
            title: typed(&self.title),
            attribution: typed(&self.attribution),
            ..self.marks.clone()
        }
    }

    /// A scene's annotations, to draw into exports (its places and lines too).
    pub fn adopt(&mut self, annotations: &Annotations) {
        self.title = annotations.title.clone().unwrap_or_default();
        self.attribution = annotations.attribution.clone().unwrap_or_default();
        self.marks = annotations.clone();
    }

    /// The export folder in full.
    pub fn folder(&self) -> PathBuf {
        let typed = self.dir.trim();
        let dir = if typed.is_empty() {
            std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."))
        } else {
            PathBuf::from(typed)
        };
        std::path::absolute(&dir).unwrap_or(dir)
    }
}
