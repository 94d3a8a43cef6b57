//! Tile stores: a map prepared once from its input files (a mosaic of tiles, or one large
//! file) into one file that holds its samples, its holes and its min-max mipmap, laid out as
//! a field in memory lays them out. Opening a store maps it read-only: nothing is decoded or
//! built, the walks read the very values they read in memory (so the answers are the same, bit
//! for bit), and only the pages they touch are read from the disk. A map may so hold more
//! samples than memory; the pages resident stay within a budget (see [`residency`]).
//!
//! A store is written by [`prepare`], which can be stopped and run again to go on where it
//! stopped. It must not be changed while a map is open from it.

mod build;
mod chunked;
mod header;
mod open;
mod prepare;
pub mod residency;
mod write;

pub use header::{is_store, Header, Input, MAGIC};
pub use open::open;
pub use prepare::{prepare, save, Stage};

use super::{HeightfieldError, LoadError, Mipmap};
use std::path::PathBuf;
use thiserror::Error;

/// Threads a core that trace a map from a store: a walk that waits on the disk for a page
/// leaves its core to another, and the disk serves several reads at once.
const THREADS_PER_CORE: usize = 4;

/// The threads that trace a map from a store on this machine (`THREADS_PER_CORE` a core).
pub fn threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get()) * THREADS_PER_CORE
}

/// The acceleration data a store holds ready, in place of building it when a terrain is made.
#[derive(Clone, Debug)]
pub struct Prebuilt {
    /// The min-max mipmap.
    pub(super) mipmap: Mipmap,
    /// The largest squared gradient of any triangle, in samples (see the terrain's slope).
    pub(super) steepest: f64,
}

/// Why a tile store could not be prepared or opened.
#[derive(Debug, Error)]
pub enum StoreError {
    /// A file could not be read or written.
    #[error("{path}: {reason}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: std::io::Error,
    },
    /// An input could not be loaded.
    #[error(transparent)]
    Input(#[from] Box<LoadError>),
    /// The inputs cannot be joined into one map.
    #[error("{0}")]
    Inputs(String),
    /// The file's header is not a store's.
    #[error("{path} is a damaged tile store ({why}); prepare it again with heightray prepare")]
    Damaged {
        /// The store.
        path: PathBuf,
        /// What is wrong with it.
        why: String,
    },
    /// The file is shorter than its header says.
    #[error(
        "{path} is truncated: it holds {len} bytes of the {expected} its header says; prepare \
         it again with heightray prepare"
    )]
    Truncated {
        /// The store.
        path: PathBuf,
        /// Its length.
        len: u64,
        /// The length its header says.
        expected: u64,
    },
    /// The store was not prepared to the end.
    #[error(
        "{path} was not prepared to the end; run heightray prepare with the same inputs again \
         to finish it"
    )]
    Unfinished {
        /// The store.
        path: PathBuf,
    },
    /// The samples do not make a height field.
    #[error("{path}: {source}")]
    Field {
        /// The store.
        path: PathBuf,
        /// Why.
        source: HeightfieldError,
    },
    /// The output names a file that is not a store (an input, say): it is left as it is.
    #[error(
        "{path} exists and is not a tile store; give the store a new name (nothing was written)"
    )]
    NotAStore {
        /// The output asked for.
        path: PathBuf,
    },
    /// Preparing was cancelled.
    #[error("preparing {path} was cancelled; run it again to go on")]
    Cancelled {
        /// The store.
        path: PathBuf,
    },
}

impl From<LoadError> for StoreError {
    fn from(error: LoadError) -> Self {
        StoreError::Input(Box::new(error))
    }
}

impl StoreError {
    /// An I/O error on `path`.
    fn io(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> StoreError + '_ {
        move |reason| StoreError::Io {
            path: path.to_owned(),
            reason,
        }
    }
}
