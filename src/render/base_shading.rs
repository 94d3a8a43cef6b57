//! How the base under a terrain is shaded: lit like the terrain (Lambert by the face's
//! normal, the same sun, shadows and sky), its walls in the ramp's colour at their height
//! darkened towards an earth tone, so they read as the block under the map, and its floor in
//! a neutral grey that reads as "no data".

use super::shade::{Culling, Shader};
use crate::geometry::Face;
use crate::render::ramp::HeightSpan;
use glam::DVec3;

/// The earth tone walls are darkened towards (linear RGB).
const EARTH: DVec3 = DVec3::new(0.20, 0.14, 0.09);
/// How much of a wall's colour is the earth tone.
const EARTH_SHARE: f64 = 0.55;
/// The floor's colour (linear RGB): a cool grey, no height's colour on any ramp.
const FLOOR: DVec3 = DVec3::new(0.16, 0.16, 0.18);

impl<'a> Shader<'a> {
    /// The unit normal of a face of the base in grid coordinates (`None` for the terrain).
    pub(super) fn base_normal(face: Face) -> Option<DVec3> {
        match face {
            Face::Terrain => None,
            Face::Wall(side) => Some(DVec3::from(side.normal())),
            Face::Floor => Some(DVec3::Z),
        }
    }

    /// The colour of a face of the base at `p` before it is lit (`None` for the terrain).
    pub(super) fn base_albedo(&self, face: Face, p: DVec3) -> Option<DVec3> {
        match face {
            Face::Terrain => None,
            Face::Wall(_) => {
                let span = HeightSpan::of(self.terrain);
                let (lo, hi) = self.terrain.z_range();
                let ramp = self.lighting.ramp.colour(p.z.clamp(lo, hi), span);
                Some(ramp.lerp(EARTH, EARTH_SHARE))
            }
            Face::Floor => Some(FLOOR),
        }
    }

    /// This shader for a hit on `face`: on the base, without the shadow verdicts proven from
    /// the terrain's slopes around a point on the terrain (no shadow possible, the horizon
    /// clear, a cone blocked whole): a point on the floor under a hole lies below the terrain
    /// around it, which may hide the sun from it however steep the sun is.
    pub(super) fn on_face(&self, face: Face) -> Option<Shader<'a>> {
        if face == Face::Terrain {
            return None;
        }
        let culling = Culling {
            no_shadow_possible: false,
            horizon_clear: false,
            cone_blocked: false,
            ..self.culling
        };
        Some(Shader {
            culling,
            ..self.clone()
        })
    }
}
