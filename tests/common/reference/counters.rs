//! The query counters the contract prescribes for a ray's walk in exact arithmetic.

use super::numbers::Q;
use super::{first_touch, Answer, Contact};
use heightray::Counters;

/// The query counters the contract prescribes for `answer` (exact arithmetic):
/// - bbox: one query, a hit iff the clip range is non-empty;
/// - cells are walked in visiting order, grouped in spans (maximal runs of consecutive cells
///   with the same minor index; a path with minor component 0 and positive length is one
///   span). The walk stops
///   at the first span or cell whose t_enter >= the best hit so far;
/// - `runs`: each span first gets a run query (the ray's lowest z over the span's t-range <=
///   highest cell maximum of its cells); a missed span's cells are skipped;
/// - each remaining cell gets a cell query (lowest z over its contact interval <= its
///   maximum); a hit cell gets a T0 and a T1 query (hit iff the ray touches it at t >= 0),
///   unless it is a hole.
pub fn counters(answer: &Answer, runs: bool) -> Counters {
    let mut counters = Counters::default();
    if !counters.bbox.record(answer.clip.is_some()) {
        return counters;
    }
    let ray = &answer.ray;
    let lowest = |lo: &Q, hi: &Q| ray.at(2, lo).min(ray.at(2, hi));
    let highest = |lo: &Q, hi: &Q| ray.at(2, lo).max(ray.at(2, hi));
    let spans = spans(answer);
    let mut best: Option<Q> = None;
    let done = |best: &Option<Q>, t: &Q| best.as_ref().is_some_and(|b| b <= t);
    'spans: for span in spans {
        if done(&best, &span[0].t_enter) {
            break;
        }
        if runs {
            let t_lo = span
                .iter()
                .map(|c| &c.t_enter)
                .min()
                .expect("non-empty span");
            let t_hi = span
                .iter()
                .map(|c| &c.t_exit)
                .max()
                .expect("non-empty span");
            let highest = span
                .iter()
                .map(|c| answer.field.cell_max(c.cell))
                .max()
                .expect("non-empty span");
            if !counters.run.record(lowest(t_lo, t_hi) <= *highest) {
                continue;
            }
        }
        for contact in span {
            if done(&best, &contact.t_enter) {
                break 'spans;
            }
            // (A ray above the cell's highest corner or below its lowest misses it.)
            let (t_enter, t_exit) = (&contact.t_enter, &contact.t_exit);
            let may_hit = lowest(t_enter, t_exit) <= *answer.field.cell_max(contact.cell)
                && highest(t_enter, t_exit) >= *answer.field.cell_min(contact.cell);
            if !counters.cell.record(may_hit) || answer.field.is_hole(contact.cell) {
                continue;
            }
            let touches = answer
                .touches
                .get(&contact.cell)
                .cloned()
                .unwrap_or_else(|| {
                    [0, 1].map(|k| first_touch(&answer.field, ray, contact.cell, k))
                });
            for t in touches.into_iter() {
                if !counters.triangle.record(t.is_some()) {
                    continue;
                }
                let t = t.expect("recorded as a hit");
                if best.as_ref().is_none_or(|b| t < *b) {
                    best = Some(t);
                }
            }
        }
    }
    counters
}

/// The covered cells grouped in spans.
fn spans(answer: &Answer) -> Vec<&[Contact]> {
    let ray = &answer.ray;
    let (major, minor) = if ray.x_major() { (0, 1) } else { (1, 0) };
    if answer.cells.is_empty() {
        return Vec::new();
    }
    // A level path of positive length walks its one or two rows as a single span; a path
    // clipped to a single point is walked like a point, row by row.
    let single_point = answer.clip.as_ref().is_some_and(|(t0, t1)| t0 == t1);
    if ray.dir[minor] == 0.0 && ray.dir[major] != 0.0 && !single_point {
        return vec![&answer.cells[..]];
    }
    answer
        .cells
        .chunk_by(|a, b| a.cell[minor] == b.cell[minor])
        .collect()
}
