//! `heightray trace` run as a program: one JSON object per ray on stdout, errors on stderr
//! with a non-zero exit.
//!
//! Contract: `heightray trace MAP --z-scale Z (--origin X,Y,Z --dir DX,DY,DZ | --rays FILE)
//! [--method mipmap|hruns|runs|dda|auto] [--arith f32|f64|rational|rational:BOUND|exact] [--cells]`; each
//! line is {"hit", "t", "t_exact" ("p/q" in exact mode, else absent or null), "point", "cell",
//! "triangle", "counters": {"bbox": {"hit", "miss"}, "run", "cell", "triangle", ...},
//! "cells" (only with --cells)}. `--rays FILE` has lines `ox oy oz dx dy dz`.

use crate::common::families::ray;
use crate::common::reference;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use tempfile::TempDir;

const ARITHS: [&str; 6] = [
    "f32",
    "f64",
    "rational",
    "rational:1000",
    "exact",
    "rational:65536",
];

/// The hand-worked field of exact_reference.rs as a P2 PGM (image row 0 is y = 2): heights
/// are the samples with --z-scale 255; 0 except z(0,0) = 1 and z(2,2) = 4.
fn write_map(dir: &TempDir) -> PathBuf {
    let path = dir.path().join("map.pgm");
    std::fs::write(&path, "P2\n4 3\n255\n0 0 4 0\n0 0 0 0\n1 0 0 0\n").unwrap();
    path
}

fn heightray(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args(args)
        .output()
        .expect("run the heightray binary")
}

fn trace_args<'a>(map: &'a Path, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec!["trace", map.to_str().unwrap(), "--z-scale", "255"];
    args.extend_from_slice(extra);
    args
}

/// Parses stdout as one JSON object per line, after checking the run succeeded.
fn json_lines(output: &Output) -> Vec<Value> {
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "exit {:?}\nstdout: {stdout}\nstderr: {}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
        .lines()
        .map(|line| serde_json::from_str(line).unwrap_or_else(|e| panic!("not JSON ({e}): {line}")))
        .collect()
}

fn hit_miss(v: &Value) -> (u64, u64) {
    (
        v["hit"].as_u64().expect("hit count"),
        v["miss"].as_u64().expect("miss count"),
    )
}

fn cells_of(v: &Value) -> Vec<[usize; 2]> {
    v.as_array()
        .expect("cells array")
        .iter()
        .map(|c| {
            [
                c[0].as_u64().unwrap() as usize,
                c[1].as_u64().unwrap() as usize,
            ]
        })
        .collect()
}

/// The hand-worked ray (see `hand_worked_counters_on_4x3_field`): o = (0, 0.25, 3),
/// d = (2, 1, -2) hits T0 of cell (1,1) at t = 1, point (2, 1.25, 1). All of its arithmetic
/// is exact in every mode (small dyadic numbers), so every mode must give this answer.
fn assert_hand_worked(line: &Value, method: &str, arith: &str) {
    let what = format!("{method} {arith}: {line}");
    assert_eq!(line["hit"], Value::Bool(true), "{what}");
    assert_eq!(line["t"].as_f64(), Some(1.0), "{what}");
    assert_eq!(line["point"], serde_json::json!([2.0, 1.25, 1.0]), "{what}");
    assert_eq!(line["cell"], serde_json::json!([1, 1]), "{what}");
    assert_eq!(line["triangle"], serde_json::json!(0), "{what}");
    if arith == "exact" {
        assert_eq!(line["t_exact"], Value::String("1/1".into()), "{what}");
    } else {
        assert!(line.get("t_exact").is_none_or(Value::is_null), "{what}");
    }
    let c = &line["counters"];
    assert_eq!(hit_miss(&c["bbox"]), (1, 0), "{what}");
    // The mipmap (the default) starts three levels below its top (level 2 here), so on this
    // small grid at single cells: (0,0) and (1,0) miss, (1,1) may be hit; it stays on level
    // 0 while the descending ray is inside the level-1 block it started in.
    // In exact arithmetic the hit point (2, 1.25) lies on the face cell (1,1) shares with
    // (2,1), whose T1 the ray also touches at t = 1: which one is the answer depends on the
    // order of the cells, so the exact walk decides. An f64 walk first clears the way for it,
    // with room for its rounding: it passes (0,0) and (1,0) and stops at (1,1); the exact
    // walk then starts just before (1,1), inside (1,0), which it tests again.
    // The hierarchical run walk starts at level 0 too (its top is level 2): row 0's run of
    // cells (0,0) and (1,0) is cleared as a whole (the ray is at 1.5 where it leaves the row,
    // above their highest sample, 1), row 1's run may be hit (z(2,2) = 4), and its first
    // cell (1,1) holds the hit: no cell is tested before it.
    let (block, run, cell) = match method {
        "dda" => ((0, 0), (0, 0), (1, 2)),
        "mipmap" | "auto" if arith == "exact" => ((0, 0), (0, 0), (2, 3)),
        "mipmap" | "auto" => ((0, 0), (0, 0), (1, 2)),
        _ => ((0, 0), (1, 1), (1, 0)),
    };
    assert_eq!(hit_miss(&c["block"]), block, "{what}");
    assert_eq!(hit_miss(&c["run"]), run, "{what}");
    assert_eq!(hit_miss(&c["triangle"]), (1, 1), "{what}");
    if arith.starts_with("rational") && method != "dda" {
        // The run walk rounds its intercept (0.75) onto the slope's denominator (2) by design
        // and then also visits cell (0,1), which the ray never touches; it must say so.
        let rounded = c["rational_rounded"].as_u64().expect("rational_rounded");
        let (hit, miss) = hit_miss(&c["cell"]);
        assert_eq!(hit, cell.0, "{what}");
        assert!(miss == cell.1 || rounded > 0, "{what}");
    } else {
        assert_eq!(hit_miss(&c["cell"]), cell, "{what}");
    }
}

#[test]
fn hand_worked_ray_in_every_arithmetic_and_method() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    for method in ["runs", "dda", "mipmap", "hruns", "auto"] {
        for arith in ARITHS {
            let args = trace_args(
                &map,
                &[
                    "--origin", "0,0.25,3", "--dir", "2,1,-2", "--method", method, "--arith", arith,
                ],
            );
            let lines = json_lines(&heightray(&args));
            assert_eq!(lines.len(), 1, "{method} {arith}");
            assert_hand_worked(&lines[0], method, arith);
            assert!(
                lines[0].get("cells").is_none(),
                "cells without --cells: {}",
                lines[0]
            );
        }
    }
}

#[test]
fn cells_flag_lists_walked_cells_in_order() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    let covered = [[0, 0], [1, 0], [1, 1], [2, 1]];
    for method in ["runs", "dda", "mipmap", "hruns"] {
        let args = trace_args(
            &map,
            &[
                "--origin", "0,0.25,3", "--dir", "2,1,-2", "--method", method, "--arith", "exact",
                "--cells",
            ],
        );
        let lines = json_lines(&heightray(&args));
        let cells = cells_of(&lines[0]["cells"]);
        // The run walk and the DDA list the cells up to the hit; the hierarchies leave out
        // those of the blocks they skip.
        let in_order = if matches!(method, "mipmap" | "hruns") {
            let mut rest = covered.iter();
            cells.iter().all(|c| rest.any(|k| k == c))
        } else {
            covered.starts_with(&cells)
        };
        assert!(in_order, "{method}: {cells:?} are not {covered:?} in order");
        assert!(
            cells.contains(&[1, 1]),
            "{method}: the hit cell is missing from {cells:?}"
        );
    }
}

#[test]
fn rays_file_gives_one_line_per_ray_in_order() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    let rays = dir.path().join("rays.txt");
    // The hand-worked ray, a ray passing above everything, a vertical ray onto the spike
    // (2, 2) at height 4, a ray pointing away from the grid.
    std::fs::write(
        &rays,
        "0 0.25 3 2 1 -2\n-1 0.5 3.5 1 0 0\n2 2 10 0 0 -1\n5 5 5 1 1 0\n",
    )
    .unwrap();
    for arith in ARITHS {
        let args = trace_args(&map, &["--rays", rays.to_str().unwrap(), "--arith", arith]);
        let lines = json_lines(&heightray(&args));
        assert_eq!(lines.len(), 4, "{arith}");
        assert_hand_worked(&lines[0], "auto", arith);
        assert_eq!(lines[1]["hit"], Value::Bool(false), "{arith}: {}", lines[1]);
        for key in ["t", "point", "cell", "triangle"] {
            assert!(
                lines[1][key].is_null(),
                "{arith}: {key} of a miss: {}",
                lines[1]
            );
        }
        assert_eq!(hit_miss(&lines[1]["counters"]["bbox"]), (1, 0), "{arith}");
        // Vertical onto the vertex (2,2): t = 6; the first covered cell touching it is (1,1)
        // (rows j=1 only, x-major order), whose T0 has P11 = (2,2).
        assert_eq!(lines[2]["t"].as_f64(), Some(6.0), "{arith}: {}", lines[2]);
        assert_eq!(
            lines[2]["point"],
            serde_json::json!([2.0, 2.0, 4.0]),
            "{arith}"
        );
        assert_eq!(lines[2]["cell"], serde_json::json!([1, 1]), "{arith}");
        assert_eq!(lines[2]["triangle"], serde_json::json!(0), "{arith}");
        assert_eq!(lines[3]["hit"], Value::Bool(false), "{arith}");
        assert_eq!(hit_miss(&lines[3]["counters"]["bbox"]), (0, 1), "{arith}");
    }
}

#[test]
fn the_command_agrees_with_the_exact_reference() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    let field = heightray::heightfield::load(&map, 255.0).unwrap();
    let rays = [
        ray([2.0, 2.0, 10.0], [0.0, 0.0, -1.0]),
        ray([-1.0, 1.0, 0.5], [1.0, 0.0, 0.0]),
        ray([3.0, 0.0, 2.0], [-1.5, 1.0, -0.5]),
    ];
    for r in rays {
        let [o, d] = [r.origin(), r.dir()].map(|v| v.map(|c| c.to_string()).join(","));
        let args = trace_args(&map, &["--origin", &o, "--dir", &d, "--arith", "exact"]);
        let line = &json_lines(&heightray(&args))[0];
        let answer = reference::solve(&field, &r);
        match answer.hit {
            None => assert_eq!(line["hit"], Value::Bool(false), "{line}"),
            Some(hit) => {
                let t = format!("{}/{}", hit.t.numer(), hit.t.denom());
                assert_eq!(line["t_exact"], Value::String(t), "{line}");
                assert_eq!(line["cell"], serde_json::json!(hit.cell), "{line}");
                assert_eq!(line["triangle"], serde_json::json!(hit.triangle), "{line}");
            }
        }
    }
}

/// Runs the command, which must fail with a message on stderr that mentions every word.
fn assert_fails(args: &[&str], words: &[&str]) {
    let output = heightray(args);
    let stderr = String::from_utf8_lossy(&output.stderr).to_lowercase();
    assert!(
        !output.status.success(),
        "{args:?} succeeded: {}",
        String::from_utf8_lossy(&output.stdout)
    );
    assert!(!stderr.trim().is_empty(), "{args:?}: nothing on stderr");
    for word in words {
        assert!(
            stderr.contains(&word.to_lowercase()),
            "{args:?}: stderr {stderr:?} does not mention {word:?}"
        );
    }
}

#[test]
fn a_missing_map_is_an_error() {
    let dir = TempDir::new().unwrap();
    let missing = dir.path().join("nope.pgm");
    assert_fails(
        &trace_args(&missing, &["--origin", "0,0,1", "--dir", "1,0,0"]),
        &["nope.pgm"],
    );
}

#[test]
fn nan_origin_is_an_error() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    assert_fails(
        &trace_args(&map, &["--origin", "NaN,0,1", "--dir", "1,0,0"]),
        &["finite"],
    );
    assert_fails(
        &trace_args(&map, &["--origin", "0,inf,1", "--dir", "1,0,0"]),
        &["finite"],
    );
}

#[test]
fn zero_direction_is_an_error() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    assert_fails(
        &trace_args(&map, &["--origin", "0,0,1", "--dir", "0,0,0"]),
        &["direction"],
    );
    assert_fails(
        &trace_args(&map, &["--origin", "0,0,1", "--dir", "-0,0,-0"]),
        &["direction"],
    );
}

#[test]
fn malformed_ray_lines_are_errors() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    for (n, line) in [
        "0 0 1 1 0",
        "0 0 1 1 0 x",
        "0 0 1 0 0 0",
        "nan 0 1 1 0 0",
        "0 0 1 1 0 0 7",
    ]
    .iter()
    .enumerate()
    {
        let rays = dir.path().join(format!("bad{n}.txt"));
        std::fs::write(&rays, format!("0 0.25 3 2 1 -2\n{line}\n")).unwrap();
        assert_fails(
            &trace_args(&map, &["--rays", rays.to_str().unwrap()]),
            &[&format!("bad{n}.txt")],
        );
    }
}

#[test]
fn malformed_arguments_are_errors() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    assert_fails(
        &trace_args(&map, &["--origin", "0,0", "--dir", "1,0,0"]),
        &[],
    );
    assert_fails(
        &trace_args(
            &map,
            &["--origin", "0,0,1", "--dir", "1,0,0", "--arith", "f16"],
        ),
        &["f16"],
    );
    assert_fails(
        &trace_args(
            &map,
            &["--origin", "0,0,1", "--dir", "1,0,0", "--method", "bvh"],
        ),
        &["bvh"],
    );
    assert_fails(&trace_args(&map, &["--origin", "0,0,1"]), &[]);
    assert_fails(
        &[
            "trace",
            map.to_str().unwrap(),
            "--origin",
            "0,0,1",
            "--dir",
            "1,0,0",
        ],
        &["z-scale"],
    );
}

/// A height map given to a benchmark, which takes scenes: the message says what a scene is and
/// how to look at the map. (`render` takes a map alone: see `cli_render`.)
#[test]
fn a_height_map_given_as_a_scene_is_named_for_what_it_is() {
    let map = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/valley513.png");
    let commands: [&[&str]; 2] = [
        &["bench", "speed", "--scenes", map],
        &["bench", "textbook", "--scenes", map],
    ];
    for args in commands {
        let output = heightray(args);
        assert!(!output.status.success(), "{args:?}");
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(
            message.contains("valley513.png is not a text file")
                && message.contains("TOML")
                && message.contains("heightray view"),
            "{args:?}: {message}"
        );
    }
}

/// A scene whose height map is missing, or too small: the message names the scene, the
/// section and the file, and says the cause once (the error chain must not repeat it).
#[test]
fn scene_errors_say_their_cause_once() {
    let dir = TempDir::new().unwrap();
    let tiny = dir.path().join("tiny.pgm");
    std::fs::write(&tiny, "P2\n1 1\n255\n7\n").unwrap();
    let missing = dir.path().join("missing.png");
    for (map, cause) in [(&missing, "No such file"), (&tiny, "at least 2x2")] {
        let scene = dir.path().join("scene.toml");
        let text = format!(
            "[heightmap]\npath = {:?}\nz_scale = 1.0\n[camera]\neye = [0.0, 0.0, 5.0]\n\
             target = [1.0, 1.0, 0.0]\nwidth = 8\nheight = 8\n",
            map.to_str().unwrap()
        );
        std::fs::write(&scene, text).unwrap();
        let out = dir.path().join("out.png");
        let output = heightray(&[
            "render",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(!output.status.success());
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(
            message.contains("scene.toml") && message.contains("[heightmap]"),
            "{message}"
        );
        assert_eq!(message.matches(cause).count(), 1, "{message}");
    }
}

/// Runs `heightray args` with stdout a pipe whose reader takes `lines` lines and hangs up
/// (with 0, before the program starts), checks that it ended with success, not a panic, and
/// returns what it wrote to stderr.
fn stop_reading_after(args: &[&str], lines: usize) -> String {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let (reader, writer) = std::io::pipe().expect("a pipe");
    let reader = (lines > 0).then_some(reader);
    let child = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args(args)
        .stdout(writer)
        .stderr(Stdio::piped())
        .spawn()
        .expect("run the heightray binary");
    if let Some(reader) = reader {
        let read = BufReader::new(reader).lines().take(lines).count();
        assert_eq!(read, lines, "lines before hanging up");
    }
    let output = child.wait_with_output().expect("wait for heightray");
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(
        output.status.success(),
        "exit {:?}: {stderr}",
        output.status
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

#[test]
fn a_reader_that_stops_early_ends_the_trace_quietly() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    // Far more output than a pipe holds, so the trace is still writing when the reader goes.
    let rays = dir.path().join("rays.txt");
    std::fs::write(&rays, "0 0.25 3 2 1 -2\n".repeat(20_000)).unwrap();
    let stderr = stop_reading_after(&trace_args(&map, &["--rays", rays.to_str().unwrap()]), 1);
    assert!(
        !stderr.contains("heightray:"),
        "an error for a reader that left: {stderr}"
    );
}

#[test]
fn a_render_whose_reader_has_gone_still_writes_its_files() {
    let dir = TempDir::new().unwrap();
    let map = write_map(&dir);
    let scene = dir.path().join("scene.toml");
    let (png, stats) = (dir.path().join("out.png"), dir.path().join("stats.json"));
    std::fs::write(
        &scene,
        format!(
            "[heightmap]\npath = {:?}\nz_scale = 255.0\n\n[camera]\neye = [-3.0, -3.0, 8.0]\n\
             target = [1.5, 1.0, 1.0]\nwidth = 16\nheight = 16\n",
            map.to_str().unwrap()
        ),
    )
    .unwrap();
    let args = [
        "render",
        scene.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--stats",
        stats.to_str().unwrap(),
    ];
    stop_reading_after(&args, 0);
    let stats: Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(stats["primary_rays"], Value::from(256));
    assert_eq!(image::open(&png).unwrap().width(), 16);
}
