//! Characterization snapshots of the rounding arithmetics: not promises, a record of how `f32`,
//! `f64` and bounded rationals answer today where they differ from the exact reference, so
//! that a change that moves them shows. Re-bless every snapshot with
//!
//! `HEIGHTRAY_BLESS=1 cargo test --profile release-tests --test suite snapshots::`
//!
//! and read the diff of `tests/snapshots/` before committing it.

use crate::common::families;
use crate::common::reference::{self, Answer};
use crate::common::{options, try_trace, METHODS};
use heightray::{Arith, Method, Ray, Terrain};
use num_traits::ToPrimitive;
use std::path::PathBuf;

/// Compares `text` with the snapshot `name`, or writes it when blessing.
fn assert_snapshot(name: &str, text: &str) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/snapshots")
        .join(format!("{name}.txt"));
    if std::env::var_os("HEIGHTRAY_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().expect("a folder")).expect("snapshot folder");
        std::fs::write(&path, text).expect("snapshot written");
        return;
    }
    let recorded = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e}; record it with HEIGHTRAY_BLESS=1 (see tests/suite/snapshots.rs)",
            path.display()
        )
    });
    assert!(
        recorded == text,
        "snapshot {} moved (re-bless with HEIGHTRAY_BLESS=1, see tests/suite/snapshots.rs)\n\
         recorded:\n{recorded}\nnow:\n{text}",
        path.display()
    );
}

const MODES: [Arith; 3] = [Arith::F32, Arith::F64, Arith::Rational { bound: 1 << 16 }];

/// Disagreements of one arithmetic with exact answers.
#[derive(Clone, Copy, Debug, Default)]
struct Tally {
    answers: u64,
    hit_miss: u64,
    cell_or_triangle: u64,
    /// Both hit, but |t - t_exact| > 1e-9 * max(|t_exact|, 1).
    t_error: u64,
    panics: u64,
}

impl Tally {
    fn add(&mut self, o: &Tally) {
        self.answers += o.answers;
        self.hit_miss += o.hit_miss;
        self.cell_or_triangle += o.cell_or_triangle;
        self.t_error += o.t_error;
        self.panics += o.panics;
    }

    fn row(&self, label: &str) -> String {
        format!(
            "{label:<48} {:>7} {:>9} {:>9} {:>9} {:>7}",
            self.answers, self.hit_miss, self.cell_or_triangle, self.t_error, self.panics
        )
    }
}

fn compare(
    terrain: &Terrain,
    ray: &Ray,
    answer: &Answer,
    method: Method,
    arith: Arith,
    tally: &mut Tally,
) {
    tally.answers += 1;
    let Ok(got) = try_trace(terrain, ray, &options(method, arith)) else {
        tally.panics += 1;
        return;
    };
    match (&got.hit, &answer.hit) {
        (None, None) => {}
        (Some(g), Some(e)) => {
            if (g.cell, g.triangle) != (e.cell, e.triangle) {
                tally.cell_or_triangle += 1;
            }
            let exact = e.t.to_f64().expect("finite t");
            if (g.t - exact).abs() > 1e-9 * exact.abs().max(1.0) {
                tally.t_error += 1;
            }
        }
        _ => tally.hit_miss += 1,
    }
}

/// Snapshot: how often each rounding arithmetic's answer differs from the reference's, by
/// family and in all, for every method (`hit/miss`: one hits where the other misses;
/// `cell/tri`: both hit, elsewhere; `t>1e-9`: the same triangle, `t` off by more than `1e-9`
/// relative). None may panic.
#[test]
fn rounded_answers_against_the_reference_by_family() {
    let header = format!(
        "{:<48} {:>7} {:>9} {:>9} {:>9} {:>7}",
        "family / arithmetic (all methods)", "answers", "hit/miss", "cell/tri", "t>1e-9", "panics"
    );
    let mut lines = vec![header.clone()];
    // By arithmetic, then method.
    let mut totals = [[Tally::default(); METHODS.len()]; 3];
    for family in families::all() {
        let mut tallies = [[Tally::default(); METHODS.len()]; 3];
        for ray in &family.rays {
            let answer = reference::solve(family.terrain.field(), ray);
            for (m, &arith) in MODES.iter().enumerate() {
                for (k, method) in METHODS.into_iter().enumerate() {
                    let tally = &mut tallies[m][k];
                    compare(&family.terrain, ray, &answer, method, arith, tally);
                }
            }
        }
        for (m, arith) in MODES.iter().enumerate() {
            let mut all = Tally::default();
            for (k, tally) in tallies[m].iter().enumerate() {
                all.add(tally);
                totals[m][k].add(tally);
            }
            lines.push(all.row(&format!("{} / {arith}", family.name)));
        }
    }
    lines.push(String::new());
    lines.push(header.replace(
        "family / arithmetic (all methods)",
        "TOTAL arithmetic / method    ",
    ));
    for (m, arith) in MODES.iter().enumerate() {
        for (k, method) in METHODS.into_iter().enumerate() {
            lines.push(totals[m][k].row(&format!("TOTAL {arith} / {method}")));
        }
    }
    assert_snapshot("rounded_by_family", &(lines.join("\n") + "\n"));
    for (m, arith) in MODES.iter().enumerate() {
        for (k, method) in METHODS.into_iter().enumerate() {
            assert_eq!(totals[m][k].panics, 0, "{arith} {method} panicked");
        }
    }
}
