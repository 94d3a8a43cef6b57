//! `heightray trace`: one JSON object per ray (README, 'The command line').

use super::{loading, TraceArgs};
use anyhow::{bail, Context};
use heightray::traverse::{trace, Trace, TraceOptions};
use heightray::{Ray, RayError};
use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::path::Path;
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
        let file = std::fs::File::open(path)
            .with_context(|| format!("cannot read rays from {}", path.display()))?;
        let mut lines = Lines::new(BufReader::new(file));
        while let Some(line) = lines.next(path)? {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            match parse_ray(line) {
                Ok(ray) => emit(ray)?,
                Err(reason) => {
                    eprintln!("heightray: {}:{}: {reason}", path.display(), lines.number);
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

/// The longest line of a rays file: six numbers, and a comment, take far less.
const MOST_PER_LINE: u64 = 1 << 16;

/// The lines of a rays file, read one at a time (the file may be a pipe, or endless), each
/// at most [`MOST_PER_LINE`] bytes of text with its end.
struct Lines<R> {
    reader: R,
    line: Vec<u8>,
    /// The number of the line last read, from 1.
    number: u64,
}

impl<R: BufRead> Lines<R> {
    fn new(reader: R) -> Self {
        Lines {
            reader,
            line: Vec::new(),
            number: 0,
        }
    }

    /// The next line, with its end; None at the end of the file.
    fn next(&mut self, path: &Path) -> anyhow::Result<Option<&str>> {
        self.line.clear();
        self.number += 1;
        let at = || format!("{}:{}", path.display(), self.number);
        let read = (&mut self.reader)
            .take(MOST_PER_LINE + 1)
            .read_until(b'\n', &mut self.line)
            .with_context(|| format!("cannot read rays from {}", at()))?;
        if read == 0 {
            return Ok(None);
        }
        if self.line.len() as u64 > MOST_PER_LINE {
            bail!(
                "{}: a line longer than {MOST_PER_LINE} bytes; a rays file has lines of six \
                 numbers 'ox oy oz dx dy dz'",
                at()
            );
        }
        match std::str::from_utf8(&self.line) {
            Ok(text) => Ok(Some(text)),
            Err(_) => bail!(
                "{}: not text; a rays file has lines of six numbers 'ox oy oz dx dy dz'",
                at()
            ),
        }
    }
}

/// Why a line of a rays file is no ray.
#[derive(Clone, Debug, thiserror::Error, PartialEq)]
enum LineError {
    /// A word that is not a number.
    #[error("not a number ({reason}): '{line}'")]
    Number {
        /// What the parser said.
        reason: std::num::ParseFloatError,
        /// The line.
        line: String,
    },
    /// Not six numbers.
    #[error("expected 6 numbers 'ox oy oz dx dy dz', got {0}")]
    Count(usize),
    /// Six numbers that make no ray.
    #[error(transparent)]
    Ray(#[from] RayError),
}

fn parse_ray(line: &str) -> Result<Ray, LineError> {
    let numbers: Result<Vec<f64>, _> = line.split_whitespace().map(str::parse::<f64>).collect();
    let numbers = numbers.map_err(|reason| LineError::Number {
        reason,
        line: line.to_owned(),
    })?;
    let [ox, oy, oz, dx, dy, dz] = numbers[..] else {
        return Err(LineError::Count(numbers.len()));
    };
    Ok(Ray::new([ox, oy, oz], [dx, dy, dz])?)
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
