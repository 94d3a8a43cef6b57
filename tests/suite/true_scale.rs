//! Georeferenced maps at true scale: heights in metres over cells in metres by default, an
//! exaggeration in scene files, and non-square cells (a geographic tile at 60 N) rendered
//! half as wide in x as in y, checked against the footprint worked out from the camera's
//! geometry by hand. Plain images keep their automatic relief.

use crate::common::files::dem_bytes;
use crate::common::scenes::load_scene_text;
use crate::common::top_down::overhead_light;
use heightray::heightfield::{load_bytes, relief};
use heightray::render::{Camera, Culling, Frame, Ramp, Renderer, Shader};
use heightray::{Arith, Heightfield, Method, Terrain};

/// A tile of 1-second cells whose middle row lies at 60 N.
fn tile_at_60_north() -> Heightfield {
    let second = 1.0 / 3600.0;
    let bytes = dem_bytes(second, [10.0, 60.0 + 8.5 * second], 2);
    load_bytes(&bytes, 1.0, "n60.tif").expect("loads")
}

/// A projected tile of 30 m square cells.
fn projected_tile() -> Heightfield {
    load_bytes(
        &dem_bytes(30.0, [500_000.0, 4_600_000.0], 1),
        1.0,
        "utm.tif",
    )
    .expect("loads")
}

/// Looking straight down from 12 units above the flat surface at the map's centre, with a 90
/// degree field of view: the 64 pixel centres of a row see world offsets
/// `12 * (2 (p + 0.5) / 64 - 1)` from the centre.
const PIXELS: u32 = 64;
const DISTANCE: f64 = 12.0;

/// Which pixels of the middle row and column see the map, rendered at true scale.
fn footprint(field: Heightfield) -> (usize, usize) {
    let z_scale = relief::default_z_scale(&field);
    let terrain = Terrain::new(field.with_z_scale(z_scale).unwrap());
    let ground = terrain.field().z(8, 8);
    let centre = terrain.world_point([8.0, 8.0, ground]);
    let eye = [centre[0], centre[1], ground + DISTANCE];
    let camera = Camera::look_at(eye, centre, [0.0, 1.0, 0.0], 90.0, (PIXELS, PIXELS)).unwrap();
    let lighting = overhead_light(Ramp::Gray);
    let renderer = Renderer {
        shader: Shader::new(&terrain, lighting, Method::Mipmap, Culling::default()),
        camera: camera.in_grid(terrain.world_from_grid()),
        arith: Arith::F64,
    };
    let mut frame = Frame::new(PIXELS, PIXELS);
    renderer.render(&mut frame);
    let middle = PIXELS / 2;
    let ground_colour = frame.pixels[(middle * PIXELS + middle) as usize];
    let on_map = |x: u32, y: u32| frame.pixels[(y * PIXELS + x) as usize] == ground_colour;
    let columns = (0..PIXELS).filter(|&x| on_map(x, middle)).count();
    let rows = (0..PIXELS).filter(|&y| on_map(middle, y)).count();
    (columns, rows)
}

/// Pixel centres of a row within `half_extent` world units of the centre.
fn pixels_within(half_extent: f64) -> usize {
    (0..PIXELS)
        .map(|p| DISTANCE * (2.0 * (f64::from(p) + 0.5) / f64::from(PIXELS) - 1.0))
        .filter(|offset| offset.abs() <= half_extent)
        .count()
}

#[test]
fn a_geographic_tile_at_60_north_renders_cells_half_as_wide_as_high() {
    let field = tile_at_60_north();
    let [x, y] = field.cell_metres().unwrap();
    // On the WGS 84 ellipsoid: cos(60°) (1 - e^2 sin^2 60°) / (1 - e^2) = 0.50084.
    assert!((x / y - 0.50084).abs() < 1e-5, "{}", x / y);
    // World units are cells along y: the map is 16 high and 16 * 0.5 = 8 wide.
    let (columns, rows) = footprint(field);
    assert_eq!(rows, pixels_within(8.0));
    assert_eq!(columns, pixels_within(4.0));
    // By hand: offsets (p + 0.5) * 0.375 - 12 within 4 are p = 21 ..= 42, within 8 p = 11 ..= 52.
    assert_eq!((columns, rows), (22, 42));
}

#[test]
fn a_projected_tile_of_square_cells_renders_square() {
    let (columns, rows) = footprint(projected_tile());
    assert_eq!((columns, rows), (pixels_within(8.0), pixels_within(8.0)));
}

#[test]
fn a_georeferenced_map_is_at_true_scale_and_a_scene_may_exaggerate_it() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("utm.tif"), dem_bytes(30.0, [0.0, 0.0], 1)).unwrap();
    let scene = |heightmap: &str| {
        let text = format!(
            "[heightmap]\npath = {:?}\n{heightmap}\n[camera]\neye = [-5.0, -5.0, 20.0]\n\
             target = [8.0, 8.0, 3.0]\nwidth = 8\nheight = 8\n",
            dir.path().join("utm.tif")
        );
        load_scene_text("scene.toml", &text)
    };
    // 3 m of bump over 30 m cells: a tenth of a cell high at true scale.
    let true_scale = scene("").unwrap().field;
    let bump = |field: &Heightfield| field.z(0, 16) - field.z(1, 16);
    assert!((bump(&true_scale) - 0.1).abs() < 1e-12);
    let doubled = scene("exaggeration = 2.0").unwrap().field;
    assert!((bump(&doubled) - 0.2).abs() < 1e-12);
    assert_eq!(relief::exaggeration(&doubled), Some(2.0));
    // A z scale as written still wins.
    assert_eq!(scene("z_scale = 5.0").unwrap().field.z_scale(), 5.0);
    let both = scene("z_scale = 5.0\nexaggeration = 2.0").unwrap_err();
    assert!(both.contains("both z_scale and exaggeration"), "{both}");
}

#[test]
fn exaggeration_on_a_plain_image_is_refused_and_its_relief_stays_automatic() {
    let dir = tempfile::tempdir().unwrap();
    let image = image::GrayImage::from_fn(9, 5, |x, _| image::Luma([x as u8 * 10]));
    image.save(dir.path().join("plain.png")).unwrap();
    let scene = |heightmap: &str| {
        let text = format!(
            "[heightmap]\npath = {:?}\n{heightmap}\n[camera]\neye = [-5.0, -5.0, 20.0]\n\
             target = [4.0, 2.0, 0.0]\nwidth = 8\nheight = 8\n",
            dir.path().join("plain.png")
        );
        load_scene_text("scene.toml", &text)
    };
    let error = scene("exaggeration = 1.0").unwrap_err();
    assert!(error.contains("needs a georeferenced map"), "{error}");
    // A quarter of the larger side (9) for the largest value, 255.
    assert_eq!(scene("").unwrap().field.z_scale(), 9.0 / 4.0);
}
