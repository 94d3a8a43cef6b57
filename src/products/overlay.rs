//! SVG drawn over a product's colour raster (16 bits a channel, unassociated coverage), with
//! the font annotations use; and the width that font gives a text.

use super::Rgba16;
use crate::render::annotate::{escaped, svg_options};
use resvg::tiny_skia::{Color, Pixmap, Transform};
use resvg::usvg::{Options, Tree};
use std::cell::RefCell;
use std::collections::HashMap;

/// Rows drawn at a time: the drawing's memory stays a band's, whatever the raster's size.
const BAND: u32 = 256;
/// Rows drawn above and below a band and dropped: marks crossing its edge are drawn whole.
const BORDER: u32 = 4;

/// Draws `svg` (of the whole raster, `size` pixels) over `pixels`, row by row from the top.
pub fn draw_over(
    svg: &str,
    pixels: &mut [Rgba16],
    (width, height): (u32, u32),
) -> Result<(), String> {
    let tree = Tree::from_str(svg, &svg_options())
        .map_err(|e| format!("cannot draw the contour lines: {e}"))?;
    let rows = BAND + 2 * BORDER;
    let mut pixmap = Pixmap::new(width, rows).ok_or("cannot draw the contour lines")?;
    for y0 in (0..height).step_by(BAND as usize) {
        pixmap.fill(Color::TRANSPARENT);
        let shift = -(y0 as f32 - BORDER as f32);
        resvg::render(
            &tree,
            Transform::from_translate(0.0, shift),
            &mut pixmap.as_mut(),
        );
        let marks = pixmap.pixels();
        for y in y0..(y0 + BAND).min(height) {
            for x in 0..width {
                let mark = marks[((y - y0 + BORDER) * width + x) as usize];
                let pixel = &mut pixels[(y * width + x) as usize];
                *pixel = over(*pixel, mark);
            }
        }
    }
    Ok(())
}

/// A mark (8-bit, its colour premultiplied by its cover) over a pixel of 16-bit colour and
/// coverage: "over" compositing, the result's colour unassociated again.
fn over(pixel: Rgba16, mark: resvg::tiny_skia::PremultipliedColorU8) -> Rgba16 {
    if mark.alpha() == 0 {
        return pixel;
    }
    let full = f64::from(u16::MAX);
    let a_mark = f64::from(mark.alpha()) / 255.0;
    let a_below = f64::from(pixel[3]) / full;
    let keep = a_below * (1.0 - a_mark);
    let a_out = a_mark + keep;
    let channel = |premultiplied: u8, below: u16| {
        let mixed = f64::from(premultiplied) / 255.0 + f64::from(below) / full * keep;
        ((mixed / a_out).clamp(0.0, 1.0) * full).round() as u16
    };
    [
        channel(mark.red(), pixel[0]),
        channel(mark.green(), pixel[1]),
        channel(mark.blue(), pixel[2]),
        (a_out.clamp(0.0, 1.0) * full).round() as u16,
    ]
}

/// Widths of texts in the annotations' font at one size, measured once each.
pub struct TextWidth {
    font_px: f64,
    options: Options<'static>,
    known: RefCell<HashMap<String, f64>>,
}

impl TextWidth {
    /// Texts `font_px` pixels high.
    pub fn new(font_px: f64) -> TextWidth {
        TextWidth {
            font_px,
            options: svg_options(),
            known: RefCell::new(HashMap::new()),
        }
    }

    /// The width of `text`'s ink, in pixels (six tenths of the size a character where the
    /// font draws nothing).
    pub fn of(&self, text: &str) -> f64 {
        if let Some(&width) = self.known.borrow().get(text) {
            return width;
        }
        let svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\" \
             font-family=\"sans-serif\"><text x=\"0\" y=\"0\" font-size=\"{}\">{}</text></svg>",
            self.font_px,
            escaped(text)
        );
        let measured = Tree::from_str(&svg, &self.options)
            .ok()
            .map(|tree| f64::from(tree.root().abs_bounding_box().width()))
            .filter(|w| w.is_finite() && *w > 0.0);
        let width = measured.unwrap_or_else(|| 0.6 * self.font_px * text.chars().count() as f64);
        self.known.borrow_mut().insert(text.to_owned(), width);
        width
    }
}
