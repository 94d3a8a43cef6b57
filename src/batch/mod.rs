//! Work split into numbered pieces that independent processes take by index: a flythrough's
//! frames and a poster's tiles. The contract a scheduler uses is the share: with `N` workers,
//! worker `I` (0 to `N-1`) takes pieces `I`, `I+N`, `I+2N`... of the list, so every piece is
//! taken exactly once and nothing is shared between workers but the output folder.

mod error;
mod frames;
mod tiles;

pub use error::BatchError;
pub use frames::{frame_file, FrameSpec};
pub use tiles::{TileGrid, TilePlace, TILE_KEYWORD};

use std::fmt;
use std::str::FromStr;

/// Worker `index` of `count` (`I/N`, from 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Share {
    /// Which worker, from 0.
    pub index: u64,
    /// How many workers.
    pub count: u64,
}

impl Share {
    /// The one worker that takes everything.
    pub const ALL: Share = Share { index: 0, count: 1 };

    /// The items of `items` this share takes: every `count`-th from its `index`.
    pub fn of<T: Copy>(&self, items: &[T]) -> Vec<T> {
        items
            .iter()
            .skip(self.index as usize)
            .step_by(self.count as usize)
            .copied()
            .collect()
    }
}

impl FromStr for Share {
    type Err = BatchError;
    fn from_str(s: &str) -> Result<Share, BatchError> {
        let parsed = s.split_once('/').and_then(|(i, n)| {
            Some((i.trim().parse::<u64>().ok()?, n.trim().parse::<u64>().ok()?))
        });
        match parsed {
            Some((index, count)) if count > 0 && index < count => Ok(Share { index, count }),
            _ => Err(BatchError::Share(s.to_owned())),
        }
    }
}

impl fmt::Display for Share {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shares_take_every_item_once() {
        let items: Vec<u64> = (10..23).collect();
        let mut taken: Vec<u64> = (0..4)
            .flat_map(|index| Share { index, count: 4 }.of(&items))
            .collect();
        assert_eq!(Share { index: 1, count: 4 }.of(&items), [11, 15, 19]);
        taken.sort();
        assert_eq!(taken, items);
        assert_eq!("3/4".parse(), Ok(Share { index: 3, count: 4 }));
        for bad in ["4/4", "1/0", "1", "a/b", "-1/2"] {
            assert!(bad.parse::<Share>().is_err(), "{bad}");
        }
    }
}
