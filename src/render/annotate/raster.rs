//! An SVG of the whole image drawn over a window of its pixels. It is rasterised in blocks
//! fixed in the whole image (each with a border around it), so that every pixel is drawn the
//! same way whichever window holds it: a poster's tiles merge into the whole picture's bytes.
//! The marks are composed over bytes (0x00RRGGBB) or over 16-bit words alike ([`Marked`]).

use super::sheet::{Annotations, Sheet};
use super::svg_options;
use crate::render::Window;
use resvg::tiny_skia::{Pixmap, PremultipliedColorU8, Transform};
use resvg::usvg::Tree;
use thiserror::Error;

/// Why an SVG could not be drawn over pixels.
#[derive(Debug, Error)]
pub enum DrawError {
    /// The SVG would not parse.
    #[error("cannot draw the {what}: {reason}")]
    Svg {
        /// What was drawn ("annotations", "contour lines").
        what: &'static str,
        /// The parser's error.
        reason: resvg::usvg::Error,
    },
    /// No canvas of the size could be made.
    #[error("cannot draw the {0}")]
    Canvas(&'static str),
}

impl DrawError {
    /// The SVG parsed as a tree, the error naming `what` was drawn.
    pub fn tree(svg: &str, what: &'static str) -> Result<Tree, DrawError> {
        Tree::from_str(svg, &svg_options()).map_err(|reason| DrawError::Svg { what, reason })
    }
}

impl Annotations {
    /// Draws these annotations into `pixels` (0x00RRGGBB, or 16-bit red, green and blue; row
    /// by row), which hold `window` of `sheet`'s whole image.
    pub fn draw<P: Marked>(
        &self,
        sheet: &Sheet<'_>,
        pixels: &mut [P],
        window: Window,
    ) -> Result<(), DrawError> {
        if self.is_empty() {
            return Ok(());
        }
        draw_over(&self.svg(sheet), pixels, window)
    }
}

/// The side of a block, in pixels.
const BLOCK: u32 = 256;
/// Pixels drawn around a block and dropped: marks crossing its edge are drawn whole.
const BORDER: u32 = 4;

/// Draws `svg` (of the whole image) over `pixels` (row by row), which hold `window` of the
/// whole image.
pub fn draw_over<P: Marked>(svg: &str, pixels: &mut [P], window: Window) -> Result<(), DrawError> {
    const WHAT: &str = "annotations";
    let tree = DrawError::tree(svg, WHAT)?;
    let side = BLOCK + 2 * BORDER;
    let mut pixmap = Pixmap::new(side, side).ok_or(DrawError::Canvas(WHAT))?;
    let (x_end, y_end) = (window.x + window.width, window.y + window.height);
    for by in (window.y / BLOCK)..y_end.div_ceil(BLOCK) {
        for bx in (window.x / BLOCK)..x_end.div_ceil(BLOCK) {
            let (x0, y0) = (bx * BLOCK, by * BLOCK);
            pixmap.fill(resvg::tiny_skia::Color::TRANSPARENT);
            let shift = |start: u32| -(start as f32 - BORDER as f32);
            let transform = Transform::from_translate(shift(x0), shift(y0));
            resvg::render(&tree, transform, &mut pixmap.as_mut());
            let marks = pixmap.pixels();
            // The block's pixels the window holds.
            for y in y0.max(window.y)..(y0 + BLOCK).min(y_end) {
                for x in x0.max(window.x)..(x0 + BLOCK).min(x_end) {
                    let mark = marks[((y - y0 + BORDER) * side + (x - x0 + BORDER)) as usize];
                    let pixel =
                        &mut pixels[((y - window.y) * window.width + x - window.x) as usize];
                    *pixel = pixel.under(mark);
                }
            }
        }
    }
    Ok(())
}

/// A pixel marks are drawn over.
pub trait Marked: Copy {
    /// This pixel under `mark` (its colour premultiplied by its cover).
    fn under(self, mark: PremultipliedColorU8) -> Self;
}

impl Marked for u32 {
    /// A 0x00RRGGBB pixel under the mark.
    fn under(self, mark: PremultipliedColorU8) -> u32 {
        let keep = 255 - u32::from(mark.alpha());
        let channel = |shift: u32, value: u8| {
            let below = (self >> shift) & 0xff;
            (u32::from(value) + (below * keep + 127) / 255).min(255) << shift
        };
        channel(16, mark.red()) | channel(8, mark.green()) | channel(0, mark.blue())
    }
}

impl Marked for [u16; 3] {
    /// 16-bit red, green and blue under the mark: the bytes' composition at 257 times the
    /// scale, so the words round to the bytes the same marks give.
    fn under(self, mark: PremultipliedColorU8) -> [u16; 3] {
        let keep = 255 - u32::from(mark.alpha());
        let channel = |below: u16, value: u8| {
            let mixed = u32::from(value) * 257 + (u32::from(below) * keep + 127) / 255;
            mixed.min(65535) as u16
        };
        let [r, g, b] = self;
        [
            channel(r, mark.red()),
            channel(g, mark.green()),
            channel(b, mark.blue()),
        ]
    }
}
