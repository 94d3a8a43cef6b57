//! How wide a text is drawn in the annotations' font: measured by laying it out with resvg
//! where annotations are rasterised (the `annotate` feature), else estimated at six tenths of
//! its size a character. Labels are kept apart by these widths.

#[cfg(feature = "annotate")]
use resvg::usvg::{Options, Tree};
use std::cell::RefCell;
use std::collections::HashMap;

/// A character's width where the font is not measured, in sizes.
const ESTIMATED_ADVANCE: f64 = 0.6;

/// Widths of texts, each measured once.
pub struct TextWidth {
    #[cfg(feature = "annotate")]
    options: Options<'static>,
    known: RefCell<HashMap<(String, u64), f64>>,
}

impl Default for TextWidth {
    fn default() -> Self {
        TextWidth::new()
    }
}

impl TextWidth {
    /// Widths in the annotations' font.
    pub fn new() -> TextWidth {
        TextWidth {
            #[cfg(feature = "annotate")]
            options: super::svg_options(),
            known: RefCell::new(HashMap::new()),
        }
    }

    /// The width of `text`'s ink at `font_px` pixels high, in pixels.
    pub fn of(&self, text: &str, font_px: f64) -> f64 {
        let key = (text.to_owned(), font_px.to_bits());
        if let Some(&width) = self.known.borrow().get(&key) {
            return width;
        }
        let width = self
            .measured(text, font_px)
            .unwrap_or_else(|| ESTIMATED_ADVANCE * font_px * text.chars().count() as f64);
        self.known.borrow_mut().insert(key, width);
        width
    }

    #[cfg(feature = "annotate")]
    fn measured(&self, text: &str, font_px: f64) -> Option<f64> {
        let svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\" \
             font-family=\"sans-serif\"><text x=\"0\" y=\"0\" font-size=\"{font_px}\">{}</text>\
             </svg>",
            super::escaped(text)
        );
        let tree = Tree::from_str(&svg, &self.options).ok()?;
        let width = f64::from(tree.root().abs_bounding_box().width());
        (width.is_finite() && width > 0.0).then_some(width)
    }

    #[cfg(not(feature = "annotate"))]
    fn measured(&self, _text: &str, _font_px: f64) -> Option<f64> {
        None
    }
}
