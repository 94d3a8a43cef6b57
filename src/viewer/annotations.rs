//! What is drawn over the 3D view: pass progress and the render size, the heat-map and height
//! legends, the loading progress, errors and notices, the drop hint and the help window.

use super::compose::{self, HeatScale};
use super::settings::HeatMode;
use super::state::{Model, Notice, Telemetry, Widgets};
use super::worker::RenderedFrame;
use crate::render::PASS_BLOCKS;
use crate::Method;
use egui::{Align2, Color32, Id, Pos2, Rect, Ui, Vec2};
use std::time::Duration;

/// How long a notice stays up.
pub const NOTICE_TIME: Duration = Duration::from_secs(4);

/// What the annotations over the view read and edit.
pub struct Overlaid<'a> {
    /// The frame on screen.
    pub latest: Option<&'a RenderedFrame>,
    /// The heat map shown, and the traversal method that may leave it empty.
    pub heat: HeatMode,
    pub method: Method,
    /// The lowered render size, the heat map's scale and the loading progress.
    pub telemetry: &'a mut Telemetry,
    /// The panel's and the help's visibility, and the drawn rectangles.
    pub widgets: &'a mut Widgets,
    /// Why the last file could not be used, until dismissed.
    pub error: &'a mut Option<String>,
    /// A short message, until its time is up.
    pub notice: &'a mut Option<Notice>,
    /// A file is being dragged over the window.
    pub drop_hover: bool,
}

impl<'a> Overlaid<'a> {
    /// The model's parts the annotations read and edit.
    pub fn of(model: &'a mut Model) -> Overlaid<'a> {
        Overlaid {
            latest: model.latest.as_deref(),
            heat: model.settings.heat,
            method: model.settings.method,
            telemetry: &mut model.telemetry,
            widgets: &mut model.widgets,
            error: &mut model.error,
            notice: &mut model.notice,
            drop_hover: model.drop_hover,
        }
    }
}

/// Everything drawn over the view `rect`.
pub fn annotations_ui(ui: &mut Ui, mut over: Overlaid<'_>, rect: Rect) {
    if over.latest.is_none() {
        ui.painter().text(
            rect.center(),
            Align2::CENTER_CENTER,
            "rendering…",
            egui::FontId::proportional(18.0),
            Color32::GRAY,
        );
    }
    status_ui(ui, &mut over, rect);
    super::legend::height_legend_ui(ui, rect, over.latest, over.heat);
    messages_ui(ui, &mut over, rect);
    if over.drop_hover {
        drop_hint_ui(ui, rect);
    }
    if !over.widgets.panels_visible {
        let hint = corner_text(ui, rect, Align2::RIGHT_TOP, "H: show panel   F1: help");
        over.widgets.rects.insert("show_panel_hint", hint);
    }
    if over.widgets.help_open {
        help_ui(ui, over.widgets);
    }
}

/// The render size when it is capped, pass progress and, in heat-map mode, the legend.
fn status_ui(ui: &mut Ui, over: &mut Overlaid<'_>, rect: Rect) {
    let mut lines: Vec<String> = over
        .telemetry
        .capped
        .iter()
        .map(ToString::to_string)
        .collect();
    if let Some(latest) = over.latest {
        frame_status_ui(ui, over, rect, latest, &mut lines);
    }
    if !lines.is_empty() {
        let status = corner_text(ui, rect, Align2::LEFT_TOP, &lines.join("\n"));
        over.widgets.rects.insert("view_status", status);
    }
}

/// The heat map's legend, and the pass in progress as a line of `lines`.
fn frame_status_ui(
    ui: &mut Ui,
    over: &mut Overlaid<'_>,
    rect: Rect,
    latest: &RenderedFrame,
    lines: &mut Vec<String>,
) {
    let frame = &latest.frame;
    if over.heat != HeatMode::Off {
        let key = (latest.generation, frame.passes_done);
        let scale = match over.telemetry.heat_scale {
            Some((g, p, scale)) if (g, p) == key && scale.mode == over.heat => scale,
            _ => {
                let scale = HeatScale::of(frame, over.heat);
                over.telemetry.heat_scale = Some((key.0, key.1, scale));
                scale
            }
        };
        legend_ui(ui, rect, scale);
        // Chosen under another method: say why the view is one flat colour.
        if let Some(why) = over.heat.unavailable(over.method) {
            let text = format!("{why}: choose another heat map or method");
            let painter = ui.painter_at(rect);
            let galley = painter.layout(
                text,
                egui::FontId::proportional(15.0),
                Color32::WHITE,
                (rect.width() - 40.0).max(80.0),
            );
            let min = rect.center() - galley.size() / 2.0;
            let backdrop = Rect::from_min_size(min, galley.size()).expand(8.0);
            painter.rect_filled(backdrop, 4.0, Color32::from_black_alpha(170));
            painter.galley(min, galley, Color32::WHITE);
        }
    }
    if let Some(level) = latest.preview {
        lines.push(format!(
            "reading the map: pass {}/{} over a 1:{} preview",
            frame.passes_done,
            PASS_BLOCKS.len(),
            1u64 << level
        ));
    } else if !frame.complete() {
        lines.push(format!(
            "refining: pass {}/{} ({} px blocks)",
            frame.passes_done,
            PASS_BLOCKS.len(),
            PASS_BLOCKS[frame
                .passes_done
                .saturating_sub(1)
                .min(PASS_BLOCKS.len() - 1)]
        ));
    }
}

/// A gradient bar from 0 to the scale's maximum.
fn legend_ui(ui: &Ui, rect: Rect, scale: HeatScale) {
    let painter = ui.painter_at(rect);
    let size = Vec2::new(220.0, 14.0);
    let origin = rect.left_bottom() + Vec2::new(16.0, -40.0);
    let bar = Rect::from_min_size(origin, size);
    let backdrop = bar
        .expand2(Vec2::new(10.0, 24.0))
        .translate(Vec2::new(0.0, -6.0));
    painter.rect_filled(backdrop, 4.0, Color32::from_black_alpha(170));
    let steps = 64;
    for k in 0..steps {
        let x0 = bar.left() + size.x * k as f32 / steps as f32;
        let x1 = bar.left() + size.x * (k + 1) as f32 / steps as f32;
        let rgb = compose::ramp(k as f32 / (steps - 1) as f32);
        let colour = Color32::from_rgb((rgb >> 16) as u8, (rgb >> 8) as u8, rgb as u8);
        painter.rect_filled(
            Rect::from_x_y_ranges(x0..=x1 + 0.5, bar.y_range()),
            0.0,
            colour,
        );
    }
    let font = egui::FontId::proportional(12.0);
    let label = format!("{} per pixel (primary + shadow)", scale.mode.label());
    painter.text(
        bar.left_top() - Vec2::new(0.0, 3.0),
        Align2::LEFT_BOTTOM,
        label,
        font.clone(),
        Color32::WHITE,
    );
    painter.text(
        bar.left_bottom() + Vec2::new(0.0, 2.0),
        Align2::LEFT_TOP,
        "0",
        font.clone(),
        Color32::WHITE,
    );
    painter.text(
        bar.right_bottom() + Vec2::new(0.0, 2.0),
        Align2::RIGHT_TOP,
        format!("≥ {}", scale.max),
        font,
        Color32::WHITE,
    );
}

/// The loading progress, the last error and short notices, at the top of the view and
/// inside it: long text wraps to the view's width, never over the panel.
fn messages_ui(ui: &mut Ui, over: &mut Overlaid<'_>, rect: Rect) {
    let mut dismiss = false;
    let width = (rect.width() - 32.0).clamp(80.0, 640.0);
    // Below the corner's hint to bring the panel back, when it is there.
    let top = if over.widgets.panels_visible {
        12.0
    } else {
        40.0
    };
    egui::Area::new(Id::new("view messages"))
        .pivot(Align2::CENTER_TOP)
        .fixed_pos(Pos2::new(rect.center().x, rect.top() + top))
        .constrain_to(rect)
        .order(egui::Order::Foreground)
        .show(ui.ctx(), |ui| {
            ui.set_max_width(width);
            if let Some(progress) = &over.telemetry.progress {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    ui.horizontal_wrapped(|ui| {
                        ui.spinner();
                        ui.label(format!(
                            "Loading {}: {}",
                            progress.label,
                            progress.stage.label()
                        ));
                    });
                    let seconds = progress.started.elapsed().as_secs_f32();
                    ui.add(
                        egui::ProgressBar::new(progress.stage.fraction())
                            .text(format!("{seconds:.1} s")),
                    );
                });
            }
            if let Some(error) = over.error.as_ref() {
                let frame = egui::Frame::popup(ui.style())
                    .fill(Color32::from_rgb(110, 24, 24))
                    .show(ui, |ui| {
                        let text = egui::RichText::new(format!("⚠ {error}")).color(Color32::WHITE);
                        // A parser's message on several lines points at a column: monospace
                        // keeps its marker under the bad key.
                        let text = if error.contains('\n') {
                            text.monospace()
                        } else {
                            text
                        };
                        ui.label(text);
                        let button = ui.button("Dismiss");
                        over.widgets.rects.insert("error_dismiss", button.rect);
                        dismiss = button.clicked();
                    });
                over.widgets
                    .rects
                    .insert("error_message", frame.response.rect);
            }
            if let Some(notice) = over.notice.as_ref() {
                if notice.at.elapsed() < NOTICE_TIME {
                    egui::Frame::popup(ui.style()).show(ui, |ui| ui.label(&notice.text));
                }
            }
        });
    if dismiss {
        *over.error = None;
    }
    if over
        .notice
        .as_ref()
        .is_some_and(|n| n.at.elapsed() >= NOTICE_TIME)
    {
        *over.notice = None;
    }
    if let Some(notice) = over.notice.as_ref() {
        // Wake up once more to take the notice down.
        ui.ctx()
            .request_repaint_after(NOTICE_TIME.saturating_sub(notice.at.elapsed()));
    }
}

/// Shown while a file is dragged over the window.
fn drop_hint_ui(ui: &Ui, rect: Rect) {
    let painter = ui.ctx().layer_painter(egui::LayerId::new(
        egui::Order::Foreground,
        Id::new("drop hint"),
    ));
    painter.rect_filled(rect, 0.0, Color32::from_black_alpha(150));
    let inner = rect.shrink(24.0);
    painter.rect_stroke(
        inner,
        12.0,
        egui::Stroke::new(3.0, Color32::from_rgb(250, 200, 80)),
        egui::StrokeKind::Inside,
    );
    let lines = [
        "Drop a height map (PNG, PGM, TIFF, .hgt, .asc)",
        "or a scene (.toml) to open it",
    ];
    for (k, line) in lines.into_iter().enumerate() {
        let y = 30.0 * (k as f32 - 0.5);
        painter.text(
            rect.center() + Vec2::new(0.0, y),
            Align2::CENTER_CENTER,
            line,
            egui::FontId::proportional(22.0),
            Color32::WHITE,
        );
    }
}

/// Writes `text` in a corner of `rect`; returns where.
fn corner_text(ui: &Ui, rect: Rect, align: Align2, text: &str) -> Rect {
    let painter = ui.painter_at(rect);
    let galley = painter.layout_no_wrap(
        text.to_owned(),
        egui::FontId::proportional(13.0),
        Color32::WHITE,
    );
    let margin = Vec2::new(10.0, 8.0);
    let min = match align {
        Align2::RIGHT_TOP => rect.right_top() + Vec2::new(-margin.x - galley.size().x, margin.y),
        _ => rect.left_top() + margin,
    };
    let backdrop = Rect::from_min_size(min, galley.size()).expand(4.0);
    painter.rect_filled(backdrop, 3.0, Color32::from_black_alpha(120));
    painter.galley(min, galley, Color32::WHITE);
    backdrop
}

/// The F1 window: what the mouse and keys do.
fn help_ui(ui: &Ui, widgets: &mut Widgets) {
    let mut open = widgets.help_open;
    egui::Window::new("Help")
        .open(&mut open)
        .collapsible(false)
        .resizable(false)
        .anchor(Align2::LEFT_TOP, Vec2::new(16.0, 40.0))
        .show(ui.ctx(), |ui| {
            egui::Grid::new("help grid").num_columns(2).show(ui, |ui| {
                for (what, does) in HELP {
                    ui.strong(*what);
                    ui.label(*does);
                    ui.end_row();
                }
            });
        });
    widgets.help_open = open;
}

const HELP: &[(&str, &str)] = &[
    ("Left drag", "orbit around the target"),
    ("Right drag, Shift + left drag", "pan"),
    ("Wheel", "zoom towards the point under the cursor"),
    ("Arrow keys", "move over the map"),
    ("Q, E", "turn around the target"),
    ("+, -", "zoom in, out"),
    ("Page Up, Page Down", "look down more, less"),
    ("F", "frame the whole map from this direction"),
    (
        "Double-click",
        "orbit around the terrain point under the cursor",
    ),
    (
        "Rest the pointer",
        "with the probe on (Statistics): the pixel's ray, its hit and its queries",
    ),
    (
        "Drop a file",
        "open a height map (PNG, PGM, TIFF, .hgt, .asc) or a scene (.toml)",
    ),
    ("R", "reset the view (the whole map)"),
    ("S", "export the rendered image (PNG, no panels)"),
    (
        "K",
        "add the view to the flythrough (played and edited in its section)",
    ),
    (
        "H",
        "hide or show the panel (it hides itself in narrow windows)",
    ),
    ("F1", "this help"),
];
