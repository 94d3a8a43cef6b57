//! Where contour lines' height labels go on a map: on stretches of a line straight enough to
//! carry the text, turned along the line and kept upright, spaced along each line, each wholly
//! inside the image and clear of every label placed before it.

/// A label placed on a line.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// What it says: the line's height.
    pub text: String,
    /// The height, in the map's height unit.
    pub value: f64,
    /// Its centre, on the line, in pixels from the image's top-left corner.
    pub at: [f64; 2],
    /// Its angle, degrees clockwise from the image's x axis, from -90 (exclusive) to 90: text
    /// is never upside down.
    pub angle_deg: f64,
    /// Its box along that angle (the text and a margin around it), width and height in pixels.
    pub size: [f64; 2],
}

impl Label {
    /// The image-aligned box around the label's turned box: `[x0, y0, x1, y1]`.
    pub fn bounds(&self) -> [f64; 4] {
        let (s, c) = self.angle_deg.to_radians().sin_cos();
        let [w, h] = self.size;
        let half_x = 0.5 * (w * c.abs() + h * s.abs());
        let half_y = 0.5 * (w * s.abs() + h * c.abs());
        let [x, y] = self.at;
        [x - half_x, y - half_y, x + half_x, y + half_y]
    }

    /// Whether the two labels' boxes overlap.
    pub fn overlaps(&self, other: &Label) -> bool {
        let ([a0, a1, a2, a3], [b0, b1, b2, b3]) = (self.bounds(), other.bounds());
        a0 < b2 && b0 < a2 && a1 < b3 && b1 < a3
    }
}

/// A line to be labelled: its height, the text, and its points in image pixels.
pub struct Labelled<'a> {
    /// The line's height, in the map's height unit.
    pub value: f64,
    /// What its labels say.
    pub text: String,
    /// Its points, in pixels from the image's top-left corner.
    pub points: &'a [[f64; 2]],
}

/// How labels are sized and spaced, in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LabelStyle {
    /// The text's size.
    pub font_px: f64,
    /// The least distance along a line between two of its labels' centres.
    pub spacing_px: f64,
}

impl LabelStyle {
    /// The margin around a label's text, on each side: room for its halo and a gap in the line.
    pub fn pad(&self) -> f64 {
        0.35 * self.font_px
    }
}

/// Places labels on `lines` in order, in an image of `size` pixels, text `width_of(text)`
/// pixels wide: along each line from its start, at the first stretch that is straight
/// enough, inside the image and clear of the labels already placed, then again at least
/// `style.spacing_px` further on.
pub fn place(
    lines: &[Labelled<'_>],
    size: (u32, u32),
    width_of: &dyn Fn(&str) -> f64,
    style: LabelStyle,
) -> Vec<Label> {
    let mut placed: Vec<Label> = Vec::new();
    let step = 0.5 * style.font_px;
    for line in lines {
        let path = Path::new(line.points);
        let box_w = width_of(&line.text) + 2.0 * style.pad();
        let box_h = style.font_px + 2.0 * style.pad();
        let mut start = 0.0;
        while start + box_w <= path.length {
            let found = path
                .straight_chord(start, box_w, 0.45 * style.font_px)
                .map(|(a, b)| upright_label(line, a, b, [box_w, box_h]))
                .filter(|label| inside(label, size) && !placed.iter().any(|p| p.overlaps(label)));
            match found {
                Some(label) => {
                    placed.push(label);
                    start += style.spacing_px.max(box_w);
                }
                None => start += step,
            }
        }
    }
    placed
}

/// The label of `line` centred on the chord from `a` to `b`, turned along it and upright.
fn upright_label(line: &Labelled<'_>, a: [f64; 2], b: [f64; 2], size: [f64; 2]) -> Label {
    let (mut dx, mut dy) = (b[0] - a[0], b[1] - a[1]);
    if dx < 0.0 || (dx == 0.0 && dy < 0.0) {
        (dx, dy) = (-dx, -dy);
    }
    Label {
        text: line.text.clone(),
        value: line.value,
        at: [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])],
        angle_deg: dy.atan2(dx).to_degrees(),
        size,
    }
}

/// Whether the label's box lies wholly inside an image of `size` pixels.
fn inside(label: &Label, (w, h): (u32, u32)) -> bool {
    let [x0, y0, x1, y1] = label.bounds();
    x0 >= 0.0 && y0 >= 0.0 && x1 <= f64::from(w) && y1 <= f64::from(h)
}

/// A polyline measured along its length.
struct Path<'a> {
    points: &'a [[f64; 2]],
    /// The length from the first point to each point.
    along: Vec<f64>,
    length: f64,
}

impl<'a> Path<'a> {
    fn new(points: &'a [[f64; 2]]) -> Path<'a> {
        let mut along = Vec::with_capacity(points.len());
        let mut total = 0.0;
        for (k, p) in points.iter().enumerate() {
            if k > 0 {
                total += distance(points[k - 1], *p);
            }
            along.push(total);
        }
        Path {
            points,
            along,
            length: total,
        }
    }

    /// The point `s` along the line.
    fn at(&self, s: f64) -> [f64; 2] {
        let k = self
            .along
            .partition_point(|&a| a <= s)
            .clamp(1, self.points.len() - 1);
        let (a, b) = (self.points[k - 1], self.points[k]);
        let span = self.along[k] - self.along[k - 1];
        let t = if span > 0.0 {
            ((s - self.along[k - 1]) / span).clamp(0.0, 1.0)
        } else {
            0.0
        };
        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    }

    /// The ends of the stretch from `s` along the line, `length` long, if the line strays no
    /// more than `tolerance` from the chord between them and the chord is nearly as long as
    /// the stretch (the line does not double back).
    fn straight_chord(&self, s: f64, length: f64, tolerance: f64) -> Option<([f64; 2], [f64; 2])> {
        let (a, b) = (self.at(s), self.at(s + length));
        let chord = distance(a, b);
        if chord < 0.93 * length || chord == 0.0 {
            return None;
        }
        let (ux, uy) = ((b[0] - a[0]) / chord, (b[1] - a[1]) / chord);
        let inner = self
            .along
            .iter()
            .zip(self.points)
            .filter(|(&d, _)| d > s && d < s + length);
        for (_, p) in inner {
            let off = (p[0] - a[0]) * uy - (p[1] - a[1]) * ux;
            if off.abs() > tolerance {
                return None;
            }
        }
        Some((a, b))
    }
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn style() -> LabelStyle {
        LabelStyle {
            font_px: 10.0,
            spacing_px: 100.0,
        }
    }

    /// The labels of one line of `points`, texts 20 pixels wide, in an image of `size`.
    fn labels_on(points: &[[f64; 2]], size: (u32, u32)) -> Vec<Label> {
        let line = Labelled {
            value: 100.0,
            text: "100".into(),
            points,
        };
        place(&[line], size, &|_| 20.0, style())
    }

    #[test]
    fn a_straight_line_is_labelled_every_spacing_inside_the_image() {
        // A level line 300 pixels long; labels 20 + 7 wide, every 100 pixels from the start.
        let labels = labels_on(&[[0.0, 50.0], [300.0, 50.0]], (300, 100));
        let xs: Vec<f64> = labels.iter().map(|l| l.at[0]).collect();
        assert_eq!(xs, vec![13.5, 113.5, 213.5]);
        assert!(labels.iter().all(|l| l.angle_deg == 0.0 && l.at[1] == 50.0));
    }

    #[test]
    fn text_runs_left_to_right_whichever_way_the_line_runs() {
        let labels = labels_on(&[[200.0, 100.0], [0.0, 0.0]], (300, 300));
        let angle = 0.5f64.atan().to_degrees();
        assert!(!labels.is_empty());
        assert!(labels.iter().all(|l| (l.angle_deg - angle).abs() < 1e-9));
    }

    #[test]
    fn a_sharp_bend_carries_no_label() {
        // A zigzag whose legs are shorter than a label.
        let points: Vec<[f64; 2]> = (0..40)
            .map(|k| [f64::from(k) * 5.0, if k % 2 == 0 { 50.0 } else { 58.0 }])
            .collect();
        assert!(labels_on(&points, (300, 100)).is_empty());
    }
}
