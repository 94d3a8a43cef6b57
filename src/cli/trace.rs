//! `heightray trace`: one JSON object per ray (README, 'The command line').

use super::{loading, TraceArgs};
use anyhow::Context;
use heightray::traverse::{trace, Trace, TraceOptions};
use heightray::Ray;
use serde_json::{json, Value};
use std::io::Write;
use std::process::ExitCode;

pub fn run(args: &TraceArgs) -> anyhow::Result<ExitCode> {
    let terrain = loading::map(&args.map, args.z_scale, &args.loading)?;
    let options = TraceOptions {
        record_cells: args.cells,
        ..TraceOptions::new(args.method, args.arith)
    };
    let mut out = std::io::stdout().lock();
    let mut failed = false;
    let mut emit = |ray: Ray| -> anyhow::Result<()> {
        let answer = trace(&terrain, &ray, &options);
        writeln!(out, "{}", to_json(&answer, args.cells))?;
        Ok(())
    };
    if let (Some(origin), Some(dir)) = (args.origin, args.dir) {
        emit(Ray::new(origin, dir)?)?;
    }
    if let Some(path) = &args.rays {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read rays from {}", path.display()))?;
        for (number, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            match parse_ray(line) {
                Ok(ray) => emit(ray)?,
                Err(reason) => {
                    eprintln!("heightray: {}:{}: {reason}", path.display(), number + 1);
                    failed = true;
                }
            }
        }
    }
    Ok(if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}

fn parse_ray(line: &str) -> Result<Ray, String> {
    let numbers: Result<Vec<f64>, _> = line.split_whitespace().map(str::parse::<f64>).collect();
    let numbers = numbers.map_err(|e| format!("not a number ({e}): '{line}'"))?;
    let [ox, oy, oz, dx, dy, dz] = numbers[..] else {
        return Err(format!(
            "expected 6 numbers 'ox oy oz dx dy dz', got {}",
            numbers.len()
        ));
    };
    Ray::new([ox, oy, oz], [dx, dy, dz]).map_err(|e| e.to_string())
}

fn to_json(answer: &Trace, with_cells: bool) -> Value {
    let hit = answer.hit.as_ref();
    let mut object = json!({
        "hit": hit.is_some(),
        "t": hit.map(|h| h.t),
        "t_exact": hit.and_then(|h| h.t_exact.as_ref()).map(|t| format!("{}/{}", t.numer(), t.denom())),
        "point": hit.map(|h| h.point),
        "cell": hit.map(|h| h.cell),
        "triangle": hit.map(|h| h.triangle),
        "counters": answer.counters,
    });
    if with_cells {
        object["cells"] = json!(answer.cells);
    }
    object
}
