//! Putting a rendered frame into the window's pixels: nearest-neighbour scaling from the
//! render size to the view rectangle, the heat-map colouring of per-pixel counters, and the
//! overlay of pixels that differ from the exact render.

use super::settings::HeatMode;
use crate::render::{Frame, PixelStats};

/// A rectangle of window pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

impl PixelRect {
    /// Whether window pixel `(x, y)` lies inside.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        x >= f64::from(self.x)
            && y >= f64::from(self.y)
            && x < f64::from(self.x + self.width)
            && y < f64::from(self.y + self.height)
    }
}

/// The window pixels an egui rectangle (in points) covers, at `pixels_per_point`.
pub fn physical_rect(rect: egui::Rect, pixels_per_point: f32) -> PixelRect {
    let x0 = (rect.min.x * pixels_per_point).round().max(0.0) as u32;
    let y0 = (rect.min.y * pixels_per_point).round().max(0.0) as u32;
    let x1 = (rect.max.x * pixels_per_point).round().max(0.0) as u32;
    let y1 = (rect.max.y * pixels_per_point).round().max(0.0) as u32;
    PixelRect {
        x: x0,
        y: y0,
        width: x1.saturating_sub(x0),
        height: y1.saturating_sub(y0),
    }
}

/// The window buffer being drawn, 0x00RRGGBB per pixel.
pub struct Canvas<'a> {
    pub pixels: &'a mut [u32],
    pub width: u32,
    pub height: u32,
}

/// The heat map's scale: counts from 0 to `max` map onto the colour ramp.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HeatScale {
    pub mode: HeatMode,
    pub max: u32,
}

impl HeatScale {
    /// The scale for a frame: its 99.5th percentile, so that a few extreme pixels do not
    /// wash the rest out (larger counts show in the top colour).
    pub fn of(frame: &Frame, mode: HeatMode) -> HeatScale {
        let mut values: Vec<u32> = frame.stats.iter().map(|s| count(s, mode)).collect();
        let max = if values.is_empty() {
            0
        } else {
            let k = (values.len() - 1) * 995 / 1000;
            *values.select_nth_unstable(k).1
        };
        HeatScale {
            mode,
            max: max.max(1),
        }
    }

    /// The colour of a count.
    pub fn colour(&self, value: u32) -> u32 {
        ramp(value as f32 / self.max as f32)
    }
}

/// The counter a heat map shows.
pub fn count(stats: &PixelStats, mode: HeatMode) -> u32 {
    match mode {
        HeatMode::Off => 0,
        HeatMode::Cells => stats.cells,
        HeatMode::Triangles => stats.triangles,
        HeatMode::Blocks => stats.blocks,
        HeatMode::Runs => stats.runs,
        HeatMode::Samples => stats.samples,
    }
}

/// A perceptually ordered ramp (dark blue, purple, orange, pale yellow) over `[0, 1]`.
pub fn ramp(x: f32) -> u32 {
    const STOPS: [[f32; 3]; 5] = [
        [12.0, 7.0, 60.0],
        [87.0, 16.0, 110.0],
        [188.0, 55.0, 84.0],
        [249.0, 142.0, 9.0],
        [252.0, 255.0, 164.0],
    ];
    let x = x.clamp(0.0, 1.0) * (STOPS.len() - 1) as f32;
    let k = (x as usize).min(STOPS.len() - 2);
    let f = x - k as f32;
    let channel = |c: usize| (STOPS[k][c] + (STOPS[k + 1][c] - STOPS[k][c]) * f) as u32;
    (channel(0) << 16) | (channel(1) << 8) | channel(2)
}

/// How to colour the frame's pixels.
#[derive(Clone, Copy, Default)]
pub struct Look<'a> {
    /// Per-pixel counters instead of the shaded image.
    pub heat: Option<HeatScale>,
    /// Pixels that differ from the exact render, one flag per frame pixel: drawn in
    /// [`HIGHLIGHT`] over the rest, dimmed so that single pixels stand out.
    pub differs: Option<&'a [bool]>,
}

/// Colour of the pixels that differ from exact (magenta: no terrain, sky or heat colour).
pub const HIGHLIGHT: u32 = 0x00ff_00ff;

/// Draws `frame` scaled into `rect` of the canvas (clipped to the canvas).
pub fn blit(canvas: &mut Canvas<'_>, rect: PixelRect, frame: &Frame, look: Look<'_>) {
    if frame.width == 0 || frame.height == 0 || rect.width == 0 || rect.height == 0 {
        return;
    }
    let x_end = (rect.x + rect.width).min(canvas.width);
    let y_end = (rect.y + rect.height).min(canvas.height);
    if rect.x >= x_end || rect.y >= y_end {
        return;
    }
    let base = |k: usize| match look.heat {
        None => frame.pixels[k],
        Some(scale) => scale.colour(count(&frame.stats[k], scale.mode)),
    };
    // A mask of another size belongs to another frame.
    let differs = look.differs.filter(|d| d.len() == frame.pixels.len());
    let colour = |k: usize| match differs {
        None => base(k),
        Some(d) if d[k] => HIGHLIGHT,
        Some(_) => (base(k) >> 1) & 0x007f_7f7f,
    };
    // Source column of each destination column, computed once.
    let columns: Vec<usize> = (rect.x..x_end)
        .map(|x| {
            ((u64::from(x - rect.x) * u64::from(frame.width)) / u64::from(rect.width)) as usize
        })
        .collect();
    let row_start = |y: u32| (y as usize) * (canvas.width as usize) + rect.x as usize;
    let mut previous: Option<(usize, u32)> = None;
    for y in rect.y..y_end {
        let sy =
            (u64::from(y - rect.y) * u64::from(frame.height) / u64::from(rect.height)) as usize;
        let start = row_start(y);
        // Scaled up, a source row fills several window rows: the first is coloured, the
        // rest copied from it.
        if let Some((_, above)) = previous.filter(|&(row, _)| row == sy) {
            let from = row_start(above);
            canvas.pixels.copy_within(from..from + columns.len(), start);
            continue;
        }
        let source = sy * frame.width as usize;
        let row = &mut canvas.pixels[start..start + columns.len()];
        for (out, &sx) in row.iter_mut().zip(&columns) {
            *out = colour(source + sx);
        }
        previous = Some((sy, y));
    }
}

/// Maps a window pixel inside `rect` to the pixel of a `width` x `height` frame it shows.
pub fn frame_pixel(
    rect: PixelRect,
    (width, height): (u32, u32),
    x: f64,
    y: f64,
) -> Option<(u32, u32)> {
    if !rect.contains(x, y) {
        return None;
    }
    let fx = ((x - f64::from(rect.x)) * f64::from(width) / f64::from(rect.width)) as u32;
    let fy = ((y - f64::from(rect.y)) * f64::from(height) / f64::from(rect.height)) as u32;
    Some((fx.min(width - 1), fy.min(height - 1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blit_scales_by_nearest_neighbour_and_clips() {
        let mut frame = Frame::new(2, 2);
        frame.pixels = vec![1, 2, 3, 4];
        let mut pixels = vec![0u32; 5 * 3];
        let mut canvas = Canvas {
            pixels: &mut pixels,
            width: 5,
            height: 3,
        };
        let rect = PixelRect {
            x: 1,
            y: 0,
            width: 4,
            height: 4,
        };
        blit(&mut canvas, rect, &frame, Look::default());
        assert_eq!(pixels, vec![0, 1, 1, 2, 2, 0, 1, 1, 2, 2, 0, 3, 3, 4, 4]);
    }

    /// Scaled up by an uneven factor, rows copied from the row above them show the same
    /// source row as those coloured afresh: every window pixel is the frame pixel
    /// `frame_pixel` maps it to.
    #[test]
    fn blit_at_any_scale_shows_the_pixel_each_window_pixel_maps_to() {
        let mut frame = Frame::new(3, 5);
        frame.pixels = (0..15).collect();
        let (width, height) = (9, 14);
        let mut pixels = vec![u32::MAX; (width * height) as usize];
        let mut canvas = Canvas {
            pixels: &mut pixels,
            width,
            height,
        };
        let rect = PixelRect {
            x: 2,
            y: 1,
            width: 7,
            height: 13,
        };
        blit(&mut canvas, rect, &frame, Look::default());
        for y in 0..height {
            for x in 0..width {
                let shown = pixels[(y * width + x) as usize];
                let expected = frame_pixel(rect, (3, 5), f64::from(x), f64::from(y))
                    .map_or(u32::MAX, |(fx, fy)| fy * 3 + fx);
                assert_eq!(shown, expected, "window pixel ({x}, {y})");
            }
        }
    }

    #[test]
    fn frame_pixel_inverts_the_scaling() {
        let rect = PixelRect {
            x: 10,
            y: 20,
            width: 200,
            height: 100,
        };
        assert_eq!(frame_pixel(rect, (100, 50), 10.0, 20.0), Some((0, 0)));
        assert_eq!(frame_pixel(rect, (100, 50), 209.9, 119.9), Some((99, 49)));
        assert_eq!(frame_pixel(rect, (100, 50), 9.0, 20.0), None);
    }

    #[test]
    fn heat_scale_ignores_rare_outliers() {
        let mut frame = Frame::new(1000, 1);
        for (k, s) in frame.stats.iter_mut().enumerate() {
            s.cells = if k == 0 { 1_000_000 } else { 10 };
        }
        assert_eq!(HeatScale::of(&frame, HeatMode::Cells).max, 10);
        assert_eq!(ramp(0.0), 0x0c073c);
    }
}
