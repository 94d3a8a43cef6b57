//! The side panel: camera, light, height map, traversal, effects and statistics.

use super::accuracy::panel::{accuracy_ui, speed_note};
use super::contours_ui::contours_ui;
use super::decoding::decoding_ui;
use super::orbit::{MIN_PITCH_DEG, PITCH_LIMIT_DEG};
use super::overlay_ui::overlay_ui;
use super::relief_ui::{exaggeration_ui, georeferencing_ui};
use super::settings::{fog, ArithKind};
use super::state::{Action, Decoding, LoadRequest, Model, Source, Widgets};
use super::stats_ui::statistics_ui;
use super::water_ui::water_ui;
use super::widgets::named;
use crate::heightfield::{place, BUILTINS};
use crate::render::effects::WIDEST_SUN_DEG;
use crate::render::{Normals, Ramp};
use crate::Method;
use egui::{CollapsingHeader, DragValue, RichText, Slider, Ui};
use std::path::PathBuf;

/// The panel's width in points: fixed, so opening a section never moves the view's edge.
const PANEL_WIDTH: f32 = 300.0;
/// Its width in windows narrower than [`NARROW_BELOW`].
const NARROW_PANEL_WIDTH: f32 = 240.0;
const NARROW_BELOW: f32 = 900.0;
/// Below this window width the panel hides itself (H brings it back).
const HIDE_BELOW: f32 = 640.0;

/// Hides the panel (in `widgets`) when the window becomes too narrow for it and the view, and
/// shows it again when the window widens, unless H was pressed in between; `narrow_window`
/// keeps what the window was. Called every frame; returns the notice that says why the panel
/// went.
pub fn fit_to_window(ui: &Ui, widgets: &mut Widgets, narrow_window: &mut bool) -> Option<Action> {
    if widgets.panels_visible {
        widgets.panel_auto_hidden = false;
    }
    let narrow = ui.available_width() < HIDE_BELOW;
    if narrow == *narrow_window {
        return None;
    }
    *narrow_window = narrow;
    if narrow && widgets.panels_visible {
        (widgets.panels_visible, widgets.panel_auto_hidden) = (false, true);
        // (The notice is set once this frame's actions run: draw again to show it.)
        ui.ctx().request_repaint();
        let notice = "The window is narrow: the panel is hidden (H shows it)";
        return Some(Action::Notify(notice.into()));
    }
    widgets.panels_visible |= !narrow && widgets.panel_auto_hidden;
    None
}

/// The panel on the right, with one collapsible section per concern. Only the sections
/// used most start open, so that the panel fits a 720 pixel high window without scrolling.
pub fn side_panel_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let width = if ui.available_width() < NARROW_BELOW {
        NARROW_PANEL_WIDTH
    } else {
        PANEL_WIDTH
    };
    let panel = egui::Panel::right("settings panel")
        .resizable(false)
        .exact_size(width)
        .show_inside(ui, |ui| {
            // A slider row is the slider, its value and its label (at most about 100 points):
            // the slider takes what is left, so the row ends at the panel's edge.
            let indent = ui.spacing().indent;
            ui.spacing_mut().slider_width = (ui.available_width() - indent - 170.0).max(50.0);
            egui::ScrollArea::vertical()
                .auto_shrink([false, false])
                .show(ui, |ui| {
                    sections_ui(ui, model, actions);
                    model.widgets.rects.insert("panel_content", ui.min_rect());
                });
        });
    model
        .widgets
        .rects
        .insert("side_panel", panel.response.rect);
}

fn sections_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    follow_shown_path(model);
    section(ui, "Camera", "Camera", true, |ui| {
        camera_ui(ui, model, actions)
    });
    section(ui, "Light", "Light", true, |ui| {
        light_ui(ui, model, actions)
    });
    let title = format!("Export: {}", shortened(&model.export.summary(), 24));
    let export = section(ui, "Export", &title, false, |ui| {
        let shown = model.latest.as_ref().map(|l| l.job.camera.size());
        super::export::settings_ui(ui, &mut model.export, shown);
        let save = ui
            .button("Save scene")
            .on_hover_text("a scene file of this view at the export size, for heightray render");
        if named(&mut model.widgets, "save_scene", save).clicked() {
            actions.push(Action::SaveScene);
        }
    });
    named(&mut model.widgets, "export_section", export);
    let title = format!("Heightmap: {}", shortened(&model.shown.source.label(), 22));
    let heightmap = section(ui, "Heightmap", &title, false, |ui| {
        heightmap_ui(ui, model, actions)
    });
    named(&mut model.widgets, "heightmap_section", heightmap);
    let summary = format!(
        "{}, {}",
        model.settings.method,
        model.settings.arith.label()
    );
    let title = format!("Traversal: {}", shortened(&summary, 24));
    let traversal = section(ui, "Traversal", &title, false, |ui| {
        traversal_ui(ui, model, actions)
    });
    named(&mut model.widgets, "traversal_section", traversal);
    let title = format!("Flythrough: {} keys", model.flythrough.keys.len());
    let flythrough = section(ui, "Flythrough", &title, false, |ui| {
        let fly = super::flythrough::flythrough_ui(ui, &mut model.flythrough, model.orbit);
        actions.extend(fly);
    });
    named(&mut model.widgets, "flythrough_section", flythrough);
    let effects = section(ui, "Effects", "Effects", false, |ui| effects_ui(ui, model));
    named(&mut model.widgets, "effects_section", effects);
    let statistics = section(ui, "Statistics", "Statistics and probe", false, |ui| {
        let heat = &mut model.settings.heat;
        let method = model.settings.method;
        let latest = model.latest.as_deref();
        statistics_ui(
            ui,
            &mut model.widgets,
            (heat, method),
            latest,
            &model.telemetry,
        );
    });
    named(&mut model.widgets, "statistics_section", statistics);
}

/// `text`, cut to `most` characters with an ellipsis (a header never wraps).
fn shortened(text: &str, most: usize) -> String {
    if text.chars().count() <= most {
        return text.to_owned();
    }
    let kept: String = text.chars().take(most.saturating_sub(1)).collect();
    format!("{kept}…")
}

/// A collapsible section (its state is kept under `id`, whatever the title says); returns
/// its header, to click open.
fn section(
    ui: &mut Ui,
    id: &str,
    title: &str,
    open: bool,
    add: impl FnOnce(&mut Ui),
) -> egui::Response {
    CollapsingHeader::new(RichText::new(title).strong())
        .id_salt(id)
        .default_open(open)
        .show(ui, add)
        .header_response
}

fn camera_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let orbit = &mut model.orbit;
    let scale = orbit.scale;
    let yaw = ui.add(Slider::new(&mut orbit.yaw_deg, -180.0..=180.0).text("yaw °"));
    named(&mut model.widgets, "camera_yaw", yaw);
    let orbit = &mut model.orbit;
    ui.add(Slider::new(&mut orbit.pitch_deg, MIN_PITCH_DEG..=PITCH_LIMIT_DEG).text("pitch °"));
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
    super::export::progress_ui(ui, &model.export);
    super::navigation::tools_ui(ui, actions);
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

fn light_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let s = &mut model.settings;
    let azimuth = ui
        .add(Slider::new(&mut s.sun_azimuth_deg, 0.0..=360.0).text("bearing °"))
        .on_hover_text("the sun's compass bearing: 0 north, 90 east, 180 south");
    let azimuth = named(&mut model.widgets, "sun_azimuth", azimuth);
    let s = &mut model.settings;
    // (Not clamped when shown: a date and time may put the sun below the horizon.)
    let elevation = ui.add(
        Slider::new(&mut s.sun_elevation_deg, 1.0..=90.0)
            .clamping(egui::SliderClamping::Edits)
            .text("elevation °"),
    );
    if azimuth.changed() || elevation.changed() {
        // The sliders now set the sun, not the clock.
        model.sun_clock.on = false;
    }
    let centre = place::centre_degrees(model.shown.terrain.field());
    actions.extend(super::sun_clock::sun_clock_ui(
        ui,
        &mut model.sun_clock,
        centre,
    ));
    let s = &mut model.settings;
    ui.add(Slider::new(&mut s.intensity, 0.0..=3.0).text("intensity"));
    ui.add(Slider::new(&mut s.ambient, 0.0..=1.0).text("ambient"));
    ui.checkbox(&mut s.shadows, "shadows");
}

fn heightmap_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    source_ui(ui, model, actions);
    actions.extend(overlay_ui(ui, &mut model.widgets, &model.shown));
    let water = &mut model.settings.effects.water;
    water_ui(ui, water, &mut model.widgets, &model.shown.terrain);
    if let Some(refused) = contours_ui(ui, &mut model.widgets, &model.shown.terrain) {
        model.error = Some(refused.to_string());
    }
    actions.extend(decoding_ui(ui, &mut model.widgets, &model.shown));
    z_scale_ui(ui, model, actions);
    let s = &mut model.settings;
    ui.horizontal(|ui| {
        ui.label("normals");
        ui.radio_value(&mut s.normals, Normals::Flat, "flat");
        ui.radio_value(&mut s.normals, Normals::Smooth, "smooth");
    });
    ui.checkbox(&mut s.base.walls, "solid base (side walls)")
        .on_hover_text("walls from the map's edge down to a floor below its lowest sample");
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
    // A georeferenced map's heights are shown in metres below; grid units only for a plain
    // image, labelled as such.
    if field.georef().is_none() {
        ui.label(format!(
            "heights {lo:.2} .. {hi:.2} grid units (step {:.3e})",
            field.step()
        ));
    }
    ui.label(format!("{} no-data samples", field.nodata_count()));
    georeferencing_ui(ui, &model.shown.terrain);
    ui.label(format!(
        "read {:.1} ms, build {:.1} ms ({:.1} MB of acceleration data)",
        model.shown.decode_time.as_secs_f64() * 1e3,
        terrain.build_time().as_secs_f64() * 1e3,
        terrain.accel_bytes() as f64 / 1e6
    ));
    super::stats_ui::store_ui(ui, model.telemetry.store.as_ref());
}

/// Fills the path field in with the file on screen whenever a new one is shown, however it
/// was opened (a built-in empties it).
fn follow_shown_path(model: &mut Model) {
    let current = &model.shown.source;
    if model.widgets.path_source.as_ref() == Some(current) {
        return;
    }
    model.widgets.path_text = match current {
        Source::File(path) => path.display().to_string(),
        Source::Builtin(_) | Source::Tiles(_) => String::new(),
    };
    model.widgets.path_source = Some(current.clone());
}

/// The built-in list and the path field.
fn source_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let current = model.shown.source.clone();
    let selected = match &current {
        Source::Builtin(name) => (*name).to_owned(),
        Source::File(_) => "(a file)".to_owned(),
        Source::Tiles(_) => "(tiles)".to_owned(),
    };
    egui::ComboBox::from_label("built-in")
        .selected_text(selected)
        .show_ui(ui, |ui| {
            for builtin in BUILTINS {
                let chosen = current == Source::Builtin(builtin.name);
                if ui.selectable_label(chosen, builtin.name).clicked() && !chosen {
                    actions.push(load(Source::Builtin(builtin.name), model.widgets.decoding));
                }
            }
        });
    ui.horizontal(|ui| {
        let field = ui.add(
            egui::TextEdit::singleline(&mut model.widgets.path_text)
                .hint_text("path to a PNG, PGM, TIFF, .hgt, .asc or .toml")
                .desired_width(ui.available_width() - 50.0),
        );
        let field = named(&mut model.widgets, "open_path", field);
        let entered = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        let open = ui.button("Open");
        let open = named(&mut model.widgets, "open", open);
        if (open.clicked() || entered) && !model.widgets.path_text.trim().is_empty() {
            let path = PathBuf::from(model.widgets.path_text.trim());
            actions.push(load(Source::File(path), model.widgets.decoding));
        }
    });
    ui.weak("or drop a file onto the window");
}

/// The z scale, applied live: each change rescales the samples in memory on the loading
/// thread (a newer change supersedes an older one still building).
fn z_scale_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let speed = (model.widgets.z_scale * 0.005).max(0.01);
    let z = ui.add(
        DragValue::new(&mut model.widgets.z_scale)
            .range(0.0..=1e7)
            .speed(speed)
            .prefix("z scale (grid units) "),
    );
    let field = model.shown.terrain.field();
    let exaggerated = exaggeration_ui(ui, &mut model.widgets.z_scale, field);
    if (z.changed() || exaggerated)
        && model.widgets.z_scale != model.shown.terrain.field().z_scale()
    {
        actions.push(Action::Load(LoadRequest {
            source: model.shown.source.clone(),
            z_scale: Some(model.widgets.z_scale),
            reframe: false,
            from_memory: Some(model.shown.terrain.clone()),
            decoding: model.shown.decoding,
            overlay: None,
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
        overlay: None,
    })
}

fn traversal_ui(ui: &mut Ui, model: &mut Model, actions: &mut Vec<Action>) {
    let s = &mut model.settings;
    ui.horizontal_wrapped(|ui| {
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
    let arith = model.settings.arith();
    if let Some((note, slow)) = speed_note(arith, model.accuracy.measure.measurement()) {
        if slow {
            ui.colored_label(egui::Color32::from_rgb(230, 180, 80), note);
        } else {
            ui.weak(note);
        }
    }
    let accuracy = accuracy_ui(ui, &mut model.accuracy, &model.settings, &mut model.widgets);
    actions.extend(accuracy);
}

/// The effects (shadows are with the light). The fog slider is a visibility distance on a
/// log scale over the useful range for this map; the renderer and scene files keep a density.
fn effects_ui(ui: &mut Ui, model: &mut Model) {
    sampling_ui(ui, model);
    let field = model.shown.terrain.field();
    let size = (field.width().max(field.height()) as f64 - 1.0).max(1.0);
    let range = fog::range(size, model.orbit.distance);
    let mut on = model.settings.fog > 0.0;
    let toggle = ui.checkbox(&mut on, "fog");
    if named(&mut model.widgets, "fog_toggle", toggle).changed() {
        // A haze: about half the contrast left on the far side of the map, more on the near.
        let far_side = model.orbit.distance + size;
        model.settings.fog = if on {
            fog::density(4.0 * far_side)
        } else {
            0.0
        };
    }
    let s = &mut model.settings;
    if s.fog > 0.0 {
        let mut distance = fog::distance(s.fog);
        let slider = Slider::new(&mut distance, range)
            .logarithmic(true)
            .max_decimals(0)
            .clamping(egui::SliderClamping::Edits)
            .text("visibility");
        let slider = ui.add(slider);
        if slider.changed() {
            model.settings.fog = fog::density(distance);
        }
        named(&mut model.widgets, "fog_visibility", slider);
        let s = &model.settings;
        ui.weak(format!(
            "contrast falls to 5% at {:.0} map units; the map is {size:.0} across",
            fog::distance(s.fog)
        ));
    }
}

/// Soft shadows, sky light and samples per pixel: each costs rays only where it is ticked.
fn sampling_ui(ui: &mut Ui, model: &mut Model) {
    let effects = &mut model.settings.effects;
    let mut soft = effects.sun_angle_deg > 0.0;
    let toggle = ui.checkbox(&mut soft, "soft shadows").on_hover_text(
        "the sun as a disc: penumbrae as wide as the sun seen from the shadowed point",
    );
    if named(&mut model.widgets, "soft_shadows", toggle).changed() {
        model.settings.effects.sun_angle_deg = if soft { REAL_SUN_DEG } else { 0.0 };
    }
    let effects = &mut model.settings.effects;
    if effects.sun_angle_deg > 0.0 {
        let slider = Slider::new(&mut effects.sun_angle_deg, 0.1..=WIDEST_SUN_DEG)
            .logarithmic(true)
            .text("sun's diameter °");
        let slider = ui.add(slider);
        named(&mut model.widgets, "sun_angle", slider);
    }
    let effects = &mut model.settings.effects;
    let sky = ui
        .checkbox(&mut effects.sky_light, "sky light")
        .on_hover_text("light from the open sky instead of a constant ambient term");
    named(&mut model.widgets, "sky_light", sky);
    let effects = &mut model.settings.effects;
    let samples = ui.add(
        Slider::new(&mut effects.samples, 1..=64)
            .logarithmic(true)
            .text("samples per pixel"),
    );
    named(&mut model.widgets, "samples", samples);
    let effects = &mut model.settings.effects;
    if effects.samples > 1 {
        let adaptive = ui.checkbox(&mut effects.adaptive, "adaptive").on_hover_text(
            "a pixel stops taking samples once two halves of them agree: flat ground early, edges late",
        );
        named(&mut model.widgets, "adaptive", adaptive);
    }
    if let Some(latest) = &model.latest {
        super::stats_ui::effect_shares(ui, &latest.frame.totals, &latest.job.lighting.effects);
    }
}

/// The real sun's angular diameter, in degrees.
const REAL_SUN_DEG: f64 = 0.53;
