//! SVG rasterised with a font embedded in the binary (the viewer's own, so no system fonts are
//! needed): for plots and for annotations drawn into pictures.

use resvg::usvg::{fontdb, Options};
use std::sync::Arc;

/// resvg's options with the embedded font as every sans-serif family.
pub fn svg_options() -> Options<'static> {
    let mut fonts = fontdb::Database::new();
    fonts.load_font_data(epaint_default_fonts::UBUNTU_LIGHT.to_vec());
    let family = fonts
        .faces()
        .next()
        .and_then(|f| f.families.first())
        .map(|f| f.0.clone())
        .unwrap_or_default();
    fonts.set_sans_serif_family(family);
    Options {
        fontdb: Arc::new(fonts),
        ..Default::default()
    }
}
