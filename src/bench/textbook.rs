//! A yardstick: the textbook max-mipmap walk (Tevs, Ihrke & Seidel 2008) in plain `f64`, with
//! the Möller–Trumbore triangle test, against heightray's own mipmap walk in `f64` on the same
//! rays. It starts, descends and climbs as heightray's walk does, so it makes about the same
//! block and cell queries; what it leaves out is what makes heightray's answers exact: the
//! slack for rounding, the lattice points (a path through a grid corner goes on diagonally,
//! past the two cells beside it), the watertight triangle test and the octant frame. So the
//! ratio of the two times is what those guarantees cost a ray. It is not a method: it misses
//! hits at lattice points and on level ground a ray grazes (see [`hard_cases_versus_exact`]).

use super::ray_sets::{hard_cases, RaySet};
use crate::arith::Arith;
use crate::render::timing::{fastest, timed};
use crate::render::Scene;
use crate::traverse::{trace, Method, TraceOptions};
use crate::{Ray, Terrain};
use std::time::Duration;

/// Rounds of the two walks, alternating, each timed as the fastest of its runs in
/// [`ROUND_TIME`]: a disturbance of the shared machine then spoils neither walk's every run.
const ROUNDS: usize = 3;
const ROUND_TIME: Duration = Duration::from_millis(500);

/// The two walks measured on a scene's camera rays, one thread.
#[derive(Clone, Debug)]
pub struct TextbookRow {
    /// Camera rays traced (one per pixel).
    pub rays: u64,
    /// Rays that hit the terrain (heightray's answers).
    pub hits: u64,
    /// heightray's block and cell queries per ray.
    pub heightray_queries: f64,
    /// The textbook walk's block and cell steps per ray.
    pub textbook_queries: f64,
    /// heightray's walk over all the rays, one after the other: the fastest run.
    pub heightray_time: Duration,
    /// The textbook walk over all the rays, one after the other: the fastest run.
    pub textbook_time: Duration,
    /// Rays whose answers differ: a hit against a miss, or `t` off by more than a relative
    /// 1e-9.
    pub differing: u64,
}

/// Traces every camera ray of `scene` with both walks (heightray's without the wedge
/// clearances the renderer adds, as the textbook walk has none).
pub fn versus_textbook(scene: &Scene, terrain: &Terrain) -> TextbookRow {
    let rays: Vec<Ray> = scene.camera.rays().collect();
    let options = TraceOptions::new(Method::Mipmap, Arith::F64);
    let textbook = Textbook::new(terrain);
    // One walk over every ray: its answers and its queries, timed.
    let run = |walk: &dyn Fn(&Ray) -> (Option<f64>, u64)| {
        timed(|| {
            let mut queries = 0;
            let mut answer = |ray| {
                let (t, asked) = walk(ray);
                queries += asked;
                t
            };
            let answers: Vec<Option<f64>> = rays.iter().map(&mut answer).collect();
            (answers, queries)
        })
    };
    let heightray = |ray: &Ray| {
        let t = trace(terrain, ray, &options);
        let queries = t.counters.block.total() + t.counters.cell.total();
        (t.hit.map(|hit| hit.t), queries)
    };
    let textbook = |ray: &Ray| {
        let (t, steps) = textbook.first_hit(ray);
        (t, u64::from(steps))
    };
    let (heightray_run, textbook_run) = (|| run(&heightray), || run(&textbook));
    let (mut heightray_time, mut textbook_time) = (Duration::MAX, Duration::MAX);
    let (mut ours, mut theirs) = ((Vec::new(), 0), (Vec::new(), 0));
    for _ in 0..ROUNDS {
        let round = fastest(ROUND_TIME, heightray_run);
        (heightray_time, ours) = (heightray_time.min(round.fastest), round.out);
        let round = fastest(ROUND_TIME, textbook_run);
        (textbook_time, theirs) = (textbook_time.min(round.fastest), round.out);
    }
    let differing = ours
        .0
        .iter()
        .zip(&theirs.0)
        .filter(|(a, b)| differ(**a, **b));
    let per_ray = |n: u64| n as f64 / rays.len().max(1) as f64;
    TextbookRow {
        rays: rays.len() as u64,
        hits: ours.0.iter().flatten().count() as u64,
        heightray_queries: per_ray(ours.1),
        textbook_queries: per_ray(theirs.1),
        heightray_time,
        textbook_time,
        differing: differing.count() as u64,
    }
}

/// Whether two answers in `f64` differ: a hit against a miss, or `t` off by more than a
/// relative 1e-9.
fn differ(a: Option<f64>, b: Option<f64>) -> bool {
    differ_by(a, b, 1e-9)
}

/// Whether two answers differ: a hit against a miss, or `t` off by more than a relative
/// `tolerance`.
pub(super) fn differ_by(a: Option<f64>, b: Option<f64>, tolerance: f64) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() > tolerance * a.abs().max(1.0),
        (a, b) => a.is_some() != b.is_some(),
    }
}

/// One set of numerically hard rays: how many answers of each of two tracers differ from
/// heightray's exact answers.
#[derive(Clone, Debug)]
pub struct HardCaseRow {
    /// The set's name.
    pub set: String,
    /// Rays in the set.
    pub rays: u64,
    /// Answers of each of the two tracers that differ from exact, in the tracers' order.
    pub differing: [u64; 2],
}

/// A tracer's answer for a ray: the `t` of its first hit, if any.
pub type Answer<'a> = Box<dyn Fn(&Ray) -> Option<f64> + 'a>;

/// The hard-case sets of the accuracy benchmark ([`hard_cases`], `per_set` rays each), every
/// ray answered by the two tracers `tracers` makes for its set and by heightray's mipmap walk
/// in exact arithmetic: how many answers of each differ from exact (a hit against a miss, or
/// `t` off by more than a relative `tolerance`).
pub fn hard_cases_against_exact(
    per_set: usize,
    tolerance: f64,
    tracers: impl for<'a> Fn(&'a RaySet) -> anyhow::Result<[Answer<'a>; 2]>,
) -> anyhow::Result<Vec<HardCaseRow>> {
    let exact = TraceOptions::new(Method::Mipmap, Arith::Exact);
    let mut rows = Vec::new();
    for set in hard_cases(per_set)? {
        let answers = tracers(&set)?;
        let mut differing = [0, 0];
        for ray in &set.rays {
            let reference = trace(&set.terrain, ray, &exact).hit.map(|hit| hit.t);
            for (count, answer) in differing.iter_mut().zip(&answers) {
                *count += u64::from(differ_by(answer(ray), reference, tolerance));
            }
        }
        rows.push(HardCaseRow {
            set: set.name.clone(),
            rays: set.rays.len() as u64,
            differing,
        });
    }
    Ok(rows)
}

/// The hard-case sets answered by heightray's mipmap walk and by the textbook walk, both in
/// `f64`, against exact (answers differ by more than a relative 1e-9 in `t`).
pub fn hard_cases_versus_exact(per_set: usize) -> anyhow::Result<Vec<HardCaseRow>> {
    hard_cases_against_exact(per_set, 1e-9, |set| {
        let textbook = Textbook::new(&set.terrain);
        Ok([
            mipmap_in(set, Arith::F64),
            Box::new(move |ray| textbook.first_hit(ray).0),
        ])
    })
}

/// heightray's mipmap walk in `arith`, answering a set's rays.
pub(super) fn mipmap_in(set: &RaySet, arith: Arith) -> Answer<'_> {
    let options = TraceOptions::new(Method::Mipmap, arith);
    Box::new(move |ray| trace(&set.terrain, ray, &options).hit.map(|hit| hit.t))
}

/// The textbook walk over one terrain.
pub struct Textbook<'a> {
    terrain: &'a Terrain,
    /// The last cell index along x and y.
    last: (i64, i64),
    /// Height of sample value 0, and of one step of sample value.
    base: f64,
    unit: f64,
}

impl<'a> Textbook<'a> {
    /// The textbook walk over `terrain`'s mipmap.
    pub fn new(terrain: &'a Terrain) -> Self {
        let field = terrain.field();
        Textbook {
            terrain,
            last: (field.width() as i64 - 2, field.height() as i64 - 2),
            base: field.height_of(0),
            unit: field.step(),
        }
    }

    /// The ray's first hit `t`, if any, and the block and cell steps the walk took.
    pub fn first_hit(&self, ray: &Ray) -> (Option<f64>, u32) {
        let (o, d) = (ray.origin(), ray.dir());
        let Some((t0, t1)) = self.clip(o, d) else {
            return (None, 0);
        };
        // A cell's index is its point's coordinate truncated (which floors the coordinates
        // inside the grid) and clamped to the grid (a point rounded just outside is in the
        // edge cell).
        let inv = [0, 1].map(|axis| 1.0 / d[axis]);
        let start = |axis: usize, last: i64| ((o[axis] + d[axis] * t0) as i64).clamp(0, last);
        let (mut ci, mut cj) = (start(0, self.last.0), start(1, self.last.1));
        let forward = (d[0] >= 0.0, d[1] >= 0.0);
        // Heights in sample units, compared with the samples as they are stored.
        let (oz, dz) = ((o[2] - self.base) / self.unit, d[2] / self.unit);
        let top = self.terrain.mipmap().top();
        let mut k = top.saturating_sub(3);
        let mut t = t0;
        let mut steps = 0;
        loop {
            steps += 1;
            let (bx, by) = (ci >> k, cj >> k);
            // Where the path leaves the block, through the face it crosses first.
            let face = |b: i64, forward: bool| ((b + i64::from(forward)) << k) as f64;
            let leave = |axis: usize, face: f64| {
                if d[axis] == 0.0 {
                    f64::INFINITY
                } else {
                    (face - o[axis]) * inv[axis]
                }
            };
            let (tx, ty) = (leave(0, face(bx, forward.0)), leave(1, face(by, forward.1)));
            let exit = tx.min(ty).min(t1);
            let lowest = oz + dz * if dz < 0.0 { exit } else { t };
            let highest = self.terrain.block_max_sample(k, bx as usize, by as usize);
            if lowest <= f64::from(highest) {
                if k > 0 {
                    k -= 1;
                    continue;
                }
                if let Some(hit) = self.triangles(o, d, ci as usize, cj as usize) {
                    return (Some(hit), steps);
                }
            }
            if exit >= t1 {
                return (None, steps);
            }
            // Into the next block: across the face crossed (both at a corner), the other
            // index where the path is, kept inside the block and from stepping back.
            let next = |b: i64, forward: bool| if forward { (b + 1) << k } else { (b << k) - 1 };
            let along = |c: i64, b: i64, forward: bool, axis: usize| {
                let at = ((o[axis] + d[axis] * exit) as i64).clamp(b << k, ((b + 1) << k) - 1);
                if forward {
                    at.max(c)
                } else {
                    at.min(c)
                }
            };
            let (ni, nj) = (
                if tx <= ty {
                    next(bx, forward.0)
                } else {
                    along(ci, bx, forward.0, 0)
                },
                if ty <= tx {
                    next(by, forward.1)
                } else {
                    along(cj, by, forward.1, 1)
                },
            );
            if ni < 0 || nj < 0 || ni > self.last.0 || nj > self.last.1 {
                return (None, steps);
            }
            // Up a level into a new parent block; a climbing ray always (its lowest point in
            // a block moves with it).
            let new_parent = ni >> (k + 1) != ci >> (k + 1) || nj >> (k + 1) != cj >> (k + 1);
            if k < top && (new_parent || dz >= 0.0) {
                k += 1;
            }
            (ci, cj, t) = (ni, nj, exit);
        }
    }

    /// The part `[t0, t1]` of the ray inside the terrain's box (slabs), if any.
    fn clip(&self, o: [f64; 3], d: [f64; 3]) -> Option<(f64, f64)> {
        let (z_lo, z_hi) = self.terrain.z_range();
        let lo = [0.0, 0.0, z_lo];
        let hi = [(self.last.0 + 1) as f64, (self.last.1 + 1) as f64, z_hi];
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for k in 0..3 {
            if d[k] == 0.0 {
                if o[k] < lo[k] || o[k] > hi[k] {
                    return None;
                }
                continue;
            }
            let (a, b) = ((lo[k] - o[k]) / d[k], (hi[k] - o[k]) / d[k]);
            (t0, t1) = (t0.max(a.min(b)), t1.min(a.max(b)));
        }
        (t0 <= t1).then_some((t0, t1))
    }

    /// The nearer hit on the two triangles of cell `(i, j)` (the surface contract,
    /// [`crate::geometry`]), if any.
    fn triangles(&self, o: [f64; 3], d: [f64; 3], i: usize, j: usize) -> Option<f64> {
        if self.terrain.field().is_hole_cell(i, j) {
            return None;
        }
        let z = self.terrain.corner_heights(i, j);
        let (x0, y0) = (i as f64, j as f64);
        let p00 = [x0, y0, z[0]];
        let p10 = [x0 + 1.0, y0, z[1]];
        let p01 = [x0, y0 + 1.0, z[2]];
        let p11 = [x0 + 1.0, y0 + 1.0, z[3]];
        let first = moller_trumbore(o, d, [p00, p10, p11]);
        let second = moller_trumbore(o, d, [p00, p11, p01]);
        match (first, second) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

/// Möller & Trumbore (1997): where `o + t*d` meets the triangle, for `t >= 0`.
fn moller_trumbore(o: [f64; 3], d: [f64; 3], [a, b, c]: [[f64; 3]; 3]) -> Option<f64> {
    let sub = |p: [f64; 3], q: [f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let cross = |p: [f64; 3], q: [f64; 3]| {
        [
            p[1] * q[2] - p[2] * q[1],
            p[2] * q[0] - p[0] * q[2],
            p[0] * q[1] - p[1] * q[0],
        ]
    };
    let dot = |p: [f64; 3], q: [f64; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    let (e1, e2) = (sub(b, a), sub(c, a));
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det == 0.0 {
        return None;
    }
    let s = sub(o, a);
    let u = dot(s, p) / det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = cross(s, e1);
    let v = dot(d, q) / det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = dot(e2, q) / det;
    (t >= 0.0).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Heightfield;
    use std::path::Path;

    /// Hand-worked: a plane `z = x` over a 5x5 grid, and a ray straight down onto it, one
    /// falling along it, and one passing over it.
    #[test]
    fn hits_a_hand_worked_plane() {
        let field = Heightfield::from_fn(5, 5, 4, 4.0, |i, _| i as u16).unwrap();
        let terrain = Terrain::new(field);
        let walk = Textbook::new(&terrain);
        let ray = |o, d| Ray::new(o, d).unwrap();
        // Down from (2.5, 1.5, 10) onto z = 2.5: t = 7.5.
        let (t, _) = walk.first_hit(&ray([2.5, 1.5, 10.0], [0.0, 0.0, -1.0]));
        assert!((t.unwrap() - 7.5).abs() < 1e-12);
        // From (0, 2.2, 3) along -z and +x: x = t, z = 3 - t meet at t = 1.5.
        let (t, _) = walk.first_hit(&ray([0.0, 2.2, 3.0], [1.0, 0.0, -1.0]));
        assert!((t.unwrap() - 1.5).abs() < 1e-12);
        // Level at z = 4.5, above every sample.
        let (t, _) = walk.first_hit(&ray([-1.0, 2.2, 4.5], [1.0, 0.3, 0.0]));
        assert_eq!(t, None);
    }

    /// On rays that are not numerically hard it is a fair yardstick: the valley's camera rays
    /// (a coarse image of them) get the exact answers.
    #[test]
    fn answers_ordinary_rays_exactly() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/valley513.toml");
        let scene = Scene::load(&path).unwrap();
        let terrain = Terrain::new(scene.field.clone());
        let walk = Textbook::new(&terrain);
        let exact = TraceOptions::new(Method::Mipmap, Arith::Exact);
        let (mut hits, mut differing) = (0, 0);
        for (x, y) in (0..512)
            .step_by(16)
            .flat_map(|y| (0..512).step_by(16).map(move |x| (x, y)))
        {
            let ray = scene.camera.ray(x, y);
            let reference = trace(&terrain, &ray, &exact).hit.map(|hit| hit.t);
            hits += usize::from(reference.is_some());
            differing += usize::from(differ(walk.first_hit(&ray).0, reference));
        }
        assert!(hits > 500, "{hits} of 1024 rays hit");
        assert_eq!(differing, 0);
    }
}
