//! How the viewer decodes height map images: the colour encoding of RGB images and the value
//! that means no data. Chosen on the command line (`--rgb`, `--nodata`) or in the height map
//! panel, it applies to every image opened or dropped from then on, and the panel can read the
//! image on screen again with it. A scene file's own `[heightmap]` keys take precedence.

use super::state::{Action, LoadRequest, Shown, Source, Widgets};
use super::widgets::named;
use crate::heightfield::{ColourEncoding, HeightUnit, NoDataValue};
use egui::{DragValue, Ui};
use std::path::{Path, PathBuf};

/// The choices, and a button that reads the shown image again when they differ from how it
/// was read: the load it asks for.
pub fn decoding_ui(ui: &mut Ui, widgets: &mut Widgets, shown: &Shown) -> Option<Action> {
    ui.horizontal_wrapped(|ui| {
        ui.label("RGB images as");
        for colour in [
            ColourEncoding::Luminance,
            ColourEncoding::Mapbox,
            ColourEncoding::Terrarium,
        ] {
            let name = match colour {
                ColourEncoding::Luminance => "decode_luminance",
                ColourEncoding::Mapbox => "decode_mapbox",
                ColourEncoding::Terrarium => "decode_terrarium",
            };
            let label = colour.to_string();
            let radio = ui.radio_value(&mut widgets.decoding.colour, colour, label);
            named(widgets, name, radio);
        }
    });
    ui.horizontal_wrapped(|ui| nodata_ui(ui, widgets));
    ui.horizontal_wrapped(|ui| height_unit_ui(ui, widgets));
    let Source::File(path) = &shown.source else {
        return None;
    };
    if shown.source.is_scene() {
        return None;
    }
    // The colour choice changes nothing in a grey image: reading it again is offered only
    // for what would change.
    let (chosen, read) = (widgets.decoding, shown.decoding);
    let differs = chosen.nodata != read.nodata
        || chosen.height_unit != read.height_unit
        || (chosen.colour != read.colour && has_colour(ui, path));
    if !differs {
        return None;
    }
    let again = ui.button(format!("read {} again", shown.source.label()));
    let again = named(widgets, "decode_again", again).clicked();
    again.then(|| {
        Action::Load(LoadRequest {
            source: shown.source.clone(),
            z_scale: None,
            reframe: true,
            from_memory: None,
            decoding: widgets.decoding,
            overlay: None,
        })
    })
}

/// Whether the image at `path` has colour channels, from its header (remembered per path:
/// the panel asks every frame). Unreadable headers count as colour, so the choice stays.
fn has_colour(ui: &Ui, path: &Path) -> bool {
    let id = egui::Id::new("image has colour");
    let known: Option<(PathBuf, bool)> = ui.data(|d| d.get_temp(id));
    if let Some((_, colour)) = known.filter(|(p, _)| p == path) {
        return colour;
    }
    let colour = image::ImageReader::open(path)
        .and_then(|reader| reader.with_guessed_format())
        .ok()
        .and_then(|reader| reader.into_decoder().ok())
        .is_none_or(|decoder| {
            use image::ImageDecoder;
            decoder.color_type().has_color()
        });
    ui.data_mut(|d| d.insert_temp(id, (path.to_path_buf(), colour)));
    colour
}

/// A georeferenced map's heights: in the unit its file implies, or in metres or feet.
fn height_unit_ui(ui: &mut Ui, widgets: &mut Widgets) {
    ui.label("heights in");
    let choices = [
        (None, "the file's unit", "height_unit_file"),
        (HeightUnit::named("m"), "m", "height_unit_m"),
        (HeightUnit::named("ft"), "ft", "height_unit_ft"),
        (HeightUnit::named("us-ft"), "US ft", "height_unit_us_ft"),
    ];
    for (chosen, label, widget) in choices {
        let radio = ui.radio_value(&mut widgets.decoding.height_unit, chosen, label);
        named(widgets, widget, radio);
    }
}

/// No data: the file's own (auto), none, or a value.
fn nodata_ui(ui: &mut Ui, widgets: &mut Widgets) {
    ui.label("no data");
    let nodata = &mut widgets.decoding.nodata;
    let auto = ui.radio(*nodata == NoDataValue::Auto, "auto");
    if named(widgets, "nodata_auto", auto).clicked() {
        widgets.decoding.nodata = NoDataValue::Auto;
    }
    let none = ui.radio(widgets.decoding.nodata == NoDataValue::Off, "none");
    if named(widgets, "nodata_none", none).clicked() {
        widgets.decoding.nodata = NoDataValue::Off;
    }
    let chosen = match widgets.decoding.nodata {
        NoDataValue::Value(v) => Some(v),
        _ => None,
    };
    let value = ui.radio(chosen.is_some(), "value");
    if named(widgets, "nodata_value", value).clicked() && chosen.is_none() {
        // SRTM's and most DEMs' marker.
        widgets.decoding.nodata = NoDataValue::Value(-32768.0);
    }
    if let Some(mut v) = chosen {
        if ui.add(DragValue::new(&mut v).speed(1.0)).changed() && v.is_finite() {
            widgets.decoding.nodata = NoDataValue::Value(v);
        }
    }
}
