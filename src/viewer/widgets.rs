//! What every panel draws its widgets with.

use super::state::Widgets;

/// Records where a named widget is, for scripted tests that drag it.
pub fn named(
    widgets: &mut Widgets,
    name: &'static str,
    response: egui::Response,
) -> egui::Response {
    widgets.rects.insert(name, response.rect);
    response
}
