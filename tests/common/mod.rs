//! Code shared by the integration tests: the exact reference ([`reference`]), the
//! deterministic ray families ([`families`]), and the comparisons of the crate against the
//! reference.

pub mod families;
pub mod files;
pub mod random;
pub mod reference;
pub mod scenes;
pub mod top_down;

use heightray::traverse::{covered_cells, HitMiss};
use heightray::{trace, Arith, Hit, Method, Ray, Terrain, Trace, TraceOptions};
use num_traits::ToPrimitive;
use reference::{Answer, ExactHit};
use std::panic::{catch_unwind, AssertUnwindSafe};

pub const METHODS: [Method; 4] = Method::ALL;

/// Options that list the cells a walk covers, `f64` rays of the hierarchies walking in packets
/// (single-ray packets here) unless `HEIGHTRAY_PACKETS=off`.
pub fn options(method: Method, arith: Arith) -> TraceOptions {
    TraceOptions {
        method,
        arith,
        record_cells: true,
        packets: std::env::var("HEIGHTRAY_PACKETS").map_or(true, |v| v != "off"),
        base: None,
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

/// Checks one ray in exact mode, for every method, against the reference (see
/// [`check_exact_against`]). Returns one line per disagreement.
pub fn check_exact(terrain: &Terrain, ray: &Ray) -> Vec<String> {
    let answer = reference::solve(terrain.field(), ray);
    check_exact_against(terrain, ray, &answer)
}

/// Checks one ray in exact mode, for every method, against the reference's `answer`:
/// - the hit: exact t, cell, triangle, and `t` and the point the nearest `f64`s of the exact
///   values;
/// - listing the cells changes nothing: the answer and every counter are the same without;
/// - `covered_cells` are the reference's covered cells;
/// - the bbox query is the reference's (or, for an oblique ray that passes within rounding of
///   the box, a hit: the `f64` walk clips it to the box grown by its rounding), and a triangle
///   query hits if and only if the ray does (a first-hit walk stops only at a hit);
/// - every recorded cell lies within rounding of the path ([`reference::passes_near`], a
///   millionth of the grid's size) or next to a cell that does (a neighbour the `f64` walk
///   tested where the exact path might stray into it: a path of a subnormal slope might
///   stray a whole row, and the walk's own path lie in the row beyond a grid line the exact
///   path runs just short of), the hit's cell among them;
/// - where the ray is not oblique (along a row or column, or vertical) the walk is made in
///   exact arithmetic alone: the run walk and the DDA record a prefix of the covered cells and
///   count exactly the reference's queries ([`reference::counters`]), and the hierarchies
///   record some of the covered cells in their order. Along an oblique path an `f64` walk
///   certifies the answer (or clears the way for the exact walk), testing the cells the exact
///   path may stray into besides its own: its queries are its own, and its cells lie near
///   the path rather than on it (and may list a cell more than once).
pub fn check_exact_against(terrain: &Terrain, ray: &Ray, answer: &Answer) -> Vec<String> {
    let mut problems = Vec::new();
    let expected_cells = answer.cell_list();
    let field = terrain.field();
    let delta = reference::qi((field.width() + field.height()) as i64) / reference::qi(1_000_000);
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
                let quiet = TraceOptions {
                    record_cells: false,
                    ..options(method, Arith::Exact)
                };
                match try_trace(terrain, ray, &quiet) {
                    Err(e) => problem(e),
                    Ok(plain) if (&plain.hit, &plain.counters) != (&got.hit, &got.counters) => {
                        problem(format!(
                            "without cells listed: {} {:?}, listing them: {} {:?}",
                            describe_hit(&plain.hit),
                            plain.counters,
                            describe_hit(&got.hit),
                            got.counters
                        ))
                    }
                    Ok(_) => {}
                }
                for problem_found in cells_and_queries(&got, answer, method, &delta) {
                    problem(problem_found);
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

/// What [`check_exact_against`] holds of the cells a walk of `method` recorded and the
/// queries it counted.
fn cells_and_queries(
    got: &Trace,
    answer: &Answer,
    method: Method,
    delta: &reference::Q,
) -> Vec<String> {
    let mut problems = Vec::new();
    let expected_cells = answer.cell_list();
    let bbox = reference::counters(answer, false).bbox;
    let grown_box_hit = answer.is_oblique()
        && reference::passes_near_box(answer, delta)
        && got.counters.bbox == HitMiss { hit: 1, miss: 0 };
    if got.counters.bbox != bbox && !grown_box_hit {
        problems.push(format!(
            "bbox queries {:?}, expected {bbox:?}",
            got.counters.bbox
        ));
    }
    if (got.counters.triangle.hit > 0) != answer.hit.is_some() {
        problems.push(format!(
            "triangle queries {:?} for {}",
            got.counters.triangle,
            describe_exact(&answer.hit)
        ));
    }
    // (A cell the path passes near: a covered cell, or one the `f64` walk's path, within
    // rounding of the exact path, may lie in.)
    let next_to_near = |[i, j]: [usize; 2]| {
        (i.saturating_sub(1)..=i + 1).any(|a| {
            (j.saturating_sub(1)..=j + 1).any(|b| reference::passes_near(answer, [a, b], delta))
        })
    };
    let far: Vec<_> = (got.cells.iter())
        .filter(|&&cell| !next_to_near(cell))
        .collect();
    if !far.is_empty() {
        problems.push(format!("recorded cells {far:?} lie off the path"));
    }
    if let Some(hit) = answer.hit.as_ref().filter(|h| !got.cells.contains(&h.cell)) {
        problems.push(format!(
            "the hit's cell {:?} is not among the recorded cells {:?}",
            hit.cell, got.cells
        ));
    }
    if answer.is_oblique() {
        return problems;
    }
    if method.is_hierarchical() {
        // A hierarchy skips whole blocks (or runs of them) and may revisit the cells where
        // two of its parts meet: the cells it reached, in order of first visit, are some of
        // the covered cells in their order.
        if !is_ordered_subset(&got.cells, &expected_cells) {
            problems.push(format!(
                "recorded cells {:?} are not covered cells {:?} in order",
                got.cells, expected_cells
            ));
        }
        return problems;
    }
    if !expected_cells.starts_with(&got.cells) {
        problems.push(format!(
            "recorded cells {:?} are not a prefix of the covered cells {:?}",
            got.cells, expected_cells
        ));
    }
    let counters = reference::counters(answer, method == Method::Runs);
    if got.counters != counters {
        problems.push(format!(
            "counters {:?}, expected {:?}",
            got.counters, counters
        ));
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
