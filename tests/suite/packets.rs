//! Packets: neighbouring rays walked down the mipmap together (`clear_packet`,
//! `trace_packets`). Each ray's answer is the one its own walk gives (hit, cell, triangle,
//! the bits of `t` and of the point), on packets whose rays straddle octants, run along grid
//! lines and through lattice points; no ray's walk starts past its first hit by the exact
//! reference; every SIMD path answers alike; and a rendered image is the same byte for byte.

use crate::common::describe;
use crate::common::families::{self, hash, integer_hills, ray, terrain};
use crate::common::random::Rng;
use crate::common::reference::{q, solve};
use heightray::bench::sized_scene;
use heightray::heightfield::landscape;
use heightray::render::{Culling, Frame, Renderer, Shader};
use heightray::traverse::{clear_packet_on, trace_packets, Clearance, SimdPath, LANES};
use heightray::{trace, Arith, Method, Ray, Terrain, Trace, TraceOptions};

/// A ray's answer down to the bits: hit `t`, cell, triangle and point.
type Bits = Option<(u64, [usize; 2], u8, [u64; 3])>;

fn bits(trace: &Trace) -> Bits {
    let hit = trace.hit.as_ref()?;
    Some((
        hit.t.to_bits(),
        hit.cell,
        hit.triangle,
        hit.point.map(f64::to_bits),
    ))
}

/// Holds each ray's answer in packets of its neighbours in `rays` to its answer alone, for
/// both hierarchical methods. Returns how many rays the packets moved the start of.
fn assert_packets_agree(name: &str, terrain: &Terrain, rays: &[Ray]) -> usize {
    for method in [Method::Mipmap, Method::HierarchicalRuns] {
        let alone = TraceOptions::new(method, Arith::F64);
        let packed = TraceOptions {
            packets: true,
            ..alone
        };
        let traces = trace_packets(terrain, rays, &packed);
        for (ray, got) in rays.iter().zip(&traces) {
            let want = trace(terrain, ray, &alone);
            assert_eq!(bits(got), bits(&want), "{name} {method}: {}", describe(ray));
        }
    }
    let moved = |c: &Option<Clearance>| c.is_some_and(|c| c.t > 0.0);
    rays.chunks(LANES)
        .map(|packet| {
            let cleared = clear_packet_on(SimdPath::detected(), terrain, packet, None);
            cleared.lanes[..packet.len()]
                .iter()
                .filter(|c| moved(c))
                .count()
        })
        .sum()
}

/// An integer in `lo..=hi`, as a float.
fn int(r: &mut Rng, lo: i64, hi: i64) -> f64 {
    (lo + r.below((hi - lo + 1) as usize) as i64) as f64
}

/// A tile of 4x2 rays from one eye, around a direction that is, by `kind`: anywhere; near an
/// axis or a diagonal of the grid, so that the tile straddles octants; or an integer
/// direction from a lattice point, whose rays pass through lattice points and along grid
/// lines.
fn tile(r: &mut Rng, terrain: &Terrain, kind: u32) -> Vec<Ray> {
    let field = terrain.field();
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let (_, z_hi) = terrain.z_range();
    let target = [r.within(0.0, w), r.within(0.0, h), 0.0];
    let eye = match kind {
        3 => [
            int(r, -2, w as i64 + 2),
            int(r, -2, h as i64 + 2),
            int(r, 1, z_hi as i64 + 3),
        ],
        _ => [
            r.within(-0.3 * w, 1.3 * w),
            r.within(-0.3 * h, 1.3 * h),
            r.within(0.5 * z_hi, 2.0 * z_hi),
        ],
    };
    let mut base = [0, 1, 2].map(|k| target[k] - eye[k]);
    let spread = match kind {
        1 => {
            // Along an axis: the tile's rays go both ways across it.
            base[int(r, 0, 1) as usize] = 0.0;
            0.02
        }
        2 => {
            // Along a diagonal: u and v swap across the tile.
            base[1] = base[0].abs() * base[1].signum();
            0.02
        }
        _ => r.within(0.001, 0.05),
    };
    let length = (base[0].powi(2) + base[1].powi(2) + base[2].powi(2)).sqrt();
    (0..LANES)
        .map(|l| {
            let (a, b) = ((l % 4) as f64 - 1.5, (l / 4) as f64 - 0.5);
            let d = if kind == 3 {
                // Small integer directions: dyadic steps through lattice points.
                [
                    base[0].round() + a,
                    base[1].round() + 2.0 * b,
                    -int(r, 1, 4),
                ]
            } else {
                [
                    base[0] + spread * length * a,
                    base[1] + spread * length * b,
                    base[2],
                ]
            };
            ray(eye, d)
        })
        .collect()
}

/// Terrains of every kind the walk meets: random integer hills, a plateau, fractal land with
/// several mipmap levels, and a field of uneven sides.
fn terrains() -> Vec<(&'static str, Terrain)> {
    vec![
        ("hilly", families::hilly()),
        ("integer hills 33", integer_hills(33, 33, 9, 4)),
        ("integer hills 70x21", integer_hills(70, 21, 40, 8)),
        (
            "terraces 40",
            terrain(40, 40, 255, 25.5, |x, y| {
                20 * (hash(x / 6, y / 6, 3, 8) + 1)
            }),
        ),
        (
            "landscape 129",
            Terrain::new(landscape(129, 7, 24.0).expect("a landscape")),
        ),
    ]
}

#[test]
fn packets_answer_as_single_rays_on_the_ray_families() {
    // Each family's rays in packets of eight neighbours: mixed octants, grid lines, lattice
    // points, vertical rays, rays starting on or under the surface.
    for family in families::all() {
        assert_packets_agree(&family.name, &family.terrain, &family.rays);
    }
}

#[test]
fn packets_answer_as_single_rays_on_random_tiles() {
    let mut r = Rng(0x5DEE_CE66_D1CE_4E5B);
    let (mut rays, mut moved) = (0, 0);
    for (name, terrain) in terrains() {
        for n in 0..160 {
            let tile = tile(&mut r, &terrain, n % 4);
            rays += tile.len();
            moved += assert_packets_agree(&format!("{name} tile {n}"), &terrain, &tile);
        }
    }
    // The packets did walk: many rays start their own walk later than at their start (the
    // others start next to the surface, or inside the terrain's box).
    assert!(3 * moved > rays, "packets moved {moved} of {rays} starts");
}

#[test]
fn no_ray_of_a_packet_starts_past_its_first_hit() {
    let mut r = Rng(0x2545_F491_4F6C_DD1D);
    for (name, terrain) in terrains() {
        for n in 0..40 {
            let tile = tile(&mut r, &terrain, n % 4);
            let cleared = clear_packet_on(SimdPath::detected(), &terrain, &tile, None);
            for (ray, lane) in tile.iter().zip(cleared.lanes) {
                let Some(Clearance { t, .. }) = lane else {
                    continue;
                };
                let Some(hit) = solve(terrain.field(), ray).hit else {
                    continue;
                };
                let at = format!("{name} tile {n}: {}", describe(ray));
                assert!(q(t) <= hit.t, "{at} hits at {}, cleared to {t}", hit.t);
            }
        }
    }
}

#[test]
fn every_simd_path_clears_alike() {
    let mut r = Rng(0x9E37_79B9_7F4A_7C15);
    let paths = [SimdPath::Scalar, SimdPath::Avx2, SimdPath::Avx512];
    for (name, terrain) in terrains() {
        for n in 0..60 {
            let tile = tile(&mut r, &terrain, n % 4);
            let scalar = clear_packet_on(SimdPath::Scalar, &terrain, &tile, None);
            for path in paths.into_iter().filter(|&p| p <= SimdPath::detected()) {
                let got = clear_packet_on(path, &terrain, &tile, None);
                assert_eq!(got, scalar, "{name} tile {n} on {path}");
            }
        }
    }
}

#[test]
fn images_are_the_same_with_packets() {
    for (samples, size) in [(65, 96), (513, 128)] {
        let scene = sized_scene(samples, size).expect("a sized scene");
        let terrain = Terrain::new(scene.field.clone());
        let renderer = Renderer {
            shader: Shader::new(&terrain, scene.lighting, Method::Mipmap, Culling::default()),
            camera: scene.camera,
            arith: Arith::F64,
        };
        let (w, h) = scene.camera.size();
        let (mut packed, mut single) = (Frame::new(w, h), Frame::new(w, h));
        renderer.render_in_packets(&mut packed);
        renderer.render(&mut single);
        assert!(
            packed.pixels == single.pixels,
            "valley{samples}: images differ"
        );
        assert_eq!(packed.totals.primary_hits, single.totals.primary_hits);
        // The packets' node tests replace some of the rays' own block tests.
        assert_ne!(packed.totals.primary.block, single.totals.primary.block);
    }
}
