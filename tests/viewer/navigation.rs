//! Moving about the map as a user does: the wheel, drags and keys never take the eye under the
//! surface nor the target below it, and R and F show the whole map whatever the view's shape.
//! The surface and the camera's projection are computed here, from the map's samples and the
//! pinhole model, not taken from the viewer.

use super::app::num;
use super::Session;
use serde_json::Value;
use std::thread::sleep;
use std::time::Duration;

const UP: u32 = 0xff52;
const DOWN: u32 = 0xff54;
const LEFT: u32 = 0xff51;
const RIGHT: u32 = 0xff53;
const PAGE_DOWN: u32 = 0xff56;

/// A height map as its image's samples (row by row from the top) with the height per sample
/// value. Image row `r` is the terrain's row `j = height - 1 - r` (y grows north).
struct Map {
    width: usize,
    height: usize,
    samples: Vec<u16>,
    unit: f64,
}

impl Map {
    fn z(&self, i: usize, j: usize) -> f64 {
        f64::from(self.samples[(self.height - 1 - j) * self.width + i]) * self.unit
    }

    fn lowest(&self) -> f64 {
        f64::from(*self.samples.iter().min().unwrap_or(&0)) * self.unit
    }

    /// The surface at `(x, y)`: the plane through the three corners of the cell's triangle
    /// that holds the point (cells split from corner (i, j) to (i+1, j+1)); off the map, the
    /// lowest height.
    fn surface(&self, x: f64, y: f64) -> f64 {
        let (w, h) = ((self.width - 1) as f64, (self.height - 1) as f64);
        if !(0.0..=w).contains(&x) || !(0.0..=h).contains(&y) {
            return self.lowest();
        }
        let (i, j) = (
            (x as usize).min(self.width - 2),
            (y as usize).min(self.height - 2),
        );
        let corner =
            |di: usize, dj: usize| [(i + di) as f64, (j + dj) as f64, self.z(i + di, j + dj)];
        let (a, c) = (corner(0, 0), corner(1, 1));
        let b = if x - i as f64 >= y - j as f64 {
            corner(1, 0)
        } else {
            corner(0, 1)
        };
        // The plane's normal n = (b - a) x (c - a); on the plane n.(p - a) = 0.
        let (u, v) = (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        a[2] - (n[0] * (x - a[0]) + n[1] * (y - a[1])) / n[2]
    }
}

/// A rough 65x65 map: a crater with a steep rim, a spire and a jagged ridge, so that zooming
/// and dragging meet steep ground everywhere. Written as a plain PGM (maxval 255).
fn write_rough_map(path: &std::path::Path) -> Vec<u16> {
    let n = 65;
    let mut samples = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64, j as f64);
            let crater = ((x - 22.0).hypot(y - 40.0) - 12.0).abs();
            let rim = 230.0 * (-crater * crater / 6.0).exp();
            let spire = 255.0 * (-((x - 48.0).hypot(y - 16.0)) / 2.5).exp();
            let ridge = if (i + 2 * j) % 7 < 2 && j < 30 {
                90.0
            } else {
                0.0
            };
            let bowl = if (x - 22.0).hypot(y - 40.0) < 10.0 {
                0.0
            } else {
                30.0
            };
            samples.push((rim + spire + ridge + bowl).min(255.0) as u16);
        }
    }
    let mut text = format!("P2\n{n} {n}\n255\n");
    for row in samples.chunks(n) {
        let row: Vec<String> = row.iter().map(u16::to_string).collect();
        text += &(row.join(" ") + "\n");
    }
    std::fs::write(path, text).expect("write the height map");
    samples
}

/// The eye from the reported orbit (target, yaw, pitch, distance), checked against the
/// reported eye.
fn eye(state: &Value) -> [f64; 3] {
    let (yaw, pitch) = (
        num(state, "/camera/yaw_deg").to_radians(),
        num(state, "/camera/pitch_deg").to_radians(),
    );
    let distance = num(state, "/camera/distance");
    let offset = [
        yaw.cos() * pitch.cos(),
        yaw.sin() * pitch.cos(),
        pitch.sin(),
    ];
    let eye: [f64; 3] =
        std::array::from_fn(|k| num(state, &format!("/camera/target/{k}")) + offset[k] * distance);
    for (k, value) in eye.iter().enumerate() {
        let reported = num(state, &format!("/camera/eye/{k}"));
        assert!(
            (reported - value).abs() <= 1e-9 * (1.0 + distance),
            "reported eye {reported} against {value}"
        );
    }
    eye
}

/// Fails unless the eye is above the surface under it and the target on or above the surface.
fn assert_above_ground(map: &Map, state: &Value, what: &str) {
    let [x, y, z] = eye(state);
    let ground = map.surface(x, y);
    assert!(
        z > ground && z > map.lowest(),
        "after {what}: the eye ({x:.3}, {y:.3}, {z:.4}) is not above the surface at {ground:.4}"
    );
    let target: [f64; 3] = std::array::from_fn(|k| num(state, &format!("/camera/target/{k}")));
    let under_target = map.surface(target[0], target[1]);
    assert!(
        target[2] >= under_target - 1e-9,
        "after {what}: the target {target:?} is below the surface at {under_target:.4}"
    );
}

/// A small deterministic generator (xorshift), so a failure can be replayed.
struct Dice(u64);

impl Dice {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A number in `lo..hi`.
    fn within(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() % 10_000) as f64 / 10_000.0
    }
}

/// Waits until the viewer has drawn a frame since `state`, so the input has been handled.
fn after_input(session: &mut Session, state: &Value) -> Value {
    sleep(Duration::from_millis(60));
    let frames = num(state, "/frames_presented");
    session.viewer.wait_for("a frame after the input", |s| {
        num(s, "/frames_presented") > frames
    })
}

#[test]
fn wheel_drags_and_keys_never_put_the_eye_under_the_surface() {
    let maps = tempfile::tempdir().expect("a temporary directory");
    let path = maps.path().join("rough.pgm");
    let samples = write_rough_map(&path);
    let path_text = path.display().to_string();
    let mut session = Session::start(&["--size", "900x600", &path_text]);
    let mut state = session.state();
    // A plain image's heights: its z scale for the largest sample value 255.
    let map = Map {
        width: 65,
        height: 65,
        samples,
        unit: num(&state, "/terrain/z_scale") / 255.0,
    };
    assert_above_ground(&map, &state, "the start");
    session.x.focus(session.window);
    let (x0, y0, x1, y1) = session.view(&state);
    let mut dice = Dice(0x5eed_1234_abcd_0042);
    let keys = [UP, DOWN, LEFT, RIGHT, PAGE_DOWN, 'q' as u32, '=' as u32];
    for step in 0..48 {
        let at = (
            dice.within(x0 as f64 + 20.0, x1 as f64 - 20.0),
            dice.within(y0 as f64 + 20.0, y1 as f64 - 20.0),
        );
        let what = match dice.next() % 5 {
            // Mostly zooming in, several notches at once, where the pointer is.
            0 | 1 => {
                session.x.move_to(session.screen(at));
                sleep(Duration::from_millis(40));
                let (button, notches) = if dice.next().is_multiple_of(4) {
                    (5, 2)
                } else {
                    (4, 6)
                };
                for _ in 0..notches {
                    session.x.press(button);
                    session.x.release(button);
                    sleep(Duration::from_millis(15));
                }
                format!("{notches} wheel notches (button {button}) at {at:?}")
            }
            // Orbit drags, mostly upwards: they lower the eye.
            2 => {
                let to = (
                    at.0 + dice.within(-150.0, 150.0),
                    at.1 - dice.within(-40.0, 300.0),
                );
                session
                    .x
                    .drag(session.screen(at), session.screen(to), 1, 12);
                format!("an orbit drag from {at:?} to {to:?}")
            }
            // Pans, in any direction.
            3 => {
                let to = (
                    at.0 + dice.within(-300.0, 300.0),
                    at.1 + dice.within(-300.0, 300.0),
                );
                session
                    .x
                    .drag(session.screen(at), session.screen(to), 3, 12);
                format!("a pan from {at:?} to {to:?}")
            }
            _ => {
                let key = keys[(dice.next() % keys.len() as u64) as usize];
                for _ in 0..3 {
                    session.x.key(key);
                }
                format!("three presses of key {key:#x}")
            }
        };
        state = after_input(&mut session, &state);
        assert_above_ground(&map, &state, &format!("step {step}, {what}"));
    }
    let converged = num(&state, "/converged_frames") as u64;
    let state = session.viewer.wait_converged(converged.saturating_sub(1));
    assert_above_ground(&map, &state, "the last frame");
}

/// Points in the reported camera's image, as fractions of the half width and height from
/// the image's centre (inside: both within -1 and 1), from the eye, target, vertical field of
/// view and the rendered frame's size.
fn on_screen(state: &Value, points: &[[f64; 3]]) -> Vec<(f64, f64)> {
    let v = |p: &str| -> [f64; 3] { std::array::from_fn(|k| num(state, &format!("{p}/{k}"))) };
    let (eye, target) = (v("/camera/eye"), v("/camera/target"));
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let unit = |a: [f64; 3]| {
        let l = dot(a, a).sqrt();
        [a[0] / l, a[1] / l, a[2] / l]
    };
    let forward = unit(sub(target, eye));
    // right = forward x z, up = right x forward.
    let right = unit([forward[1], -forward[0], 0.0]);
    let up = [
        right[1] * forward[2] - right[2] * forward[1],
        right[2] * forward[0] - right[0] * forward[2],
        right[0] * forward[1] - right[1] * forward[0],
    ];
    let h = (num(state, "/camera/fov_y_deg").to_radians() / 2.0).tan();
    let aspect = num(state, "/frame/width") / num(state, "/frame/height");
    points
        .iter()
        .map(|&p| {
            let q = sub(p, eye);
            let depth = dot(q, forward);
            assert!(depth > 0.0, "{p:?} is behind the eye");
            (dot(q, right) / depth / (h * aspect), dot(q, up) / depth / h)
        })
        .collect()
}

/// Fails unless every sample of the map (its corners among them) is inside the image, and the
/// map fills a fair part of it.
fn assert_framed(state: &Value, samples: &[[f64; 3]], what: &str) {
    assert_eq!(
        state["camera"]["framed"], true,
        "{what}: not the framed view"
    );
    let projected = on_screen(state, samples);
    let outside = projected
        .iter()
        .zip(samples)
        .find(|((x, y), _)| x.abs() >= 1.0 || y.abs() >= 1.0);
    assert!(
        outside.is_none(),
        "{what}: a sample outside the view: {outside:?}"
    );
    let widest = projected
        .iter()
        .map(|(x, y)| x.abs().max(y.abs()))
        .fold(0.0, f64::max);
    assert!(
        widest > 0.85,
        "{what}: the map is small in the view ({widest:.2})"
    );
}

/// Every sample of the built-in valley as a point, at the z scale the viewer reports.
fn valley_samples(state: &Value) -> Vec<[f64; 3]> {
    let field = heightray::heightfield::Builtin::named("valley513")
        .expect("the built-in valley")
        .load_scaled(num(state, "/terrain/z_scale"))
        .expect("the built-in valley decodes");
    let (w, h) = (field.width(), field.height());
    (0..h)
        .flat_map(|j| (0..w).map(move |i| (i, j)))
        .map(|(i, j)| [i as f64, j as f64, field.z(i, j)])
        .collect()
}

/// Waits for a fully refined frame of a framed view of the current camera.
fn framed_frame(session: &mut Session, what: &str) -> Value {
    sleep(Duration::from_millis(100));
    session.viewer.wait_for(what, |s| {
        s["camera"]["framed"] == true && s["rendering"] == false && s["frame"]["complete"] == true
    })
}

#[test]
fn r_and_f_frame_the_whole_map_at_any_window_shape() {
    let mut session = Session::start(&["--size", "800x500"]);
    let start = session.state();
    let range = valley_samples(&start);
    assert_framed(&start, &range, "the default view at 800x500");

    // Lost somewhere: turned, zoomed in and panned.
    let (cx, cy) = session.view_centre(&start);
    session.x.drag(
        session.screen((cx, cy)),
        session.screen((cx + 120.0, cy - 60.0)),
        1,
        10,
    );
    session.x.move_to(session.screen((cx - 50.0, cy + 40.0)));
    sleep(Duration::from_millis(40));
    for _ in 0..8 {
        session.x.press(4);
        session.x.release(4);
    }
    session.x.drag(
        session.screen((cx, cy)),
        session.screen((cx - 100.0, cy + 30.0)),
        3,
        10,
    );
    let moved = session
        .viewer
        .wait_for("the camera to move", |s| s["camera"]["framed"] == false);
    session.x.focus(session.window);
    session.x.key('r' as u32);
    let reset = framed_frame(&mut session, "R to frame the map");
    assert_framed(&reset, &range, "R at 800x500");
    assert_eq!(reset["camera"]["yaw_deg"], start["camera"]["yaw_deg"]);

    // Hiding the panels widens the view: the untouched framed view follows.
    session.x.key('h' as u32);
    let wide = session.viewer.wait_for("the view to fill the window", |s| {
        s["panels_visible"] == false && num(s, "/view_rect/2") == num(s, "/window_size/0")
    });
    let aspect = |s: &Value| num(s, "/frame/width") / num(s, "/frame/height");
    let wide = session.viewer.wait_for("a frame of the wide view", |s| {
        s["frame"]["complete"] == true
            && s["rendering"] == false
            && (aspect(s) - num(&wide, "/view_rect/2") / num(&wide, "/view_rect/3")).abs() < 0.01
    });
    assert_framed(&wide, &range, "R, then the panels hidden");
    assert!(aspect(&wide) > aspect(&reset) + 0.2);

    // F frames from the direction the camera looks now.
    let (cx, cy) = session.view_centre(&wide);
    session.x.drag(
        session.screen((cx, cy)),
        session.screen((cx + 200.0, cy)),
        1,
        10,
    );
    session.viewer.wait_for("the drag to turn the camera", |s| {
        s["camera"]["framed"] == false && s["camera"]["yaw_deg"] != wide["camera"]["yaw_deg"]
    });
    // (The drag's last moves may still be on their way.)
    sleep(Duration::from_millis(400));
    let turned = session.state();
    session.x.key('f' as u32);
    let framed = framed_frame(&mut session, "F to frame the map");
    assert_framed(&framed, &range, "F after turning");
    assert_eq!(framed["camera"]["yaw_deg"], turned["camera"]["yaw_deg"]);
    assert_ne!(moved["camera"], framed["camera"]);
}
