//! Contour lines on map products seen straight down: on a plane `z = a x + b y` every label
//! sits where the plane has the height it reads, only index lines carry labels, labels never
//! overlap each other or the image's edge (on the plane and on the real DEM in `assets/`),
//! ink falls only near the analytic lines; the command line draws them on pictures and
//! refuses to draw them into values.

use heightray::heightfield::load;
use heightray::products::{Label, MapContours, MapStyle, OrthoGrid, Rgba16};
use heightray::render::Contours;
use heightray::Heightfield;
use std::path::Path;
use std::process::Command;

/// The plane's slope along x and y, grid height per sample.
const SLOPE: [f64; 2] = [1.0, 2.0];
/// Its size in samples.
const PLANE: (usize, usize) = (400, 300);

/// The plane `z = x + 2 y` (samples are heights: maxval and scale cancel).
fn plane() -> Heightfield {
    let (w, h) = PLANE;
    Heightfield::from_fn(w, h, 1000, 1000.0, |i, j| {
        (SLOPE[0] * i as f64 + SLOPE[1] * j as f64) as u16
    })
    .unwrap()
}

/// Lines every 20, index lines every 100, drawn over white, with their labels.
fn drawn(field: &Heightfield) -> (OrthoGrid, Vec<Rgba16>, Vec<Label>) {
    let grid = OrthoGrid::over(field, None).unwrap();
    let contours = MapContours::new(&Contours::new(20.0, 5).unwrap(), field);
    let mut pixels = vec![[u16::MAX; 4]; grid.pixels()];
    let labels = contours.draw(field, &grid, &mut pixels).unwrap();
    (grid, pixels, labels)
}

/// Grid coordinates of a point of the image, pixels from its top-left corner.
fn grid_point(grid: &OrthoGrid, [x, y]: [f64; 2]) -> [f64; 2] {
    grid.point(0, 0, (x, y))
}

fn assert_apart_and_inside(labels: &[Label], grid: &OrthoGrid) {
    for (n, label) in labels.iter().enumerate() {
        let [x0, y0, x1, y1] = label.bounds();
        assert!(
            x0 >= 0.0 && y0 >= 0.0 && x1 <= f64::from(grid.width) && y1 <= f64::from(grid.height),
            "{label:?} leaves the {}x{} image",
            grid.width,
            grid.height
        );
        for other in &labels[n + 1..] {
            let [a0, b0, a1, b1] = other.bounds();
            let apart = x1 <= a0 || a1 <= x0 || y1 <= b0 || b1 <= y0;
            assert!(apart, "{label:?} overlaps {other:?}");
        }
    }
}

#[test]
fn labels_on_a_plane_read_its_height_where_they_sit() {
    let field = plane();
    let (grid, _, labels) = drawn(&field);
    let style = MapStyle::of(&grid);
    let gradient = SLOPE[0].hypot(SLOPE[1]);
    assert!(labels.len() >= 6, "{} labels", labels.len());
    for label in &labels {
        let [x, y] = grid_point(&grid, label.at);
        let height = SLOPE[0] * x + SLOPE[1] * y;
        // Within half an index line's width (two ordinary lines) of the line it names.
        let off_px = (height - label.value).abs() / gradient;
        assert!(off_px <= style.line_px, "{label:?} sits at height {height}");
        assert_eq!(label.text, format!("{}", label.value));
        assert_eq!(
            label.value % 100.0,
            0.0,
            "a minor line is labelled: {label:?}"
        );
    }
    // Every index line crossing the image (100 to 900; 0 and 1000 lie outside it) is
    // labelled; lines 45 pixels apart leave room for them all.
    let mut named: Vec<i64> = labels.iter().map(|l| l.value as i64).collect();
    named.dedup();
    named.sort_unstable();
    named.dedup();
    assert_eq!(named, (1..=9).map(|k| k * 100).collect::<Vec<_>>());
    assert_apart_and_inside(&labels, &grid);
}

#[test]
fn ink_falls_only_near_the_planes_levels() {
    let field = plane();
    let (grid, pixels, labels) = drawn(&field);
    let style = MapStyle::of(&grid);
    let gradient = SLOPE[0].hypot(SLOPE[1]);
    let (mut inked_on_index, mut index_pixels) = (0, 0);
    for row in 0..grid.height {
        for column in 0..grid.width {
            let centre = [f64::from(column) + 0.5, f64::from(row) + 0.5];
            let near_label = labels.iter().any(|l| {
                let [x0, y0, x1, y1] = l.bounds();
                centre[0] >= x0 - 2.0
                    && centre[0] <= x1 + 2.0
                    && centre[1] >= y0 - 2.0
                    && centre[1] <= y1 + 2.0
            });
            let [x, y] = grid_point(&grid, centre);
            let height = SLOPE[0] * x + SLOPE[1] * y;
            let nearest = (height / 20.0).round() * 20.0;
            let off_px = (height - nearest).abs() / gradient;
            let pixel = pixels[(row * grid.width + column) as usize];
            let white = pixel == [u16::MAX; 4];
            if off_px > style.line_px + 1.5 && !near_label {
                assert!(
                    white,
                    "ink at ({column}, {row}), {off_px:.2} px from a line"
                );
            }
            let index = (nearest / 100.0).fract() == 0.0;
            // (The outer half pixels lie beyond the samples, where lines end.)
            let within = column > 0 && row > 0 && column + 1 < grid.width && row + 1 < grid.height;
            if index && off_px < 0.25 && !near_label && within {
                index_pixels += 1;
                // An index line covers most of the white beneath it.
                inked_on_index += usize::from(pixel[0] < 40_000);
            }
        }
    }
    assert!(index_pixels > 500, "{index_pixels}");
    assert_eq!(inked_on_index, index_pixels);
}

#[test]
fn labels_on_a_real_dem_never_overlap_or_leave_the_image() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/jacksboro.tif");
    let field = load(&path, 1.0).unwrap();
    for cell in [None, Some(0.0004)] {
        let grid = OrthoGrid::over(&field, cell).unwrap();
        let contours = MapContours::new(&Contours::new(50.0, 5).unwrap(), &field);
        let mut pixels = vec![[u16::MAX; 4]; grid.pixels()];
        let labels = contours.draw(&field, &grid, &mut pixels).unwrap();
        assert!(labels.len() >= 3, "{cell:?}: {} labels", labels.len());
        assert!(labels.iter().all(|l| l.value % 250.0 == 0.0), "{labels:?}");
        assert_apart_and_inside(&labels, &grid);
    }
}

/// `heightray render ARGS`: whether it succeeded, and its error output.
fn render(args: &[&str]) -> (bool, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .arg("render")
        .args(args)
        .output()
        .expect("run heightray render");
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    (output.status.success(), stderr)
}

#[test]
fn the_command_line_draws_contours_on_pictures_not_into_values() {
    let dir = tempfile::tempdir().unwrap();
    let dem = dir.path().join("plane.png");
    let (w, h) = (64u32, 48u32);
    let image = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(w, h, |x, y| {
        image::Luma([(x * 600 + (h - 1 - y) * 500) as u16])
    });
    image.save(&dem).unwrap();
    let d = dem.to_str().unwrap();
    let out = |name: &str| dir.path().join(name).to_str().unwrap().to_owned();
    let (plain, lined) = (out("plain.tif"), out("lined.tif"));
    assert!(render(&[d, "--ortho", "-o", &plain]).0);
    let (ok, stderr) = render(&[d, "--ortho", "--contours", "1", "-o", &lined]);
    assert!(ok, "{stderr}");
    let read = |p: &str| image::open(p).unwrap().to_rgba16().into_raw();
    let changed = read(&plain)
        .iter()
        .zip(read(&lined))
        .filter(|(a, b)| **a != *b)
        .count();
    assert!(changed > 100, "{changed} channels changed by the lines");
    // Values are not pictures: refused, with the way to a picture; their PNG takes lines.
    let sky_view = |out: &str| {
        render(&[
            d,
            "--ortho",
            "--product",
            "sky-view",
            "--contours",
            "1",
            "-o",
            out,
        ])
    };
    let values = out("svf.tif");
    let (ok, stderr) = sky_view(&values);
    assert!(!ok && stderr.contains(".png"), "{stderr}");
    assert!(!Path::new(&values).exists());
    let (ok, stderr) = sky_view(&out("svf.png"));
    assert!(ok, "{stderr}");
    assert!(!render(&[d, "--ortho", "--contours", "0", "-o", &lined]).0);
}
