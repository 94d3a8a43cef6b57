//! A hit's surface before light and shadow: its shading normal, how it faces the sun, and its
//! colour. On the terrain these come from the hit triangle, the ramp and the drape; the base
//! is lit like the terrain (Lambert by its face's normal, the same sun, shadows and sky), its
//! walls in the ramp's colour at their height darkened towards an earth tone, so they read as
//! the block under the map, and its floor in a neutral grey that reads as "no data".

use super::context::{Context, Culling};
use super::normals;
use super::ramp::HeightSpan;
use super::scene::Normals;
use crate::geometry::{gradient, Face};
use glam::DVec3;

/// The earth tone walls are darkened towards (linear RGB).
const EARTH: DVec3 = DVec3::new(0.20, 0.14, 0.09);
/// How much of a wall's colour is the earth tone.
const EARTH_SHARE: f64 = 0.55;
/// The floor's colour (linear RGB): a cool grey, no height's colour on any ramp.
const FLOOR: DVec3 = DVec3::new(0.16, 0.16, 0.18);

impl<'a> Context<'a> {
    /// How the surface at `p` on `face` (triangle `triangle` of `cell` on the terrain) faces
    /// the sun: the cosine of the angle between the shading normal and the sun (not positive
    /// where it faces away).
    // (This, `normal` and `lit_colour` inlined by hand: every arithmetic's `sample_with`
    // calls them once per pixel.)
    #[inline(always)]
    pub fn facing(&self, face: Face, cell: (usize, usize), triangle: u8, p: DVec3) -> f64 {
        self.normal(face, cell, triangle, p)
            .dot(DVec3::from(self.lighting.sun))
    }

    /// The surface's colour at `p` on `face` before it is lit: on the terrain the ramp's,
    /// under the drape where one lies.
    #[inline(always)]
    pub(super) fn albedo(&self, face: Face, p: DVec3) -> DVec3 {
        if let Some(colour) = self.base_albedo(face, p) {
            return colour;
        }
        let ramp = self.lighting.ramp.colour(p.z, HeightSpan::of(self.terrain));
        let drape = self.terrain.field().drape();
        match drape.and_then(|drape| drape.colour(p.x, p.y)) {
            Some((rgb, cover)) => ramp.lerp(DVec3::from(rgb), cover),
            None => ramp,
        }
    }

    /// The (unnormalised) normal of the hit triangle's plane: `(-gx, -gy, 1)`.
    fn geometric_normal(&self, (i, j): (usize, usize), triangle: u8) -> DVec3 {
        let heights = self.terrain.corner_heights(i, j);
        let (gx, gy) = gradient(triangle, heights);
        DVec3::new(-gx, -gy, 1.0)
    }

    /// The shading normal at `p` on `face` (triangle `triangle` of cell `(i, j)` on the
    /// terrain), in world coordinates (where cells may be non-square).
    #[inline(always)]
    pub(crate) fn normal(&self, face: Face, cell: (usize, usize), triangle: u8, p: DVec3) -> DVec3 {
        let normal = match (Context::base_normal(face), self.lighting.normals) {
            (Some(normal), _) => normal,
            (None, Normals::Flat) => self.geometric_normal(cell, triangle).normalize_or(DVec3::Z),
            (None, Normals::Smooth) => normals::smooth_normal(self.terrain, cell, triangle, p),
        };
        // A normal maps by the inverse transpose of the points' map: divided per axis.
        match self.terrain.world_from_grid() {
            Some(scale) => (normal / DVec3::from(scale)).normalize_or(DVec3::Z),
            None => normal,
        }
    }

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

    /// This context for a hit on `face`: on the base, without the shadow verdicts proven from
    /// the terrain's slopes around a point on the terrain (no shadow possible, the horizon
    /// clear, a cone blocked whole): a point on the floor under a hole lies below the terrain
    /// around it, which may hide the sun from it however steep the sun is.
    pub(super) fn on_face(&self, face: Face) -> Option<Context<'a>> {
        if face == Face::Terrain {
            return None;
        }
        let culling = Culling {
            no_shadow_possible: false,
            horizon_clear: false,
            cone_blocked: false,
            ..self.culling
        };
        Some(Context {
            culling,
            ..self.clone()
        })
    }
}
