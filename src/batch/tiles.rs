//! A poster cut into tiles: `C x R` rectangles of nearly equal size, numbered row by row from
//! the top left (horizontal bands are `1 x N`). Each rendered tile says where it lies in a PNG
//! text chunk, so parts merge without being told their order.

use super::BatchError;
use crate::render::Window;
use std::str::FromStr;

/// The PNG text chunk's keyword that holds a tile's place.
pub const TILE_KEYWORD: &str = "heightray-tile";

/// Columns and rows of tiles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileGrid {
    /// Tiles across.
    pub columns: u32,
    /// Tiles down.
    pub rows: u32,
}

impl TileGrid {
    /// `count` horizontal bands.
    pub fn bands(count: u32) -> TileGrid {
        TileGrid {
            columns: 1,
            rows: count,
        }
    }

    /// How many tiles.
    pub fn count(&self) -> u64 {
        u64::from(self.columns) * u64::from(self.rows)
    }

    /// Tile `index` of an image of `size` (row by row), or a message if there is no such tile
    /// or the image has fewer pixels than the grid has tiles along a side.
    pub fn tile(&self, index: u64, (width, height): (u32, u32)) -> Result<TilePlace, BatchError> {
        let (columns, rows) = (self.columns, self.rows);
        if index >= self.count() {
            return Err(BatchError::NoSuchTile {
                index,
                columns: columns.into(),
                rows: rows.into(),
            });
        }
        if columns > width || rows > height {
            return Err(BatchError::TooSmall {
                width,
                height,
                columns,
                rows,
            });
        }
        let cut = |k: u64, of: u32, length: u32| (k * u64::from(length) / u64::from(of)) as u32;
        let (c, r) = (
            index % u64::from(self.columns),
            index / u64::from(self.columns),
        );
        let (x0, x1) = (cut(c, self.columns, width), cut(c + 1, self.columns, width));
        let (y0, y1) = (cut(r, self.rows, height), cut(r + 1, self.rows, height));
        Ok(TilePlace {
            window: Window {
                x: x0,
                y: y0,
                width: x1 - x0,
                height: y1 - y0,
            },
            whole: (width, height),
        })
    }
}

impl FromStr for TileGrid {
    type Err = BatchError;
    fn from_str(s: &str) -> Result<TileGrid, BatchError> {
        let parsed = s.split_once(['x', 'X']).and_then(|(c, r)| {
            Some((c.trim().parse::<u32>().ok()?, r.trim().parse::<u32>().ok()?))
        });
        match parsed {
            Some((columns, rows)) if (1..=256).contains(&columns) && (1..=256).contains(&rows) => {
                Ok(TileGrid { columns, rows })
            }
            _ => Err(BatchError::Tiles(s.to_owned())),
        }
    }
}

/// Where a tile lies in its whole image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TilePlace {
    /// Its pixels.
    pub window: Window,
    /// The whole image's width and height.
    pub whole: (u32, u32),
}

impl TilePlace {
    /// The text a tile's PNG keeps under [`TILE_KEYWORD`]: `x y width height W H`.
    pub fn to_text(&self) -> String {
        let w = &self.window;
        format!(
            "{} {} {} {} {} {}",
            w.x, w.y, w.width, w.height, self.whole.0, self.whole.1
        )
    }

    /// Reads [`TilePlace::to_text`]'s text back, checking the tile lies in the image.
    pub fn from_text(text: &str) -> Option<TilePlace> {
        let numbers: Vec<u32> = text
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .ok()?;
        let [x, y, width, height, w, h] = numbers[..] else {
            return None;
        };
        let inside = |start: u32, len: u32, whole: u32| {
            len > 0 && start.checked_add(len).is_some_and(|end| end <= whole)
        };
        (inside(x, width, w) && inside(y, height, h)).then_some(TilePlace {
            window: Window {
                x,
                y,
                width,
                height,
            },
            whole: (w, h),
        })
    }

    /// This tile grown by `margin` pixels on every side, within the image.
    pub fn grown(&self, margin: u32) -> Window {
        let w = &self.window;
        let (x0, y0) = (w.x.saturating_sub(margin), w.y.saturating_sub(margin));
        let x1 = (w.x + w.width).saturating_add(margin).min(self.whole.0);
        let y1 = (w.y + w.height).saturating_add(margin).min(self.whole.1);
        Window {
            x: x0,
            y: y0,
            width: x1 - x0,
            height: y1 - y0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_cover_the_image_once() {
        let grid: TileGrid = "3x2".parse().unwrap();
        let size = (10, 7);
        let mut covered = vec![0; 70];
        for index in 0..grid.count() {
            let place = grid.tile(index, size).unwrap();
            assert_eq!(TilePlace::from_text(&place.to_text()), Some(place));
            let w = place.window;
            for y in w.y..w.y + w.height {
                for x in w.x..w.x + w.width {
                    covered[(y * 10 + x) as usize] += 1;
                }
            }
        }
        assert!(covered.iter().all(|&c| c == 1), "{covered:?}");
        // Columns cut at 10/3 and 20/3, rows at 7/2: the last tile is 4 x 4 from (6, 3).
        let last = grid.tile(5, size).unwrap().window;
        assert_eq!((last.x, last.y, last.width, last.height), (6, 3, 4, 4));
        assert!(grid.tile(6, size).is_err());
        assert!(TileGrid::bands(8).tile(0, (4, 4)).is_err());
        let grown = grid.tile(4, size).unwrap().grown(2);
        assert_eq!((grown.x, grown.y, grown.width, grown.height), (1, 1, 7, 6));
        assert_eq!(TilePlace::from_text("0 0 5 5 4 4"), None);
    }
}
