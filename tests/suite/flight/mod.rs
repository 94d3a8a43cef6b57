//! Flythroughs and posters: camera paths in scene files, frames rendered alone, in ranges and
//! in shares, resumed; tiles merged into the whole; videos; a Slurm job array.

mod frames;
mod paths;
mod slurm;
mod tiles;
mod tracks;
mod video;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `heightray ARGS`, which must succeed; its output.
pub fn heightray(args: &[&str]) -> Output {
    let output = run(args);
    assert!(
        output.status.success(),
        "heightray {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// `heightray ARGS`, as it ends.
pub fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args(args)
        .output()
        .expect("run heightray")
}

/// A path as an argument.
pub fn arg(path: &Path) -> &str {
    path.to_str().expect("a UTF-8 path")
}

/// A 65x65 generated map and a scene in `dir` whose camera orbits it at `rate` degrees a second
/// for 12 frames at 12 fps, 64x48, with shadows and `extra` appended (more sections).
pub fn orbit_scene(dir: &Path, extra: &str) -> PathBuf {
    let map = dir.join("map.png");
    heightray(&["generate", "--size", "65", "--seed", "3", "-o", arg(&map)]);
    let scene = dir.join("fly.toml");
    let text = format!(
        "[heightmap]\npath = \"map.png\"\nz_scale = 16.0\n\
         [camera]\norbit = {{ target = [32.0, 32.0, 4.0], yaw_deg = 200.0, pitch_deg = 30.0, \
         distance = 90.0 }}\nwidth = 64\nheight = 48\n\
         [effects]\nshadows = true\n\
         [animation]\nfps = 12\norbit_deg_per_s = 30.0\nduration_s = 0.95\n{extra}"
    );
    std::fs::write(&scene, text).expect("write the scene");
    scene
}

/// Whether a tool this test needs is installed; if not, the test is skipped with a printed
/// reason, unless `require` (an environment variable) is set, which makes it fail.
pub fn have_tool(tool: &str, require: &str) -> bool {
    let found = Command::new(tool).arg("--version").output().is_ok()
        || Command::new(tool).arg("-version").output().is_ok();
    if !found {
        assert!(
            std::env::var_os(require).is_none(),
            "{tool} is not installed, and {require} says this machine must have it"
        );
        eprintln!("skipped: {tool} is not installed (set {require}=1 to make this a failure)");
    }
    found
}
