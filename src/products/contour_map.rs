//! Contour lines on a map product seen straight down: the surface's lines of equal height
//! ([`isolines`]) drawn at a constant width, every index line labelled with its height
//! ([`contour_labels`]), the line broken under its label. They are drawn over pictures only
//! (colours), never into a product's values.

use super::contour_labels::{self, Label, LabelStyle, Labelled};
use super::grid::OrthoGrid;
use super::isolines::isolines;
use crate::heightfield::Heightfield;
use crate::render::annotate::{escaped, trimmed};
use crate::render::{level_in_map_units, Contours};
use std::fmt::Write;

/// The lines' colour: a dark brown, as printed maps draw contours.
const INK: &str = "#55412b";
/// The labels' colour, darker than the lines so the digits read.
const LABEL_INK: &str = "#3b2a1a";
/// How much of the picture a line covers: ordinary and index lines.
const STRENGTH: [f64; 2] = [0.55, 0.85];
/// The image height whose ordinary lines are one pixel wide; taller images draw wider lines.
const ONE_PIXEL_HEIGHT: f64 = 900.0;

/// Contour lines over a map product.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapContours {
    /// Grid height between lines.
    interval_z: f64,
    /// The same interval in the map's height unit, which labels are written in.
    interval: f64,
    /// Every this many lines is a labelled index line (0: none).
    index_every: u32,
}

/// One level's lines, in image pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// Its height, in the map's height unit.
    pub value: f64,
    /// Whether it is an index line (wider, labelled).
    pub index: bool,
    /// Its lines, as points in pixels from the image's top-left corner.
    pub lines: Vec<Vec<[f64; 2]>>,
}

/// How wide lines are drawn and how labels are sized, in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapStyle {
    /// An ordinary line's width (index lines are twice as wide).
    pub line_px: f64,
    /// The labels' size and spacing.
    pub labels: LabelStyle,
}

impl MapStyle {
    /// The style of a raster of `grid`'s size: lines one pixel wide up to 900 rows, text a
    /// thirty-second of the shorter side (12 to 72 pixels), labels on a line at least a
    /// third of the longer side apart.
    pub fn of(grid: &OrthoGrid) -> MapStyle {
        let (w, h) = (f64::from(grid.width), f64::from(grid.height));
        let font_px = (w.min(h) / 32.0).clamp(12.0, 72.0);
        MapStyle {
            line_px: (h / ONE_PIXEL_HEIGHT).max(1.0),
            labels: LabelStyle {
                font_px,
                spacing_px: (w.max(h) / 3.0).max(15.0 * font_px),
            },
        }
    }
}

impl MapContours {
    /// The lines `contours` asks for on `field`.
    pub fn new(contours: &Contours, field: &Heightfield) -> MapContours {
        MapContours {
            interval_z: contours.interval_z(),
            interval: level_in_map_units(field, contours.interval_z()),
            index_every: contours.index_every(),
        }
    }

    /// Every level's lines on `grid`, from the lowest level.
    pub fn levels(&self, field: &Heightfield, grid: &OrthoGrid) -> Vec<Level> {
        isolines(field, self.interval_z)
            .into_iter()
            .map(|(k, lines)| Level {
                value: k as f64 * self.interval,
                index: self.index_every > 0 && k.rem_euclid(i64::from(self.index_every)) == 0,
                lines: lines
                    .iter()
                    .map(|line| line.iter().map(|&p| grid.image_point(p)).collect())
                    .collect(),
            })
            .collect()
    }

    /// The labels of the index lines of `levels`, text `width_of(text)` pixels wide.
    pub fn labels(
        levels: &[Level],
        grid: &OrthoGrid,
        style: &MapStyle,
        width_of: &dyn Fn(&str) -> f64,
    ) -> Vec<Label> {
        let lines: Vec<Labelled<'_>> = levels
            .iter()
            .filter(|level| level.index)
            .flat_map(|level| {
                level.lines.iter().map(|points| Labelled {
                    value: level.value,
                    text: trimmed(level.value),
                    points,
                })
            })
            .collect();
        contour_labels::place(&lines, (grid.width, grid.height), width_of, style.labels)
    }

    /// The SVG of the lines and labels over an image of `grid`'s size: lines broken under
    /// the labels, labels dark on a light halo.
    pub fn svg(levels: &[Level], labels: &[Label], grid: &OrthoGrid, style: &MapStyle) -> String {
        let (w, h) = (grid.width, grid.height);
        let font = style.labels.font_px;
        let turned = |label: &Label| {
            let [x, y] = label.at;
            format!("translate({x:.3} {y:.3}) rotate({:.3})", label.angle_deg)
        };
        let mut svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             font-family=\"sans-serif\"><defs><mask id=\"gaps\" maskUnits=\"userSpaceOnUse\" \
             x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\"><rect width=\"{w}\" height=\"{h}\" \
             fill=\"#ffffff\"/>"
        );
        for label in labels {
            let [bw, bh] = label.size;
            let _ = write!(
                svg,
                "<rect x=\"{:.3}\" y=\"{:.3}\" width=\"{bw:.3}\" height=\"{bh:.3}\" \
                 transform=\"{}\" fill=\"#000000\"/>",
                -0.5 * bw,
                -0.5 * bh,
                turned(label)
            );
        }
        let _ = write!(
            svg,
            "</mask></defs><g mask=\"url(#gaps)\" fill=\"none\" stroke=\"{INK}\" \
             stroke-linejoin=\"round\" stroke-linecap=\"round\">"
        );
        for level in levels {
            let mut d = String::new();
            for line in &level.lines {
                for (k, [x, y]) in line.iter().enumerate() {
                    let _ = write!(d, "{}{x:.3} {y:.3} ", if k == 0 { 'M' } else { 'L' });
                }
            }
            let kind = usize::from(level.index);
            let _ = write!(
                svg,
                "<path d=\"{d}\" stroke-width=\"{:.3}\" stroke-opacity=\"{}\"/>",
                style.line_px * if level.index { 2.0 } else { 1.0 },
                STRENGTH[kind]
            );
        }
        svg.push_str("</g>");
        for label in labels {
            let _ = write!(
                svg,
                "<text transform=\"{}\" y=\"{:.3}\" font-size=\"{font:.3}\" \
                 text-anchor=\"middle\" fill=\"{LABEL_INK}\" stroke=\"#ffffff\" \
                 stroke-opacity=\"0.85\" stroke-width=\"{:.3}\" stroke-linejoin=\"round\" \
                 paint-order=\"stroke\">{}</text>",
                turned(label),
                0.36 * font,
                0.28 * font,
                escaped(&label.text)
            );
        }
        svg.push_str("</svg>");
        svg
    }

    /// Draws the lines and labels over `pixels`, a colour raster of `grid`; the labels drawn.
    #[cfg(feature = "annotate")]
    pub fn draw(
        &self,
        field: &Heightfield,
        grid: &OrthoGrid,
        pixels: &mut [super::Rgba16],
    ) -> Result<Vec<Label>, crate::render::annotate::DrawError> {
        let style = MapStyle::of(grid);
        let levels = self.levels(field, grid);
        let measure = crate::render::annotate::TextWidth::new();
        let font_px = style.labels.font_px;
        let labels = MapContours::labels(&levels, grid, &style, &|text| measure.of(text, font_px));
        let svg = MapContours::svg(&levels, &labels, grid, &style);
        super::overlay::draw_over(&svg, pixels, (grid.width, grid.height))?;
        Ok(labels)
    }
}
