//! How steeply the terrain can rise as seen from a point, from the min-max mipmap, over all
//! directions or over a sector of azimuths: a ray from the point that climbs more steeply
//! than the bound clears the whole map, so it needs no walk. Soft shadows settle a whole cone
//! towards the sun with it, sky light each ray.

use crate::geometry::gradient;
use crate::heightfield::Terrain;
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// Azimuths from `lo` counter-clockwise to `hi` (less than a half turn apart), as unit
/// vectors, with the one halfway.
#[derive(Clone, Copy, Debug)]
pub struct Sector {
    lo: DVec2,
    hi: DVec2,
    mid: DVec2,
}

impl Sector {
    /// The azimuths within `half` (radians, under a quarter turn) of `mid`'s.
    pub fn around(mid: DVec2, half: f64) -> Sector {
        let mid = mid.normalize();
        Sector {
            lo: DVec2::from_angle(-half).rotate(mid),
            hi: DVec2::from_angle(half).rotate(mid),
            mid,
        }
    }

    /// Sector `k` of `n` equal sectors from azimuth 0 (`n` at least 3), a hair wider on each
    /// side: a direction [`sector_of`] puts in it by a rounded angle lies inside.
    pub fn nth(k: usize, n: usize) -> Sector {
        let width = 2.0 * PI / n as f64;
        let mid = DVec2::from_angle((k as f64 + 0.5) * width);
        Sector::around(mid, width / 2.0 + 1e-9)
    }

    /// The most `g . u` over the unit vectors `u` of the sector: how fast a plane of gradient
    /// `g` rises along the steepest of its azimuths.
    pub fn steepest_rise(&self, g: DVec2) -> f64 {
        let inside = self.lo.perp_dot(g) >= 0.0 && g.perp_dot(self.hi) >= 0.0;
        if inside {
            g.length()
        } else {
            g.dot(self.lo).max(g.dot(self.hi))
        }
    }

    /// Whether a rectangle whose corners are seen from the apex in horizontal directions
    /// `corners` may reach into the sector (false only where it provably does not).
    fn may_hold_all(&self, corners: &[DVec2; 4]) -> bool {
        let right_of_lo = corners.iter().all(|c| self.lo.perp_dot(*c) < 0.0);
        let left_of_hi = corners.iter().all(|c| self.hi.perp_dot(*c) > 0.0);
        let behind = corners.iter().all(|c| self.mid.dot(*c) < 0.0);
        !(right_of_lo || left_of_hi || behind)
    }
}

/// The sector of `n` equal ones from azimuth 0 that holds the horizontal direction `d`.
pub fn sector_of(d: DVec3, n: usize) -> usize {
    let angle = d.y.atan2(d.x).rem_euclid(2.0 * PI);
    ((angle / (2.0 * PI / n as f64)) as usize).min(n - 1)
}

/// A block of level `k` is looked at through its children while the point is closer to it
/// than this many times its size: nearer blocks bound the slope too loosely.
const REFINE: f64 = 2.0;

/// Relative room for the rounding of the bound's own arithmetic.
const ROOM: f64 = 1e-9;

/// An upper bound of `(z(q) - o.z) / |q - o|` (horizontal distance) over every point `q` of
/// the surface (in `sector` as seen from `o`, if given), and at least 0; infinite where `o`
/// lies below the surface (a start no bound describes). `o` is a point on or above the
/// surface inside the map, as a shadow ray's start.
pub fn slope_bound(terrain: &Terrain, o: DVec3, sector: Option<Sector>) -> f64 {
    slope_bound_within(terrain, o, sector, f64::INFINITY)
}

/// [`slope_bound`] over the points of the surface no further than `reach` from `o`
/// horizontally (grid units): a ray that asks only so far is clear if it climbs above it.
pub fn slope_bound_within(terrain: &Terrain, o: DVec3, sector: Option<Sector>, reach: f64) -> f64 {
    let (cell, near) = match near_rise(terrain, o, sector.as_ref()) {
        Some(near) => near,
        None => return f64::INFINITY,
    };
    let field = terrain.field();
    let (cells_x, cells_y) = (field.width() - 1, field.height() - 1);
    let mut search = Search {
        terrain,
        o,
        cell,
        near,
        cells: (cells_x, cells_y),
        sector,
        reach,
        best: 0.0,
    };
    let top = terrain.mipmap().top();
    search.block(top, 0, 0);
    let bound = search.best.min(terrain.max_slope());
    bound * (1.0 + ROOM) + ROOM
}

/// Whether no point of the surface within `reach` of `o` horizontally (grid units) lies
/// above `o`: then every rising ray from `o` that asks only so far is open. From the highest
/// samples of the 2x2 mipmap blocks, at least `2 * reach` wide, that hold every such point.
pub fn level_within(terrain: &Terrain, o: DVec3, reach: f64) -> bool {
    let (_, z_max) = terrain.z_range();
    if z_max <= o.z {
        return true;
    }
    let top = terrain.mipmap().top();
    let Some(k) = (1..top).find(|&k| f64::from(1u32 << k) >= 2.0 * reach) else {
        return false;
    };
    let field = terrain.field();
    let cells = |c: f64, n: usize| {
        let cell = |x: f64| (x.floor().max(0.0) as usize).min(n - 1) >> k;
        cell(c - reach)..=cell(c + reach)
    };
    let (xs, ys) = (
        cells(o.x, field.width() - 1),
        cells(o.y, field.height() - 1),
    );
    ys.flat_map(|bj| xs.clone().map(move |bi| (bi, bj)))
        .all(|(bi, bj)| field.height_of(terrain.block_max_sample(k, bi, bj)) <= o.z)
}

/// The cell of `o` (a point inside the map) and how fast the surface rises from `o` within
/// the 3x3 cells around it (a convex region holding every point within a cell's width of
/// `o`): no faster than the steepest of their triangles along the sector's azimuths. `None`
/// where `o` lies below the surface.
fn near_rise(
    terrain: &Terrain,
    o: DVec3,
    sector: Option<&Sector>,
) -> Option<((usize, usize), f64)> {
    let field = terrain.field();
    let (cells_x, cells_y) = (field.width() - 1, field.height() - 1);
    let cell = (
        (o.x.max(0.0) as usize).min(cells_x - 1),
        (o.y.max(0.0) as usize).min(cells_y - 1),
    );
    let surface = surface_height(terrain, cell, o);
    if o.z < surface - ROOM * (1.0 + surface.abs()) {
        return None;
    }
    Some((cell, near_slope(terrain, cell, (cells_x, cells_y), sector)))
}

/// Whether direction `d` climbs strictly more steeply than `slope` (a [`slope_bound`]).
pub fn climbs_above(d: DVec3, slope: f64) -> bool {
    // (Not `hypot`: a unit direction cannot overflow; the bound's room covers the rounding.)
    d.z > 0.0 && d.z > slope * (d.x * d.x + d.y * d.y).sqrt()
}

/// The height of the surface at `o`'s horizontal position, on cell `(i, j)` (a position off
/// the cell is taken at the cell's nearest point).
fn surface_height(terrain: &Terrain, (i, j): (usize, usize), o: DVec3) -> f64 {
    let within = |x: f64, c: usize| (x - c as f64).clamp(0.0, 1.0);
    terrain
        .field()
        .surface_z((i, j), (within(o.x, i), within(o.y, j)))
}

/// How fast the steepest triangle of the (up to) 3x3 cells around `cell` rises along the
/// azimuths of `sector` (any azimuth without one).
fn near_slope(
    terrain: &Terrain,
    (i, j): (usize, usize),
    (nx, ny): (usize, usize),
    sector: Option<&Sector>,
) -> f64 {
    let mut steepest = 0.0f64;
    for cj in j.saturating_sub(1)..(j + 2).min(ny) {
        for ci in i.saturating_sub(1)..(i + 2).min(nx) {
            let heights = terrain.corner_heights(ci, cj);
            for triangle in 0..2 {
                let g = DVec2::from(gradient(triangle, heights));
                let rise = match sector {
                    Some(sector) => sector.steepest_rise(g),
                    None => g.length(),
                };
                steepest = steepest.max(rise);
            }
        }
    }
    steepest
}

/// The search over the mipmap's blocks.
struct Search<'a> {
    terrain: &'a Terrain,
    o: DVec3,
    cell: (usize, usize),
    near: f64,
    cells: (usize, usize),
    sector: Option<Sector>,
    /// Blocks further than this from `o` horizontally are left out.
    reach: f64,
    best: f64,
}

impl Search<'_> {
    /// Raises `best` to the bound of block `(bi, bj)` of level `k`, looking through it at its
    /// children where the point is too close for its own bound to be useful.
    fn block(&mut self, k: u32, bi: usize, bj: usize) {
        let (x0, y0) = (bi << k, bj << k);
        if x0 >= self.cells.0 || y0 >= self.cells.1 {
            return;
        }
        let x1 = ((bi + 1) << k).min(self.cells.0);
        let y1 = ((bj + 1) << k).min(self.cells.1);
        let highest = self
            .terrain
            .field()
            .height_of(self.terrain.block_max_sample(k, bi, bj));
        let rise = highest - self.o.z;
        if rise <= 0.0 {
            return;
        }
        let dx = (x0 as f64 - self.o.x).max(self.o.x - x1 as f64).max(0.0);
        let dy = (y0 as f64 - self.o.y).max(self.o.y - y1 as f64).max(0.0);
        // (Not `hypot`: its care for overflow costs a tenth of a sky-lit frame.)
        let distance = (dx * dx + dy * dy).sqrt();
        if distance > self.reach {
            return;
        }
        if let Some(sector) = self.sector.filter(|_| distance > 0.0) {
            let (x0, y0, x1, y1) = (x0 as f64, y0 as f64, x1 as f64, y1 as f64);
            let o = DVec2::new(self.o.x, self.o.y);
            let corners =
                [(x0, y0), (x1, y0), (x0, y1), (x1, y1)].map(|(x, y)| DVec2::new(x, y) - o);
            if !sector.may_hold_all(&corners) {
                return;
            }
        }
        // Refining only lowers a block's bound: one already below the best needs no look.
        if distance > 0.0 && rise / distance <= self.best {
            return;
        }
        if k == 0 {
            let (ci, cj) = self.cell;
            let neighbour = bi.abs_diff(ci) <= 1 && bj.abs_diff(cj) <= 1;
            // Cells outside the 3x3 around the point lie at least a cell's width away.
            let bound = if neighbour {
                self.near
            } else {
                rise / distance
            };
            self.best = self.best.max(bound);
            return;
        }
        if distance >= REFINE * f64::from(1u32 << k) {
            self.best = self.best.max(rise / distance);
            return;
        }
        for (ci, cj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            self.block(k - 1, 2 * bi + ci, 2 * bj + cj);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::Heightfield;

    /// A `w x h` terrain of random samples below 200 (heights below 100) from `seed`, and the
    /// generator, which goes on from there.
    fn random_terrain(w: usize, h: usize, mut state: u64) -> (Terrain, impl FnMut() -> u64) {
        let mut next = move || {
            state = super::super::sampling::mix(state);
            state
        };
        let samples: Vec<u16> = (0..w * h).map(|_| (next() % 200) as u16).collect();
        let field = Heightfield::from_fn(w, h, 255, 127.5, |x, y| samples[y * w + x]);
        (Terrain::new(field.expect("a valid size")), next)
    }

    /// A random field and random points on it: no sample rises above the bound's slope from
    /// the point (the bound against brute force over every sample).
    #[test]
    fn bound_holds_over_every_sample() {
        let (w, h) = (40usize, 33usize);
        let (terrain, mut next) = random_terrain(w, h, 12345);
        for _ in 0..200 {
            let (x, y) = (
                (next() % 10_000) as f64 / 10_000.0 * (w - 1) as f64,
                (next() % 10_000) as f64 / 10_000.0 * (h - 1) as f64,
            );
            let cell = ((x as usize).min(w - 2), (y as usize).min(h - 2));
            let o = DVec3::new(x, y, surface_height(&terrain, cell, DVec3::new(x, y, 0.0)));
            let bound = slope_bound(&terrain, o, None);
            let field = terrain.field();
            for j in 0..h {
                for i in 0..w {
                    let r = (i as f64 - x).hypot(j as f64 - y);
                    if r > 0.0 {
                        let slope = (field.z(i, j) - o.z) / r;
                        assert!(
                            slope <= bound,
                            "({x}, {y}) to ({i}, {j}): {slope} > {bound}"
                        );
                    }
                }
            }
        }
    }

    /// The bound of each of 16 sectors against brute force: no sample, and no point on a
    /// triangle of the 3x3 cells around the start, in the sector rises above its slope.
    #[test]
    fn sector_bound_holds_over_every_sample_in_the_sector() {
        let (w, h) = (30usize, 27usize);
        let (terrain, mut next) = random_terrain(w, h, 777);
        let unit = |n: u64| (n % 100_000) as f64 / 100_000.0;
        for _ in 0..100 {
            let (x, y) = (unit(next()) * (w - 1) as f64, unit(next()) * (h - 1) as f64);
            let cell = ((x as usize).min(w - 2), (y as usize).min(h - 2));
            let o = DVec3::new(x, y, surface_height(&terrain, cell, DVec3::new(x, y, 0.0)));
            for k in 0..16 {
                let bound = slope_bound(&terrain, o, Some(Sector::nth(k, 16)));
                let check = |q: DVec3| {
                    let r = (q.x - x).hypot(q.y - y);
                    if r > 1e-12 && sector_of(q - o, 16) == k {
                        let slope = (q.z - o.z) / r;
                        assert!(
                            slope <= bound,
                            "({x}, {y}) to {q} in {k}: {slope} > {bound}"
                        );
                    }
                };
                let field = terrain.field();
                for j in 0..h {
                    for i in 0..w {
                        check(DVec3::new(i as f64, j as f64, field.z(i, j)));
                    }
                }
                for _ in 0..200 {
                    let (qx, qy) = (x - 1.0 + 3.0 * unit(next()), y - 1.0 + 3.0 * unit(next()));
                    let (qx, qy) = (qx.clamp(0.0, (w - 1) as f64), qy.clamp(0.0, (h - 1) as f64));
                    let c = ((qx as usize).min(w - 2), (qy as usize).min(h - 2));
                    let z = surface_height(&terrain, c, DVec3::new(qx, qy, 0.0));
                    check(DVec3::new(qx, qy, z));
                }
            }
        }
    }
}
