//! A store's header and where its sections lie.
//!
//! The file starts with [`MAGIC`], the header's length and the room kept for it (both `u64`,
//! little-endian), then the header as JSON, rewritten in place as preparing goes on. After
//! the room, each section starts on a page: the samples (`u16` by `j * width + i`), the valid
//! samples' bits where there are holes (a set bit is a sample with data, so that the gaps of
//! a sparse mosaic are runs of zeros the file need not store), then the mipmap's highest and
//! lowest samples as [`Mipmap::layout`](crate::heightfield::Mipmap) stacks them. Every value is
//! little-endian.

use super::StoreError;
use crate::heightfield::georef::Georef;
use crate::heightfield::{Mipmap, Quantisation};
use serde::{Deserialize, Serialize};
use std::fs::File;
use std::os::unix::fs::FileExt;
use std::path::{Path, PathBuf};

/// The first bytes of every store.
pub const MAGIC: &[u8; 16] = b"heightray store\n";

/// The layout this code reads and writes.
const VERSION: u32 = 1;

/// Bytes before the header's JSON: the magic, its length and its room.
const PREFIX: u64 = 32;

/// Sections start on pages of this many bytes.
const PAGE: u64 = 4096;

/// What a store holds and how far preparing it has come.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// The layout's version.
    pub version: u32,
    /// Samples along x.
    pub width: u64,
    /// Samples along y.
    pub height: u64,
    /// How samples map to heights (at z scale 1).
    pub quantisation: Quantisation,
    /// Where the samples lie, if the inputs said.
    pub georef: Option<Georef>,
    /// How many samples hold no data, where any do: then the valid samples' bits are stored.
    pub holes: Option<u64>,
    /// The inputs, in the order given (the first to cover a sample gives it).
    pub inputs: Vec<Input>,
    /// The steepest squared gradient, set once the mipmap is built: the store is complete.
    pub steepest: Option<f64>,
}

/// One input file and where its samples go.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Input {
    /// The file.
    pub path: PathBuf,
    /// Its length when it was planned (a changed input starts the store over).
    pub bytes: u64,
    /// Its lower-left sample's place in the store.
    pub at: [u64; 2],
    /// Its samples along x and y.
    pub size: [u64; 2],
    /// Whether its samples are written.
    pub written: bool,
}

/// Where a store's sections lie: byte offsets and lengths in values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sections {
    /// The samples.
    pub samples: (u64, u64),
    /// The valid samples' bits, in `u64` words, where there are holes.
    pub valid: Option<(u64, u64)>,
    /// The mipmap's highest samples.
    pub max: (u64, u64),
    /// The mipmap's lowest samples.
    pub min: (u64, u64),
    /// The file's length.
    pub end: u64,
}

impl Header {
    /// A new header of the layout this code writes.
    pub fn new(width: u64, height: u64, quantisation: Quantisation) -> Self {
        Header {
            version: VERSION,
            width,
            height,
            quantisation,
            georef: None,
            holes: None,
            inputs: Vec::new(),
            steepest: None,
        }
    }

    /// Where the sections lie after `room` bytes of header.
    pub fn sections(&self, room: u64) -> Sections {
        let n = self.width * self.height;
        let layout = Mipmap::layout(self.width as usize, self.height as usize);
        let page = |at: u64| at.div_ceil(PAGE) * PAGE;
        let samples = (page(PREFIX + room), n);
        let mut end = samples.0 + 2 * n;
        let valid = self.holes.map(|_| {
            let words = n.div_ceil(64);
            let at = page(end);
            end = at + 8 * words;
            (at, words)
        });
        let max = (page(end), layout.max_len as u64);
        let min = (page(max.0 + 2 * max.1), layout.min_len as u64);
        Sections {
            samples,
            valid,
            max,
            min,
            end: min.0 + 2 * min.1,
        }
    }

    /// The header room a new store keeps: twice the header's length, and a page at least, so
    /// that it can grow as preparing goes on.
    pub fn room(&self) -> u64 {
        let len = serde_json::to_vec(self).map_or(0, |json| json.len() as u64);
        (2 * len).max(PAGE)
    }

    /// Writes the header into the `room` kept for it at the start of `file`.
    pub fn write(&self, file: &File, room: u64, path: &Path) -> Result<(), StoreError> {
        let json = serde_json::to_vec(self).map_err(|e| damaged(path, e.to_string()))?;
        if json.len() as u64 > room {
            return Err(damaged(
                path,
                "its header outgrew the room kept for it".into(),
            ));
        }
        let mut bytes = Vec::with_capacity(PREFIX as usize + json.len());
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&(json.len() as u64).to_le_bytes());
        bytes.extend_from_slice(&room.to_le_bytes());
        bytes.extend_from_slice(&json);
        file.write_all_at(&bytes, 0).map_err(StoreError::io(path))
    }

    /// Reads the header of the store `file`, `len` bytes long, and the room kept for it.
    pub fn read(file: &File, len: u64, path: &Path) -> Result<(Header, u64), StoreError> {
        let mut prefix = [0u8; PREFIX as usize];
        file.read_exact_at(&mut prefix, 0)
            .map_err(|_| damaged(path, "it is shorter than a store's first bytes".into()))?;
        if &prefix[..16] != MAGIC {
            return Err(damaged(path, "it does not start as a store does".into()));
        }
        let word = |k: usize| u64::from_le_bytes(prefix[k..k + 8].try_into().unwrap_or([0; 8]));
        let (json_len, room) = (word(16), word(24));
        if json_len > room || PREFIX + room > len {
            return Err(damaged(path, "its header's length is out of range".into()));
        }
        let mut json = vec![0u8; json_len as usize];
        file.read_exact_at(&mut json, PREFIX)
            .map_err(StoreError::io(path))?;
        let header: Header = serde_json::from_slice(&json)
            .map_err(|e| damaged(path, format!("its header does not read: {e}")))?;
        if header.version != VERSION {
            return Err(damaged(
                path,
                format!(
                    "it has layout version {}, this program reads {VERSION}",
                    header.version
                ),
            ));
        }
        if header.width < 2 || header.height < 2 {
            return Err(damaged(path, "it holds fewer than 2x2 samples".into()));
        }
        if header
            .width
            .checked_mul(header.height)
            .is_none_or(|n| n > 1 << 46)
        {
            return Err(damaged(path, "its size is out of range".into()));
        }
        Ok((header, room))
    }
}

/// Whether `file` starts as a store does.
pub fn is_store(file: &File) -> bool {
    let mut start = [0u8; 16];
    file.read_exact_at(&mut start, 0).is_ok() && &start == MAGIC
}

/// A damaged store's error.
pub fn damaged(path: &Path, why: String) -> StoreError {
    StoreError::Damaged {
        path: path.to_owned(),
        why,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sections_start_on_pages_and_do_not_overlap() {
        let mut header = Header::new(1001, 517, Quantisation::Maxval(255));
        header.holes = Some(3);
        let s = header.sections(4096);
        let spans = [
            (s.samples.0, 2 * s.samples.1),
            s.valid.map_or((0, 0), |(at, words)| (at, 8 * words)),
            (s.max.0, 2 * s.max.1),
            (s.min.0, 2 * s.min.1),
        ];
        for pair in spans.windows(2) {
            assert!(pair[0].0 + pair[0].1 <= pair[1].0, "{spans:?}");
        }
        assert!(spans.iter().all(|(at, _)| at % PAGE == 0));
        assert_eq!(s.samples.1, 1001 * 517);
        assert_eq!(s.valid.map(|v| v.1), Some((1001u64 * 517).div_ceil(64)));
        assert_eq!(s.end, s.min.0 + 2 * s.min.1);
    }
}
