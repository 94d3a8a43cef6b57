//! `heightray bench speed --sizes`: the same landscape at several sizes, every method, with
//! the memory each method needs per sample (a property of the data structures, asserted here;
//! speeds are only reported, never asserted).

use std::process::Command;

/// The cells of the table row for `method` under the heading of `size`.
fn row(output: &str, size: usize, method: &str) -> Vec<String> {
    let heading = format!("at {size}x{size}: {size}x{size} samples");
    let table = output
        .split_once(&heading)
        .unwrap_or_else(|| panic!("no table for {size}: {output}"))
        .1;
    let line = table
        .lines()
        .find(|l| l.starts_with(&format!("| {method} |")))
        .unwrap_or_else(|| panic!("no {method} row for {size}: {output}"));
    line.split('|')
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
        .collect()
}

#[test]
fn speed_at_sizes_reports_every_method_with_its_memory_and_growth() {
    let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args([
            "bench",
            "speed",
            "--sizes",
            "33,129",
            "--size",
            "16",
            "--methods",
            "mipmap,runs,dda",
            "--ariths",
            "f64",
            "--threads",
            "1",
        ])
        .output()
        .expect("runs");
    assert!(output.status.success(), "{output:?}");
    let text = String::from_utf8_lossy(&output.stdout).to_string();
    for size in [33, 129] {
        // method | arith | threads | build ms | bytes/sample | primary | shadow | ...
        let bytes = |method| -> f64 { row(&text, size, method)[4].parse().expect("a number") };
        // The mipmap: levels from 2x2 cells up, 2 bytes per block: about 2/3 byte per sample.
        let mipmap = bytes("mipmap");
        assert!(
            mipmap > 0.4 && mipmap <= 1.0,
            "{size}: mipmap {mipmap} bytes per sample"
        );
        // Row and column range maxima: about 8 bytes per sample; the DDA reads the samples.
        assert!(bytes("runs") > 6.0, "{size}");
        assert_eq!(bytes("dda"), 0.0, "{size}");
        for method in ["mipmap", "runs", "dda"] {
            let primary: f64 = row(&text, size, method)[5].parse().expect("a number");
            assert!(primary > 0.0, "{size} {method}: {primary}");
        }
    }
    let growth = text
        .split_once("growth of time per primary ray")
        .expect("a growth table")
        .1;
    for method in ["mipmap", "runs", "dda", "log2 N"] {
        assert!(
            growth
                .lines()
                .any(|l| l.starts_with(&format!("| {method} |"))),
            "{method}: {growth}"
        );
    }
    // Queries per primary ray at each size: each method asks its own kind of span query,
    // and the hierarchy's camera rays share beams.
    let queries = growth
        .split_once("queries per primary ray: block / run / cell / triangle / beam")
        .expect("a table of queries")
        .1;
    for (method, block, run) in [
        ("mipmap", true, false),
        ("runs", false, true),
        ("dda", false, false),
    ] {
        let line = queries
            .lines()
            .find(|l| l.starts_with(&format!("| {method} |")))
            .unwrap_or_else(|| panic!("{method}: {queries}"));
        for size in line.split('|').skip(3).filter(|c| !c.trim().is_empty()) {
            let per_ray: Vec<f64> = size
                .split('/')
                .map(|q| q.trim().parse().expect("a number"))
                .collect();
            assert_eq!(per_ray.len(), 5, "{line}");
            let asked = (per_ray[0] > 0.0, per_ray[1] > 0.0, per_ray[4] > 0.0);
            assert_eq!(asked, (block, run, block), "{line}");
            assert!(per_ray[2] > 0.0 && per_ray[3] > 0.0, "{line}");
        }
    }
}

#[test]
fn sizes_too_large_or_too_small_are_refused_without_allocating() {
    for size in ["1", "100000"] {
        let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
            .args(["bench", "speed", "--sizes", size, "--threads", "1"])
            .output()
            .expect("runs");
        assert!(!output.status.success(), "{size}");
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(message.contains("samples"), "{size}: {message}");
    }
}
