//! The ground under the camera: the terrain's surface height anywhere on the plane, and the
//! rule every camera move ends with: the target over the map and on or above the surface, the
//! eye above the surface under it (so the camera never looks at the terrain from below).

use super::orbit::{Orbit, MIN_PITCH_DEG, PITCH_LIMIT_DEG};
use crate::render::framing::EYE_CLEARANCE;
pub use crate::render::framing::{on_map, surface_z};
use crate::Terrain;

/// The height the eye keeps above the surface.
pub fn clearance(orbit: &Orbit) -> f64 {
    EYE_CLEARANCE * orbit.scale
}

/// How far the eye is below where it may be (negative or zero: it is fine).
fn shortfall(orbit: &Orbit, terrain: &Terrain) -> f64 {
    let eye = orbit.eye();
    surface_z(terrain, eye.x, eye.y) + clearance(orbit) - eye.z
}

/// Brings the orbit back within the rules after a move: the target over the map, not below
/// its surface nor above its highest point, the pitch within its limits, and the eye above the surface under it.
/// An eye that is too low first rises on its orbit (more pitch, the same target and
/// distance), as if it slid up over the ground; if even looking straight down is too low, the
/// whole camera rises.
pub fn keep_above(orbit: &mut Orbit, terrain: &Terrain) {
    orbit.target = on_map(orbit.target, terrain);
    orbit.pitch_deg = orbit.pitch_deg.clamp(MIN_PITCH_DEG, PITCH_LIMIT_DEG);
    if shortfall(orbit, terrain) <= 0.0 {
        return;
    }
    let mut high = *orbit;
    high.pitch_deg = PITCH_LIMIT_DEG;
    let still_short = shortfall(&high, terrain);
    if still_short > 0.0 {
        // (A little more than the shortfall: the eye's z is a sum that rounds.)
        high.target[2] += still_short + 1e-3 * clearance(orbit);
        *orbit = high;
        return;
    }
    // The lowest pitch that is high enough, to within a hundredth of a degree: the pitch
    // found is always one that was checked.
    let (mut low, mut enough) = (orbit.pitch_deg, PITCH_LIMIT_DEG);
    while enough - low > 0.01 {
        let mut middle = *orbit;
        middle.pitch_deg = 0.5 * (low + enough);
        if shortfall(&middle, terrain) > 0.0 {
            low = middle.pitch_deg;
        } else {
            enough = middle.pitch_deg;
        }
    }
    orbit.pitch_deg = enough;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Heightfield;

    /// A 3x3 map whose middle sample stands 8 high and the rest 0.
    fn peak() -> Terrain {
        let field = Heightfield::from_fn(
            3,
            3,
            255,
            255.0,
            |i, j| {
                if (i, j) == (1, 1) {
                    8
                } else {
                    0
                }
            },
        );
        Terrain::new(field.expect("a valid map"))
    }

    #[test]
    fn surface_follows_the_cells_triangles_and_is_lowest_off_the_map() {
        let terrain = peak();
        assert_eq!(surface_z(&terrain, 1.0, 1.0), 8.0);
        // On the diagonal of cell (0, 0) from P00 to P11: halfway up.
        assert_eq!(surface_z(&terrain, 0.5, 0.5), 4.0);
        // Triangle P00, P10, P11 of cell (0, 0): only P11 is high.
        assert_eq!(surface_z(&terrain, 0.75, 0.25), 2.0);
        // Cell (1, 0): its P01 is the peak, and (1.25, 0.5) lies in triangle P00, P11, P01.
        assert_eq!(surface_z(&terrain, 1.25, 0.5), 2.0);
        assert_eq!(surface_z(&terrain, -1.0, 1.0), 0.0);
        assert_eq!(surface_z(&terrain, f64::NAN, 1.0), 0.0);
    }

    #[test]
    fn a_low_eye_rises_over_the_ground_and_the_target_stays_on_the_map() {
        let terrain = peak();
        let mut orbit = Orbit {
            target: [5.0, 1.0, -3.0],
            yaw_deg: 180.0,
            pitch_deg: -60.0,
            distance: 1.0,
            fov_y_deg: 45.0,
            scale: 10.0,
        };
        keep_above(&mut orbit, &terrain);
        assert_eq!(orbit.target[0], 2.0);
        assert!(orbit.target[2] >= 0.0);
        // A target in the air comes down to the highest point of the map.
        let mut high = Orbit {
            target: [1.0, 0.0, 50.0],
            pitch_deg: 80.0,
            ..orbit
        };
        keep_above(&mut high, &terrain);
        assert_eq!(high.target, [1.0, 0.0, 8.0]);
        let eye = orbit.eye();
        assert!(eye.z >= surface_z(&terrain, eye.x, eye.y) + clearance(&orbit));
        // A target on the peak's flank, the eye level with it inside the other flank: the eye
        // slides up over the peak until it clears the near flank (tan(pitch) >= 8).
        let mut orbit = Orbit {
            target: [0.5, 1.0, 0.0],
            yaw_deg: 0.0,
            pitch_deg: 0.0,
            distance: 1.0,
            ..orbit
        };
        keep_above(&mut orbit, &terrain);
        assert_eq!(orbit.target, [0.5, 1.0, 4.0]);
        let eye = orbit.eye();
        assert!(
            orbit.pitch_deg > 82.8 && orbit.pitch_deg < 83.5,
            "{}",
            orbit.pitch_deg
        );
        assert!(eye.z >= surface_z(&terrain, eye.x, eye.y) + clearance(&orbit));
    }
}
