//! `heightray bench speed --sizes`: the same landscape at several sizes, every method, with
//! the memory each method needs per sample (a property of the data structures, asserted here;
//! speeds are only reported, never asserted). `heightray bench accuracy`: its report and plot.
//! `heightray bench textbook`: its two tables. `--embree` in a build without Embree.

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
    let dir = tempfile::tempdir().expect("a temporary directory");
    let json = dir.path().join("speed.json");
    let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args([
            "bench",
            "speed",
            "--sizes",
            "33,129",
            "--size",
            "16",
            "--methods",
            "mipmap,hruns,runs,dda",
            "--ariths",
            "f64",
            "--threads",
            "1",
            "--out",
        ])
        .arg(&json)
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
        // The hierarchical run walk tests its runs against the same mipmap.
        assert_eq!(bytes("hruns"), mipmap, "{size}");
        // Row and column range maxima: about 8 bytes per sample; the DDA reads the samples.
        assert!(bytes("runs") > 6.0, "{size}");
        assert_eq!(bytes("dda"), 0.0, "{size}");
        for method in ["mipmap", "hruns", "runs", "dda"] {
            let primary: f64 = row(&text, size, method)[5].parse().expect("a number");
            assert!(primary > 0.0, "{size} {method}: {primary}");
        }
    }
    same_figures_in_json_and_table(&json, &text);
    let growth = text
        .split_once("growth of time per primary ray")
        .expect("a growth table")
        .1;
    for method in ["mipmap", "hruns", "runs", "dda", "log2 N"] {
        assert!(
            growth
                .lines()
                .any(|l| l.starts_with(&format!("| {method} |"))),
            "{method}: {growth}"
        );
    }
    // Queries per primary ray at each size: each method asks its own kind of span query,
    // and the hierarchies' camera rays each look up their wedge's clearance. (The
    // hierarchies' camera rays are mostly answered from their clearance cell by cell, with
    // no block or run query: rounded, they may ask none per ray.)
    let queries = growth
        .split_once("queries per primary ray: block / run / cell / triangle / wedge")
        .expect("a table of queries")
        .1;
    for (method, block, run, wedge) in [
        ("mipmap", None, Some(false), true),
        ("hruns", Some(false), None, true),
        ("runs", Some(false), Some(true), false),
        ("dda", Some(false), Some(false), false),
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
            let asks = |expected: Option<bool>, asked: f64| {
                expected.is_none_or(|expected| expected == (asked > 0.0))
            };
            assert!(asks(block, per_ray[0]) && asks(run, per_ray[1]), "{line}");
            assert_eq!(per_ray[4] > 0.0, wedge, "{line}");
            assert!(per_ray[2] > 0.0 && per_ray[3] > 0.0, "{line}");
        }
    }
}

/// `--out`'s JSON holds the figures of the tables on stdout: a row for every method at every
/// size, each with the frame's pixels as its primary rays and the table's rounded figures.
fn same_figures_in_json_and_table(json: &std::path::Path, text: &str) {
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(json).expect("--out wrote the file"))
            .expect("JSON");
    assert!(report["command"]
        .as_str()
        .is_some_and(|c| c.contains("--sizes")));
    assert!(report["machine"]["threads"]
        .as_u64()
        .is_some_and(|t| t >= 1));
    let terrains = report["terrains"].as_array().expect("terrains");
    assert_eq!(terrains.len(), 2);
    for (terrain, size) in terrains.iter().zip([33, 129]) {
        assert_eq!(terrain["samples"], serde_json::json!([size, size]));
        let rows = terrain["rows"].as_array().expect("rows");
        assert_eq!(rows.len(), 4, "{terrain}");
        for json_row in rows {
            let method = json_row["method"].as_str().expect("method");
            let cells = row(text, size, method);
            assert_eq!(json_row["primary_rays"], 16 * 16, "{json_row}");
            let number = |key: &str| json_row[key].as_f64().expect(key);
            assert_eq!(format!("{:.2}", number("bytes_per_sample")), cells[4]);
            assert_eq!(format!("{:.3}", number("primary_mrays_per_s")), cells[5]);
            assert_eq!(format!("{:.1}", number("frame_with_shadows_ms")), cells[7]);
            let queries = &json_row["queries_per_primary_ray"];
            assert!(
                queries["triangle"].as_f64().is_some_and(|q| q > 0.0),
                "{json_row}"
            );
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

/// The rows of the table under `heading` in a Markdown report, as cells.
fn table(report: &str, heading: &str) -> Vec<Vec<String>> {
    rows_after(report, &format!("### {heading}\n"))
}

#[test]
fn accuracy_reports_every_method_and_arithmetic_against_exact() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let (report, plot) = (dir.path().join("report.md"), dir.path().join("plot.svg"));
    let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args([
            "bench",
            "accuracy",
            "--size",
            "12",
            "--per-set",
            "4",
            "--methods",
            "mipmap,runs",
            "--ariths",
            "f64",
        ])
        .arg("--out")
        .arg(&report)
        .arg("--plot")
        .arg(&plot)
        .output()
        .expect("runs");
    assert!(output.status.success(), "{output:?}");
    let text = std::fs::read_to_string(&report).expect("the report is written");
    assert_eq!(
        text,
        String::from_utf8_lossy(&output.stdout),
        "printed as written"
    );
    // Exact is measured though not asked for: it is the reference.
    let all: Vec<_> = table(&text, "All sets")
        .into_iter()
        .map(|r| (r[0].clone(), r[1].clone()))
        .collect();
    let pairs = [
        ("mipmap", "f64"),
        ("mipmap", "exact"),
        ("runs", "f64"),
        ("runs", "exact"),
    ];
    assert_eq!(all, pairs.map(|(m, a)| (m.to_string(), a.to_string())));
    // method | arith | rays | ns/ray | x f64 | hit/miss | cell/tri | t err > 1e-9 | ...
    for row in table(&text, "valley513: camera rays") {
        assert_eq!(row[2], "144", "12x12 rays: {row:?}");
        assert_eq!(row[5], "0", "f64 hits what exact hits there: {row:?}");
    }
    // Rays to the sun start on the surface, so their t is tiny and f64's relative error large:
    // the comparison with exact finds those.
    for row in table(&text, "valley513: rays to the sun") {
        let t_errors: u64 = row[7].parse().expect("a count");
        assert_eq!(t_errors > 0, row[1] == "f64", "{row:?}");
    }
    for row in table(&text, "valley513: pixels that differ from the exact render") {
        assert_eq!(row[2], "0 of 144", "{row:?}");
    }
    let svg = std::fs::read_to_string(&plot).expect("the plot is written");
    assert!(svg.starts_with("<svg") && svg.contains("exact"), "{svg}");
}

/// The rows of the first Markdown table after `marker` in `text`, as trimmed cells.
fn rows_after(text: &str, marker: &str) -> Vec<Vec<String>> {
    let after = text
        .split_once(marker)
        .unwrap_or_else(|| panic!("no {marker:?} in {text}"))
        .1;
    let lines = after
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'));
    // (Past the header and its rule; a row starts and ends with an empty cell.)
    lines
        .skip(2)
        .map(|l| {
            l.split('|')
                .map(|c| c.trim().to_string())
                .collect::<Vec<_>>()
        })
        .map(|cells| cells[1..cells.len() - 1].to_vec())
        .collect()
}

#[test]
fn textbook_compares_the_walks_on_every_scene_and_hard_case_set() {
    let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
        .args(["bench", "textbook", "--size", "12", "--per-set", "16"])
        .output()
        .expect("runs");
    assert!(output.status.success(), "{output:?}");
    let text = String::from_utf8_lossy(&output.stdout).to_string();
    // scene | rays | hits | queries | heightray Mrays/s | textbook Mrays/s | ratio | differ
    let scenes = rows_after(&text, "camera rays, one thread");
    assert_eq!(scenes.len(), 2, "the built-in scenes: {text}");
    for row in &scenes {
        assert_eq!(row[1], "144", "12x12 rays: {row:?}");
        for rate in [&row[4], &row[5]] {
            assert!(rate.parse::<f64>().expect("a rate") > 0.0, "{row:?}");
        }
        // Ordinary camera rays: the textbook walk finds the same hits.
        assert_eq!(row[7], "0", "{row:?}");
    }
    // set | rays | heightray differing | textbook differing
    let sets = rows_after(&text, "the hard-case sets");
    let names: Vec<&str> = sets.iter().map(|r| r[0].as_str()).collect();
    assert!(
        names.contains(&"lattice points") && names.contains(&"grazing plateaus"),
        "{names:?}"
    );
    for row in &sets {
        let count = |k: usize| row[k].parse::<u64>().expect("a count");
        assert!(count(2) <= count(1) && count(3) <= count(1), "{row:?}");
    }
}

/// A build without the `embree` feature says how to get one when asked for Embree, and
/// measures nothing.
#[cfg(not(feature = "embree"))]
#[test]
fn asking_for_embree_without_it_says_how_to_build_it() {
    for args in [
        ["bench", "speed", "--sizes", "33", "--embree"].as_slice(),
        ["bench", "textbook", "--size", "4", "--embree"].as_slice(),
    ] {
        let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
            .args(args)
            .output()
            .expect("runs");
        assert!(!output.status.success(), "{args:?}: {output:?}");
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(
            message.contains("built without Embree") && message.contains("--features embree"),
            "{args:?}: {message}"
        );
        assert!(output.stdout.is_empty(), "{args:?}: {output:?}");
    }
}
