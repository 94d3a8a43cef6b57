//! The reader the decoders read a file through: buffered, it reports how far decoding has got
//! in the file, stops reading (and so decoding) when the load is cancelled, and remembers why
//! reading failed.

use super::Progress;
use std::cell::{Cell, RefCell};
use std::io::{self, BufRead, BufReader, Read, Seek, SeekFrom};

/// Bytes read from the file at once into the buffer.
const BUFFER: usize = 1 << 16;

/// The most read from the file at once: a decoder asking for a whole strip or raster in one
/// call still gets it in pieces, with a check for cancellation between them.
const MOST_AT_ONCE: usize = 1 << 20;

/// Whom to tell about reading a file of `len` bytes, and what happened.
pub struct Watch<'a> {
    len: u64,
    progress: Progress<'a>,
    /// How far decoding moves in the file between reports: 1/256 of a small file, 64 KiB of
    /// a large one (so that a small image in a huge file is still checked often).
    step: u64,
    last_report: Cell<Option<u64>>,
    cancelled: Cell<bool>,
    /// The first error of the file itself (not an end of file, not cancellation).
    failure: RefCell<Option<io::Error>>,
}

impl<'a> Watch<'a> {
    pub fn new(len: u64, progress: Progress<'a>) -> Self {
        Watch {
            len,
            progress,
            step: (len / 256).clamp(1, BUFFER as u64),
            last_report: Cell::new(None),
            cancelled: Cell::new(false),
            failure: RefCell::new(None),
        }
    }

    /// `file`, read from its start through a buffer, with this watch.
    pub fn reader<R: Read>(&self, file: R) -> Watched<'_, 'a, R> {
        Watched {
            watch: self,
            inner: BufReader::with_capacity(BUFFER, file),
            position: 0,
        }
    }

    /// Whether the progress callback asked to stop.
    pub fn cancelled(&self) -> bool {
        self.cancelled.get()
    }

    /// The error the file gave when read, if it gave one.
    pub fn take_failure(&self) -> Option<io::Error> {
        self.failure.borrow_mut().take()
    }

    /// Reports reaching `position` if decoding has moved a step since the last report; an
    /// error once cancelled.
    fn reached(&self, position: u64) -> io::Result<()> {
        let due = self
            .last_report
            .get()
            .is_none_or(|last| position.abs_diff(last) >= self.step);
        if due && !self.cancelled.get() {
            self.last_report.set(Some(position));
            let fraction = position.min(self.len) as f64 / self.len.max(1) as f64;
            if (self.progress)(fraction).is_break() {
                self.cancelled.set(true);
            }
        }
        if self.cancelled.get() {
            // Not `Interrupted`: readers retry on that.
            return Err(io::Error::other("cancelled"));
        }
        Ok(())
    }

    /// Keeps the first error the file gave (a retry is no error), and gives the decoder one of
    /// the same kind.
    fn failed(&self, error: io::Error) -> io::Error {
        if error.kind() == io::ErrorKind::Interrupted {
            return error;
        }
        let copy = io::Error::new(error.kind(), error.to_string());
        self.failure.borrow_mut().get_or_insert(error);
        copy
    }
}

/// A file (or bytes in memory) under a [`Watch`], buffered.
pub struct Watched<'w, 'a, R> {
    watch: &'w Watch<'a>,
    inner: BufReader<R>,
    /// Where decoding is in the file.
    position: u64,
}

impl<R: Seek> Watched<'_, '_, R> {
    /// Goes back `count` bytes, within the buffer when they are still in it.
    pub fn back(&mut self, count: u64) -> io::Result<()> {
        let count = i64::try_from(count).map_err(io::Error::other)?;
        self.inner
            .seek_relative(-count)
            .map_err(|error| self.watch.failed(error))?;
        self.position = self.position.saturating_sub(count as u64);
        Ok(())
    }
}

impl<R: Read> Read for Watched<'_, '_, R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.watch.reached(self.position)?;
        let most = buf.len().min(MOST_AT_ONCE);
        let count = self
            .inner
            .read(&mut buf[..most])
            .map_err(|error| self.watch.failed(error))?;
        self.position += count as u64;
        Ok(count)
    }
}

impl<R: Read> BufRead for Watched<'_, '_, R> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        self.watch.reached(self.position)?;
        let watch = self.watch;
        self.inner.fill_buf().map_err(|error| watch.failed(error))
    }
    fn consume(&mut self, amount: usize) {
        self.inner.consume(amount);
        self.position += amount as u64;
    }
}

impl<R: Seek> Seek for Watched<'_, '_, R> {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        // Relative when it can be, so that a seek to bytes still in the buffer keeps it: a
        // TIFF of millions of small strips seeks once a strip.
        if let SeekFrom::Start(target) = to {
            if let Ok(delta) = i64::try_from(i128::from(target) - i128::from(self.position)) {
                self.inner
                    .seek_relative(delta)
                    .map_err(|error| self.watch.failed(error))?;
                self.position = target;
                return Ok(target);
            }
        }
        self.position = self
            .inner
            .seek(to)
            .map_err(|error| self.watch.failed(error))?;
        Ok(self.position)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ops::ControlFlow;

    #[test]
    fn an_endless_source_stops_being_read_once_cancelled() {
        let calls = Cell::new(0u32);
        let stop_at_the_tenth = |_| {
            calls.set(calls.get() + 1);
            if calls.get() >= 10 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        };
        let watch = Watch::new(u64::MAX, &stop_at_the_tenth);
        let mut endless = watch.reader(io::repeat(7));
        let mut all = Vec::new();
        let error = endless
            .read_to_end(&mut all)
            .expect_err("reading stops with an error");
        assert!(watch.cancelled());
        assert_eq!(error.to_string(), "cancelled");
        // Nine reads of at most a MiB each went through; the tenth was refused.
        assert!(
            !all.is_empty() && all.len() <= 9 * MOST_AT_ONCE,
            "{}",
            all.len()
        );
        assert!(all.iter().all(|&b| b == 7));
        assert!(watch.take_failure().is_none(), "cancelling is no failure");
    }

    #[test]
    fn progress_is_the_share_of_the_file_read_and_seeks_move_it() {
        let seen = RefCell::new(Vec::new());
        let record = |fraction| {
            seen.borrow_mut().push(fraction);
            ControlFlow::Continue(())
        };
        let bytes = [1u8; 100];
        let watch = Watch::new(100, &record);
        let mut reader = watch.reader(io::Cursor::new(&bytes[..]));
        let mut part = [0u8; 25];
        reader.read_exact(&mut part).expect("25 bytes");
        reader.seek(SeekFrom::Start(80)).expect("seek");
        reader.read_exact(&mut part[..20]).expect("20 bytes");
        assert_eq!(reader.read(&mut part).expect("the end"), 0);
        assert_eq!(*seen.borrow(), [0.0, 0.8, 1.0]);
    }

    #[test]
    fn a_failing_file_is_remembered_and_passed_on() {
        struct Failing;
        impl Read for Failing {
            fn read(&mut self, _: &mut [u8]) -> io::Result<usize> {
                Err(io::Error::new(io::ErrorKind::PermissionDenied, "no access"))
            }
        }
        let go_on = |_| ControlFlow::Continue(());
        let watch = Watch::new(10, &go_on);
        let error = watch
            .reader(Failing)
            .read(&mut [0; 4])
            .expect_err("the file's error");
        assert_eq!(error.kind(), io::ErrorKind::PermissionDenied);
        let kept = watch.take_failure().expect("the failure is kept");
        assert_eq!(kept.to_string(), "no access");
    }
}
