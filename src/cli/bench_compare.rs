//! `heightray bench compare`: two heightray binaries measure the same `bench speed` frames in
//! turn (baseline, candidate, baseline, ...), each writing its `--out` JSON, so a slow spell
//! of a shared machine falls on both; each row's figures, candidate over baseline, are given
//! per round and summed up as a median and a range.

use super::{CompareArgs, SpeedFrames};
use anyhow::Context;
use heightray::output_file;
use serde::{Deserialize, Serialize};
use std::ffi::OsString;
use std::io::Write;
use std::path::Path;
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

pub fn run(args: &CompareArgs) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(args.rounds >= 1, "--rounds must be at least 1");
    let candidate = match &args.candidate {
        Some(path) => path.clone(),
        None => std::env::current_exe().context("cannot find this program's own binary")?,
    };
    let binaries = [
        Binary::new("baseline", &args.baseline)?,
        Binary::new("candidate", &candidate)?,
    ];
    let flags = speed_flags(&args.frames);
    let out = std::env::temp_dir().join(format!("heightray-compare-{}.json", std::process::id()));
    let mut runs: [Vec<Report>; 2] = [Vec::new(), Vec::new()];
    for round in 1..=args.rounds {
        for (binary, reports) in binaries.iter().zip(&mut runs) {
            let start = Instant::now();
            let report = binary.speed(&flags, &out);
            // (Removed whatever happened, so that no run reads another's report.)
            let _ = std::fs::remove_file(&out);
            reports.push(report?);
            eprintln!(
                "round {round}/{}: {} in {:.1} s",
                args.rounds,
                binary.role,
                start.elapsed().as_secs_f64()
            );
        }
    }
    let [old, new] = &runs;
    let comparison = Comparison {
        command: std::env::args().collect::<Vec<_>>().join(" "),
        baseline: args.baseline.display().to_string(),
        candidate: candidate.display().to_string(),
        rounds: args.rounds,
        rows: compare(old, new),
    };
    let stdout = &mut std::io::stdout().lock();
    print(stdout, &comparison)?;
    if let Some(path) = &args.out {
        let json = serde_json::to_string_pretty(&comparison)?;
        output_file::write_bytes(path, (json + "\n").as_bytes()).map_err(anyhow::Error::msg)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// A binary to run, named by its part in the comparison.
struct Binary<'a> {
    role: &'static str,
    path: &'a Path,
}

impl<'a> Binary<'a> {
    /// The binary at `path`, if it is an executable file.
    fn new(role: &'static str, path: &'a Path) -> anyhow::Result<Binary<'a>> {
        let shown = path.display();
        let metadata = std::fs::metadata(path)
            .with_context(|| format!("cannot use {shown} as the {role} binary"))?;
        anyhow::ensure!(
            metadata.is_file(),
            "the {role} binary {shown} is not a file (a heightray binary is needed)"
        );
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            anyhow::ensure!(
                metadata.permissions().mode() & 0o111 != 0,
                "the {role} binary {shown} is not executable (chmod +x, or build it with cargo build --release)"
            );
        }
        Ok(Binary { role, path })
    }

    /// Runs its `bench speed` with `flags`, its report written to `out`, and reads it.
    fn speed(&self, flags: &[OsString], out: &Path) -> anyhow::Result<Report> {
        let (role, shown) = (self.role, self.path.display());
        let output = Command::new(self.path)
            .args(["bench", "speed"])
            .args(flags)
            .arg("--out")
            .arg(out)
            .stdin(Stdio::null())
            .output()
            .with_context(|| format!("cannot run the {role} binary {shown}"))?;
        if !output.status.success() {
            let stderr = String::from_utf8_lossy(&output.stderr);
            let last: Vec<&str> = stderr.lines().rev().take(5).collect();
            let said: Vec<&str> = last.into_iter().rev().collect();
            anyhow::bail!(
                "the {role} binary {shown} failed ({}) on `bench speed {}`: {}",
                output.status,
                flags_shown(flags),
                said.join("\n")
            );
        }
        let json = std::fs::read_to_string(out).map_err(|_| {
            anyhow::anyhow!(
                "the {role} binary {shown} wrote no `bench speed --out` report: is it heightray?"
            )
        })?;
        serde_json::from_str(&json).map_err(|e| {
            anyhow::anyhow!(
                "the {role} binary {shown} wrote a report that is not `bench speed` JSON ({e})"
            )
        })
    }
}

/// The flags that give `bench speed` the frames of `frames`.
fn speed_flags(frames: &SpeedFrames) -> Vec<OsString> {
    fn list<T: ToString>(items: &[T]) -> OsString {
        let items: Vec<String> = items.iter().map(T::to_string).collect();
        items.join(",").into()
    }
    let mut flags: Vec<OsString> = Vec::new();
    if !frames.scenes.is_empty() {
        let mut scenes = OsString::new();
        for (k, scene) in frames.scenes.iter().enumerate() {
            if k > 0 {
                scenes.push(",");
            }
            scenes.push(scene);
        }
        flags.extend(["--scenes".into(), scenes]);
    }
    if !frames.sizes.is_empty() {
        flags.extend(["--sizes".into(), list(&frames.sizes)]);
    }
    if let Some(size) = frames.size {
        flags.extend(["--size".into(), size.to_string().into()]);
    }
    flags.extend(["--methods".into(), list(&frames.methods)]);
    flags.extend(["--ariths".into(), list(&frames.ariths)]);
    flags.extend(["--threads".into(), list(&frames.threads)]);
    flags
}

fn flags_shown(flags: &[OsString]) -> String {
    let flags: Vec<_> = flags.iter().map(|f| f.to_string_lossy()).collect();
    flags.join(" ")
}

/// The part of a `bench speed` report compared (older reports hold the same fields).
#[derive(Deserialize)]
struct Report {
    terrains: Vec<TerrainRows>,
}

#[derive(Deserialize)]
struct TerrainRows {
    label: String,
    rows: Vec<Row>,
}

#[derive(Deserialize, Clone)]
struct Row {
    method: String,
    arith: String,
    threads: usize,
    primary_mrays_per_s: f64,
    shadow_mrays_per_s: Option<f64>,
    frame_with_shadows_ms: f64,
}

/// The whole comparison, as printed and written.
#[derive(Serialize)]
struct Comparison {
    command: String,
    baseline: String,
    candidate: String,
    rounds: usize,
    rows: Vec<RowComparison>,
}

/// One row (terrain, method, arithmetic, threads) of both binaries' reports.
#[derive(Serialize, Debug, PartialEq)]
struct RowComparison {
    terrain: String,
    method: String,
    arith: String,
    threads: usize,
    /// Each round's primary (camera) rays per second, in millions: baseline, candidate.
    camera_mrays_per_s: [Vec<f64>; 2],
    /// Candidate over baseline, per round: camera rays per second.
    camera_x: Spread,
    /// Shadow rays per second, in the rounds where both binaries measured them.
    shadow_x: Option<Spread>,
    /// The frame with shadows: time, candidate over baseline (below 1: the candidate is
    /// faster).
    frame_time_x: Spread,
}

/// Ratios of the rounds: each, and their median and range.
#[derive(Serialize, Debug, PartialEq)]
struct Spread {
    rounds: Vec<f64>,
    median: f64,
    min: f64,
    max: f64,
}

impl Spread {
    /// `None` for no values.
    fn of(rounds: Vec<f64>) -> Option<Spread> {
        let mut sorted = rounds.clone();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let median = match n {
            0 => return None,
            _ if n % 2 == 1 => sorted[n / 2],
            _ => (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0,
        };
        Some(Spread {
            median,
            min: sorted[0],
            max: sorted[n - 1],
            rounds,
        })
    }
}

/// The rows both binaries measured in every round, in the candidate's order; `old` and
/// `new` are the rounds' reports.
fn compare(old: &[Report], new: &[Report]) -> Vec<RowComparison> {
    let find = |report: &Report, terrain: &str, row: &Row| {
        let rows = report.terrains.iter().find(|t| t.label == terrain)?;
        let same =
            |r: &&Row| (&r.method, &r.arith, r.threads) == (&row.method, &row.arith, row.threads);
        rows.rows.iter().find(same).cloned()
    };
    let Some(first) = new.first() else {
        return Vec::new();
    };
    let mut rows = Vec::new();
    for terrain in &first.terrains {
        for row in &terrain.rows {
            let pairs: Option<Vec<(Row, Row)>> = old
                .iter()
                .zip(new)
                .map(|(o, n)| Some((find(o, &terrain.label, row)?, find(n, &terrain.label, row)?)))
                .collect();
            let Some(pairs) = pairs else { continue };
            let ratios = |f: &dyn Fn(&Row) -> Option<f64>| -> Vec<f64> {
                let each = pairs.iter().filter_map(|(o, n)| Some(f(n)? / f(o)?));
                each.collect()
            };
            let (Some(camera_x), Some(frame_time_x)) = (
                Spread::of(ratios(&|r| Some(r.primary_mrays_per_s))),
                Spread::of(ratios(&|r| Some(r.frame_with_shadows_ms))),
            ) else {
                continue;
            };
            rows.push(RowComparison {
                terrain: terrain.label.clone(),
                method: row.method.clone(),
                arith: row.arith.clone(),
                threads: row.threads,
                camera_mrays_per_s: [
                    pairs.iter().map(|(o, _)| o.primary_mrays_per_s).collect(),
                    pairs.iter().map(|(_, n)| n.primary_mrays_per_s).collect(),
                ],
                camera_x,
                shadow_x: Spread::of(ratios(&|r| r.shadow_mrays_per_s)),
                frame_time_x,
            });
        }
    }
    rows
}

/// The comparison's table.
fn print(out: &mut impl Write, comparison: &Comparison) -> std::io::Result<()> {
    writeln!(
        out,
        "candidate {} against baseline {}: {} rounds of `bench speed`, alternating, baseline first",
        comparison.candidate, comparison.baseline, comparison.rounds
    )?;
    writeln!(out, "(new / old per round: median [lowest, highest]; rays per second above 1 and frame time below 1: the candidate is faster)")?;
    writeln!(out, "| terrain | method | arith | threads | camera Mrays/s old / new (median) | camera rays/s new / old | shadow rays/s new / old | frame with shadows time new / old |")?;
    writeln!(out, "|---|---|---|---:|---:|---:|---:|---:|")?;
    let spread = |s: &Spread| format!("{:.3} [{:.3}, {:.3}]", s.median, s.min, s.max);
    for row in &comparison.rows {
        let rates = row
            .camera_mrays_per_s
            .each_ref()
            .map(|r| Spread::of(r.clone()).map_or("-".into(), |s| format!("{:.3}", s.median)));
        writeln!(
            out,
            "| {} | {} | {} | {} | {} / {} | {} | {} | {} |",
            row.terrain,
            row.method,
            row.arith,
            row.threads,
            rates[0],
            rates[1],
            spread(&row.camera_x),
            row.shadow_x.as_ref().map_or("-".into(), spread),
            spread(&row.frame_time_x),
        )?;
    }
    if comparison.rows.is_empty() {
        writeln!(out, "(no row was measured by both binaries in every round)")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    #[test]
    fn a_spread_is_the_median_and_range_of_the_rounds() {
        let odd = Spread::of(vec![1.2, 0.9, 1.0]).unwrap();
        assert_eq!((odd.median, odd.min, odd.max), (1.0, 0.9, 1.2));
        assert_eq!(odd.rounds, [1.2, 0.9, 1.0], "in the order of the rounds");
        let even = Spread::of(vec![4.0, 1.0, 2.0, 3.0]).unwrap();
        assert_eq!((even.median, even.min, even.max), (2.5, 1.0, 4.0));
        assert_eq!(Spread::of(Vec::new()), None);
    }

    fn report(rows: &[(&str, f64, Option<f64>, f64)]) -> Report {
        let rows = rows.iter().map(|&(method, camera, shadow, frame)| Row {
            method: method.into(),
            arith: "f64".into(),
            threads: 1,
            primary_mrays_per_s: camera,
            shadow_mrays_per_s: shadow,
            frame_with_shadows_ms: frame,
        });
        Report {
            terrains: vec![TerrainRows {
                label: "small".into(),
                rows: rows.collect(),
            }],
        }
    }

    /// Rows are paired by round and by method; a row missing from a round of either binary
    /// is left out, and a shadow rate missing from a round leaves that round out of its
    /// spread only.
    #[test]
    fn rows_are_compared_round_by_round() {
        let old = [
            report(&[("mipmap", 2.0, Some(4.0), 100.0), ("dda", 1.0, None, 10.0)]),
            report(&[("mipmap", 4.0, None, 200.0), ("dda", 1.0, None, 10.0)]),
        ];
        let new = [
            report(&[("mipmap", 3.0, Some(2.0), 50.0), ("dda", 1.0, None, 10.0)]),
            report(&[("mipmap", 4.0, Some(1.0), 100.0)]),
        ];
        let rows = compare(&old, &new);
        assert_eq!(rows.len(), 1, "dda is missing from the second new round");
        let mipmap = &rows[0];
        assert_eq!(mipmap.camera_x.rounds, [1.5, 1.0]);
        assert_eq!(mipmap.camera_x.median, 1.25);
        assert_eq!(mipmap.shadow_x.as_ref().unwrap().rounds, [0.5]);
        assert_eq!(mipmap.frame_time_x.rounds, [0.5, 0.5]);
        assert_eq!(mipmap.camera_mrays_per_s, [vec![2.0, 4.0], vec![3.0, 4.0]]);
    }

    #[test]
    fn the_frames_are_passed_as_bench_speed_flags() {
        let frames = SpeedFrames {
            scenes: Vec::new(),
            sizes: vec![513, 2049],
            size: Some(64),
            methods: vec![
                heightray::Method::Mipmap,
                heightray::Method::HierarchicalRuns,
            ],
            ariths: vec![
                heightray::Arith::F64,
                heightray::Arith::Rational { bound: 256 },
            ],
            threads: vec![1, 2],
        };
        let flags = flags_shown(&speed_flags(&frames));
        assert_eq!(
            flags,
            "--sizes 513,2049 --size 64 --methods mipmap,hruns --ariths f64,rational:256 --threads 1,2"
        );
        let scenes = SpeedFrames {
            scenes: vec![PathBuf::from("a.toml"), PathBuf::from("b c.toml")],
            sizes: Vec::new(),
            size: None,
            ..frames
        };
        assert_eq!(
            speed_flags(&scenes)[..2],
            [
                OsString::from("--scenes"),
                OsString::from("a.toml,b c.toml")
            ]
        );
    }
}
