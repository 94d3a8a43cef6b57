//! Code shared by the integration tests: the exact reference ([`reference`]), the
//! deterministic ray families ([`families`]), and the comparisons of the crate against the
//! reference.

pub mod families;
pub mod files;
pub mod random;
pub mod reference;
pub mod scenes;
pub mod top_down;

use heightray::traverse::covered_cells;
use heightray::{trace, Arith, Hit, Method, Ray, Terrain, Trace, TraceOptions};
use num_traits::ToPrimitive;
use reference::{Answer, ExactHit};
use std::panic::{catch_unwind, AssertUnwindSafe};

pub const METHODS: [Method; 4] = Method::ALL;

/// Options that list the cells a walk covers; where a test leaves them out, `f64` rays walk in
/// packets (single-ray packets here), unless `HEIGHTRAY_PACKETS=off`.
pub fn options(method: Method, arith: Arith) -> TraceOptions {
    TraceOptions {
        method,
        arith,
        record_cells: true,
        packets: std::env::var("HEIGHTRAY_PACKETS").map_or(true, |v| v != "off"),
    }
}

/// `o=[..] d=[..]` with every component printed so it round-trips.
pub fn describe(ray: &Ray) -> String {
    format!("o={:?} d={:?}", ray.origin(), ray.dir())
}

fn describe_hit(hit: &Option<Hit>) -> String {
    match hit {
        None => "miss".into(),
        Some(h) => format!(
            "hit t={} (t_exact={}) cell={:?} triangle={}",
            h.t,
            h.t_exact.as_ref().map_or("none".into(), |t| t.to_string()),
            h.cell,
            h.triangle
        ),
    }
}

fn describe_exact(hit: &Option<ExactHit>) -> String {
    match hit {
        None => "miss".into(),
        Some(h) => format!(
            "hit t={} (~{}) cell={:?} triangle={}",
            h.t,
            h.t.to_f64().unwrap_or(f64::NAN),
            h.cell,
            h.triangle
        ),
    }
}

fn panic_message(payload: Box<dyn std::any::Any + Send>) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(non-string panic)".into())
}

/// Traces a ray, turning a panic into an error message.
pub fn try_trace(terrain: &Terrain, ray: &Ray, options: &TraceOptions) -> Result<Trace, String> {
    catch_unwind(AssertUnwindSafe(|| trace(terrain, ray, options))).map_err(|p| {
        format!(
            "trace({}, {}) panicked: {}",
            options.method,
            options.arith,
            panic_message(p)
        )
    })
}

fn try_covered(
    terrain: &Terrain,
    ray: &Ray,
    method: Method,
    arith: Arith,
) -> Result<Vec<[usize; 2]>, String> {
    catch_unwind(AssertUnwindSafe(|| {
        covered_cells(terrain, ray, method, arith)
    }))
    .map_err(|p| {
        format!(
            "covered_cells({method}, {arith}) panicked: {}",
            panic_message(p)
        )
    })
}

/// Checks one ray in exact mode, for every method, against the reference: the hit (exact t,
/// cell, triangle), `covered_cells`, the recorded cells (a prefix of the covered list) and
/// every query counter. Returns one line per disagreement.
pub fn check_exact(terrain: &Terrain, ray: &Ray) -> Vec<String> {
    let answer = reference::solve(terrain.field(), ray);
    check_exact_against(terrain, ray, &answer)
}

pub fn check_exact_against(terrain: &Terrain, ray: &Ray, answer: &Answer) -> Vec<String> {
    let mut problems = Vec::new();
    let expected_cells = answer.cell_list();
    for method in METHODS {
        let mut problem = |what: String| problems.push(format!("{method}: {what}"));
        match try_trace(terrain, ray, &options(method, Arith::Exact)) {
            Err(e) => problem(e),
            Ok(got) => {
                let same_hit = match (&got.hit, &answer.hit) {
                    (None, None) => true,
                    (Some(g), Some(e)) => {
                        g.t_exact.as_ref() == Some(&e.t)
                            && g.cell == e.cell
                            && g.triangle == e.triangle
                    }
                    _ => false,
                };
                if !same_hit {
                    problem(format!(
                        "got {}, expected {}",
                        describe_hit(&got.hit),
                        describe_exact(&answer.hit)
                    ));
                } else if let (Some(g), Some(e)) = (&got.hit, &answer.hit) {
                    // t and the point are the nearest f64 of the exact values.
                    let point = [0, 1, 2].map(|k| answer.ray.at(k, &e.t).to_f64().unwrap());
                    if g.t != e.t.to_f64().unwrap() || g.point != point {
                        problem(format!(
                            "t {} point {:?}, expected the nearest f64s {} {point:?}",
                            g.t,
                            g.point,
                            e.t.to_f64().unwrap()
                        ));
                    }
                }
                // Without cells to list, an f64 walk answers (or clears the way for the
                // exact walk): the same answer.
                let certified = TraceOptions {
                    record_cells: false,
                    ..options(method, Arith::Exact)
                };
                match try_trace(terrain, ray, &certified) {
                    Err(e) => problem(e),
                    Ok(fast) if fast.hit != got.hit => problem(format!(
                        "from the f64 walk: {}, listing cells: {}",
                        describe_hit(&fast.hit),
                        describe_hit(&got.hit)
                    )),
                    Ok(_) => {}
                }
                if method.is_hierarchical() {
                    // A hierarchy skips whole blocks (or runs of them) and may revisit the
                    // cells where two of its parts meet: the cells it reached, in order of
                    // first visit, are some of the covered cells in their order; the queries
                    // are its own.
                    if !is_ordered_subset(&got.cells, &expected_cells) {
                        problem(format!(
                            "recorded cells {:?} are not covered cells {:?} in order",
                            got.cells, expected_cells
                        ));
                    }
                    let bbox = reference::counters(answer, false).bbox;
                    if got.counters.bbox != bbox {
                        problem(format!(
                            "bbox queries {:?}, expected {bbox:?}",
                            got.counters.bbox
                        ));
                    }
                } else {
                    if !expected_cells.starts_with(&got.cells) {
                        problem(format!(
                            "recorded cells {:?} are not a prefix of the covered cells {:?}",
                            got.cells, expected_cells
                        ));
                    }
                    let counters = reference::counters(answer, method == Method::Runs);
                    if got.counters != counters {
                        problem(format!(
                            "counters {:?}, expected {:?}",
                            got.counters, counters
                        ));
                    }
                }
            }
        }
        match try_covered(terrain, ray, method, Arith::Exact) {
            Err(e) => problem(e),
            Ok(cells) if cells != expected_cells => problem(format!(
                "covered_cells {cells:?}, expected {expected_cells:?}"
            )),
            Ok(_) => {}
        }
    }
    problems
}

/// Whether the distinct cells of `got`, in order of first appearance, appear in `all` in the
/// same order.
fn is_ordered_subset(got: &[[usize; 2]], all: &[[usize; 2]]) -> bool {
    let mut seen = std::collections::HashSet::new();
    let mut rest = all.iter();
    got.iter()
        .filter(|c| seen.insert(**c))
        .all(|c| rest.any(|a| a == c))
}

/// Checks every ray and fails with a summary of the disagreements (the first few in full).
pub fn assert_exact(name: &str, terrain: &Terrain, rays: &[Ray]) {
    let mut failures = Vec::new();
    for ray in rays {
        let problems = check_exact(terrain, ray);
        if !problems.is_empty() {
            failures.push(format!(
                "{}\n    {}",
                describe(ray),
                problems.join("\n    ")
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{name}: {} of {} rays disagree with the exact reference; the first ones:\n{}",
        failures.len(),
        rays.len(),
        failures
            .iter()
            .take(8)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

pub fn assert_family(family: &families::Family) {
    assert!(!family.rays.is_empty(), "{}: no rays", family.name);
    assert_exact(&family.name, &family.terrain, &family.rays);
}
