//! The sun as a compass bearing: `[sun] azimuth_deg` and `elevation_deg` against the direction
//! worked by hand, and the NREL SPA paper's example (Reda & Andreas 2004, Table A5.1) given as
//! a local time in the place's time zone, read back from `render --stats` as a bearing.

use crate::common::scenes::load_scene_text;
use std::process::Command;

const MAP: &str = "[heightmap]\npath = \"builtin:small49\"\nz_scale = 12.0\n";

#[test]
fn a_bearing_and_an_elevation_place_the_sun_clockwise_from_north() {
    let scene = load_scene_text(
        "se.toml",
        &format!("{MAP}[sun]\nazimuth_deg = 135.0\nelevation_deg = 30.0\n"),
    )
    .unwrap();
    // South-east, 30 degrees up: x (east) = sin 135 cos 30, y (north) = cos 135 cos 30.
    let half = 0.5f64.sqrt();
    let want = [half * 0.75f64.sqrt(), -half * 0.75f64.sqrt(), 0.5];
    for (got, want) in scene.lighting.sun.iter().zip(want) {
        assert!((got - want).abs() < 1e-12, "{:?}", scene.lighting.sun);
    }
    for (keys, says) in [
        ("azimuth_deg = 10.0\n", "go together"),
        (
            "azimuth_deg = 10.0\nelevation_deg = 5.0\ntime = \"2026-06-21T10:00:00Z\"\n",
            "give one",
        ),
        (
            "azimuth_deg = 10.0\nelevation_deg = 95.0\n",
            "from -90 to 90",
        ),
        (
            "time = \"2026-06-21T10:00\"\nlat = 1.0\nlon = 2.0\nzone = \"Nowhere/Land\"\n",
            "zone",
        ),
    ] {
        let error = load_scene_text("bad.toml", &format!("{MAP}[sun]\n{keys}")).unwrap_err();
        assert!(error.contains(says), "{keys}: {error}");
    }
}

#[test]
fn the_spa_example_at_local_time_reads_back_as_its_bearing() {
    // 17 October 2003, 12:30:30 at UTC-7 in Golden, Colorado: 13:30:30 on Denver's clocks
    // (summer time, UTC-6). SPA: topocentric azimuth 194.34024°, zenith 50.11162°.
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("golden.toml");
    std::fs::write(
        &scene,
        format!(
            "{MAP}[camera]\neye = [-5.0, -5.0, 30.0]\ntarget = [24.0, 24.0, 3.0]\nwidth = 8\n\
             height = 8\n[sun]\ntime = \"2003-10-17T13:30:30\"\nlat = 39.742476\n\
             lon = -105.1786\n"
        ),
    )
    .unwrap();
    let stats = dir.path().join("stats.json");
    let status = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .arg("render")
        .arg(&scene)
        .arg("-o")
        .arg(dir.path().join("out.png"))
        .arg("--stats")
        .arg(&stats)
        .stdout(std::process::Stdio::null())
        .status()
        .unwrap();
    assert!(status.success());
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    let azimuth = json["sun"]["azimuth_deg"].as_f64().unwrap();
    let elevation = json["sun"]["elevation_deg"].as_f64().unwrap();
    // Sea level, a standard atmosphere and an estimated Delta T move it by under 0.01°.
    assert!((azimuth - 194.34024).abs() < 0.01, "{azimuth}");
    assert!((90.0 - elevation - 50.11162).abs() < 0.01, "{elevation}");
}

#[test]
fn a_scene_error_keeps_the_parsers_lines_so_the_marker_stands_under_the_key() {
    let error =
        load_scene_text("typo.toml", &format!("{MAP}[sun]\nazimuth = 135.0\n")).unwrap_err();
    // TOML's message: the line, then a `^` under the unknown key, on lines of their own.
    let lines: Vec<&str> = error.lines().collect();
    let key = lines
        .iter()
        .position(|l| l.contains("azimuth = 135.0"))
        .expect(&error);
    let marker = lines.get(key + 1).expect(&error);
    let column = |l: &str, c: char| l.find(c);
    assert_eq!(column(marker, '^'), column(lines[key], 'a'), "{error}");
}
