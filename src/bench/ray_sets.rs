//! Sets of rays to measure on: a scene's camera rays and rays towards its sun, and generated
//! numerically hard rays (through lattice points, along grid lines and cell diagonals,
//! grazing flat plateaus, near-vertical, long and shallow, random).

use crate::arith::Arith;
use crate::geometry::Ray;
use crate::heightfield::{landscape, Heightfield, Terrain};
use crate::render::Scene;
use crate::traverse::{trace, Method, TraceOptions};

/// A scene's camera rays, and rays from where they hit (found in `f64`, lifted by a
/// relative 1e-9) towards the sun: the shadow rays of the scene, as plain first-hit queries
/// that every arithmetic answers for the same numbers.
pub fn scene_sets(name: &str, scene: &Scene) -> anyhow::Result<[RaySet; 2]> {
    let terrain = Terrain::new(scene.field.clone());
    let primary: Vec<Ray> = scene.camera.rays().collect();
    let options = TraceOptions::new(Method::Runs, Arith::F64);
    let mut sun = Vec::new();
    for ray in &primary {
        if let Some(hit) = trace(&terrain, ray, &options).hit {
            let [x, y, z] = hit.point;
            sun.push(Ray::new(
                [x, y, z + 1e-9 * z.abs().max(1.0)],
                scene.lighting.sun,
            )?);
        }
    }
    Ok([
        RaySet {
            name: format!("{name}: camera rays"),
            terrain: terrain.clone(),
            rays: primary,
        },
        RaySet {
            name: format!("{name}: rays to the sun"),
            terrain,
            rays: sun,
        },
    ])
}

/// Rays of one kind on the terrain they are hard for.
pub struct RaySet {
    /// The set's name in reports.
    pub name: String,
    /// The terrain the rays are traced against.
    pub terrain: Terrain,
    /// The rays.
    pub rays: Vec<Ray>,
}

/// SplitMix64: a small deterministic generator (the sets must be the same in every run).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// Every hard-case set; `per_set` rays each (fewer for the long walks).
pub fn hard_cases(per_set: usize) -> anyhow::Result<Vec<RaySet>> {
    let hills = landscape(65, 3, 20.0)?;
    let z = |f: &Heightfield, i: usize, j: usize| f.z(i, j);
    let mut rng = Rng(2024);
    let mut sets = Vec::new();

    // Rays that pass exactly through a vertex, with rational slopes in every octant.
    let slopes = [(0, 1), (1, 1), (1, 2), (2, 3), (17, 41), (41, 17), (3, 7)];
    let mut rays = Vec::new();
    for k in 0..per_set {
        let (p, q) = slopes[k % slopes.len()];
        let (sx, sy) = (
            if k & 8 == 0 { 1.0 } else { -1.0 },
            if k & 16 == 0 { 1.0 } else { -1.0 },
        );
        let (i, j) = (8 + rng.below(49) as usize, 8 + rng.below(49) as usize);
        let dir = [sx * q as f64, sy * p as f64, -rng.range(0.5, 4.0)];
        let s = rng.range(1.0, 6.0).round();
        let at = [i as f64, j as f64, z(&hills, i, j)];
        rays.push(ray(
            [at[0] - s * dir[0], at[1] - s * dir[1], at[2] - s * dir[2]],
            dir,
        )?);
    }
    sets.push(RaySet {
        name: "lattice points".into(),
        terrain: Terrain::new(hills.clone()),
        rays,
    });

    // Along grid lines (x = i or y = j) and along cell diagonals, descending.
    let mut rays = Vec::new();
    for k in 0..per_set {
        let line = 1.0 + rng.below(63) as f64;
        let dz = -rng.range(0.02, 0.3);
        let (origin, dir) = match k % 4 {
            0 => ([-2.0, line, 25.0], [1.0, 0.0, dz]),
            1 => ([line, 66.0, 25.0], [0.0, -1.0, dz]),
            2 => ([-2.0, line - 2.0, 25.0], [1.0, 1.0, dz]),
            _ => ([66.0, line + 2.0, 25.0], [-1.0, -1.0, dz]),
        };
        rays.push(ray(origin, dir)?);
    }
    sets.push(RaySet {
        name: "grid lines and diagonals".into(),
        terrain: Terrain::new(hills.clone()),
        rays,
    });

    // Level rays exactly at the height of a terrace: they graze flat plateaus.
    let levels = 6u16;
    let terraces = Heightfield::from_fn(65, 65, 65535, 20.0, |i, j| {
        let step = 65535 / levels;
        hills.sample(i, j) / step * step
    })?;
    let mut rays = Vec::new();
    for _ in 0..per_set {
        let level = 1 + rng.below(u64::from(levels) - 1) as u16;
        let height = terraces.height_of(level * (65535 / levels));
        let angle = rng.range(0.0, std::f64::consts::TAU);
        let (c, s) = (angle.cos(), angle.sin());
        rays.push(ray(
            [32.0 - 40.0 * c, 32.0 - 40.0 * s, height],
            [c, s, 0.0],
        )?);
    }
    sets.push(RaySet {
        name: "grazing plateaus".into(),
        terrain: Terrain::new(terraces),
        rays,
    });

    // Straight down but for 1e-12 sideways.
    let mut rays = Vec::new();
    for _ in 0..per_set {
        let angle = rng.range(0.0, std::f64::consts::TAU);
        let origin = [rng.range(0.0, 64.0), rng.range(0.0, 64.0), 30.0];
        rays.push(ray(
            origin,
            [1e-12 * angle.cos(), 1e-12 * angle.sin(), -1.0],
        )?);
    }
    sets.push(RaySet {
        name: "near-vertical".into(),
        terrain: Terrain::new(hills.clone()),
        rays,
    });

    // Long shallow walks over a 16384-cell strip towards a spike at its far end.
    let strip = Heightfield::from_fn(16385, 3, 255, 10.0, |i, _| if i == 16380 { 255 } else { 0 })?;
    let mut rays = Vec::new();
    for _ in 0..per_set.div_ceil(8) {
        let (y0, y1) = (rng.range(0.05, 0.95), rng.range(1.05, 1.95));
        rays.push(ray([-0.5, y0, 9.0], [16380.5, y1 - y0, -4.0])?);
    }
    sets.push(RaySet {
        name: "long shallow (16384 cells)".into(),
        terrain: Terrain::new(strip),
        rays,
    });

    // Random rays from above.
    let mut rays = Vec::new();
    for _ in 0..per_set {
        let origin = [
            rng.range(-10.0, 74.0),
            rng.range(-10.0, 74.0),
            rng.range(5.0, 40.0),
        ];
        let target = [
            rng.range(0.0, 64.0),
            rng.range(0.0, 64.0),
            rng.range(0.0, 10.0),
        ];
        rays.push(ray(origin, [0, 1, 2].map(|k| target[k] - origin[k]))?);
    }
    sets.push(RaySet {
        name: "random".into(),
        terrain: Terrain::new(hills),
        rays,
    });
    Ok(sets)
}

fn ray(origin: [f64; 3], dir: [f64; 3]) -> anyhow::Result<Ray> {
    Ok(Ray::new(origin, dir)?)
}
