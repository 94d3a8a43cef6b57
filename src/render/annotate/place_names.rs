//! Where places' names go in a perspective picture, so that no two overlap. Places are taken
//! in order of importance: the higher `priority` first, then the nearer to the eye, then the
//! order of the files; each name tries the four corners around its marker (upper right, as
//! the picture has always put it, then upper left, lower right, lower left) and takes the
//! first clear of every name already placed and of the picture's other marks (title,
//! attribution, scale bar, north arrow, legend). A name with no clear corner is left out; its
//! marker stays, as a map marks a spot it has no room to name.

use super::sheet::Annotations;

/// A visible place to be named.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// Its name.
    pub name: String,
    /// Its priority (higher first).
    pub priority: f64,
    /// Its distance from the eye, in world units.
    pub distance: f64,
    /// Its marker in the image, in pixels.
    pub marker: [f64; 2],
}

/// A name placed beside its marker.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedName {
    /// The name.
    pub name: String,
    /// Its baseline's anchor point, in pixels.
    pub at: [f64; 2],
    /// Whether the text ends at `at` (left of the marker) rather than starts there.
    pub ends_at: bool,
    /// Its box, `[x0, y0, x1, y1]` in pixels: the text and its halo.
    pub bounds: [f64; 4],
}

impl PlacedName {
    /// Whether the two names' boxes overlap.
    pub fn overlaps(&self, other: &PlacedName) -> bool {
        meet(self.bounds, other.bounds)
    }
}

/// Whether two boxes `[x0, y0, x1, y1]` overlap.
fn meet([a0, a1, a2, a3]: [f64; 4], [b0, b1, b2, b3]: [f64; 4]) -> bool {
    a0 < b2 && b0 < a2 && a1 < b3 && b1 < a3
}

/// A name's size, in ems.
pub const NAME_SIZE: f64 = 0.85;
/// The share of the size a name's capitals rise above the baseline, and its descenders fall.
const ASCENT: f64 = 0.78;
const DESCENT: f64 = 0.22;

/// The boxes `[x0, y0, x1, y1]` of the marks `annotations` draws besides names, in an image of
/// `size` pixels, text sized in `em` pixels and `width_of(text, font_px)` wide (as
/// [`super::svg`] lays them out; the scale bar's box is its longest, the legend's its widest).
pub fn reserved(
    annotations: &Annotations,
    (w, h): (f64, f64),
    em: f64,
    width_of: &dyn Fn(&str, f64) -> f64,
) -> Vec<[f64; 4]> {
    let mut boxes = Vec::new();
    let text = |x: f64, y: f64, text: &str, size: f64, ends_at: bool| {
        let (font, width) = (size * em, width_of(text, size * em));
        let x0 = if ends_at { x - width } else { x };
        let pad = 0.15 * font;
        [
            x0 - pad,
            y - ASCENT * font - pad,
            x0 + width + pad,
            y + DESCENT * font + pad,
        ]
    };
    if let Some(title) = &annotations.title {
        boxes.push(text(em, 2.2 * em, title, 1.6, false));
    }
    if let Some(attribution) = &annotations.attribution {
        boxes.push(text(w - em, h - 0.8 * em, attribution, 0.65, true));
    }
    if annotations.scale_bar {
        boxes.push([0.0, h - 4.0 * em, 0.22 * w + 4.0 * em, h]);
    }
    if annotations.north_arrow {
        boxes.push([w - 4.0 * em, 0.5 * em, w - 0.8 * em, 5.0 * em]);
    }
    if annotations.legend {
        let bottom = h - 2.4 * em;
        let top = bottom - (0.3 * h).min(12.0 * em);
        boxes.push([w - 7.0 * em, top - 1.4 * em, w, bottom + 0.6 * em]);
    }
    boxes
}

/// Names for `candidates` (see the module's note), text sized in `em` pixels and
/// `width_of(text, font_px)` wide, clear of the boxes `reserved`; in the order they were
/// placed.
pub fn arrange(
    candidates: &[Candidate],
    reserved: &[[f64; 4]],
    em: f64,
    width_of: &dyn Fn(&str, f64) -> f64,
) -> Vec<PlacedName> {
    let mut order: Vec<&Candidate> = candidates.iter().collect();
    order.sort_by(|a, b| {
        b.priority
            .total_cmp(&a.priority)
            .then(a.distance.total_cmp(&b.distance))
    });
    let font = NAME_SIZE * em;
    // The halo (a stroke of 0.22 sizes, half outside the glyphs) and a little air.
    let pad = 0.15 * font;
    let mut placed: Vec<PlacedName> = Vec::new();
    for place in order {
        let width = width_of(&place.name, font);
        let [px, py] = place.marker;
        let (above, below) = (py - 0.4 * em, py + 0.4 * em + ASCENT * font);
        let corners = [
            (px + 0.5 * em, above, false),
            (px - 0.5 * em, above, true),
            (px + 0.5 * em, below, false),
            (px - 0.5 * em, below, true),
        ];
        let clear = corners.into_iter().map(|(x, y, ends_at)| {
            let (x0, x1) = if ends_at {
                (x - width, x)
            } else {
                (x, x + width)
            };
            PlacedName {
                name: place.name.clone(),
                at: [x, y],
                ends_at,
                bounds: [
                    x0 - pad,
                    y - ASCENT * font - pad,
                    x1 + pad,
                    y + DESCENT * font + pad,
                ],
            }
        });
        let found = clear.into_iter().find(|name| {
            !placed.iter().any(|p| p.overlaps(name))
                && !reserved.iter().any(|&r| meet(r, name.bounds))
        });
        placed.extend(found);
    }
    placed
}

#[cfg(test)]
mod tests {
    use super::*;

    fn candidate(name: &str, priority: f64, distance: f64, marker: [f64; 2]) -> Candidate {
        Candidate {
            name: name.into(),
            priority,
            distance,
            marker,
        }
    }

    #[test]
    fn crowded_names_take_the_other_corners_then_drop_the_least() {
        // Five places on one spot: four corners, five names.
        let places: Vec<Candidate> = (0..5)
            .map(|k| candidate(&format!("P{k}"), 0.0, f64::from(5 - k), [100.0, 100.0]))
            .collect();
        let names = arrange(&places, &[], 20.0, &|text, px| 0.5 * px * text.len() as f64);
        let order: Vec<&str> = names.iter().map(|n| n.name.as_str()).collect();
        // The nearest (P4) first, at the upper right; the farthest (P0) has no room.
        assert_eq!(order, ["P4", "P3", "P2", "P1"]);
        let ends: Vec<bool> = names.iter().map(|n| n.ends_at).collect();
        assert_eq!(ends, [false, true, false, true]);
        assert!(names[0].at[1] < 100.0 && names[2].at[1] > 100.0);
    }
}
