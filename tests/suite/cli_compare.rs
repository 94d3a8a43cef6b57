//! `heightray bench compare`: two binaries measure the same frames in turn, and a baseline
//! that cannot be run, or that writes no `bench speed` report, is refused with a message
//! that says so.

use std::path::Path;
use std::process::{Command, Output};

fn compare(baseline: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args(["bench", "compare", "--baseline"])
        .arg(baseline)
        .args(["--sizes", "33", "--size", "8", "--methods", "mipmap"])
        .args(["--ariths", "f64", "--threads", "1"])
        .args(extra)
        .output()
        .expect("runs")
}

/// The binary against itself: runs alternate baseline and candidate, and each round's ratio
/// is the candidate's figure over the baseline's of the same round.
#[test]
fn compare_runs_both_binaries_in_turn_and_gives_each_rounds_ratio() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let json = dir.path().join("compare.json");
    let itself = Path::new(env!("CARGO_BIN_EXE_heightray"));
    let output = compare(
        itself,
        &["--rounds", "2", "--out", json.to_str().expect("utf-8")],
    );
    assert!(output.status.success(), "{output:?}");
    let progress = String::from_utf8_lossy(&output.stderr);
    let runs: Vec<&str> = progress
        .lines()
        .filter(|l| l.starts_with("round "))
        .collect();
    assert_eq!(runs.len(), 4, "{progress}");
    for (run, expected) in runs.iter().zip([
        "round 1/2: baseline",
        "round 1/2: candidate",
        "round 2/2: baseline",
        "round 2/2: candidate",
    ]) {
        assert!(run.starts_with(expected), "{run}");
    }
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("--out written"))
            .expect("JSON");
    assert_eq!(report["rounds"], 2);
    let rows = report["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 1, "{report}");
    let row = &rows[0];
    assert_eq!(
        (row["method"].as_str(), row["threads"].as_u64()),
        (Some("mipmap"), Some(1))
    );
    let rates = |k: usize| -> Vec<f64> {
        let rounds = row["camera_mrays_per_s"][k].as_array().expect("rates");
        rounds.iter().map(|r| r.as_f64().expect("a rate")).collect()
    };
    let (old, new) = (rates(0), rates(1));
    assert_eq!((old.len(), new.len()), (2, 2));
    let ratios = row["camera_x"]["rounds"].as_array().expect("ratios");
    for k in 0..2 {
        assert!(old[k] > 0.0 && new[k] > 0.0, "{row}");
        let ratio = ratios[k].as_f64().expect("a ratio");
        assert!((ratio - new[k] / old[k]).abs() <= 1e-12 * ratio, "{row}");
    }
    let text = String::from_utf8_lossy(&output.stdout);
    let line = text
        .lines()
        .find(|l| l.starts_with("| valley landscape"))
        .unwrap_or_else(|| panic!("a row: {text}"));
    assert!(line.contains("| mipmap | f64 | 1 |"), "{line}");
}

/// Each way a baseline can be unusable gets its own message, naming the binary.
#[cfg(unix)]
#[test]
fn a_baseline_that_is_not_a_heightray_binary_is_refused_with_a_clear_message() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().expect("a temporary directory");
    let script = |name: &str, body: &str, mode: u32| {
        let path = dir.path().join(name);
        std::fs::write(&path, format!("#!/bin/sh\n{body}\n")).expect("written");
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(mode)).expect("chmod");
        path
    };
    // Writes `text` to the file after `--out`.
    let writing = |text: &str| {
        format!("while [ $# -gt 0 ]; do if [ \"$1\" = --out ]; then echo '{text}' > \"$2\"; fi; shift; done")
    };
    let cases = [
        (dir.path().join("missing"), "cannot use"),
        (dir.path().to_path_buf(), "is not a file"),
        (script("plain", "exit 0", 0o644), "is not executable"),
        (
            script("silent", "exit 0", 0o755),
            "wrote no `bench speed --out` report",
        ),
        (
            script("other", &writing("{\"not\": \"a report\"}"), 0o755),
            "not `bench speed` JSON",
        ),
        (
            script("garbage", &writing("12 monkeys"), 0o755),
            "not `bench speed` JSON",
        ),
        (
            script("failing", "echo 'unknown flag --sizes' >&2; exit 2", 0o755),
            "unknown flag --sizes",
        ),
    ];
    for (baseline, expected) in cases {
        let output = compare(&baseline, &["--rounds", "1"]);
        assert!(!output.status.success(), "{baseline:?}: {output:?}");
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(
            message.contains(expected) && message.contains(&*baseline.to_string_lossy()),
            "{baseline:?}: {message}"
        );
        assert!(output.stdout.is_empty(), "{baseline:?}: {output:?}");
    }
}
