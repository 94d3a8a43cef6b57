//! Hours of sunlight with each sun's strip bounds and without are the same hours, bit for bit
//! in the GeoTIFF, in `f64` and in exact arithmetic: the bounds only spare walks.

use std::path::Path;
use std::process::Command;

#[test]
fn strip_bounds_leave_sunlight_hours_unchanged() {
    let dem = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/jacksboro.tif");
    let dir = tempfile::tempdir().unwrap();
    // Midsummer and midwinter (long shadows), in f64 on a finer grid and exactly on a coarser.
    for (date, arith, cell) in [
        ("2026-06-21", "f64", "0.0025"),
        ("2026-12-21", "f64", "0.0025"),
        ("2026-12-21", "exact", "0.008"),
    ] {
        let written: Vec<(Vec<u8>, String)> = ["on", "off"]
            .iter()
            .map(|bounds| {
                let out = dir.path().join(format!("{date}-{arith}-{bounds}.tif"));
                let output = Command::new(env!("CARGO_BIN_EXE_heightray"))
                    .arg("render")
                    .arg(&dem)
                    .args(["--ortho", "--product", "sunlight-hours", "--date", date])
                    .args(["--sun-step", "20", "--cell", cell, "--arith", arith])
                    .args(["--strip-bounds", bounds, "-o"])
                    .arg(&out)
                    .output()
                    .unwrap();
                let stderr = String::from_utf8_lossy(&output.stderr);
                assert!(output.status.success(), "{stderr}");
                let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
                (std::fs::read(&out).unwrap(), stdout)
            })
            .collect();
        assert!(
            written[0].0 == written[1].0,
            "{date} {arith}: the hours differ"
        );
        // Shadows were cast: the least hours fall short of the most ("values LO to HI").
        let range: Vec<f64> = written[0]
            .1
            .split("values ")
            .nth(1)
            .unwrap_or_default()
            .split(" to ")
            .filter_map(|v| v.trim().parse().ok())
            .collect();
        assert!(
            range.len() == 2 && range[0] < range[1] - 1.0,
            "{}",
            written[0].1
        );
    }
}
