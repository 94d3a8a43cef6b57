//! SVG drawn over a product's colour raster (16 bits a channel, unassociated coverage), with
//! the font annotations use.

use super::Rgba16;
use crate::render::annotate::DrawError;
use resvg::tiny_skia::{Color, Pixmap, Transform};

/// Rows drawn at a time: the drawing's memory stays a band's, whatever the raster's size.
const BAND: u32 = 256;
/// Rows drawn above and below a band and dropped: marks crossing its edge are drawn whole.
const BORDER: u32 = 4;

/// Draws `svg` (of the whole raster, `size` pixels) over `pixels`, row by row from the top.
pub fn draw_over(
    svg: &str,
    pixels: &mut [Rgba16],
    (width, height): (u32, u32),
) -> Result<(), DrawError> {
    const WHAT: &str = "contour lines";
    let tree = DrawError::tree(svg, WHAT)?;
    let rows = BAND + 2 * BORDER;
    let mut pixmap = Pixmap::new(width, rows).ok_or(DrawError::Canvas(WHAT))?;
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
