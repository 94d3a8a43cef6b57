//! The Height map panel's overlay controls: an image path and its opacity to drape over the
//! map, what is draped now, and whether a file dropped onto the window is a height map or an
//! overlay.

use super::loader::{LoadRequest, OverlayChange, Source};
use super::model::{Action, Model};
use super::panels::named;
use egui::{Slider, Ui};
use std::path::PathBuf;

/// What a file dropped onto the window loads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DropLoads {
    /// A new height map (or scene).
    #[default]
    HeightMap,
    /// An image draped over the map on screen.
    Overlay,
}

/// The overlay controls' state.
#[derive(Clone, Debug, PartialEq)]
pub struct OverlayControls {
    /// The overlay path field.
    pub path_text: String,
    /// The opacity an overlay is laid with.
    pub opacity: f64,
    /// What a dropped file loads.
    pub drop_loads: DropLoads,
}

impl Default for OverlayControls {
    fn default() -> Self {
        OverlayControls {
            path_text: String::new(),
            opacity: 1.0,
            drop_loads: DropLoads::default(),
        }
    }
}

/// The request that drapes `change` over the map on screen, keeping its samples and view.
pub fn overlay_request(model: &Model, change: OverlayChange) -> LoadRequest {
    LoadRequest {
        source: model.shown.source.clone(),
        z_scale: Some(model.shown.terrain.field().z_scale()),
        reframe: false,
        from_memory: Some(model.shown.terrain.clone()),
        decoding: model.shown.decoding,
        overlay: Some(change),
    }
}

/// The request a file dropped onto the window makes.
pub fn dropped(model: &Model, path: PathBuf) -> LoadRequest {
    match model.overlay.drop_loads {
        DropLoads::HeightMap => LoadRequest {
            source: Source::File(path),
            z_scale: None,
            reframe: true,
            from_memory: None,
            decoding: model.decoding,
            overlay: None,
        },
        DropLoads::Overlay => {
            let opacity = model.overlay.opacity;
            overlay_request(model, OverlayChange::Lay { path, opacity })
        }
    }
}

/// The overlay path, opacity and drop target; what is draped now.
pub fn overlay_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    ui.horizontal(|ui| {
        let field = ui.add(
            egui::TextEdit::singleline(&mut model.overlay.path_text)
                .hint_text("overlay image: PNG, JPEG or TIFF")
                .desired_width(ui.available_width() - 70.0),
        );
        let field = named(model, "overlay_path", field);
        let entered = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        let lay = named(model, "overlay_open", ui.button("Overlay"));
        let path = model.overlay.path_text.trim();
        if (lay.clicked() || entered) && !path.is_empty() {
            let change = OverlayChange::Lay {
                path: PathBuf::from(path),
                opacity: model.overlay.opacity,
            };
            actions.push(Action::Load(overlay_request(model, change)));
        }
    });
    let opacity = ui.add(Slider::new(&mut model.overlay.opacity, 0.0..=1.0).text("opacity"));
    let opacity = named(model, "overlay_opacity", opacity);
    let drape = model.shown.terrain.field().drape();
    let shown = drape.map(|d| {
        (
            d.size(),
            d.georeferenced(),
            d.path().to_owned(),
            d.opacity(),
        )
    });
    match shown {
        Some(((w, h), georeferenced, path, laid_with)) => {
            let placed = if georeferenced {
                "placed by its georeferencing"
            } else {
                "stretched over the map"
            };
            let name = path.file_name().unwrap_or_default().to_string_lossy();
            ui.label(format!("overlay {name}: {w} x {h} px, {placed}"));
            let relay = opacity.drag_stopped() && model.overlay.opacity != laid_with;
            let change = OverlayChange::Lay {
                path,
                opacity: model.overlay.opacity,
            };
            let remove = named(model, "overlay_remove", ui.button("Remove overlay"));
            if remove.clicked() {
                actions.push(Action::Load(overlay_request(model, OverlayChange::Remove)));
            } else if relay {
                actions.push(Action::Load(overlay_request(model, change)));
            }
        }
        None => {
            ui.weak("no overlay: the colour ramp colours the map");
        }
    }
    ui.horizontal(|ui| {
        ui.label("a dropped file is");
        let controls = &mut model.overlay;
        ui.radio_value(
            &mut controls.drop_loads,
            DropLoads::HeightMap,
            "a height map",
        );
        ui.radio_value(&mut controls.drop_loads, DropLoads::Overlay, "an overlay");
    });
}
