//! The heightray viewer as a child process on the private display, and its state report.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::thread::sleep;
use std::time::{Duration, Instant};
use tempfile::TempDir;

/// How long anything may take in a test (a loaded CI machine with 2 cores).
pub const PATIENCE: Duration = Duration::from_secs(90);

/// A running viewer; killed on drop.
pub struct Viewer {
    child: Child,
    pub dir: TempDir,
    state: PathBuf,
    log: PathBuf,
}

impl Viewer {
    /// `heightray view --report-state ... EXTRA` on `display`.
    pub fn start(display: &str, extra: &[&str]) -> Viewer {
        let dir = tempfile::tempdir().expect("a temporary directory");
        let state = dir.path().join("state.json");
        let log = dir.path().join("viewer.log");
        let log_file = std::fs::File::create(&log).expect("a log file");
        // The viewer refuses an export folder that does not exist: made first, as a user would.
        if let Some(k) = extra.iter().position(|&a| a == "--export-dir") {
            if let Some(folder) = extra.get(k + 1) {
                std::fs::create_dir_all(dir.path().join(folder)).expect("the export folder");
            }
        }
        let child = Command::new(env!("CARGO_BIN_EXE_heightray"))
            .arg("view")
            .arg("--report-state")
            .arg(&state)
            .args(extra)
            .current_dir(dir.path())
            .env("DISPLAY", display)
            // The private X server, whatever desktop the tests run from.
            .env_remove("WAYLAND_DISPLAY")
            .env_remove("WINIT_X11_SCALE_FACTOR")
            .stdout(Stdio::null())
            .stderr(log_file)
            .spawn()
            .expect("start the heightray binary");
        Viewer {
            child,
            dir,
            state,
            log,
        }
    }

    /// The last state report, if one was written.
    pub fn state(&self) -> Option<Value> {
        let text = std::fs::read_to_string(&self.state).ok()?;
        serde_json::from_str(&text).ok()
    }

    /// Waits until the report satisfies `ready`; fails with the last report and the viewer's
    /// error output if it does not in time or the viewer exits.
    pub fn wait_for(&mut self, what: &str, ready: impl Fn(&Value) -> bool) -> Value {
        let deadline = Instant::now() + PATIENCE;
        loop {
            if let Some(state) = self.state().filter(|s| ready(s)) {
                return state;
            }
            if let Ok(Some(status)) = self.child.try_wait() {
                panic!(
                    "the viewer exited ({status}) waiting for {what}; its stderr:\n{}",
                    self.stderr()
                );
            }
            if Instant::now() > deadline {
                panic!(
                    "timed out waiting for {what}; last state:\n{}\nstderr:\n{}",
                    self.state().map_or("none".into(), |s| s.to_string()),
                    self.stderr()
                );
            }
            sleep(Duration::from_millis(50));
        }
    }

    /// Waits for a fully refined frame newer than `after` converged frames.
    pub fn wait_converged(&mut self, after: u64) -> Value {
        self.wait_for("a fully refined frame", |s| {
            s["converged_frames"].as_u64() > Some(after) && s["rendering"] == false
        })
    }

    /// Waits for the process to exit by itself.
    pub fn wait_exit(&mut self) -> std::process::ExitStatus {
        let deadline = Instant::now() + PATIENCE;
        loop {
            if let Ok(Some(status)) = self.child.try_wait() {
                return status;
            }
            assert!(
                Instant::now() < deadline,
                "the viewer did not exit; stderr:\n{}",
                self.stderr()
            );
            sleep(Duration::from_millis(50));
        }
    }

    /// The most memory the viewer has held at once (VmHWM), in bytes.
    pub fn peak_memory(&self) -> u64 {
        let path = format!("/proc/{}/status", self.child.id());
        let status = std::fs::read_to_string(&path).expect("the viewer's /proc status");
        let kib = status
            .lines()
            .find_map(|line| line.strip_prefix("VmHWM:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .unwrap_or_else(|| panic!("no VmHWM in {path}"));
        kib * 1024
    }

    pub fn stderr(&self) -> String {
        std::fs::read_to_string(&self.log).unwrap_or_default()
    }

    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }
}

impl Drop for Viewer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A number from the report.
pub fn num(state: &Value, pointer: &str) -> f64 {
    state
        .pointer(pointer)
        .and_then(Value::as_f64)
        .unwrap_or_else(|| panic!("no number at {pointer} in {state}"))
}

/// A named widget's rectangle (window pixels) from the report: x0, y0, x1, y1.
pub fn widget(state: &Value, name: &str) -> [f64; 4] {
    let r = |k: usize| num(state, &format!("/widgets/{name}/{k}"));
    [r(0), r(1), r(2), r(3)]
}

/// Where failing tests leave screenshots for a person to look at.
pub fn artifacts() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("viewer");
    let _ = std::fs::create_dir_all(&dir);
    dir
}
