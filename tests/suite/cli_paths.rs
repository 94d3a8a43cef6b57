//! Paths that are not ordinary files given to the commands: a device, a FIFO or a directory
//! as a height map or a scene is refused at once with what it is; an endless rays file ends
//! with a message instead of being read into memory.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::sync::mpsc;
use std::time::Duration;
use tempfile::TempDir;

/// Runs `heightray args`; fails the test if it takes more than ten seconds (and stops it).
pub fn heightray_within_ten_seconds(args: &[&str]) -> Output {
    let child = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run the heightray binary");
    let id = child.id();
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(child.wait_with_output());
    });
    match receive.recv_timeout(Duration::from_secs(10)) {
        Ok(output) => output.expect("the program's output"),
        Err(_) => {
            let _ = Command::new("kill").arg("-9").arg(id.to_string()).status();
            panic!("heightray {args:?} took more than 10 s");
        }
    }
}

/// The command fails, and its stderr mentions every word.
pub fn assert_fails(args: &[&str], words: &[&str]) {
    let output = heightray_within_ten_seconds(args);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{args:?} succeeded");
    for word in words {
        assert!(
            stderr.contains(word),
            "{args:?}: {stderr:?} does not mention {word:?}"
        );
    }
}

fn fifo(dir: &TempDir, name: &str) -> String {
    let path = dir.path().join(name);
    let made = Command::new("mkfifo")
        .arg(&path)
        .status()
        .expect("run mkfifo");
    assert!(made.success(), "mkfifo failed");
    path.to_str().expect("a UTF-8 path").to_owned()
}

fn trace(map: &str) -> Vec<&str> {
    vec![
        "trace",
        map,
        "--z-scale",
        "1",
        "--origin",
        "0,0,5",
        "--dir",
        "1,1,-1",
    ]
}

#[test]
fn a_device_fifo_or_directory_as_a_height_map_is_refused_at_once() {
    let dir = TempDir::new().unwrap();
    let pipe = fifo(&dir, "pipe.png");
    let folder = dir.path().to_str().unwrap();
    for (map, what) in [
        ("/dev/zero", "/dev/zero is a character device, not a file"),
        (pipe.as_str(), "pipe.png is a FIFO (named pipe), not a file"),
        (folder, "is a directory, not a file"),
    ] {
        assert_fails(&trace(map), &[what, "choose a height map file"]);
    }
}

#[test]
fn a_scene_that_is_a_fifo_too_long_or_names_a_device_is_refused_at_once() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("out.png");
    let out = out.to_str().unwrap();
    let pipe = fifo(&dir, "pipe.toml");
    assert_fails(
        &["render", &pipe, "-o", out],
        &["pipe.toml is a FIFO (named pipe), not a file", "scene"],
    );
    // Text, but far longer than any scene.
    let long = dir.path().join("long.toml");
    std::fs::write(&long, "# a comment\n".repeat(100_000)).unwrap();
    assert_fails(
        &["render", long.to_str().unwrap(), "-o", out],
        &["long.toml is longer than 1048576 bytes"],
    );
    let scene = dir.path().join("zero.toml");
    let text = "[heightmap]\npath = \"/dev/zero\"\nz_scale = 1.0\n[camera]\n\
                eye = [0.0, 0.0, 5.0]\ntarget = [1.0, 1.0, 0.0]\nwidth = 8\nheight = 8\n";
    std::fs::write(&scene, text).unwrap();
    assert_fails(
        &["render", scene.to_str().unwrap(), "-o", out],
        &[
            "zero.toml",
            "[heightmap]",
            "/dev/zero is a character device",
        ],
    );
    assert!(!Path::new(out).exists());
}

#[test]
fn an_endless_rays_file_ends_with_a_message() {
    let dir = TempDir::new().unwrap();
    let map = dir.path().join("map.pgm");
    std::fs::write(&map, "P2 2 2 255\n0 1\n2 3\n").unwrap();
    let map = map.to_str().unwrap();
    let base = ["trace", map, "--z-scale", "1", "--rays"];
    let args = |rays: &'static str| base.iter().copied().chain([rays]).collect::<Vec<_>>();
    assert_fails(
        &args("/dev/zero"),
        &["/dev/zero:1: a line longer than 65536 bytes"],
    );
    assert_fails(&args("/dev/urandom"), &["/dev/urandom:", "not text"]);
}
