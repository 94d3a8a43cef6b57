//! Beams: the camera rays of a tile cleared as a whole (`Beam::clear_until`), so that each
//! ray's own walk starts where the beam stopped. No ray of a beam may touch the surface before
//! the beam's clearance: checked for every pixel against the exact reference's first hit
//! (rationals, no mipmap and no beam involved), on hard views: grazing flat ground, looking
//! straight down, along grid lines through lattice points, and from far away.

use crate::common::families::{hash, integer_hills, terrain};
use crate::common::reference::{q, solve};
use heightray::bench::sized_scene;
use heightray::render::Camera;
use heightray::traverse::Clearance;
use heightray::Terrain;

/// Checks every `tile x tile` tile of the camera's image. Returns how far the beams got,
/// summed over tiles whose rays hit: the clearance over the nearest hit.
fn check_tiles(name: &str, terrain: &Terrain, camera: &Camera, tile: u32) -> (f64, usize) {
    let (w, h) = camera.size();
    let (mut reached, mut tiles_hit) = (0.0, 0);
    for y0 in (0..h).step_by(tile as usize) {
        for x0 in (0..w).step_by(tile as usize) {
            let (x1, y1) = ((x0 + tile).min(w) - 1, (y0 + tile).min(h) - 1);
            let (cleared, tests) = camera.beam((x0, y0), (x1, y1)).clear_until(terrain);
            let tile_at = format!("{name}: tile ({x0}, {y0})");
            assert!(cleared.t >= 0.0, "{tile_at} cleared to {}", cleared.t);
            assert!(tests.total() < 200, "{tile_at}: {tests:?}");
            let mut nearest = f64::INFINITY;
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let ray = camera.ray(x, y);
                    let Some(hit) = solve(terrain.field(), &ray).hit else {
                        continue;
                    };
                    let at = format!("{name}: pixel ({x}, {y}) hits at {:?}", hit.t);
                    assert!(
                        cleared.t.is_finite() && q(cleared.t) <= hit.t,
                        "{at}, but its beam cleared to {cleared:?}"
                    );
                    nearest = nearest.min(num_traits::ToPrimitive::to_f64(&hit.t).unwrap());
                }
            }
            if nearest.is_finite() {
                reached += cleared.t / nearest;
                tiles_hit += 1;
            }
        }
    }
    (reached, tiles_hit)
}

/// How far, on average over the tiles whose rays hit, the beams got towards the nearest hit.
fn mean_reach(name: &str, terrain: &Terrain, camera: &Camera, tile: u32) -> f64 {
    let (reached, tiles_hit) = check_tiles(name, terrain, camera, tile);
    assert!(tiles_hit > 0, "{name}: some rays hit");
    reached / tiles_hit as f64
}

#[test]
fn no_ray_of_a_beam_touches_the_surface_before_its_clearance() {
    let scene = sized_scene(65, 32).unwrap();
    let terrain = Terrain::new(scene.field.clone());
    let reach = mean_reach("valley65", &terrain, &scene.camera, 8);
    // The beams are worth their march: they get most of the way to the nearest hit.
    assert!(reach > 0.5, "valley65: beams reached {reach:.2} of the way");
}

#[test]
fn beams_grazing_flat_ground_stop_before_it() {
    // Flat ground at 3.0 with a bump; the eye at the ground's height looks level along it:
    // the upper half of the image never comes down, the lower half grazes the ground.
    let ground = terrain(
        17,
        13,
        255,
        25.5,
        |x, y| if (x, y) == (12, 6) { 60 } else { 30 },
    );
    let camera = Camera::look_at(
        [-2.0, 6.0, 3.0],
        [16.0, 6.0, 3.0],
        [0.0, 0.0, 1.0],
        30.0,
        (16, 16),
    );
    let reach = mean_reach("grazing", &ground, &camera.unwrap(), 4);
    assert!(reach > 0.0, "grazing: beams got somewhere ({reach})");
}

#[test]
fn beams_looking_straight_down_stop_above_the_surface() {
    let hills = integer_hills(9, 9, 8, 3);
    let camera = Camera::look_at(
        [4.0, 4.0, 40.0],
        [4.0, 4.0, 0.0],
        [0.0, 1.0, 0.0],
        20.0,
        (12, 12),
    );
    let reach = mean_reach("straight down", &hills, &camera.unwrap(), 4);
    assert!(
        reach > 0.5,
        "straight down: beams reached {reach:.2} of the way"
    );
}

#[test]
fn beams_along_grid_lines_through_lattice_points() {
    // Integer heights and an eye on the lattice: the middle rays run along grid lines and
    // through lattice points, where the corners of the footprint fall on cell edges.
    let hills = integer_hills(13, 13, 6, 5);
    for (eye, target) in [
        ([0.0, 6.0, 9.0], [12.0, 6.0, 0.0]),
        ([0.0, 0.0, 10.0], [12.0, 12.0, 0.0]),
        ([6.0, -2.0, 8.0], [6.0, 12.0, 2.0]),
    ] {
        let camera = Camera::look_at(eye, target, [0.0, 0.0, 1.0], 40.0, (9, 9)).unwrap();
        check_tiles(&format!("grid lines from {eye:?}"), &hills, &camera, 3);
    }
}

#[test]
fn beams_from_far_away() {
    let rough = terrain(33, 33, 1000, 40.0, |x, y| hash(x, y, 9, 1000));
    let camera = Camera::look_at(
        [-3.0e4, -2.0e4, 9.0e3],
        [16.0, 16.0, 20.0],
        [0.0, 0.0, 1.0],
        0.2,
        (16, 16),
    );
    let reach = mean_reach("far away", &rough, &camera.unwrap(), 8);
    assert!(reach > 0.9, "far away: beams reached {reach:.3} of the way");
}

#[test]
fn a_beam_that_misses_the_terrain_clears_it_all() {
    let hills = integer_hills(9, 9, 8, 3);
    // Looking up and away from the terrain.
    let camera = Camera::look_at(
        [4.0, 4.0, 20.0],
        [30.0, 4.0, 60.0],
        [0.0, 0.0, 1.0],
        30.0,
        (8, 8),
    );
    let (cleared, _) = camera.unwrap().beam((0, 0), (7, 7)).clear_until(&hills);
    assert_eq!(
        cleared,
        Clearance {
            t: f64::INFINITY,
            ..cleared
        }
    );
}
