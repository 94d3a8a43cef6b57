//! Which cells a span of the walk covers, and how high the terrain rises over a run of them.

use super::frame::{Frame, Span};
use crate::arith::scalar::Scalar;
use crate::heightfield::Terrain;

/// The highest height over frame cells `cols` of frame rows `rows` (both inclusive, valid), from
/// the terrain's row or column maxima.
pub fn run_highest<S: Scalar>(
    terrain: &Terrain,
    frame: &Frame<S>,
    cols: (i64, i64),
    rows: (i64, i64),
) -> f64 {
    let (a, b) = (frame.cell(cols.0, rows.0), frame.cell(cols.1, rows.1));
    let (lo_i, hi_i, lo_j, hi_j) = (a.0.min(b.0), a.0.max(b.0), a.1.min(b.1), a.1.max(b.1));
    if frame.swap {
        (lo_i..=hi_i)
            .map(|i| terrain.column_max(i, lo_j, hi_j))
            .fold(f64::NEG_INFINITY, f64::max)
    } else {
        (lo_j..=hi_j)
            .map(|j| terrain.row_max(j, lo_i, hi_i))
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

/// Frame cells of a span in visiting order: along the row, or column by column for two rows.
pub fn frame_cells<S>(span: &Span<S>) -> impl Iterator<Item = (i64, i64)> {
    let (row, rows) = (span.row, i64::from(span.rows));
    (span.cols.0..=span.cols.1).flat_map(move |cu| (row..row + rows).map(move |cv| (cu, cv)))
}

/// Original cells of a span in visiting order.
pub fn span_cells<'f, S: Scalar>(
    frame: &'f Frame<S>,
    span: &Span<S>,
) -> impl Iterator<Item = (usize, usize)> + 'f {
    frame_cells(span).map(move |(cu, cv)| frame.cell(cu, cv))
}
