//! The side panel: camera, light, height map, traversal, effects and statistics.

use super::accuracy::panel::accuracy_ui;
use super::decoding::{decoding_ui, Decoding};
use super::loader::{LoadRequest, Source};
use super::model::{Action, Model};
use super::settings::ArithKind;
use super::stats_ui::statistics_ui;
use crate::heightfield::BUILTINS;
use crate::render::{Normals, Ramp};
use crate::Method;
use egui::{CollapsingHeader, DragValue, Slider, Ui};
use std::path::PathBuf;

/// The panel on the right, with one collapsible section per concern.
pub fn side_panel_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    // Never more than half the window: the view is what the window is for.
    let widest = (ui.available_width() * 0.5).clamp(120.0, 560.0);
    egui::Panel::right("settings panel")
        .resizable(true)
        .default_size(320.0_f32.min(widest))
        .size_range(240.0_f32.min(widest)..=widest)
        .show_inside(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                section(ui, "Camera", |ui| camera_ui(ui, model, actions));
                section(ui, "Light", |ui| light_ui(ui, model));
                section(ui, "Heightmap", |ui| heightmap_ui(ui, model, actions));
                let traversal =
                    section_closed(ui, "Traversal", |ui| traversal_ui(ui, model, actions));
                named(model, "traversal_section", traversal);
                section_closed(ui, "Effects", |ui| effects_ui(ui, model));
                section(ui, "Statistics", |ui| statistics_ui(ui, model));
            });
        });
}

fn section(ui: &mut Ui, title: &str, add: impl FnOnce(&mut Ui)) {
    CollapsingHeader::new(title)
        .default_open(true)
        .show(ui, add);
}

/// A section that starts closed; returns its header (to click open).
fn section_closed(ui: &mut Ui, title: &str, add: impl FnOnce(&mut Ui)) -> egui::Response {
    CollapsingHeader::new(title)
        .default_open(false)
        .show(ui, add)
        .header_response
}

/// Records where a named widget is, for scripted tests that drag it.
pub(super) fn named(
    model: &mut Model,
    name: &'static str,
    response: egui::Response,
) -> egui::Response {
    model.widget_rects.insert(name, response.rect);
    response
}

fn camera_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let orbit = &mut model.orbit;
    let scale = orbit.scale;
    let yaw = ui.add(Slider::new(&mut orbit.yaw_deg, -180.0..=180.0).text("yaw °"));
    named(model, "camera_yaw", yaw);
    let orbit = &mut model.orbit;
    ui.add(Slider::new(&mut orbit.pitch_deg, -89.0..=89.0).text("pitch °"));
    ui.add(
        Slider::new(&mut orbit.distance, scale * 1e-3..=scale * 50.0)
            .logarithmic(true)
            .text("distance"),
    );
    ui.add(Slider::new(&mut orbit.fov_y_deg, 5.0..=120.0).text("fov y °"));
    ui.horizontal(|ui| {
        ui.label("target");
        for c in &mut orbit.target {
            ui.add(DragValue::new(c).speed(scale * 1e-3).max_decimals(2));
        }
    });
    ui.horizontal(|ui| {
        if ui.button("Reset view (R)").clicked() {
            actions.push(Action::ResetView);
        }
        if ui.button("Export image (S)").clicked() {
            actions.push(Action::Screenshot);
        }
    });
    super::navigation::tools_ui(ui, model, actions);
    let settings = &mut model.settings;
    ui.add(
        Slider::new(&mut settings.render_scale, 0.25..=2.0)
            .text("render scale")
            .step_by(0.05),
    )
    .on_hover_text("rays per window pixel along each axis; the cost grows with its square");
    if let Some(latest) = &model.latest {
        ui.weak(format!(
            "{} x {} rays in a {} x {} window (HiDPI scale {:.2})",
            latest.frame.width,
            latest.frame.height,
            model.window_size.0,
            model.window_size.1,
            model.scale_factor
        ));
    }
}

fn light_ui(ui: &mut Ui, model: &mut Model) {
    let s = &mut model.settings;
    let azimuth = ui.add(Slider::new(&mut s.sun_azimuth_deg, -180.0..=180.0).text("sun azimuth °"));
    named(model, "sun_azimuth", azimuth);
    let s = &mut model.settings;
    ui.add(Slider::new(&mut s.sun_elevation_deg, 1.0..=90.0).text("sun elevation °"));
    ui.add(Slider::new(&mut s.intensity, 0.0..=3.0).text("intensity"));
    ui.add(Slider::new(&mut s.ambient, 0.0..=1.0).text("ambient"));
    ui.checkbox(&mut s.shadows, "shadows");
}

fn heightmap_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    source_ui(ui, model, actions);
    decoding_ui(ui, model, actions);
    z_scale_ui(ui, model, actions);
    let s = &mut model.settings;
    ui.horizontal(|ui| {
        ui.label("normals");
        ui.radio_value(&mut s.normals, Normals::Flat, "flat");
        ui.radio_value(&mut s.normals, Normals::Smooth, "smooth");
    });
    egui::ComboBox::from_label("colour ramp")
        .selected_text(s.ramp.name())
        .show_ui(ui, |ui| {
            for ramp in Ramp::ALL {
                ui.selectable_value(&mut s.ramp, ramp, ramp.name());
            }
        });
    let terrain = &model.shown.terrain;
    let field = terrain.field();
    let (lo, hi) = terrain.z_range();
    ui.label(format!(
        "{}: {} x {} samples",
        model.shown.source.label(),
        field.width(),
        field.height()
    ));
    ui.label(format!(
        "heights {lo:.2} .. {hi:.2} (step {:.3e}), {} no-data samples",
        field.step(),
        field.nodata_count()
    ));
    ui.label(format!(
        "read {:.1} ms, build {:.1} ms ({:.1} MB of acceleration data)",
        model.shown.decode_time.as_secs_f64() * 1e3,
        terrain.build_time().as_secs_f64() * 1e3,
        terrain.accel_bytes() as f64 / 1e6
    ));
}

/// The built-in list and the path field.
fn source_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let current = model.shown.source.clone();
    let selected = match &current {
        Source::Builtin(name) => (*name).to_owned(),
        Source::File(_) => "(a file)".to_owned(),
    };
    egui::ComboBox::from_label("built-in")
        .selected_text(selected)
        .show_ui(ui, |ui| {
            for builtin in BUILTINS {
                let chosen = current == Source::Builtin(builtin.name);
                if ui.selectable_label(chosen, builtin.name).clicked() && !chosen {
                    actions.push(load(Source::Builtin(builtin.name), model.decoding));
                }
            }
        });
    ui.horizontal(|ui| {
        let field = ui.add(
            egui::TextEdit::singleline(&mut model.path_text)
                .hint_text("path to a PNG, PGM, TIFF or .toml")
                .desired_width(190.0),
        );
        let field = named(model, "open_path", field);
        let entered = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        let open = ui.button("Open");
        let open = named(model, "open", open);
        if (open.clicked() || entered) && !model.path_text.trim().is_empty() {
            let path = PathBuf::from(model.path_text.trim());
            actions.push(load(Source::File(path), model.decoding));
        }
    });
    ui.weak("or drop a file onto the window");
}

/// The z scale, applied live: each change rescales the samples in memory on the loading
/// thread (a newer change supersedes an older one still building).
fn z_scale_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let speed = (model.z_scale * 0.005).max(0.01);
    let z = ui.add(
        DragValue::new(&mut model.z_scale)
            .range(0.0..=1e7)
            .speed(speed)
            .prefix("z scale "),
    );
    if z.changed() && model.z_scale != model.shown.terrain.field().z_scale() {
        actions.push(Action::Load(LoadRequest {
            source: model.shown.source.clone(),
            z_scale: Some(model.z_scale),
            reframe: false,
            from_memory: Some(model.shown.terrain.clone()),
            decoding: model.shown.decoding,
        }));
    }
}

/// Loads `source` (an image decoded as the panel says) and frames it.
fn load(source: Source, decoding: Decoding) -> Action {
    Action::Load(LoadRequest {
        source,
        z_scale: None,
        reframe: true,
        from_memory: None,
        decoding,
    })
}

fn traversal_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let s = &mut model.settings;
    ui.horizontal(|ui| {
        ui.label("method");
        ui.radio_value(&mut s.method, Method::Mipmap, "mipmap");
        ui.radio_value(&mut s.method, Method::HierarchicalRuns, "hierarchical runs");
        ui.radio_value(&mut s.method, Method::Runs, "runs");
        ui.radio_value(&mut s.method, Method::Dda, "cell DDA");
    });
    egui::ComboBox::from_label("arithmetic")
        .selected_text(s.arith.label())
        .show_ui(ui, |ui| {
            for kind in ArithKind::ALL {
                ui.selectable_value(&mut s.arith, kind, kind.label());
            }
        });
    if s.arith == ArithKind::Rational {
        ui.add(
            DragValue::new(&mut s.rational_bound)
                .range(1..=1u32 << 30)
                .speed(64.0)
                .prefix("denominator bound "),
        );
    }
    if s.arith == ArithKind::Exact {
        ui.weak("exact arithmetic is much slower: passes take a while");
    }
    accuracy_ui(ui, model, actions);
}

fn effects_ui(ui: &mut Ui, model: &mut Model) {
    let s = &mut model.settings;
    ui.checkbox(&mut s.shadows, "shadows");
    ui.add(
        Slider::new(&mut s.fog, 0.0..=0.02)
            .logarithmic(true)
            .smallest_positive(1e-5)
            .text("fog density"),
    );
}
