//! The Height map panel's overlay controls: an image path and its opacity to drape over the
//! map, what is draped now, and whether files dropped onto the window are a height map (or
//! tiles) or an overlay.

use super::state::{Action, DropLoads, LoadRequest, Model, OverlayChange, Shown, Widgets};
use super::widgets::named;
use egui::{Slider, Ui};
use std::path::PathBuf;

/// The request that drapes `change` over the map on screen, keeping its samples and view.
pub fn overlay_request(shown: &Shown, change: OverlayChange) -> LoadRequest {
    LoadRequest {
        source: shown.source.clone(),
        z_scale: Some(shown.terrain.field().z_scale()),
        reframe: false,
        from_memory: Some(shown.terrain.clone()),
        decoding: shown.decoding,
        overlay: Some(change),
    }
}

/// Takes the opacity of the overlay shown (a scene's, or one just laid), and says what a
/// change of overlay did.
pub fn shown(model: &mut Model, change: Option<&OverlayChange>) {
    if let Some(drape) = model.shown.terrain.field().drape() {
        model.widgets.overlay.opacity = drape.opacity();
    }
    match change {
        Some(OverlayChange::Lay { path, .. }) => {
            let why = match model.widgets.overlay.dropped_picture.take() {
                Some(what) => format!(" as an overlay: it is {what}, not a height map"),
                None => String::new(),
            };
            model.notify(format!("Draped {} over the map{why}", path.display()))
        }
        Some(OverlayChange::Remove) => model.notify("Removed the overlay"),
        None => {}
    }
}

/// The overlay path, opacity and drop target; what is draped now. Returns the loads asked for.
pub fn overlay_ui(ui: &mut Ui, widgets: &mut Widgets, shown: &Shown) -> Vec<Action> {
    let mut actions = Vec::new();
    ui.horizontal(|ui| {
        let field = ui.add(
            egui::TextEdit::singleline(&mut widgets.overlay.path_text)
                .hint_text("overlay image: PNG, JPEG or TIFF")
                .desired_width(ui.available_width() - 70.0),
        );
        let field = named(widgets, "overlay_path", field);
        let entered = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        let lay = named(widgets, "overlay_open", ui.button("Overlay"));
        let path = widgets.overlay.path_text.trim();
        if (lay.clicked() || entered) && !path.is_empty() {
            let change = OverlayChange::Lay {
                path: PathBuf::from(path),
                opacity: widgets.overlay.opacity,
            };
            actions.push(Action::Load(overlay_request(shown, change)));
        }
    });
    let opacity = ui.add(Slider::new(&mut widgets.overlay.opacity, 0.0..=1.0).text("opacity"));
    let opacity = named(widgets, "overlay_opacity", opacity);
    let drape = shown.terrain.field().drape();
    let draped = drape.map(|d| {
        (
            d.size(),
            d.georeferenced(),
            d.path().to_owned(),
            d.opacity(),
        )
    });
    match draped {
        Some(((w, h), georeferenced, path, laid_with)) => {
            let placed = if georeferenced {
                "placed by its georeferencing"
            } else {
                "stretched over the map"
            };
            let name = path.file_name().unwrap_or_default().to_string_lossy();
            ui.label(format!("overlay {name}: {w} x {h} px, {placed}"));
            let relay = opacity.drag_stopped() && widgets.overlay.opacity != laid_with;
            let change = OverlayChange::Lay {
                path,
                opacity: widgets.overlay.opacity,
            };
            let remove = named(widgets, "overlay_remove", ui.button("Remove overlay"));
            if remove.clicked() {
                actions.push(Action::Load(overlay_request(shown, OverlayChange::Remove)));
            } else if relay {
                actions.push(Action::Load(overlay_request(shown, change)));
            }
        }
        None => {
            ui.weak("no overlay: the colour ramp colours the map");
        }
    }
    ui.horizontal(|ui| {
        ui.label("a drop opens");
        let controls = &mut widgets.overlay;
        ui.radio_value(&mut controls.drop_loads, DropLoads::HeightMap, "a map");
        let overlay = ui.radio_value(&mut controls.drop_loads, DropLoads::Overlay, "an overlay");
        named(widgets, "drop_overlay", overlay);
    });
    actions
}
