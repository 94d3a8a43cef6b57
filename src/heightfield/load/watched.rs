//! The reader the decoders read a file through: buffered, it reports how far decoding has got
//! in the file, stops reading (and so decoding) when the load is cancelled, and remembers why
//! reading failed.

use super::Progress;
use std::cell::{Cell, RefCell};
use std::io::{self, BufRead, Read, Seek, SeekFrom};

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
            inner: file,
            buffer: vec![0; BUFFER].into_boxed_slice(),
            start: 0,
            filled: 0,
            position: 0,
            next_fill: BUFFER,
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
///
/// The buffer holds bytes `start..start + filled` of the file, and the file itself stands at
/// `start + filled`; decoding is at `position`, within those bytes or at their end. Reading on
/// refills the buffer from where the file stands; a seek elsewhere reads a small window around
/// its target instead of a whole buffer, so that a decoder that jumps about (a TIFF's strips
/// in any order) pays for a KiB a jump, and a walk backwards finds most targets in the window
/// before. Refills after a window double up to the whole buffer, as reading goes on.
pub struct Watched<'w, 'a, R> {
    watch: &'w Watch<'a>,
    inner: R,
    buffer: Box<[u8]>,
    start: u64,
    filled: usize,
    position: u64,
    /// How much the next refill reads.
    next_fill: usize,
}

/// Bytes read around the target of a seek that leaves the buffer: half before, half after.
const WINDOW: usize = 1 << 10;

impl<R> Watched<'_, '_, R> {
    fn end(&self) -> u64 {
        self.start + self.filled as u64
    }

    /// The buffered bytes from `position` on.
    fn buffered(&self) -> &[u8] {
        let from = (self.position - self.start) as usize;
        &self.buffer[from..self.filled]
    }
}

impl<R: Read> Watched<'_, '_, R> {
    /// Reads once from the file into the buffer, from where it stands, at most `most` bytes.
    fn refill(&mut self, most: usize) -> io::Result<()> {
        let at = self.end();
        let count = loop {
            match self.inner.read(&mut self.buffer[..most]) {
                Err(error) if error.kind() == io::ErrorKind::Interrupted => continue,
                other => break other.map_err(|error| self.watch.failed(error))?,
            }
        };
        self.start = at;
        self.filled = count;
        Ok(())
    }
}

impl<R: Read + Seek> Watched<'_, '_, R> {
    /// Goes back `count` bytes, within the buffer when they are still in it.
    pub fn back(&mut self, count: u64) -> io::Result<()> {
        let to = self.position.saturating_sub(count);
        self.seek_to(to).map_err(|error| self.watch.failed(error))
    }

    /// Moves decoding to `target`: within the buffer when it is there, else through a window
    /// read around it.
    fn seek_to(&mut self, target: u64) -> io::Result<()> {
        if (self.start..=self.end()).contains(&target) {
            self.position = target;
            return Ok(());
        }
        let from = target.saturating_sub(WINDOW as u64 / 2);
        self.inner.seek(SeekFrom::Start(from))?;
        self.start = from;
        self.filled = 0;
        self.refill(WINDOW)?;
        self.next_fill = 2 * WINDOW;
        if target > self.end() {
            // Past the end of the file: reading there finds nothing.
            self.inner.seek(SeekFrom::Start(target))?;
            self.start = target;
            self.filled = 0;
        }
        self.position = target;
        Ok(())
    }
}

impl<R: Read> Read for Watched<'_, '_, R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.watch.reached(self.position)?;
        let most = buf.len().min(MOST_AT_ONCE);
        if self.position == self.end() && most >= self.buffer.len() {
            // A large read goes straight to the caller.
            let count = self
                .inner
                .read(&mut buf[..most])
                .map_err(|error| self.watch.failed(error))?;
            self.position += count as u64;
            self.start = self.position;
            self.filled = 0;
            return Ok(count);
        }
        let available = self.fill_buf()?;
        let count = available.len().min(most);
        buf[..count].copy_from_slice(&available[..count]);
        self.consume(count);
        Ok(count)
    }
}

impl<R: Read> BufRead for Watched<'_, '_, R> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        self.watch.reached(self.position)?;
        if self.position == self.end() {
            let most = self.next_fill;
            self.refill(most)?;
            self.next_fill = (most * 2).min(self.buffer.len());
        }
        Ok(self.buffered())
    }
    fn consume(&mut self, amount: usize) {
        self.position = (self.position + amount as u64).min(self.end());
    }
}

impl<R: Read + Seek> Seek for Watched<'_, '_, R> {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        let target = match to {
            SeekFrom::Start(target) => Some(target),
            SeekFrom::Current(delta) => self.position.checked_add_signed(delta),
            SeekFrom::End(_) => {
                let target = self
                    .inner
                    .seek(to)
                    .map_err(|error| self.watch.failed(error))?;
                self.start = target;
                self.filled = 0;
                self.position = target;
                return Ok(target);
            }
        };
        let target = target.ok_or_else(|| {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                "a seek before the file's start",
            )
        })?;
        self.seek_to(target)
            .map_err(|error| self.watch.failed(error))?;
        Ok(target)
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

    /// Seeks anywhere (backwards, forwards, past the end) and reads of any length, small ones
    /// through the buffer and large ones past it, give the file's own bytes.
    #[test]
    fn reads_after_any_seek_give_the_bytes_there() {
        let bytes: Vec<u8> = (0..300_000u32).map(|i| (i * 31 % 251) as u8).collect();
        let go_on = |_| ControlFlow::Continue(());
        let watch = Watch::new(bytes.len() as u64, &go_on);
        let mut reader = watch.reader(io::Cursor::new(&bytes[..]));
        let mut state = 12345u64;
        let mut next = |below: u64| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) % below
        };
        let mut at = 0u64;
        for _ in 0..2000 {
            match next(4) {
                0 => at = next(bytes.len() as u64 + 100),
                1 => at = at.saturating_sub(next(3000)),
                _ => {}
            }
            assert_eq!(reader.seek(SeekFrom::Start(at)).expect("seek"), at);
            let want = [1, 7, 600, 5000, 70_000][next(5) as usize];
            let mut got = vec![0; want];
            let count = reader.read(&mut got).expect("read");
            let from = (at as usize).min(bytes.len());
            let expected = &bytes[from..(from + want).min(bytes.len())];
            assert!(count <= expected.len() && count > 0 || expected.is_empty());
            assert_eq!(&got[..count], &expected[..count], "{count} bytes at {at}");
            at += count as u64;
            assert_eq!(reader.stream_position().expect("position"), at);
        }
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
