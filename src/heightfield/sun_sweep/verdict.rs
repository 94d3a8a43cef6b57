//! A shadow ray settled by the sweep's bounds: lit or shadowed for sure, or left to the walk.

use super::SunSweep;
use crate::geometry::{gradient, plane_height};
use crate::heightfield::Terrain;
use std::ops::RangeInclusive;

/// Where a shadow ray towards the table's sun starts.
#[derive(Clone, Copy, Debug)]
pub struct SweepStart {
    /// The start in grid coordinates, before the walk raises it for rounding.
    pub point: [f64; 3],
    /// The cell of the hit the ray starts from.
    pub cell: (usize, usize),
    /// The hit triangle (0 or 1), which the walk may leave untested.
    pub triangle: u8,
    /// The start lies on the hit triangle's plane (flat shading); otherwise it is checked to
    /// lie above the surface and the triangle's plane.
    pub on_plane: bool,
    /// How far, relative to `largest`, the walk's start and path may stray from the ray
    /// from `point` in the table's direction (its arithmetic's rounding, with room).
    pub relative: f64,
    /// The largest coordinate magnitude the start was computed from.
    pub largest: f64,
}

/// What the bounds say of a shadow ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Nothing lies in the ray's way: the walk finds no hit.
    Lit,
    /// The ray passes strictly below the surface somewhere after leaving it upwards: the walk
    /// finds a hit.
    Shadowed,
    /// The bounds cannot tell: the ray is to be walked.
    Unknown,
}

impl SunSweep {
    /// Whether the shadow ray from `start` towards the table's sun is lit or shadowed for sure.
    ///
    /// The ray first rises over one column (a step): every triangle whose cell the step's
    /// segment may cross climbs along the sun's direction less steeply than the ray, and the
    /// ray starts on or above the surface (and the hit triangle's plane), so over the step it
    /// stays strictly above the surface, and never meets the hit triangle again. It is then
    /// lit if after the step it is above `U` of the cells it has reached, and shadowed if it
    /// starts below `L` of its own cell: the terrain rises above it further on, so it goes
    /// down through a triangle other than the hit one.
    pub fn verdict(&self, terrain: &Terrain, start: &SweepStart) -> Verdict {
        let [x, y, z] = start.point;
        let [nx, ny] = self.cells.map(|n| n as f64);
        if !(0.0..=nx).contains(&x) || !(0.0..=ny).contains(&y) {
            return Verdict::Unknown;
        }
        let slope = 1.0 + terrain.max_slope();
        let (z_lo, z_hi) = terrain.z_range();
        let across = start.relative * (1.0 + start.largest);
        let up = start.relative * (1.0 + start.largest + z_lo.abs() + z_hi.abs()) * slope;
        let [sx, sy, dz] = self.step;
        let around = |c: f64| [c - across, c + across];
        let far =
            self.blocks(around(x + sx), around(y + sy))
                .map_or(f64::NEG_INFINITY, |(bi, bj)| {
                    let code = self.fold(bi, bj, &self.upper, u16::max, 0);
                    self.upper_height(code)
                });
        let lit = z + dz - up > far;
        let shadowed = !lit
            && self.blocks(around(x), around(y)).is_some_and(|(bi, bj)| {
                let code = self.fold(bi, bj, &self.lower, u16::min, u16::MAX);
                z + up < self.lower_height(code)
            });
        if !(lit || shadowed) || !self.rises_clear(terrain, start, across, up) {
            return Verdict::Unknown;
        }
        if lit {
            Verdict::Lit
        } else {
            Verdict::Shadowed
        }
    }

    /// Whether the ray from `start` stays strictly above the surface over its first step and
    /// never meets the hit triangle after its start (see [`SunSweep::verdict`]).
    fn rises_clear(&self, terrain: &Terrain, start: &SweepStart, across: f64, up: f64) -> bool {
        let [x, y, z] = start.point;
        let [sx, sy, dz] = self.step;
        let climb = self.step.map(f64::abs);
        let slack = start.relative * (climb[2] + terrain.max_slope() * (climb[0] + climb[1]));
        let limit = dz - slack;
        let rises_below = |(i, j): (usize, usize), k: u8| {
            let (gx, gy) = gradient(k, terrain.corner_heights(i, j));
            gx * sx + gy * sy < limit
        };
        let span = |a: f64, b: f64| [a.min(b) - across, a.max(b) + across];
        let Some((is, js)) = self.cells_over(span(x, x + sx), span(y, y + sy)) else {
            return false;
        };
        if !rises_below(start.cell, start.triangle) {
            return false;
        }
        for j in js {
            for i in is.clone() {
                if !(rises_below((i, j), 0) && rises_below((i, j), 1)) {
                    return false;
                }
            }
        }
        if start.on_plane {
            return true;
        }
        // Above the hit triangle's plane, and above both triangles' planes of every cell the
        // start may lie in (the surface over a point is one of them).
        let below = |(i, j): (usize, usize), k: u8| {
            let heights = terrain.corner_heights(i, j);
            plane_height(k, (i, j), heights, x, y) <= z - up
        };
        let Some((is, js)) = self.cells_over([x - across, x + across], [y - across, y + across])
        else {
            return false;
        };
        if !below(start.cell, start.triangle) {
            return false;
        }
        for j in js {
            for i in is.clone() {
                if !(below((i, j), 0) && below((i, j), 1)) {
                    return false;
                }
            }
        }
        true
    }

    /// The cells whose closed squares meet the box `xs` x `ys` (`None` where none does).
    #[inline]
    fn cells_over(
        &self,
        xs: [f64; 2],
        ys: [f64; 2],
    ) -> Option<(RangeInclusive<usize>, RangeInclusive<usize>)> {
        // (Truncation floors the clamped, non-negative ends: no call to `floor`.)
        let range = |[lo, hi]: [f64; 2], n: usize| {
            let top = (n - 1) as f64;
            (hi >= 0.0 && lo <= n as f64)
                .then(|| lo.clamp(0.0, top) as usize..=hi.clamp(0.0, top) as usize)
        };
        Some((range(xs, self.cells[0])?, range(ys, self.cells[1])?))
    }

    /// The blocks holding the cells that meet the box `xs` x `ys`.
    #[inline]
    fn blocks(
        &self,
        xs: [f64; 2],
        ys: [f64; 2],
    ) -> Option<(RangeInclusive<usize>, RangeInclusive<usize>)> {
        let (is, js) = self.cells_over(xs, ys)?;
        let k = self.level;
        Some((
            is.start() >> k..=is.end() >> k,
            js.start() >> k..=js.end() >> k,
        ))
    }

    /// `codes` of the blocks `bi` x `bj` folded by `pick` from `first`.
    fn fold(
        &self,
        bi: RangeInclusive<usize>,
        bj: RangeInclusive<usize>,
        codes: &[u16],
        pick: fn(u16, u16) -> u16,
        first: u16,
    ) -> u16 {
        let mut acc = first;
        for j in bj {
            for i in bi.clone() {
                acc = pick(acc, codes[j * self.blocks_x + i]);
            }
        }
        acc
    }
}
