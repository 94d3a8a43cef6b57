//! Good height maps in every format load with the size and heights the test wrote: PNG
//! (8/16-bit gray, gray with alpha, RGB and RGBA as luminance, Mapbox and Terrarium
//! terrain-RGB), PGM (P2/P5, 8/16-bit) and TIFF (8/16-bit unsigned, 16-bit signed with SRTM's
//! no-data value, 32/64-bit float, GDAL_NODATA); and the colour ramp spans the heights a map
//! uses, not its format's range.

use crate::common::files::tiff;
use crate::common::top_down::render_top_down;
use heightray::heightfield::{
    load, load_with, ColourEncoding, LoadOptions, NoDataValue, Quantisation,
};
use heightray::render::Ramp;
use heightray::{Heightfield, Terrain};
use image::{GrayImage, ImageBuffer, Luma, LumaA, Rgb, Rgba};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use tempfile::TempDir;
use tiff::encoder::colortype::{Gray16, Gray32Float, Gray64Float, Gray8, GrayI16};

fn write(dir: &TempDir, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).expect("write test file");
    path
}

fn load_as(path: &Path, options: LoadOptions) -> Heightfield {
    load_with(path, &options, &|_| ControlFlow::Continue(())).expect("loads")
}

/// Checks size, maxval and every height: `rows[r][c]` is image row `r` (top first), so
/// sample `(c, H-1-r)`.
fn assert_field(field: &Heightfield, rows: &[Vec<u32>], maxval: u32, z_scale: f64) {
    let (w, h) = (rows[0].len(), rows.len());
    assert_eq!((field.width(), field.height()), (w, h));
    assert_eq!(u32::from(field.maxval()), maxval);
    for (r, row) in rows.iter().enumerate() {
        for (c, &s) in row.iter().enumerate() {
            let j = h - 1 - r;
            assert_eq!(u32::from(field.sample(c, j)), s, "sample ({c}, {j})");
            let expected = f64::from(s) * (z_scale / f64::from(maxval));
            assert_eq!(
                field.z(c, j).to_bits(),
                expected.to_bits(),
                "height ({c}, {j})"
            );
        }
    }
}

/// 5 columns x 3 rows of distinct samples up to `maxval`.
fn test_rows(maxval: u32) -> Vec<Vec<u32>> {
    (0..3)
        .map(|r| (0..5).map(|c| (r * 5 + c) * maxval / 14).collect())
        .collect()
}

#[test]
fn eight_bit_png_loads_with_its_heights() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(255);
    let path = dir.path().join("eight.png");
    GrayImage::from_fn(5, 3, |x, y| Luma([rows[y as usize][x as usize] as u8]))
        .save(&path)
        .unwrap();
    let field = load(&path, 12.5).unwrap();
    assert_field(&field, &rows, 255, 12.5);
}

#[test]
fn sixteen_bit_png_loads_with_its_heights() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(65535);
    let path = dir.path().join("sixteen.png");
    ImageBuffer::<Luma<u16>, Vec<u16>>::from_fn(5, 3, |x, y| {
        Luma([rows[y as usize][x as usize] as u16])
    })
    .save(&path)
    .unwrap();
    let field = load(&path, 3000.0).unwrap();
    assert_field(&field, &rows, 65535, 3000.0);
}

#[test]
fn ascii_pgm_with_maxval_1000_loads_with_its_heights() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(1000);
    let mut text = String::from("P2\n# written by bad_input.rs\n5 3\n1000\n");
    for row in &rows {
        text += &row.iter().map(u32::to_string).collect::<Vec<_>>().join(" ");
        text += "\n";
    }
    let path = write(&dir, "ascii.pgm", text.as_bytes());
    let field = load(&path, 0.7).unwrap();
    assert_field(&field, &rows, 1000, 0.7);
}

#[test]
fn binary_pgm_with_maxval_1000_loads_with_its_heights() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(1000);
    let mut bytes = b"P5\n5 3\n1000\n".to_vec();
    for &s in rows.iter().flatten() {
        bytes.extend((s as u16).to_be_bytes());
    }
    let path = write(&dir, "binary.pgm", &bytes);
    let field = load(&path, 25.0).unwrap();
    assert_field(&field, &rows, 1000, 25.0);
}

#[test]
fn pgm_p5_at_8_and_16_bits_and_p2_at_8_bits_load_with_their_heights() {
    let dir = TempDir::new().unwrap();
    for maxval in [255u32, 65535] {
        let rows = test_rows(maxval);
        let mut bytes = format!("P5\n5 3\n{maxval}\n").into_bytes();
        for &s in rows.iter().flatten() {
            if maxval < 256 {
                bytes.push(s as u8);
            } else {
                bytes.extend((s as u16).to_be_bytes());
            }
        }
        let field = load(&write(&dir, "binary.pgm", &bytes), 9.0).unwrap();
        assert_field(&field, &rows, maxval, 9.0);
    }
    let rows = test_rows(255);
    let mut text = String::from("P2 5 3 255\n");
    for row in &rows {
        text += &row.iter().map(u32::to_string).collect::<Vec<_>>().join(" ");
        text += "\n";
    }
    let field = load(&write(&dir, "ascii.pgm", text.as_bytes()), 2.0).unwrap();
    assert_field(&field, &rows, 255, 2.0);
}

#[test]
fn gray_png_with_alpha_ignores_the_alpha() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(255);
    let path = dir.path().join("alpha.png");
    ImageBuffer::from_fn(5, 3, |x, y| {
        LumaA([rows[y as usize][x as usize] as u8, (x * 50) as u8])
    })
    .save(&path)
    .unwrap();
    assert_field(&load(&path, 4.0).unwrap(), &rows, 255, 4.0);
}

/// Rec. 709 luminance, rounded, as the README states it.
fn luminance(r: u32, g: u32, b: u32) -> u32 {
    (2126 * r + 7152 * g + 722 * b + 5000) / 10000
}

#[test]
fn rgb_and_rgba_pngs_load_as_luminance() {
    let dir = TempDir::new().unwrap();
    let pixel = |x: u32, y: u32| [x * 40 + 7, y * 90 + 3, (x * y * 31) % 256];
    let rows: Vec<Vec<u32>> = (0..3)
        .map(|y| {
            (0..5)
                .map(|x| {
                    let [r, g, b] = pixel(x, y);
                    luminance(r, g, b)
                })
                .collect()
        })
        .collect();
    let rgb = dir.path().join("rgb.png");
    ImageBuffer::from_fn(5, 3, |x, y| Rgb(pixel(x, y).map(|c| c as u8)))
        .save(&rgb)
        .unwrap();
    assert_field(&load(&rgb, 3.0).unwrap(), &rows, 255, 3.0);
    // 16 bits per channel, with alpha: the same formula on 16-bit values.
    let wide = |x: u32, y: u32| pixel(x, y).map(|c| c * 257 + x);
    let rows16: Vec<Vec<u32>> = (0..3)
        .map(|y| {
            (0..5)
                .map(|x| {
                    let [r, g, b] = wide(x, y);
                    luminance(r, g, b)
                })
                .collect()
        })
        .collect();
    let rgba = dir.path().join("rgba16.png");
    ImageBuffer::from_fn(5, 3, |x, y| {
        let [r, g, b] = wide(x, y).map(|c| c as u16);
        Rgba([r, g, b, 1000])
    })
    .save(&rgba)
    .unwrap();
    assert_field(&load(&rgba, 3.0).unwrap(), &rows16, 65535, 3.0);
}

/// Checks that every height is the written value (times z_scale) to within half the
/// quantisation step, and that the step is the range over 65535 levels.
fn assert_quantised(field: &Heightfield, values: &[Vec<f64>], z_scale: f64) {
    let (w, h) = (values[0].len(), values.len());
    assert_eq!((field.width(), field.height()), (w, h));
    let all = values.iter().flatten().copied();
    let (lo, hi) = all
        .clone()
        .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
    let step = (hi - lo) / 65535.0 * z_scale;
    assert!(
        (field.step() - step).abs() <= 1e-12 * step.max(1.0),
        "step {}",
        field.step()
    );
    for (r, row) in values.iter().enumerate() {
        for (c, &v) in row.iter().enumerate() {
            let z = field.z(c, h - 1 - r);
            assert!(
                (z - v * z_scale).abs() <= 0.5 * step * (1.0 + 1e-9),
                "({c}, {r}): {z} for {v}"
            );
        }
    }
}

#[test]
fn mapbox_terrain_rgb_decodes_to_metres() {
    let dir = TempDir::new().unwrap();
    let code = |x: u32, y: u32| 100_000 + x * 4_321 + y * 77_777;
    let values: Vec<Vec<f64>> = (0..3)
        .map(|y| {
            (0..5)
                .map(|x| -10000.0 + f64::from(code(x, y)) * 0.1)
                .collect()
        })
        .collect();
    let path = dir.path().join("mapbox.png");
    ImageBuffer::from_fn(5, 3, |x, y| {
        let c = code(x, y);
        Rgba([(c >> 16) as u8, (c >> 8) as u8, c as u8, 255])
    })
    .save(&path)
    .unwrap();
    let options = LoadOptions {
        colour: ColourEncoding::Mapbox,
        ..LoadOptions::new(0.5)
    };
    assert_quantised(&load_as(&path, options), &values, 0.5);
}

#[test]
fn terrarium_whole_metres_load_exactly() {
    let dir = TempDir::new().unwrap();
    // Whole metres from -400 to 8000 (B = 0): stored exactly, one sample per metre.
    let metres = |x: u32, y: u32| -400 + (x * 1500 + y * 600) as i32;
    let path = dir.path().join("terrarium.png");
    ImageBuffer::from_fn(5, 3, |x, y| {
        let v = (metres(x, y) + 32768) as u32;
        Rgb([(v >> 8) as u8, v as u8, 0])
    })
    .save(&path)
    .unwrap();
    let options = LoadOptions {
        colour: ColourEncoding::Terrarium,
        ..LoadOptions::new(2.0)
    };
    let field = load_as(&path, options);
    assert_eq!(
        field.quantisation(),
        Quantisation::Offset {
            lowest: -400.0,
            step: 1.0
        }
    );
    for r in 0..3 {
        for c in 0..5 {
            assert_eq!(
                field.z(c as usize, 2 - r as usize),
                f64::from(metres(c, r)) * 2.0
            );
        }
    }
}

#[test]
fn unsigned_tiffs_load_like_grayscale_images() {
    let dir = TempDir::new().unwrap();
    let rows = test_rows(255);
    let flat: Vec<u8> = rows.iter().flatten().map(|&s| s as u8).collect();
    let path = write(&dir, "gray8.tif", &tiff::<Gray8>(5, 3, &flat, None));
    assert_field(&load(&path, 6.0).unwrap(), &rows, 255, 6.0);
    let rows = test_rows(65535);
    let flat: Vec<u16> = rows.iter().flatten().map(|&s| s as u16).collect();
    let path = write(&dir, "gray16.tif", &tiff::<Gray16>(5, 3, &flat, None));
    assert_field(&load(&path, 6.0).unwrap(), &rows, 65535, 6.0);
}

#[test]
fn signed_tiff_dem_keeps_its_metres_and_srtm_voids_are_holes() {
    let dir = TempDir::new().unwrap();
    // Image rows, top first; -32768 is SRTM's void.
    let values: [i16; 15] = [
        -12, 0, 5, 900, -32768, 7, 8, 9, 10, 11, 2000, -32768, 3, 4, 5,
    ];
    let path = write(&dir, "srtm.tif", &tiff::<GrayI16>(5, 3, &values, None));
    let field = load(&path, 1.0).unwrap();
    assert_eq!(field.nodata_count(), 2);
    for (k, &v) in values.iter().enumerate() {
        let (c, j) = (k % 5, 2 - k / 5);
        if v == -32768 {
            assert!(field.is_nodata(c, j), "({c}, {j})");
        } else {
            assert!(!field.is_nodata(c, j));
            assert_eq!(field.z(c, j), f64::from(v), "({c}, {j})");
        }
    }
    // With no-data switched off, -32768 is a height like any other.
    let options = LoadOptions {
        nodata: NoDataValue::Off,
        ..LoadOptions::new(1.0)
    };
    let field = load_as(&path, options);
    assert_eq!(field.nodata_count(), 0);
    assert_eq!(field.z(4, 2), -32768.0);
}

#[test]
fn float_tiff_dems_load_in_their_units_with_the_file_nodata_value() {
    let dir = TempDir::new().unwrap();
    let values: Vec<Vec<f64>> = (0..3)
        .map(|r| {
            (0..5)
                .map(|c| 1234.5 + f64::from(c) * 0.37 - f64::from(r) * 11.125)
                .collect()
        })
        .collect();
    let flat32: Vec<f32> = values.iter().flatten().map(|&v| v as f32).collect();
    let values32: Vec<Vec<f64>> = flat32
        .chunks(5)
        .map(|r| r.iter().map(|&v| f64::from(v)).collect())
        .collect();
    let path = write(&dir, "dem32.tif", &tiff::<Gray32Float>(5, 3, &flat32, None));
    let field = load(&path, 3.0).unwrap();
    assert_eq!(field.nodata_count(), 0);
    assert_quantised(&field, &values32, 3.0);
    let flat64: Vec<f64> = values.iter().flatten().copied().collect();
    let path = write(&dir, "dem64.tif", &tiff::<Gray64Float>(5, 3, &flat64, None));
    assert_quantised(&load(&path, 3.0).unwrap(), &values, 3.0);
    // A GeoTIFF's own no-data value.
    let mut marked = flat32.clone();
    marked[7] = -9999.0;
    let path = write(
        &dir,
        "nodata.tif",
        &tiff::<Gray32Float>(5, 3, &marked, Some("-9999")),
    );
    let field = load(&path, 3.0).unwrap();
    assert_eq!(field.nodata_count(), 1);
    assert!(field.is_nodata(2, 1));
}

#[test]
fn the_colour_ramp_spans_the_heights_a_map_uses() {
    // A 16-bit ramp that uses samples 1000..=1200 of 0..=65535, rising eastwards.
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("narrow.png");
    ImageBuffer::from_fn(9, 9, |x, _| Luma([1000 + 25 * x as u16]))
        .save(&path)
        .unwrap();
    let terrain = Terrain::new(load(&path, 100.0).unwrap());
    assert_eq!(
        terrain.z_range(),
        (1000.0 * 100.0 / 65535.0, 1200.0 * 100.0 / 65535.0)
    );
    let frame = render_top_down(&terrain, Ramp::Gray, 30.0, 10.0);
    // Gray ramp: 0.25 + 0.75 e with e the position in the map's own range, then gamma 2.2.
    // The view spans x = 1.55 .. 6.45 of 0 .. 8, so e runs from about 0.2 to 0.8: about 168
    // to 238 in 8 bits. Over 0..=65535 e would stay below 0.02 and every pixel near 136.
    let row = &frame.pixels[8 * 16..9 * 16];
    let (west, east) = (row[0] & 0xff, row[15] & 0xff);
    assert!(
        (160..180).contains(&west) && (228..248).contains(&east),
        "west {west}, east {east}"
    );
}

/// A scene file chooses the encoding and the no-data value of its height map: the same
/// terrain-RGB tile is Terrarium metres with `rgb = "terrarium"`, and one of its heights is a
/// hole with `nodata = <that height>`; a misspelt encoding is an error naming the key.
#[test]
fn scene_files_choose_the_rgb_encoding_and_the_nodata_value() {
    let dir = TempDir::new().unwrap();
    let metres = |x: u32, y: u32| -400 + (x * 1500 + y * 600) as i32;
    ImageBuffer::from_fn(5, 3, |x, y| {
        let v = (metres(x, y) + 32768) as u32;
        Rgb([(v >> 8) as u8, v as u8, 0])
    })
    .save(dir.path().join("tile.png"))
    .unwrap();
    let scene = |heightmap_keys: &str| {
        let text = format!(
            "[heightmap]\npath = \"tile.png\"\nz_scale = 1.0\n{heightmap_keys}\n\
             [camera]\neye = [-5.0, -5.0, 9000.0]\ntarget = [2.0, 1.0, 0.0]\nwidth = 8\nheight = 8\n"
        );
        let path = write(&dir, "scene.toml", text.as_bytes());
        heightray::render::Scene::load(&path)
    };
    let field = scene("rgb = \"terrarium\"").expect("loads").field;
    assert_eq!(field.z(1, 2), f64::from(metres(1, 0)));
    assert_eq!(field.nodata_count(), 0);
    // Metres(1, 0) = 1100 (image row 0 is y = 2).
    let field = scene("rgb = \"terrarium\"\nnodata = 1100")
        .expect("loads")
        .field;
    assert_eq!(field.nodata_count(), 1);
    assert!(field.is_nodata(1, 2));
    let field = scene("rgb = \"terrarium\"\nnodata = \"none\"")
        .expect("loads")
        .field;
    assert_eq!(field.nodata_count(), 0);
    let error = scene("rgb = \"terraruim\"")
        .expect_err("misspelt")
        .to_string();
    assert!(
        error.contains("[heightmap] rgb") && error.contains("terraruim"),
        "{error}"
    );
    let error = scene("nodata = \"never\"")
        .expect_err("bad word")
        .to_string();
    assert!(error.contains("[heightmap] nodata"), "{error}");
}
