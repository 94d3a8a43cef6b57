//! Embree's scene is heightray's surface, and its packets answer as its single rays.

use super::*;
use crate::render::{Scene, SceneFile};
use crate::{trace, Arith, Method, TraceOptions};
use crate::{Heightfield, Ray, Terrain};
use std::path::Path;

/// Embree's scene is heightray's surface: the camera rays of every built-in scene hit the
/// same cell and triangle at the same `t` as heightray's exact answer (a 64x64 image
/// each), but for rays within `f32` rounding of an edge, where either neighbour may win.
#[test]
fn embree_hits_what_the_exact_trace_hits() {
    let exact = TraceOptions::new(Method::Mipmap, Arith::Exact);
    for (name, mut file) in SceneFile::builtins().unwrap() {
        file.size = Some((64, 64));
        let scene = Scene::from_file(&file, Path::new(""), Path::new(name)).unwrap();
        let terrain = Terrain::new(scene.field.clone());
        let embree = EmbreeScene::build(&terrain, Geometry::Triangles).unwrap();
        let (mut rays, mut hits, mut near_edges) = (0, 0, 0);
        for ray in scene.camera.rays() {
            rays += 1;
            let ours = trace(&terrain, &ray, &exact).hit;
            let theirs = embree.intersect(&ray);
            match (&ours, &theirs) {
                (Some(ours), Some(theirs))
                    if ours.cell == [theirs.cell.0, theirs.cell.1]
                        && ours.triangle == theirs.triangle =>
                {
                    hits += 1;
                    let off = (ours.t - theirs.t).abs() / ours.t;
                    assert!(off < 1e-5, "{name}: t {} against {}", ours.t, theirs.t);
                }
                (None, None) => {}
                _ => {
                    // Only where the exact hit point lies within rounding of a cell's
                    // or triangle's edge (the diagonal `x - i = y - j`).
                    let p = ours.as_ref().map(|h| h.point).or(theirs.map(|h| {
                        (DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * h.t).into()
                    }));
                    let [x, y, _] = p.unwrap();
                    let near = |v: f64| (v - v.round()).abs() < 1e-3;
                    let diagonal = (x - x.floor()) - (y - y.floor());
                    assert!(
                        near(x) || near(y) || diagonal.abs() < 1e-3,
                        "{name}: {ray:?}: exact {ours:?}, Embree {theirs:?}"
                    );
                    near_edges += 1;
                }
            }
        }
        assert!(hits > rays / 4, "{name}: {hits} of {rays} rays hit");
        assert!(near_edges * 100 < rays, "{name}: {near_edges} near edges");
    }
}

/// Embree's grid splits cells its own way, so on a tilted plane, where either diagonal
/// gives the same surface, its hits are heightray's exact ones: every ray from above
/// aimed at a point of the plane hits it there, at the cell and triangle under the point
/// (away from edges, where either neighbour may answer).
#[test]
fn grid_hits_a_plane_where_the_exact_trace_does() {
    // z = (3i + 2j) * 100 / 1000: a plane through every sample.
    let sample = |i: usize, j: usize| (3 * i + 2 * j) as u16;
    let field = Heightfield::from_fn(40, 30, 1000, 100.0, sample).unwrap();
    let terrain = Terrain::new(field);
    let grid = EmbreeScene::build(&terrain, Geometry::Grid).unwrap();
    let exact = TraceOptions::new(Method::Mipmap, Arith::Exact);
    for k in 0..200 {
        // Points inside cells, clear of their edges and diagonals.
        let (i, j) = (1 + k % 37, 1 + (k * 7) % 27);
        let (u, v) = if k % 2 == 0 { (0.7, 0.2) } else { (0.2, 0.7) };
        let (x, y) = (i as f64 + u, j as f64 + v);
        let target = [x, y, (3.0 * x + 2.0 * y) * 0.1];
        let dir = [0.3 - 0.01 * (k % 5) as f64, -0.2, -1.0];
        let origin = [0, 1, 2].map(|a| target[a] - 20.0 * dir[a]);
        let ray = Ray::new(origin, dir).unwrap();
        let ours = trace(&terrain, &ray, &exact).hit.unwrap();
        let theirs = grid.intersect(&ray).unwrap();
        assert_eq!(ours.cell, [i, j], "{ray:?}");
        assert_eq!([theirs.cell.0, theirs.cell.1], ours.cell, "{ray:?}");
        assert_eq!(theirs.triangle, ours.triangle, "{ray:?}");
        assert!(
            (theirs.t - 20.0).abs() < 1e-4 && (ours.t - 20.0).abs() < 1e-9,
            "{ray:?}"
        );
    }
    assert!(
        matches!(
            EmbreeScene::build(&terrain_with_hole(), Geometry::Grid),
            Err(EmbreeError::Holes)
        ),
        "a grid over no data is refused"
    );
}

/// A small terrain with one no-data sample.
fn terrain_with_hole() -> Terrain {
    let mut hole = crate::heightfield::NoDataMask::new(16);
    hole.insert(5);
    let maxval = crate::heightfield::Quantisation::Maxval(255);
    let field = Heightfield::new(4, 4, vec![5u16; 16], maxval, 1.0, Some(hole));
    Terrain::new(field.unwrap())
}

/// A shadow ray is blocked by the terrain exactly where heightray's exact trace says:
/// rays from above the highest sample down onto the terrain are occluded, rays rising
/// from above it are not.
#[test]
fn occlusion_follows_the_surface() {
    let field = crate::heightfield::landscape(33, 1, 8.0).unwrap();
    let terrain = Terrain::new(field);
    let embree = EmbreeScene::build(&terrain, Geometry::Triangles).unwrap();
    let (_, top) = terrain.z_range();
    for k in 0..64 {
        // Inside the grid, and still inside where the downward rays reach the ground.
        let (x, y) = (1.0 + 0.45 * k as f64, 29.0 - 0.36 * k as f64);
        let origin = [x, y, top + 1.0];
        assert!(embree.occluded(origin, [0.1, 0.2, -1.0]), "{origin:?} down");
        assert!(!embree.occluded(origin, [0.1, 0.2, 1.0]), "{origin:?} up");
    }
    assert!(embree.bytes() > 33 * 33 * 12, "{} bytes", embree.bytes());
}

/// The built-in scenes at `w x h` pixels, with Embree's scene of each terrain's triangles.
fn builtin_scenes(w: u32, h: u32) -> Vec<(Scene, Terrain, EmbreeScene)> {
    let scenes = SceneFile::builtins()
        .unwrap()
        .into_iter()
        .map(|(name, mut file)| {
            file.size = Some((w, h));
            let scene = Scene::from_file(&file, Path::new(""), Path::new(name)).unwrap();
            let terrain = Terrain::new(scene.field.clone());
            let embree = EmbreeScene::build(&terrain, Geometry::Triangles).unwrap();
            (scene, terrain, embree)
        });
    scenes.collect()
}

/// Every packet answer is the single-ray answer for the same ray: the same primitive (cell
/// and triangle) at the same `t` (to `f32` rounding: the packet kernels order their
/// arithmetic their own way), or a miss for a miss; the same occlusion for the shadow rays
/// from every hit. Rays go in packets of every count from 1 to `N`, so partial masks are
/// tested too.
fn packets_answer_as_single_rays<const N: usize>()
where
    ffi::Width<N>: ffi::Packet<N>,
{
    for (scene, _, embree) in builtin_scenes(48, 40) {
        let rays: Vec<Ray> = scene.camera.rays().collect();
        let sun = scene.lighting.sun;
        let (mut at, mut count, mut hits, mut starts) = (0, 1, 0, Vec::new());
        while at < rays.len() {
            let packet = &rays[at..(at + count).min(rays.len())];
            let answers = embree.intersect_packet::<N>(packet);
            for (k, ray) in packet.iter().enumerate() {
                let single = embree.intersect(ray);
                match (single, answers[k]) {
                    (None, None) => {}
                    (Some(one), Some(many)) => {
                        assert_eq!(
                            (one.cell, one.triangle),
                            (many.cell, many.triangle),
                            "{ray:?}"
                        );
                        assert!(
                            (one.t - many.t).abs() <= 1e-6 * one.t,
                            "{ray:?}: {one:?} {many:?}"
                        );
                        assert!(
                            (one.up - many.up).length() < 1e-6,
                            "{ray:?}: {one:?} {many:?}"
                        );
                        hits += 1;
                        let p = DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * one.t;
                        starts.push((p + one.up * 1e-3).to_array());
                    }
                    (one, many) => panic!("{ray:?}: single {one:?}, packet {many:?}"),
                }
            }
            assert!(answers[packet.len()..].iter().all(Option::is_none));
            (at, count) = (at + packet.len(), count % N + 1);
        }
        assert!(hits > rays.len() / 4, "{hits} of {} rays hit", rays.len());
        let (mut at, mut count, mut blocked) = (0, N, 0);
        while at < starts.len() {
            let packet = &starts[at..(at + count).min(starts.len())];
            let answers = embree.occluded_packet::<N>(packet, sun);
            for (k, &start) in packet.iter().enumerate() {
                assert_eq!(answers[k], embree.occluded(start, sun), "from {start:?}");
                blocked += usize::from(answers[k]);
            }
            assert!(!answers[packet.len()..].iter().any(|&b| b));
            (at, count) = (at + packet.len(), count % N + 1);
        }
        assert!(
            blocked > 0 && blocked < starts.len(),
            "{blocked} of {} in shadow",
            starts.len()
        );
    }
}

#[test]
fn packets_of_8_answer_as_single_rays() {
    packets_answer_as_single_rays::<8>();
}

#[test]
fn packets_of_16_answer_as_single_rays() {
    packets_answer_as_single_rays::<16>();
}

/// A frame traced in packets is the frame traced a ray at a time: the same pixels and the
/// same counts of rays, on a frame whose sides are not whole tiles (partial packets at the
/// right and bottom edges) and on two threads.
#[test]
fn packet_frames_equal_single_ray_frames() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    for (scene, terrain, embree) in builtin_scenes(45, 23) {
        let embree = Arc::new(embree);
        let renderer =
            crate::bench::view(&scene, &terrain, crate::bench::Tracer::Reference(0), true);
        let frame = |api| {
            let tracer = EmbreeTracer {
                scene: embree.clone(),
                api,
            };
            let mut frame = Frame::new(45, 23);
            pool.install(|| crate::bench::Reference::render(&tracer, &renderer, &mut frame));
            frame
        };
        let single = frame(Api::Single);
        assert!(single.totals.shadow_rays > 0 && single.totals.primary_hits > 0);
        for api in [Api::Packets8, Api::Packets16] {
            let packets = frame(api);
            assert_eq!(packets.pixels, single.pixels, "{api:?}");
            assert_eq!(packets.totals.primary_rays, 45 * 23, "{api:?}");
            assert_eq!(
                packets.totals.primary_hits, single.totals.primary_hits,
                "{api:?}"
            );
            assert_eq!(
                packets.totals.shadow_rays, single.totals.shadow_rays,
                "{api:?}"
            );
        }
    }
}
