//! Any bytes, any loader options: the loader returns a field or an error, never panics.
#![no_main]

use heightray::heightfield::{load_bytes_with, ColourEncoding, LoadOptions, NoDataValue};
use libfuzzer_sys::fuzz_target;
use std::ops::ControlFlow;

fuzz_target!(|data: &[u8]| {
    // The first byte picks the options; the rest is the file.
    let Some((&choice, file)) = data.split_first() else {
        return;
    };
    let colour = match choice % 3 {
        0 => ColourEncoding::Luminance,
        1 => ColourEncoding::Mapbox,
        _ => ColourEncoding::Terrarium,
    };
    let nodata = match (choice / 3) % 3 {
        0 => NoDataValue::Auto,
        1 => NoDataValue::Off,
        _ => NoDataValue::Value(0.0),
    };
    let options = LoadOptions {
        z_scale: 10.0,
        colour,
        nodata,
        height_unit: None,
    };
    if let Ok(field) = load_bytes_with(file, &options, "fuzz", &|_| ControlFlow::Continue(())) {
        assert!(field.width() >= 2 && field.height() >= 2);
    }
});
