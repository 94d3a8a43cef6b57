//! The bytes of a file as a reader that reports how far decoding has got and stops it when
//! the load is cancelled.

use super::Progress;
use std::cell::Cell;
use std::io::{self, BufRead, Cursor, Read, Seek, SeekFrom};

/// A file's bytes and whom to tell about reading them.
pub struct Watched<'a> {
    bytes: &'a [u8],
    progress: Progress<'a>,
    cancelled: Cell<bool>,
    /// The next position (in 1/256ths of the file) at which to report.
    next_report: Cell<u64>,
}

impl<'a> Watched<'a> {
    pub fn new(bytes: &'a [u8], progress: Progress<'a>) -> Self {
        Watched {
            bytes,
            progress,
            cancelled: Cell::new(false),
            next_report: Cell::new(0),
        }
    }

    /// A reader from the start of the bytes.
    pub fn reader(&self) -> WatchedReader<'_, 'a> {
        WatchedReader {
            watched: self,
            cursor: Cursor::new(self.bytes),
        }
    }

    /// Whether the progress callback asked to stop.
    pub fn cancelled(&self) -> bool {
        self.cancelled.get()
    }

    /// Reports reaching `position` (at most 256 times per file); an error once cancelled.
    fn reached(&self, position: u64) -> io::Result<()> {
        let len = self.bytes.len().max(1) as u64;
        let step = position.min(len) * 256 / len;
        if step >= self.next_report.get() {
            self.next_report.set(step + 1);
            if (self.progress)(step as f64 / 256.0).is_break() {
                self.cancelled.set(true);
            }
        }
        if self.cancelled.get() {
            // Not `Interrupted`: readers retry on that.
            return Err(io::Error::other("cancelled"));
        }
        Ok(())
    }
}

/// A reader over [`Watched`] bytes.
pub struct WatchedReader<'w, 'a> {
    watched: &'w Watched<'a>,
    cursor: Cursor<&'a [u8]>,
}

impl Read for WatchedReader<'_, '_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.watched.reached(self.cursor.position())?;
        self.cursor.read(buf)
    }
}

impl BufRead for WatchedReader<'_, '_> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        self.watched.reached(self.cursor.position())?;
        self.cursor.fill_buf()
    }
    fn consume(&mut self, amount: usize) {
        self.cursor.consume(amount);
    }
}

impl Seek for WatchedReader<'_, '_> {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        self.cursor.seek(to)
    }
}
