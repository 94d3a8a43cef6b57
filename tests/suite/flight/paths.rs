//! Camera paths against hand-worked positions: keys passed at their times, two keys a straight
//! line at constant speed, an orbit's eye on its circle, a tangent that turns smoothly at a key,
//! and an eye kept above the surface where the keys dip below it.

use glam::DVec3;
use heightray::render::animation::{Animation, AnimationSection};
use heightray::render::framing::{self, EYE_CLEARANCE};
use heightray::render::{Orbit, Scene, SceneFile};
use heightray::{Heightfield, Terrain};

/// The `[animation]` section of `text`.
fn section(text: &str) -> AnimationSection {
    toml::from_str(text).expect("an [animation] section")
}

/// Keys at `times` through eyes `eyes`, all looking at one far point.
fn keyed(times: &[f64], eyes: &[[f64; 3]]) -> Animation {
    let mut text = String::from("fps = 10\n");
    for (t, e) in times.iter().zip(eyes) {
        text += &format!(
            "[[key]]\ntime_s = {t}\neye = [{}, {}, {}]\ntarget = [500.0, 500.0, 0.0]\n",
            e[0], e[1], e[2]
        );
    }
    Animation::new(&section(&text), None, 45.0, [0.0, 0.0, 1.0], None).expect("a valid path")
}

#[test]
fn keys_are_passed_at_their_times_and_two_keys_make_a_straight_line() {
    let eyes = [
        [0.0, 0.0, 50.0],
        [30.0, 5.0, 40.0],
        [35.0, 40.0, 45.0],
        [0.0, 60.0, 70.0],
    ];
    let path = keyed(&[0.0, 1.0, 3.5, 4.0], &eyes);
    for (t, eye) in [0.0, 1.0, 3.5, 4.0].iter().zip(eyes) {
        let at = path.view_at(*t).eye;
        assert!((at - DVec3::from(eye)).length() < 1e-9, "{t}: {at}");
    }
    // 4 s at 10 fps: frames 0 to 40.
    assert_eq!(path.frames(), 41);
    // Two keys: the ends reflected make four evenly spaced collinear points, so the centripetal
    // knots are evenly spaced and the segment is the straight line at constant speed.
    let line = keyed(&[1.0, 3.0], &[[0.0, 0.0, 10.0], [8.0, -4.0, 2.0]]);
    for (t, expected) in [
        (1.5, [2.0, -1.0, 8.0]),
        (2.0, [4.0, -2.0, 6.0]),
        (2.75, [7.0, -3.5, 3.0]),
    ] {
        let at = line.view_at(t).eye;
        assert!((at - DVec3::from(expected)).length() < 1e-9, "{t}: {at}");
    }
    // Before the first key the camera waits at it.
    assert_eq!(line.view_at(0.0).eye, DVec3::new(0.0, 0.0, 10.0));
}

#[test]
fn the_tangent_turns_smoothly_through_a_key() {
    // A square's corners: at the second, the path turns from +x towards +y.
    let path = keyed(
        &[0.0, 1.0, 2.0, 3.0],
        &[
            [0.0, 0.0, 20.0],
            [10.0, 0.0, 20.0],
            [10.0, 10.0, 20.0],
            [0.0, 10.0, 20.0],
        ],
    );
    let h = 1e-6;
    let before = (path.view_at(1.0).eye - path.view_at(1.0 - h).eye).normalize();
    let after = (path.view_at(1.0 + h).eye - path.view_at(1.0).eye).normalize();
    assert!(before.dot(after) > 1.0 - 1e-6, "{before} then {after}");
    // It cuts the corner: heading between +x and +y, not along either side.
    assert!(before.x > 0.1 && before.y > 0.1, "{before}");
    // And it bulges outside the square beyond the corner, as a smooth curve through it must.
    assert!(path.view_at(1.5).eye.x > 10.0);
}

#[test]
fn an_orbit_turns_at_its_rate_on_its_circle() {
    let orbit = Orbit {
        target: [10.0, 20.0, 5.0],
        yaw_deg: 30.0,
        pitch_deg: 20.0,
        distance: 100.0,
    };
    let path = Animation::new(
        &section("fps = 24\norbit_deg_per_s = 15\n"),
        Some(orbit),
        50.0,
        [0.0, 0.0, 1.0],
        None,
    )
    .expect("a valid orbit");
    // One whole turn by default: 24 s, frames 0 to 576.
    assert_eq!(path.frames(), 577);
    let view = path.view_at(2.0);
    let (yaw, pitch) = (60f64.to_radians(), 20f64.to_radians());
    let expected = DVec3::new(
        10.0 + 100.0 * yaw.cos() * pitch.cos(),
        20.0 + 100.0 * yaw.sin() * pitch.cos(),
        5.0 + 100.0 * pitch.sin(),
    );
    assert!((view.eye - expected).length() < 1e-9, "{}", view.eye);
    assert_eq!(view.target, DVec3::new(10.0, 20.0, 5.0));
    assert_eq!(view.fov_y_deg, 50.0);
}

#[test]
fn the_eye_stays_above_a_surface_the_keys_dip_under() {
    // A flat map 20 high (sample 200 of 255 at z scale 25.5).
    let field = Heightfield::from_fn(9, 9, 255, 25.5, |_, _| 200).expect("a flat map");
    let terrain = Terrain::new(field);
    let floor = 20.0 + EYE_CLEARANCE * framing::scale(&terrain);
    let path = keyed(
        &[0.0, 1.0, 2.0],
        &[[1.0, 1.0, 40.0], [4.0, 4.0, -30.0], [7.0, 7.0, 40.0]],
    );
    let mut lifted = 0;
    for frame in 0..path.frames() {
        let eye = path
            .camera(frame, &terrain, (8, 6))
            .expect("a camera")
            .eye();
        let wanted = path.view_at(frame as f64 / 10.0).eye;
        assert!(eye[2] >= floor - 1e-9, "frame {frame}: {eye:?}");
        if wanted.z >= floor {
            assert_eq!(eye, <[f64; 3]>::from(wanted), "frame {frame}");
        } else {
            assert_eq!([eye[0], eye[1]], [wanted.x, wanted.y], "frame {frame}");
            lifted += 1;
        }
    }
    assert!(lifted >= 5, "only {lifted} frames dipped");
}

#[test]
fn bad_paths_are_refused_naming_the_key() {
    let scene = |animation: &str| {
        let text = format!(
            "[heightmap]\npath = \"builtin:small49\"\n[camera]\neye = [0.0, 0.0, 30.0]\n\
             target = [24.0, 24.0, 0.0]\nwidth = 8\nheight = 8\n[animation]\n{animation}"
        );
        let file: Result<SceneFile, _> = toml::from_str(&text);
        match file {
            Err(e) => e.to_string(),
            Ok(file) => Scene::from_file(
                &file,
                std::path::Path::new("."),
                std::path::Path::new("s.toml"),
            )
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default(),
        }
    };
    let key = |t: f64| {
        format!(
            "[[animation.key]]\ntime_s = {t}\neye = [0.0, 0.0, 30.0]\ntarget = [1.0, 1.0, 0.0]\n"
        )
    };
    let cases = [
        ("fsp = 24\n".to_owned(), "fsp"),
        ("fps = 24\n".to_owned(), "orbit_deg_per_s"),
        (
            format!("fps = 24\n{}{}", key(2.0), key(1.0)),
            "order of time",
        ),
        (
            "fps = 24\norbit_deg_per_s = 10\n".to_owned(),
            "[camera] orbit",
        ),
        (format!("fps = 0\n{}", key(0.0)), "fps"),
    ];
    for (animation, named) in cases {
        let message = scene(&animation);
        assert!(message.contains(named), "{animation}: '{message}'");
    }
}
