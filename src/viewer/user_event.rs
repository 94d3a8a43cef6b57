//! The news the render, loading and saving threads send the window thread.

use super::state::{ExportError, Exported, LoadEvent};

/// News for the window thread from the render, loading and saving threads.
pub enum UserEvent {
    /// The render worker published a pass.
    FrameReady,
    /// A measurement or comparison reported progress or a result.
    Accuracy,
    /// The loader's progress, or its result.
    Load(LoadEvent),
    /// An export was written (`None`: cancelled), or why not.
    Exported(Result<Option<Exported>, ExportError>),
}
