//! The annotations of a picture as one SVG document of the whole image's size, every length
//! in output pixels: the title and attribution, the scale bar, the north arrow, the height
//! legend, and the vector layers' places and lines where the terrain lets the eye see them.

use super::layout::{north_angle_deg, trimmed, ScaleBar};
use super::measure::TextWidth;
use super::place_names::{arrange, reserved, Candidate, PlacedName, NAME_SIZE};
use super::sheet::{Annotations, Sheet};
use super::sight::Sight;
use super::vectors::VectorLayer;
use crate::heightfield::place;
use crate::render::{level_in_map_units, HeightSpan};
use glam::{DVec2, DVec3};
use std::fmt::Write;

impl Annotations {
    /// The places' names drawn over `sheet`'s whole image, where they are.
    pub fn place_names(&self, sheet: &Sheet<'_>) -> Vec<PlacedName> {
        place_names(self, sheet)
    }

    /// The SVG document of these annotations over `sheet`'s whole image.
    pub fn svg(&self, sheet: &Sheet<'_>) -> String {
        compose(self, sheet)
    }
}

/// Grid units between the points along a line tested for sight.
const LINE_STEP: f64 = 0.5;
/// The most points along all lines tested for sight: a longer line is tested more sparsely.
const MOST_LINE_POINTS: f64 = 200_000.0;
/// A line's height above the ground where its sight is tested, in world units.
const LINE_LIFT: f64 = 0.05;
/// Colour stops of the legend's ramp.
const LEGEND_STOPS: usize = 48;

/// The SVG of `annotations` over the picture `sheet` describes.
fn compose(annotations: &Annotations, sheet: &Sheet<'_>) -> String {
    let (w, h) = sheet.camera.whole_size();
    let (w, h) = (f64::from(w), f64::from(h));
    let mut svg = Svg {
        text: String::new(),
        em: em(sheet),
        size: DVec2::new(w, h),
    };
    for layer in &annotations.vectors {
        svg.lines(layer, sheet);
    }
    svg.places(annotations, sheet);
    if let Some(title) = &annotations.title {
        let em = svg.em;
        svg.label([em, 2.2 * em], title, 1.6, "start");
    }
    if let Some(attribution) = &annotations.attribution {
        let em = svg.em;
        svg.label([w - em, h - 0.8 * em], attribution, 0.65, "end");
    }
    if annotations.scale_bar {
        svg.scale_bar(sheet);
    }
    if annotations.north_arrow {
        svg.north_arrow(sheet);
    }
    if annotations.legend {
        svg.legend(sheet);
    }
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         font-family=\"sans-serif\">{}</svg>",
        svg.text
    )
}

/// The text size of `sheet`'s annotations, in pixels: every mark is sized in it.
fn em(sheet: &Sheet<'_>) -> f64 {
    (f64::from(sheet.camera.whole_size().1) / 40.0).clamp(14.0, 120.0)
}

/// The names of the places the eye sees, kept apart and off the other marks (see
/// [`arrange`]).
fn place_names(annotations: &Annotations, sheet: &Sheet<'_>) -> Vec<PlacedName> {
    let width = TextWidth::new();
    let width_of = |text: &str, px: f64| width.of(text, px);
    let (w, h) = sheet.camera.whole_size();
    let em = em(sheet);
    let marks = reserved(annotations, (f64::from(w), f64::from(h)), em, &width_of);
    arrange(&visible_places(annotations, sheet), &marks, em, &width_of)
}

/// The places of every layer the eye sees, with their markers in the image.
fn visible_places(annotations: &Annotations, sheet: &Sheet<'_>) -> Vec<Candidate> {
    let sight = sheet.sight();
    let eye = DVec3::from(sheet.camera.eye());
    let mut found = Vec::new();
    for layer in &annotations.vectors {
        for place in &layer.places {
            let [x, y] = place.at;
            let anchor = [x, y, sight.ground(place.at) + layer.lift];
            let Some(marker) = sheet.on_image(anchor) else {
                continue;
            };
            if !sight.sees(anchor) {
                continue;
            }
            let world = DVec3::from(sheet.terrain.world_point(anchor));
            found.push(Candidate {
                name: place.name.clone(),
                priority: place.priority,
                distance: world.distance(eye),
                marker,
            });
        }
    }
    found
}

/// An SVG document being written.
struct Svg {
    text: String,
    /// The text size, in pixels: every mark is sized in it.
    em: f64,
    /// The image's size.
    size: DVec2,
}

impl Svg {
    /// Text at `at` (its baseline), `size` ems high, white on a dark halo.
    fn label(&mut self, [x, y]: [f64; 2], text: &str, size: f64, anchor: &str) {
        let (px, halo) = (size * self.em, 0.22 * size * self.em);
        let _ = write!(
            self.text,
            "<text x=\"{x:.2}\" y=\"{y:.2}\" font-size=\"{px:.2}\" text-anchor=\"{anchor}\" \
             fill=\"#ffffff\" stroke=\"#1a1a1a\" stroke-width=\"{halo:.2}\" \
             stroke-linejoin=\"round\" paint-order=\"stroke\">{}</text>",
            escaped(text)
        );
    }

    /// The scale bar in the bottom-left corner, at the depth of the view's target.
    fn scale_bar(&mut self, sheet: &Sheet<'_>) {
        let metres = sheet.terrain.field().cell_metres().map(|[_, y]| y);
        let Some(bar) = ScaleBar::at_target(&sheet.camera, metres) else {
            return;
        };
        let em = self.em;
        let (x0, y) = (1.2 * em, self.size.y - 2.6 * em);
        let (length, thick) = (bar.pixels, 0.45 * em);
        for k in 0..4 {
            let fill = if k % 2 == 0 { "#1a1a1a" } else { "#ffffff" };
            let _ = write!(
                self.text,
                "<rect x=\"{:.2}\" y=\"{y:.2}\" width=\"{:.2}\" height=\"{thick:.2}\" \
                 fill=\"{fill}\" stroke=\"#1a1a1a\" stroke-width=\"{:.2}\"/>",
                x0 + length * f64::from(k) / 4.0,
                length / 4.0,
                0.08 * em
            );
        }
        self.label([x0, y - 0.35 * em], "0", 0.8, "middle");
        self.label([x0 + length, y - 0.35 * em], &bar.label, 0.8, "middle");
        let note = "at the view's target (perspective)";
        self.label([x0, y + thick + 1.0 * em], note, 0.65, "start");
    }

    /// The north arrow in the top-right corner: grid north as the image shows it at the
    /// view's target.
    fn north_arrow(&mut self, sheet: &Sheet<'_>) {
        let Some(angle) = north_angle_deg(&sheet.camera) else {
            return;
        };
        let em = self.em;
        let (cx, cy) = (self.size.x - 2.4 * em, 3.4 * em);
        // A compass needle: the north half dark, the south half white.
        let (tip, half) = (1.1 * em, 0.32 * em);
        let _ = write!(
            self.text,
            "<circle cx=\"{cx:.2}\" cy=\"{cy:.2}\" r=\"{:.2}\" fill=\"#ffffff\" \
             fill-opacity=\"0.8\" stroke=\"#1a1a1a\" stroke-width=\"{:.2}\"/>\
             <g transform=\"translate({cx:.2} {cy:.2}) rotate({angle:.4})\" \
             stroke=\"#1a1a1a\" stroke-width=\"{:.2}\" stroke-linejoin=\"round\">\
             <path d=\"M0 {:.2} L{half:.2} 0 L0 {tip:.2} L{:.2} 0 Z\" fill=\"#ffffff\"/>\
             <path d=\"M0 {:.2} L{half:.2} 0 L{:.2} 0 Z\" fill=\"#b01c10\"/></g>",
            1.35 * em,
            0.08 * em,
            0.07 * em,
            -tip,
            -half,
            -tip,
            -half,
        );
        let (s, c) = angle.to_radians().sin_cos();
        let at = [cx + s * 2.1 * em, cy - c * 2.1 * em + 0.32 * em];
        self.label(at, "N", 0.9, "middle");
    }

    /// The height legend: the ramp as a vertical bar on the right, round heights marked.
    fn legend(&mut self, sheet: &Sheet<'_>) {
        let field = sheet.terrain.field();
        if field.drape().is_some_and(|d| d.opacity() >= 1.0) {
            // The map shows the drape's colours, not the ramp's.
            return;
        }
        let span = HeightSpan::of(sheet.terrain);
        let (lo, hi) = (span.lo, span.hi);
        let metres = place::elevation_metres(field, 1.0);
        // Heights are shown in metres on a georeferenced map, else in the map's units; both
        // are proportional to grid height.
        let per_z = metres.unwrap_or_else(|| level_in_map_units(field, 1.0));
        let em = self.em;
        let length = (0.3 * self.size.y).min(12.0 * em);
        let (x, bottom) = (self.size.x - 1.6 * em, self.size.y - 2.4 * em);
        let top = bottom - length;
        let mut stops = String::new();
        for k in 0..=LEGEND_STOPS {
            let f = k as f64 / LEGEND_STOPS as f64;
            let [r, g, b] = sheet.ramp.display_rgb(lo + (hi - lo) * f, span);
            let _ = write!(
                stops,
                "<stop offset=\"{f:.4}\" stop-color=\"#{r:02x}{g:02x}{b:02x}\"/>"
            );
        }
        let _ = write!(
            self.text,
            "<defs><linearGradient id=\"ramp\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">{stops}\
             </linearGradient></defs><rect x=\"{:.2}\" y=\"{top:.2}\" width=\"{:.2}\" \
             height=\"{length:.2}\" fill=\"url(#ramp)\" stroke=\"#1a1a1a\" \
             stroke-width=\"{:.2}\"/>",
            x - 0.8 * em,
            0.8 * em,
            0.08 * em
        );
        let unit = if metres.is_some() { " (m)" } else { "" };
        self.label([x, top - 0.6 * em], &format!("height{unit}"), 0.7, "end");
        for value in round_marks(lo * per_z, hi * per_z) {
            let y = bottom - length * (value / per_z - lo) / (hi - lo);
            let _ = write!(
                self.text,
                "<line x1=\"{:.2}\" x2=\"{:.2}\" y1=\"{y:.2}\" y2=\"{y:.2}\" \
                 stroke=\"#1a1a1a\" stroke-width=\"{:.2}\"/>",
                x - 1.1 * em,
                x - 0.8 * em,
                0.1 * em
            );
            self.label([x - 1.3 * em, y + 0.25 * em], &trimmed(value), 0.65, "end");
        }
    }

    /// A vector layer's lines where the eye sees them.
    fn lines(&mut self, layer: &VectorLayer, sheet: &Sheet<'_>) {
        let sight = sheet.sight();
        let total: f64 = layer
            .lines
            .iter()
            .flat_map(|l| l.windows(2))
            .map(|p| DVec2::from(p[0]).distance(DVec2::from(p[1])))
            .sum();
        let step = LINE_STEP.max(total / MOST_LINE_POINTS);
        let [r, g, b] = layer.colour;
        for line in &layer.lines {
            for run in seen_runs(line, step, &sight, sheet) {
                let points: String = run.iter().map(|[x, y]| format!("{x:.2},{y:.2} ")).collect();
                for (colour, width) in [
                    ("#1a1a1a".to_owned(), 0.4),
                    (format!("#{r:02x}{g:02x}{b:02x}"), 0.22),
                ] {
                    let _ = write!(
                        self.text,
                        "<polyline points=\"{points}\" fill=\"none\" stroke=\"{colour}\" \
                         stroke-width=\"{:.2}\" stroke-linejoin=\"round\" \
                         stroke-linecap=\"round\"/>",
                        width * self.em
                    );
                }
            }
        }
    }

    /// Every visible place's marker, then the names there is room for.
    fn places(&mut self, annotations: &Annotations, sheet: &Sheet<'_>) {
        for place in &visible_places(annotations, sheet) {
            let [px, py] = place.marker;
            let _ = write!(
                self.text,
                "<circle cx=\"{px:.2}\" cy=\"{py:.2}\" r=\"{:.2}\" fill=\"#ffffff\" \
                 stroke=\"#1a1a1a\" stroke-width=\"{:.2}\"/>",
                0.28 * self.em,
                0.12 * self.em
            );
        }
        for name in place_names(annotations, sheet) {
            let anchor = if name.ends_at { "end" } else { "start" };
            self.label(name.at, &name.name, NAME_SIZE, anchor);
        }
    }
}

/// The parts of a line (grid coordinates) the eye sees, as runs of image points, the line
/// tested every `step` grid units.
fn seen_runs(
    line: &[[f64; 2]],
    step: f64,
    sight: &Sight<'_>,
    sheet: &Sheet<'_>,
) -> Vec<Vec<[f64; 2]>> {
    let mut runs = vec![Vec::new()];
    let mut add = |p: DVec2| {
        let point = [p.x, p.y, sight.ground(p.into()) + LINE_LIFT];
        let seen = sheet.on_image(point).filter(|_| sight.sees(point));
        match (seen, runs.last_mut()) {
            (Some(xy), Some(run)) => run.push(xy),
            (None, Some(run)) if !run.is_empty() => runs.push(Vec::new()),
            _ => {}
        }
    };
    for pair in line.windows(2) {
        let (a, b) = (DVec2::from(pair[0]), DVec2::from(pair[1]));
        let n = (a.distance(b) / step).ceil().max(1.0) as usize;
        for k in 0..n {
            add(a.lerp(b, k as f64 / n as f64));
        }
    }
    if let Some(&last) = line.last() {
        add(DVec2::from(last));
    }
    runs.retain(|run| run.len() >= 2);
    runs
}

/// Round values (1, 2 or 5 times a power of ten apart) from `lo` to `hi`, four to ten of them.
pub fn round_marks(lo: f64, hi: f64) -> Vec<f64> {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) {
        return vec![lo];
    }
    let decade = 10f64.powf((span / 4.0).log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .map(|m| m * decade)
        .into_iter()
        .find(|&s| span / s <= 10.0)
        .unwrap_or(10.0 * decade);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// Text with XML's special characters escaped.
pub fn escaped(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
