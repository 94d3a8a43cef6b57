//! Framing the whole map in the viewer's orbit (the geometry is the renderer's, see
//! [`crate::render::framing`]).

use super::orbit::Orbit;
use crate::render::framing::{self, Fit};
pub use crate::render::framing::{DEFAULT_FOV_Y_DEG, DEFAULT_PITCH_DEG, DEFAULT_YAW_DEG};
use crate::Terrain;

/// The orbit from `yaw_deg` and `pitch_deg` that shows the whole map in a view of `aspect`
/// (width over height), as near as it can.
pub fn fit(terrain: &Terrain, yaw_deg: f64, pitch_deg: f64, fov_y_deg: f64, aspect: f64) -> Orbit {
    let Fit { target, distance } = framing::fit(terrain, yaw_deg, pitch_deg, fov_y_deg, aspect);
    Orbit {
        target,
        yaw_deg,
        pitch_deg,
        distance,
        fov_y_deg,
        scale: framing::scale(terrain),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::Builtin;
    use crate::viewer::ground::keep_above;
    use glam::DVec3;

    /// Every sample of the map lands inside the image of the orbit's camera.
    fn map_inside(terrain: &Terrain, orbit: &Orbit, size: (u32, u32)) -> bool {
        let (forward, right, up) = orbit.axes();
        let eye = orbit.eye();
        let h = (orbit.fov_y_deg.to_radians() / 2.0).tan();
        let aspect = f64::from(size.0) / f64::from(size.1);
        let field = terrain.field();
        (0..field.height()).all(|j| {
            (0..field.width()).all(|i| {
                let q = DVec3::new(i as f64, j as f64, field.z(i, j)) - eye;
                let depth = q.dot(forward);
                let (sx, sy) = (q.dot(right) / depth / (h * aspect), q.dot(up) / depth / h);
                depth > 0.0 && sx.abs() < 1.0 && sy.abs() < 1.0
            })
        })
    }

    #[test]
    fn the_whole_map_fits_any_aspect_and_fills_it() {
        let field = Builtin::named("small49").and_then(|b| b.load().ok());
        let terrain = Terrain::new(field.expect("the built-in terrain decodes"));
        for (size, yaw, pitch) in [
            ((1280, 720), DEFAULT_YAW_DEG, DEFAULT_PITCH_DEG),
            ((800, 500), DEFAULT_YAW_DEG, DEFAULT_PITCH_DEG),
            ((300, 900), 20.0, 60.0),
            ((2000, 300), 100.0, 10.0),
        ] {
            let aspect = f64::from(size.0) / f64::from(size.1);
            let orbit = fit(&terrain, yaw, pitch, DEFAULT_FOV_Y_DEG, aspect);
            assert!(map_inside(&terrain, &orbit, size), "{size:?}");
            // Already where the ground rule would put it: the framing lasts.
            let mut kept = orbit;
            keep_above(&mut kept, &terrain);
            assert_eq!(kept, orbit, "{size:?}");
            // Tight: a fifth closer and some corner leaves the view.
            let closer = Orbit {
                distance: 0.8 * orbit.distance,
                ..orbit
            };
            assert!(!map_inside(&terrain, &closer, size), "{size:?}");
        }
    }
}
