//! The Traversal panel's accuracy part: the measure button, its table (and plot), and the
//! compare-with-exact switch with its count.

use super::measure::{label, ns_per_ray, BOUNDS, PIXEL_BUDGETS};
use super::AccuracyState;
use super::{CompareState, MeasureState, Measurement};
use crate::viewer::compose::HIGHLIGHT;
use crate::viewer::settings::Settings;
use crate::viewer::state::{Action, Widgets};
use crate::Arith;
use egui::{Color32, RichText, Ui};

/// Colour of the pixels that differ from exact: the overlay's, in the panel and the plot.
pub const DIFFERING: Color32 = Color32::from_rgb(
    (HIGHLIGHT >> 16) as u8,
    (HIGHLIGHT >> 8) as u8,
    HIGHLIGHT as u8,
);

/// The measurement and the comparison with exact, for the view `settings` render; the
/// measurement asked for or cancelled, if the button was pressed.
pub fn accuracy_ui(
    ui: &mut Ui,
    state: &mut AccuracyState,
    settings: &Settings,
    widgets: &mut Widgets,
) -> Option<Action> {
    ui.separator();
    ui.strong("What accuracy costs in this view");
    let action = measure_ui(ui, state, settings, widgets);
    ui.separator();
    compare_ui(ui, state, widgets);
    action
}

/// A warning or note on what the arithmetic on screen costs, and whether it is a warning:
/// from the measurement of this view when it has the row, else from the README's figures
/// (bounded rationals cost hundreds of times f64 per ray; exact about 1.3 times).
pub fn speed_note(arith: Arith, measurement: Option<&Measurement>) -> Option<(String, bool)> {
    let measured = measurement.and_then(|m| {
        let f64_ns = ns_per_ray(m.row(Arith::F64)?);
        Some(ns_per_ray(m.row(arith)?) / f64_ns.max(1e-9))
    });
    match (arith, measured) {
        (Arith::Rational { .. }, Some(ratio)) => Some((
            format!("measured here: {ratio:.0}x the time of f64 per ray; frames take a while"),
            ratio > 10.0,
        )),
        (Arith::Rational { .. }, None) => Some((
            "bounded rationals are slow: hundreds to a thousand times f64 per ray, so a frame \
             can take many seconds"
                .into(),
            true,
        )),
        (Arith::Exact, Some(ratio)) => Some((
            format!("measured here: exact takes {ratio:.1}x the time of f64 per ray"),
            ratio > 10.0,
        )),
        (Arith::Exact, None) => Some((
            "exact costs about 1.3x the time of f64 per ray on the built-in maps".into(),
            false,
        )),
        _ => None,
    }
}

fn measure_ui(
    ui: &mut Ui,
    state: &mut AccuracyState,
    settings: &Settings,
    widgets: &mut Widgets,
) -> Option<Action> {
    let mut action = None;
    let busy = matches!(
        state.measure,
        MeasureState::Running { .. } | MeasureState::Waiting
    );
    ui.horizontal_wrapped(|ui| {
        let text = if busy {
            "Cancel measuring"
        } else {
            "Measure all arithmetics"
        };
        let button = ui.button(text);
        widgets.rects.insert("measure_button", button.rect);
        if button.clicked() {
            action = Some(Action::MeasureArithmetics);
        }
        ui.add_enabled_ui(!busy, |ui| {
            egui::ComboBox::from_id_salt("measure size")
                .selected_text(format!("{} px", state.budget))
                .show_ui(ui, |ui| {
                    for budget in PIXEL_BUDGETS {
                        ui.selectable_value(&mut state.budget, budget, format!("{budget} px"));
                    }
                });
        });
    });
    let shadows = if settings.shadows {
        "its shadow ray included"
    } else {
        "shadows are off"
    };
    let bounds: Vec<String> = BOUNDS
        .iter()
        .map(|b| format!("2^{}", b.trailing_zeros()))
        .collect();
    ui.weak(format!(
        "This view at about {} pixels in each arithmetic (rational bounds {}), one thread, \
         against the exact render. Time per primary ray, {shadows}.",
        state.budget,
        bounds.join(", ")
    ));
    match &state.measure {
        MeasureState::Waiting => {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label("waiting for the view to settle");
            });
        }
        MeasureState::Running {
            report: Some(report),
            ..
        } => {
            ui.add(egui::ProgressBar::new(report.fraction).text(report.status.as_str()));
        }
        MeasureState::Running { .. } => {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label("starting");
            });
        }
        MeasureState::Done { .. } if state.measured_elsewhere() => {
            ui.colored_label(
                Color32::from_rgb(230, 180, 80),
                "measured for an earlier view: measure again for this one",
            );
        }
        MeasureState::Cancelled { .. } => {
            ui.weak("cancelled");
        }
        MeasureState::Failed(why) => {
            ui.colored_label(Color32::from_rgb(230, 110, 110), why);
        }
        MeasureState::Idle | MeasureState::Done { .. } => {}
    }
    if let Some(measurement) = state.measure.measurement() {
        table_ui(ui, measurement, settings.arith());
        super::plot::plot_ui(ui, measurement);
    }
    action
}

/// Arithmetic, time per ray, ratio to f64, pixels differing from exact.
fn table_ui(ui: &mut Ui, measurement: &Measurement, on_screen: Arith) {
    let (w, h) = measurement.size;
    ui.weak(format!("{w} x {h} = {} pixels", w * h));
    let f64_ns = measurement.row(Arith::F64).map(ns_per_ray);
    egui::Grid::new("arithmetic costs")
        .num_columns(4)
        .striped(true)
        .show(ui, |ui| {
            for heading in ["arithmetic", "ns/ray", "× f64", "px ≠ exact"] {
                ui.strong(heading);
            }
            ui.end_row();
            // Measured exact first (it is the reference); listed last, as in the README.
            let ordered = measurement
                .rows
                .iter()
                .filter(|r| r.arith != Arith::Exact)
                .chain(measurement.row(Arith::Exact));
            for row in ordered {
                let mut name = RichText::new(label(row.arith));
                if row.arith == on_screen {
                    name = name.strong().color(Color32::WHITE);
                }
                ui.label(name)
                    .on_hover_text_at_pointer("bold: the arithmetic on screen");
                let ns = ns_per_ray(row);
                ui.label(format!("{ns:.0}"));
                ui.label(f64_ns.map_or("…".into(), |f| format!("{:.2}", ns / f)));
                ui.label(row.differing.to_string());
                ui.end_row();
            }
        });
}

fn compare_ui(ui: &mut Ui, state: &mut AccuracyState, widgets: &mut Widgets) {
    let toggle = ui.checkbox(&mut state.compare_on, "Compare with exact");
    widgets.rects.insert("compare_toggle", toggle.rect);
    // Both states take the same height, so ticking or unticking never moves what is below
    // or makes a scrolled panel jump.
    ui.vertical(|ui| {
        ui.set_min_height(64.0);
        compare_status_ui(ui, state);
    });
}

/// What the switch does when off; how far the comparison is when on.
fn compare_status_ui(ui: &mut Ui, state: &AccuracyState) {
    if !state.compare_on {
        ui.weak(
            "renders the frame on screen again in exact arithmetic and marks the pixels that \
             differ in magenta",
        );
        return;
    }
    match &state.compare {
        CompareState::Running {
            report: Some(report),
            ..
        } => {
            ui.add(egui::ProgressBar::new(report.fraction).text(report.status.as_str()));
        }
        CompareState::Done(c) if Some(c.generation) == state.shown_generation => {
            ui.label(
                RichText::new(format!(
                    "{} of {} pixels differ, by up to {} in a colour byte",
                    c.differing, c.pixels, c.largest
                ))
                .color(DIFFERING)
                .strong(),
            );
            ui.weak(format!(
                "the exact render took {:.1} s (all threads)",
                c.exact_time.as_secs_f64()
            ));
        }
        _ => {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label("comparing once the view has settled");
            });
        }
    }
}
