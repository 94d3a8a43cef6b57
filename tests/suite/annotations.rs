//! Annotations against hand-worked camera geometry, contour lines against a plane's analytic
//! lines, and place labels against the exact brute-force reference's sight lines.

use crate::common::reference;
use crate::common::top_down::overhead_light;
use heightray::render::annotate::{
    north_angle_deg, Annotations, Coordinates, Place, ScaleBar, Sheet, Sight, VectorLayer,
    VectorSection,
};
use heightray::render::{Camera, Contours, Culling, Frame, Ramp, Renderer, Shader};
use heightray::{Arith, Heightfield, Method, Ray, Terrain};

/// A camera 500 units from its target with a 90° field of view, 1000x500 pixels: at the
/// target's depth a pixel spans `2 * 500 * tan(45°) / 500 = 2` units. With 30 m units that is
/// 60 m a pixel; the bar may take 22% of 1000 pixels, 13.2 km, so it is the round 10 km,
/// `10000 / 60` pixels long.
#[test]
fn scale_bar_is_the_round_length_at_the_targets_depth() {
    let camera = Camera::look_at(
        [0.0, -300.0, 400.0],
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        90.0,
        (1000, 500),
    )
    .unwrap();
    let bar = ScaleBar::at_target(&camera, Some(30.0)).unwrap();
    assert_eq!(bar.label, "10 km");
    assert!((bar.pixels - 10_000.0 / 60.0).abs() < 1e-9, "{bar:?}");
    // Two points at the target, the bar's ground length apart across the view, project that
    // far apart.
    let half = 0.5 * 10_000.0 / 30.0;
    let [a, b] = [-half, half].map(|x| camera.project([x, 0.0, 0.0]).unwrap());
    assert!(((b[0] - a[0]) - bar.pixels).abs() < 1e-9, "{a:?} {b:?}");
    assert!((a[1] - 250.0).abs() < 1e-9 && (b[1] - 250.0).abs() < 1e-9);
    // A plain image is measured in cells: 2 units a pixel, at most 440, so 200 cells.
    let cells = ScaleBar::at_target(&camera, None).unwrap();
    assert_eq!(cells.label, "200 cells");
    assert!((cells.pixels - 100.0).abs() < 1e-9, "{cells:?}");
}

/// An orbit at yaw `φ` (the eye's bearing from the target, from +x towards +y) and pitch `p`
/// looks along `-(cos φ, sin φ)` on the ground. At the target (the image's centre) the image's
/// right is `(-sin φ, cos φ)` and its up is the ground's far direction foreshortened by
/// `sin p`: north `(0, 1)` shows `cos φ` to the right and `-sin φ sin p` up.
#[test]
fn north_arrow_points_to_grid_north_in_a_rotated_view() {
    for (yaw, pitch, expected) in [
        (-90.0, 35.0, 0.0),                    // from the south: north is up
        (0.0, 35.0, 90.0),                     // from the east, looking west: right
        (90.0, 35.0, 180.0),                   // from the north: down
        (30.0, 40.0, hand_worked(30.0, 40.0)), // 110.36°
    ] {
        let camera = Camera::orbit([10.0, 20.0, 5.0], yaw, pitch, 300.0, 50.0, (800, 600)).unwrap();
        let angle = north_angle_deg(&camera).unwrap();
        let difference = (angle - expected + 540.0).rem_euclid(360.0) - 180.0;
        assert!(
            difference.abs() < 1e-3,
            "yaw {yaw}: {angle} against {expected}"
        );
    }
    assert!((hand_worked(30.0, 40.0) - 110.3606).abs() < 1e-3);
}

fn hand_worked(yaw_deg: f64, pitch_deg: f64) -> f64 {
    let (yaw, pitch) = (yaw_deg.to_radians(), pitch_deg.to_radians());
    yaw.cos().atan2(-yaw.sin() * pitch.sin()).to_degrees()
}

/// The plane `z = x` (33x33 samples), seen from above: its contour lines every 6 units are
/// the columns `x = 6k`. A pixel whose hit lies within half a pixel of one (by the plane's
/// analytic hit and the height's analytic change from pixel to pixel) is darkened; one more
/// than 1.2 pixels from every line keeps the colour it has without contours.
#[test]
fn contour_lines_lie_on_the_planes_analytic_lines() {
    let field = Heightfield::from_fn(33, 33, 32, 32.0, |x, _| x as u16).unwrap();
    let terrain = Terrain::new(field);
    let camera = Camera::look_at(
        [16.0, 16.0, 40.0],
        [16.0, 16.0, 16.0],
        [0.0, 1.0, 0.0],
        60.0,
        (64, 64),
    )
    .unwrap();
    let render = |contours: Option<Contours>| {
        let mut shader = Shader::new(
            &terrain,
            overhead_light(Ramp::Gray),
            Method::Mipmap,
            Culling::default(),
        );
        shader.contours = contours.map(|c| c.seen_by(&camera));
        let renderer = Renderer {
            shader,
            camera,
            arith: Arith::F64,
        };
        let mut frame = Frame::new(64, 64);
        renderer.render(&mut frame);
        frame.pixels
    };
    let (plain, lined) = (render(None), render(Contours::new(6.0, 0)));
    // Where the ray through image point (x, y) meets z = x.
    let hit = |x: f64, y: f64| {
        let ray = camera.ray_at(x, y);
        let (o, d) = (ray.origin(), ray.dir());
        let t = (o[0] - o[2]) / (d[2] - d[0]);
        [0, 1, 2].map(|k| o[k] + t * d[k])
    };
    let hit_z = |x: f64, y: f64| hit(x, y)[2];
    let (mut on, mut off) = (0, 0);
    for py in 0..64 {
        for px in 0..64 {
            let (x, y) = (px as f64 + 0.5, py as f64 + 0.5);
            let z = hit_z(x, y);
            let across = hit_z(x + 0.5, y) - hit_z(x - 0.5, y);
            let down = hit_z(x, y + 0.5) - hit_z(x, y - 0.5);
            let per_pixel = across.hypot(down);
            let distance = (z - 6.0 * (z / 6.0).round()).abs() / per_pixel;
            let k = py * 64 + px;
            // (Pixels near the map's edges or beyond it are left out.)
            if !hit(x, y).iter().all(|c| (0.5..=31.5).contains(c)) {
                continue;
            }
            if distance < 0.5 {
                assert_ne!(
                    lined[k], plain[k],
                    "pixel ({px}, {py}) at z = {z} is on a line"
                );
                on += 1;
            } else if distance > 1.2 {
                assert_eq!(
                    lined[k], plain[k],
                    "pixel ({px}, {py}) at z = {z} is off lines"
                );
                off += 1;
            }
        }
    }
    assert!(
        on > 200 && off > 1000,
        "{on} pixels on lines, {off} off them"
    );
}

/// A flat 17x21 field with a ridge 10 high along `y = 10`, and an eye south of it.
fn ridge() -> Terrain {
    let field = Heightfield::from_fn(17, 21, 10, 10.0, |_, y| if y == 10 { 10 } else { 0 });
    Terrain::new(field.unwrap())
}

const EYE: [f64; 3] = [8.0, -5.0, 13.0];

/// Whether the exact brute-force reference sees `point` from `eye`: the segment from the eye
/// to it touches no triangle before the point (at `t <= 1`).
fn reference_sees(terrain: &Terrain, eye: [f64; 3], point: [f64; 3]) -> bool {
    let dir: [f64; 3] = std::array::from_fn(|k| point[k] - eye[k]);
    let ray = Ray::new(eye, dir).unwrap();
    let answer = reference::solve(terrain.field(), &ray);
    // (`Ray::new` may rescale the direction by a power of two: `t` is along the ray's own.)
    let scale = dir[1] / ray.dir()[1];
    answer.hit.is_none_or(|hit| hit.t > reference::q(scale))
}

#[test]
fn a_place_behind_a_ridge_is_hidden_and_one_in_front_shows() {
    let terrain = ridge();
    for arith in [Arith::F64, Arith::Exact] {
        let sight = Sight {
            terrain: &terrain,
            eye: EYE,
            method: Method::Mipmap,
            arith,
        };
        let front = [8.0, 5.0, 1.0];
        let behind = [8.0, 15.0, 1.0];
        assert!(sight.sees(front), "{arith}");
        assert!(!sight.sees(behind), "{arith}");
        assert!(reference_sees(&terrain, EYE, front) && !reference_sees(&terrain, EYE, behind));
        // The same places as labels drawn over a picture from that eye.
        let camera = Camera::look_at(EYE, [8.0, 10.0, 5.0], [0.0, 0.0, 1.0], 70.0, (96, 64));
        let sheet = Sheet {
            terrain: &terrain,
            camera: camera.unwrap(),
            ramp: Ramp::Terrain,
            method: Method::Mipmap,
            arith,
        };
        let place = |name: &str, at: [f64; 2]| Place {
            name: name.into(),
            at,
            priority: 0.0,
        };
        let annotations = Annotations {
            vectors: vec![VectorLayer {
                places: vec![
                    place("Meadow", [8.0, 5.0]),
                    place("Hidden lake", [8.0, 15.0]),
                ],
                lines: Vec::new(),
                colour: [255, 0, 0],
                lift: 1.0,
                section: VectorSection {
                    path: "places.geojson".into(),
                    coordinates: Coordinates::Grid,
                    colour: None,
                    lift: Some(1.0),
                },
            }],
            ..Annotations::default()
        };
        for at in [[8.0, 5.0, 1.0], [8.0, 15.0, 1.0]] {
            assert!(
                sheet.on_image(at).is_some(),
                "{at:?} lies outside the picture"
            );
        }
        let svg = annotations.svg(&sheet);
        assert!(
            svg.contains(">Meadow<") && !svg.contains("Hidden lake"),
            "{svg}"
        );
    }
}

/// The segment from the eye to `(8, 15, 9)` grazes the ridge's top edge at `(8, 10, 10)`:
/// touching counts, so the place is hidden; a point a rounding higher shows, and one lower is
/// hidden. Exact sight decides each as the brute-force reference does.
#[test]
fn a_place_exactly_on_the_silhouette_is_decided_as_the_exact_ray_decides() {
    let terrain = ridge();
    let sight = Sight {
        terrain: &terrain,
        eye: EYE,
        method: Method::Mipmap,
        arith: Arith::Exact,
    };
    let grazing = [8.0, 15.0, 9.0];
    let above = [8.0, 15.0, 9f64.next_up()];
    let below = [8.0, 15.0, 9f64.next_down()];
    assert!(!reference_sees(&terrain, EYE, grazing));
    assert!(reference_sees(&terrain, EYE, above));
    assert!(!reference_sees(&terrain, EYE, below));
    for point in [grazing, above, below] {
        assert_eq!(
            sight.sees(point),
            reference_sees(&terrain, EYE, point),
            "{point:?}"
        );
    }
    // Off the ridge's line of symmetry too: a grazing point at an inexact fraction of a cell.
    for x in [3.3, 8.7, 12.1] {
        let point = [x, 15.0, 9.0];
        let eye_line = [x, EYE[1], EYE[2]];
        let sight = Sight {
            eye: eye_line,
            ..sight
        };
        assert_eq!(
            sight.sees(point),
            reference_sees(&terrain, eye_line, point),
            "x = {x}"
        );
    }
}
