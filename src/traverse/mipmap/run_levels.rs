//! The hierarchical run walk: the run walk's runs (Henning & Stephenson) at every level of the
//! min-max mipmap.
//!
//! At level `k` the path is walked one row of `2^k x 2^k` blocks at a time; the blocks of one
//! such row that the path crosses are a run, from where the path enters the row to where it
//! leaves it. One test, the ray's lowest height over the run against the highest sample of its
//! blocks, skips the run whole. A run of level `k` covers the runs of its `2^k` rows of cells:
//! a run over a coarse level is a run of runs. A run the ray may touch is walked again one
//! level down, as the two runs of its two rows of half-size blocks; at the cells, a run that
//! may be touched is crossed cell by cell, each cell with the cell test and its triangles, as
//! the mipmap walk crosses a cell. Where the path leaves a row into a new row of the level
//! above, the walk climbs back to that level.
//!
//! Why skipping is exact: as for the mipmap's blocks, the surface over a closed block never
//! rises above its highest sample, and a run's blocks cover every point of the path in the
//! row (a path through a block corner touches the next block of its row, which the run holds,
//! at a point every block meeting there shares; where rounding leaves it unclear whether the
//! path crosses into the next column at the row's edge, that column's block is tested with
//! the run). Points where the path leaves a row are snapped onto the row's face, as the
//! mipmap walk snaps its exit points, so rounding never steps back into a row it passed.

use super::path::{cell_in_grid, ends_inside, exit_point};
use crate::arith::scalar::Scalar;
use crate::traverse::frame::{BlockRun, Follower, Frame};
use crate::traverse::frame::{Part, Point};
use std::ops::ControlFlow;

/// The run walk from level `k` down to cells and up again (at most to `top`).
pub(in crate::traverse) fn descend_runs<S: Scalar>(
    f: &Frame<S>,
    top: u32,
    mut k: u32,
    follower: &mut impl Follower<S>,
) -> ControlFlow<()> {
    let mut at = Point::start(f);
    let mut first_part = true;
    // A run of cells that may be touched is being crossed cell by cell, up to its row's end.
    let mut in_cells = false;
    loop {
        follower.stop_before(&at.t)?;
        let (cu, cv) = match cell_in_grid(f, &at, follower) {
            Ok(cell) => cell,
            Err(left) => return left,
        };
        if in_cells {
            let exit = exit_point(f, &at, cu + 1, cv + 1);
            let ends_inside = ends_inside(f, &exit);
            let t_hi = if ends_inside { &f.t1 } else { &exit.t };
            let cell = f.cell(cu, cv);
            if follower.may_hit(0, cell, &at.t, t_hi) {
                let part = Part::crossing(f, (cu, cv), (&at, &exit), ends_inside, first_part);
                follower.cell(cell, part)?;
            } else {
                follower.passed(cell);
            }
            if ends_inside {
                return ControlFlow::Continue(());
            }
            if exit.on_v {
                // The run's row is left: runs again, a level up if a new row of level-1
                // blocks begins.
                in_cells = false;
                if top > 0 && (cv + 1) & 1 == 0 {
                    k = 1;
                }
            }
            at = exit;
            first_part = false;
            continue;
        }
        // The run of this row of level-`k` blocks: it ends where the path leaves the row (or
        // the grid's far side, or ends).
        let ev = ((cv >> k) + 1) << k;
        let exit = exit_point(f, &at, f.cols.1 + 1, ev);
        let ends_inside = ends_inside(f, &exit);
        let t_hi = if ends_inside { &f.t1 } else { &exit.t };
        let (end_u, end_col) = if ends_inside {
            (&f.ue, f.ue.floor_i64())
        } else {
            (&exit.u, exit.cell.0)
        };
        let last = end_col.clamp(cu, f.cols.1);
        // A path that enters or leaves a row of cells at a column's edge as far as the
        // arithmetic can tell may touch the cell beyond it there: it is tested with the run.
        // (Above the cells, the block walk's rule: a block touched at a corner the path
        // passes within rounding of is left to the blocks around it.)
        let near = |u: &S, edge: i64| k == 0 && u.nearly_equal(&S::from_i64(edge));
        let tested = (
            if cu > f.cols.0 && near(&at.u, cu) {
                cu - 1
            } else {
                cu
            },
            if last < f.cols.1 && near(end_u, last + 1) {
                last + 1
            } else {
                last
            },
        );
        let run = BlockRun {
            k,
            row: cv >> k,
            blocks: (tested.0 >> k, tested.1 >> k),
        };
        if follower.run_may_hit(f, &run, &at.t, t_hi) {
            if k > 0 {
                k -= 1;
            } else {
                in_cells = true;
            }
            continue;
        }
        if k == 0 {
            for c in cu..=last {
                follower.passed(f.cell(c, cv));
            }
        }
        if ends_inside {
            return ControlFlow::Continue(());
        }
        if exit.on_v && k < top && ev & ((2 << k) - 1) == 0 {
            k += 1;
        }
        at = exit;
        first_part = false;
    }
}
