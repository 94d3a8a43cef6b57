//! A bounded, seeded fuzz of the loader on the stable toolchain: valid files of every format
//! are mutated (bytes flipped, runs overwritten with 0x00 or 0xff, cut short, bytes inserted)
//! and loaded with every option; no input may panic, and whatever loads is a valid field.
//! The unbounded, coverage-guided fuzz target is in tests/fuzz (README, 'Testing').

use crate::common::files::tiff;
use crate::common::random::Rng;
use heightray::heightfield::{load_bytes_with, ColourEncoding, LoadOptions, NoDataValue};
use image::{ImageBuffer, ImageFormat, Luma, Rgb};
use std::io::Cursor;
use std::ops::ControlFlow;
use std::panic::{catch_unwind, AssertUnwindSafe};
use tiff::encoder::colortype::{Gray16, Gray32Float, GrayI16};

fn png(image: image::DynamicImage) -> Vec<u8> {
    let mut bytes = Cursor::new(Vec::new());
    image.write_to(&mut bytes, ImageFormat::Png).expect("PNG");
    bytes.into_inner()
}

/// One valid file of each format and sample type, 7x5 samples.
fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    let (w, h) = (7u32, 5u32);
    let gray16 = ImageBuffer::from_fn(w, h, |x, y| Luma([(x * 9000 + y * 300) as u16]));
    let rgb = ImageBuffer::from_fn(w, h, |x, y| Rgb([x as u8 * 30, y as u8 * 50, 128]));
    let values: Vec<u16> = (0..w * h).map(|k| (k * 1000) as u16).collect();
    let signed: Vec<i16> = (0..w * h).map(|k| k as i16 * 100 - 1000).collect();
    let floats: Vec<f32> = (0..w * h).map(|k| k as f32 * 0.5 - 3.0).collect();
    let mut ascii = format!("P2\n{w} {h}\n1000\n");
    for k in 0..w * h {
        ascii += &format!("{} ", k * 20);
    }
    let mut binary = format!("P5 {w} {h} 65535\n").into_bytes();
    binary.extend(values.iter().flat_map(|v| v.to_be_bytes()));
    vec![
        ("gray16.png", png(gray16.into())),
        ("rgb.png", png(rgb.into())),
        ("ascii.pgm", ascii.into_bytes()),
        ("binary.pgm", binary),
        ("gray16.tif", tiff::<Gray16>(w, h, &values, None)),
        ("signed.tif", tiff::<GrayI16>(w, h, &signed, Some("-1000"))),
        ("float.tif", tiff::<Gray32Float>(w, h, &floats, None)),
    ]
}

fn mutate(bytes: &mut Vec<u8>, rng: &mut Rng) {
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(bytes.len());
        match rng.below(5) {
            0 => bytes[at] ^= 1 << rng.below(8),
            1 => bytes[at] = rng.next() as u8,
            2 => {
                // Overwrite a run, as a corrupted size field or a zeroed sector would.
                let fill = if rng.below(2) == 0 { 0x00 } else { 0xff };
                let end = (at + 1 + rng.below(8)).min(bytes.len());
                bytes[at..end].fill(fill);
            }
            3 => bytes.truncate(at),
            _ => bytes.insert(at, rng.next() as u8),
        }
        if bytes.is_empty() {
            return;
        }
    }
}

#[test]
fn mutated_files_never_panic_the_loader() {
    let colours = [
        ColourEncoding::Luminance,
        ColourEncoding::Mapbox,
        ColourEncoding::Terrarium,
    ];
    let nodata = [NoDataValue::Auto, NoDataValue::Off, NoDataValue::Value(0.0)];
    let mut rng = Rng(0x4845_4947_4854_5241);
    let (mut loaded, mut refused) = (0, 0);
    for (name, seed) in seeds() {
        for case in 0..1500 {
            let mut bytes = seed.clone();
            mutate(&mut bytes, &mut rng);
            let options = LoadOptions {
                z_scale: 10.0,
                colour: colours[case % 3],
                nodata: nodata[(case / 3) % 3],
                height_unit: None,
            };
            let result = catch_unwind(AssertUnwindSafe(|| {
                load_bytes_with(&bytes, &options, name, &|_| ControlFlow::Continue(()))
            }));
            match result {
                Err(_) => panic!("{name} case {case} panicked; bytes {bytes:?}"),
                Ok(Ok(field)) => {
                    assert!(field.width() >= 2 && field.height() >= 2);
                    assert!(field.samples().len() == field.width() * field.height());
                    loaded += 1;
                }
                Ok(Err(error)) => {
                    assert!(error.to_string().contains(name), "{error}");
                    refused += 1;
                }
            }
        }
    }
    // The mutations must exercise both outcomes, or the loop tests nothing.
    assert!(
        loaded > 100 && refused > 100,
        "{loaded} loaded, {refused} refused"
    );
}
