//! Which frames of a flythrough to render: `N` (frame N alone), `A..B` (A up to but not
//! including B), `A..=B` (up to B), `A..B/STEP` (every STEP-th from A), or `all`; and the file
//! each frame goes to.

use super::BatchError;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// A set of frame numbers as `--frames` takes it, before the path's length is known.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameSpec {
    start: u64,
    /// One past the last, or `None` for the path's end.
    end: Option<u64>,
    step: u64,
}

impl FrameSpec {
    /// The frames of a path of `frames` frames, in order; an error names the path's frames
    /// when the spec reaches beyond them or takes none.
    pub fn frames(&self, frames: u64) -> Result<Vec<u64>, BatchError> {
        let end = self.end.unwrap_or(frames);
        if end > frames || self.start >= end {
            return Err(BatchError::Beyond {
                asked: self.to_string(),
                frames,
            });
        }
        Ok((self.start..end).step_by(self.step as usize).collect())
    }
}

impl std::fmt::Display for FrameSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.end {
            None => write!(f, "all")?,
            Some(end) if end == self.start + 1 => write!(f, "{}", self.start)?,
            Some(end) => write!(f, "{}..{end}", self.start)?,
        }
        if self.step > 1 {
            write!(f, "/{}", self.step)?;
        }
        Ok(())
    }
}

impl FromStr for FrameSpec {
    type Err = BatchError;
    fn from_str(s: &str) -> Result<FrameSpec, BatchError> {
        let bad = || BatchError::Frames(s.to_owned());
        let number = |t: &str| t.trim().parse::<u64>().map_err(|_| bad());
        let (range, step) = match s.split_once('/') {
            Some((range, step)) => (range, number(step)?),
            None => (s, 1),
        };
        if step == 0 {
            return Err(bad());
        }
        let (start, end) = if range.trim() == "all" {
            (0, None)
        } else if let Some((a, b)) = range.split_once("..=") {
            (number(a)?, Some(number(b)?.checked_add(1).ok_or_else(bad)?))
        } else if let Some((a, b)) = range.split_once("..") {
            (number(a)?, Some(number(b)?))
        } else {
            let n = number(range)?;
            (n, Some(n.checked_add(1).ok_or_else(bad)?))
        };
        if end.is_some_and(|end| end <= start) {
            return Err(BatchError::NoFrames(s.to_owned()));
        }
        Ok(FrameSpec { start, end, step })
    }
}

/// The file frame `frame` is written to in `folder`: `frame-00042.png` (five digits or more).
pub fn frame_file(folder: &Path, frame: u64) -> PathBuf {
    folder.join(format!("frame-{frame:05}.png"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames(spec: &str, of: u64) -> Result<Vec<u64>, BatchError> {
        spec.parse::<FrameSpec>()?.frames(of)
    }

    #[test]
    fn every_form_names_its_frames() {
        assert_eq!(frames("3", 10), Ok(vec![3]));
        assert_eq!(frames("2..5", 10), Ok(vec![2, 3, 4]));
        assert_eq!(frames("2..=5", 10), Ok(vec![2, 3, 4, 5]));
        assert_eq!(frames("0..10/4", 10), Ok(vec![0, 4, 8]));
        assert_eq!(frames("all", 4), Ok(vec![0, 1, 2, 3]));
        assert_eq!(frames("all/2", 5), Ok(vec![0, 2, 4]));
        let beyond = frames("8..12", 10).unwrap_err().to_string();
        assert!(beyond.contains("0..10"), "{beyond}");
        for bad in ["5..5", "5..2", "a", "1..2/0", "-1", "1..", ""] {
            assert!(bad.parse::<FrameSpec>().is_err(), "{bad}");
        }
        assert_eq!(
            frame_file(Path::new("out"), 42),
            Path::new("out/frame-00042.png")
        );
    }
}
