//! Drapes: an image laid over the map colours the surface. Looking straight down from 4 units
//! above flat ground with a 90 degree field of view, an 8x8 frame's pixel `(px, py)` sees grid
//! point `(px + 0.5, 7.5 - py)` (the ground spans 8 units across the frame), which is where
//! the pixel centres of the images below land: each rendered pixel shows one image pixel
//! whole, under the overhead light at full strength, its byte unchanged.

use crate::common::files::{tagged_tiff, TagData};
use crate::common::top_down::overhead_light;
use heightray::render::{Camera, Culling, Frame, Ramp, Renderer, Scene, Shader};
use heightray::{Arith, Method, Terrain};
use std::path::Path;
use tiff::encoder::colortype::{ColorType, Gray32Float, RGB8};
use tiff::encoder::TiffValue;
use tiff::tags::Tag;

/// The test image's pixel `(c, r)`: every pixel a different colour.
fn pattern(c: u32, r: u32) -> [u8; 3] {
    [
        (c * 32 + 10) as u8,
        (r * 32 + 10) as u8,
        ((c + r) * 16 + 5) as u8,
    ]
}

/// `pattern` as 0x00RRGGBB, the renderer's pixel format.
fn packed(c: u32, r: u32) -> u32 {
    let [red, green, blue] = pattern(c, r).map(u32::from);
    (red << 16) | (green << 8) | blue
}

/// A PNG of `side` x `side` pixels of `pattern`.
fn write_png(path: &Path, side: u32) {
    image::RgbImage::from_fn(side, side, |c, r| image::Rgb(pattern(c, r)))
        .save(path)
        .expect("the overlay written");
}

/// The scene at `scene` seen from 4 units above the ground at grid point (4, 4), 8x8 pixels.
fn render_from_above(scene: &Scene) -> Frame {
    let terrain = Terrain::new(scene.field.clone());
    let ground = terrain.field().z(4, 4);
    let camera = Camera::look_at(
        [4.0, 4.0, ground + 4.0],
        [4.0, 4.0, ground],
        [0.0, 1.0, 0.0],
        90.0,
        (8, 8),
    )
    .expect("a valid camera");
    let renderer = Renderer {
        shader: Shader::new(
            &terrain,
            overhead_light(Ramp::Gray),
            Method::Mipmap,
            Culling::default(),
        ),
        camera: camera.in_grid(terrain.world_from_grid()),
        arith: Arith::F64,
    };
    let mut frame = Frame::new(8, 8);
    renderer.render(&mut frame);
    frame
}

/// Writes `scene` as a scene file in `dir` and loads it.
fn load(dir: &Path, scene: &str) -> Result<Scene, String> {
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene).expect("the scene written");
    Scene::load(&path).map_err(|e| e.to_string())
}

/// A flat 9x9 plain map (PGM), whose 8x8 cells the frame covers exactly.
fn write_flat_map(dir: &Path) {
    let mut pgm = b"P5\n9 9\n255\n".to_vec();
    pgm.extend([0u8; 81]);
    std::fs::write(dir.join("flat.pgm"), pgm).expect("the map written");
}

#[test]
fn a_stretched_overlay_puts_each_image_pixel_on_its_cell() {
    let dir = tempfile::tempdir().unwrap();
    write_flat_map(dir.path());
    // 8x8 pixels stretched over 8x8 cells: image pixel (c, r) covers cell (c, 7 - r).
    write_png(&dir.path().join("ortho.png"), 8);
    let scene = "[heightmap]\npath = \"flat.pgm\"\nz_scale = 1.0\n\
                 [overlay]\npath = \"ortho.png\"\n";
    let frame = render_from_above(&load(dir.path(), scene).unwrap());
    for py in 0..8 {
        for px in 0..8 {
            let got = frame.pixels[(py * 8 + px) as usize];
            assert_eq!(got, packed(px, py), "pixel ({px}, {py}): {got:06x}");
        }
    }
}

#[test]
fn opacity_blends_the_overlay_with_the_ramp() {
    let dir = tempfile::tempdir().unwrap();
    write_flat_map(dir.path());
    write_png(&dir.path().join("ortho.png"), 8);
    let plain = load(
        dir.path(),
        "[heightmap]\npath = \"flat.pgm\"\nz_scale = 1.0\n",
    )
    .unwrap();
    let half = "[heightmap]\npath = \"flat.pgm\"\nz_scale = 1.0\n\
                [overlay]\npath = \"ortho.png\"\nopacity = 0.5\n";
    let (plain, half) = (
        render_from_above(&plain),
        render_from_above(&load(dir.path(), half).unwrap()),
    );
    // Half the ramp's linear light and half the image's, through a gamma of 2.2.
    let linear = |byte: u32| (f64::from(byte) / 255.0).powf(2.2);
    for (k, (&ramp, &blend)) in plain.pixels.iter().zip(&half.pixels).enumerate() {
        let image = packed(k as u32 % 8, k as u32 / 8);
        for shift in [16, 8, 0] {
            let channel = |rgb: u32| (rgb >> shift) & 0xff;
            let mixed = 0.5 * linear(channel(ramp)) + 0.5 * linear(channel(image));
            let expected = mixed.powf(1.0 / 2.2) * 255.0;
            // The ramp's own colour is known only to its byte: within one byte.
            let got = f64::from(channel(blend));
            assert!(
                (got - expected).abs() <= 1.0,
                "pixel {k}: {got} against {expected}"
            );
        }
    }
}

/// A square GeoTIFF `side` pixels wide of 10 m pixels in a projected CRS in metres, the
/// top-left pixel's corner at `corner`.
fn projected_tiff<C: ColorType>(side: u32, data: &[C::Inner], corner: [f64; 2]) -> Vec<u8>
where
    [C::Inner]: TiffValue,
{
    let keys = [1, 1, 0, 1, 1024, 0, 1, 1];
    let tiepoint = [0.0, 0.0, 0.0, corner[0], corner[1], 0.0];
    let tags = [
        (Tag::GeoKeyDirectoryTag, TagData::Shorts(&keys)),
        (
            Tag::ModelPixelScaleTag,
            TagData::Doubles(&[10.0, 10.0, 0.0]),
        ),
        (Tag::ModelTiepointTag, TagData::Doubles(&tiepoint)),
    ];
    tagged_tiff::<C>(side, side, data, &tags)
}

/// A flat 9x9 float DEM, 100 m high, of 10 m cells, the top-left pixel's corner at
/// (1000, 2090) in a projected CRS: sample (i, j) at (1005 + 10 i, 2005 + 10 j). One sample
/// in the top-left corner is 103 m, so that the DEM has a range to quantise.
fn write_dem(dir: &Path) {
    let mut heights = vec![100.0f32; 81];
    heights[0] = 103.0;
    let bytes = projected_tiff::<Gray32Float>(9, &heights, [1000.0, 2090.0]);
    std::fs::write(dir.join("dem.tif"), bytes).expect("the DEM written");
}

/// The frame of the DEM with and without the overlay `name`.
fn georeferenced_frames(dir: &Path, name: &str) -> (Frame, Frame) {
    let plain = load(dir, "[heightmap]\npath = \"dem.tif\"\n").unwrap();
    let draped = format!("[heightmap]\npath = \"dem.tif\"\n[overlay]\npath = \"{name}\"\n");
    let draped = load(dir, &draped).unwrap();
    (render_from_above(&plain), render_from_above(&draped))
}

/// A 4x4 overlay of 10 m pixels whose top-left pixel's centre is at (1030, 2070): pixel
/// `(c, r)` centred on map point `(1030 + 10 c, 2070 - 10 r)`, grid point
/// `(2.5 + c, 6.5 - r)`, which frame pixel `(c + 2, r + 1)` sees. Elsewhere the ramp shows.
fn assert_placed_with_offset(plain: &Frame, draped: &Frame) {
    for py in 0..8u32 {
        for px in 0..8u32 {
            let k = (py * 8 + px) as usize;
            let inside = (2..6).contains(&px) && (1..5).contains(&py);
            let expected = if inside {
                packed(px - 2, py - 1)
            } else {
                plain.pixels[k]
            };
            assert_eq!(draped.pixels[k], expected, "pixel ({px}, {py})");
        }
    }
}

#[test]
fn a_geotiff_overlay_lands_where_its_map_coordinates_say() {
    let dir = tempfile::tempdir().unwrap();
    write_dem(dir.path());
    let rgb: Vec<u8> = (0..16).flat_map(|k| pattern(k % 4, k / 4)).collect();
    let bytes = projected_tiff::<RGB8>(4, &rgb, [1025.0, 2075.0]);
    std::fs::write(dir.path().join("ortho.tif"), bytes).unwrap();
    let (plain, draped) = georeferenced_frames(dir.path(), "ortho.tif");
    assert_placed_with_offset(&plain, &draped);
}

#[test]
fn a_world_file_places_a_png_overlay() {
    let dir = tempfile::tempdir().unwrap();
    write_dem(dir.path());
    write_png(&dir.path().join("ortho.png"), 4);
    // Pixel size, two rotation terms, minus the pixel height, the top-left pixel's centre.
    std::fs::write(dir.path().join("ortho.pgw"), "10\n0\n0\n-10\n1030\n2070\n").unwrap();
    let (plain, draped) = georeferenced_frames(dir.path(), "ortho.png");
    assert_placed_with_offset(&plain, &draped);
}

#[test]
fn bad_overlays_are_explained() {
    let dir = tempfile::tempdir().unwrap();
    write_dem(dir.path());
    let scene = |overlay: &str| {
        format!("[heightmap]\npath = \"dem.tif\"\n[overlay]\npath = \"{overlay}\"\n")
    };
    std::fs::write(dir.path().join("notes.png"), "not an image").unwrap();
    std::fs::write(dir.path().join("empty.jpg"), "").unwrap();
    std::fs::create_dir(dir.path().join("folder")).unwrap();
    // Far away from the DEM.
    write_png(&dir.path().join("far.png"), 4);
    std::fs::write(dir.path().join("far.pgw"), "10\n0\n0\n-10\n90000\n2070\n").unwrap();
    write_png(&dir.path().join("turned.png"), 4);
    std::fs::write(dir.path().join("turned.pgw"), "10\n1\n1\n-10\n1030\n2070\n").unwrap();
    for (file, words) in [
        ("notes.png", "cannot be decoded"),
        ("empty.jpg", "cannot be decoded"),
        ("missing.png", "cannot read overlay"),
        ("folder", "is a directory"),
        ("far.png", "lies outside the map"),
        ("turned.png", "rotated"),
    ] {
        let error = load(dir.path(), &scene(file)).expect_err(file);
        assert!(error.contains("[overlay]"), "{file}: {error}");
        assert!(error.contains(words), "{file}: {error}");
    }
    let bad_opacity = format!("{}opacity = 1.5\n", scene("far.png"));
    let error = load(dir.path(), &bad_opacity).err().unwrap();
    assert!(error.contains("opacity"), "{error}");
}
