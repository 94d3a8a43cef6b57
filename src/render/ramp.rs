//! Colour by height: the ramps a scene names, and the sea below height 0.
//!
//! `terrain` and `gray` are the renderer's own; `hypsometric` is the atlas convention of
//! layer tints (green lowland, yellow and tan uplands, brown mountains, pale summits);
//! `viridis`, `magma` and `turbo` are the perceptual colour maps of matplotlib and Google, as
//! the `colorous` crate holds them. The land ramps, `terrain` and `hypsometric`, colour a
//! field that reaches below height 0 as land and sea: heights from 0 up take the land ramp
//! over `0 ..= highest`, heights below 0 a blue bathymetric ramp, lighter in the shallows and
//! darker with depth down to the lowest height. Maps in metres (float and signed rasters)
//! have their sea level at 0 whatever the z scale. Fields without negative heights, which
//! include every unsigned raster, are coloured over their whole range as before. The data
//! ramps, `gray`, `viridis`, `magma` and `turbo`, always span the field's whole range.

use super::gamma;
use crate::heightfield::Terrain;
use glam::DVec3;
use serde::Deserialize;

/// Colour by elevation.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Ramp {
    /// Greens, browns and grey rock up to snow; a sea below 0.
    #[default]
    Terrain,
    /// From dark to light gray.
    Gray,
    /// The atlas layer tints; a sea below 0.
    Hypsometric,
    /// matplotlib's perceptual blue-green-yellow map.
    Viridis,
    /// matplotlib's perceptual black-purple-yellow map.
    Magma,
    /// Google's rainbow-like map, perceptually smoothed.
    Turbo,
}

/// The heights a field is coloured over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightSpan {
    /// The lowest height.
    pub lo: f64,
    /// The highest height.
    pub hi: f64,
    /// How far from 0 a height still counts as sea level: half the field's quantisation step
    /// (a height stored as 0 lies within it), and at least what rounding moves a hit point.
    pub shore: f64,
}

impl HeightSpan {
    /// The span of a terrain's heights.
    pub fn of(terrain: &Terrain) -> HeightSpan {
        let (lo, hi) = terrain.z_range();
        HeightSpan {
            lo,
            hi,
            shore: (0.5 * terrain.field().step()).max(1e-9 * (hi - lo)),
        }
    }
}

impl Ramp {
    /// Every ramp, in the order the viewer lists them.
    pub const ALL: [Ramp; 6] = [
        Ramp::Terrain,
        Ramp::Hypsometric,
        Ramp::Gray,
        Ramp::Viridis,
        Ramp::Magma,
        Ramp::Turbo,
    ];

    /// The name a scene file gives it.
    pub fn name(self) -> &'static str {
        match self {
            Ramp::Terrain => "terrain",
            Ramp::Gray => "gray",
            Ramp::Hypsometric => "hypsometric",
            Ramp::Viridis => "viridis",
            Ramp::Magma => "magma",
            Ramp::Turbo => "turbo",
        }
    }

    /// Whether a field whose heights span `span` is coloured as land and sea, the sea below
    /// sea level.
    pub fn shows_sea(self, span: HeightSpan) -> bool {
        matches!(self, Ramp::Terrain | Ramp::Hypsometric) && span.lo < -span.shore
    }

    /// The surface colour (linear light, before shading) at height `z` of a field whose
    /// heights span `span`.
    pub fn colour(self, z: f64, span: HeightSpan) -> DVec3 {
        let HeightSpan { lo, hi, shore } = span;
        if self.shows_sea(span) {
            // Ground at sea level is land, though quantisation and rounding put some of it a
            // little below 0: a coastal plain is not speckled with sea.
            if z < -shore {
                return sea((z / lo).clamp(0.0, 1.0));
            }
            return self.land(fraction(z, 0.0, hi));
        }
        self.land(fraction(z, lo, hi))
    }

    /// The colour at height `z` as display bytes `[r, g, b]`, unshaded: what a legend shows.
    pub fn display_rgb(self, z: f64, span: HeightSpan) -> [u8; 3] {
        let c = self.colour(z, span);
        gamma::bytes(c.to_array())
    }

    /// The colour at `e`, from the lowest (0) to the highest (1) height it covers.
    fn land(self, e: f64) -> DVec3 {
        match self {
            Ramp::Gray => DVec3::splat(0.25 + 0.75 * e),
            Ramp::Terrain => between_stops(&TERRAIN, e),
            Ramp::Hypsometric => linear(between_stops(&HYPSOMETRIC, e)),
            Ramp::Viridis => library(colorous::VIRIDIS, e),
            Ramp::Magma => library(colorous::MAGMA, e),
            Ramp::Turbo => library(colorous::TURBO, e),
        }
    }
}

/// Where `z` lies between `lo` (0) and `hi` (1), clamped. A flat field has one colour (and
/// rounding must not make up a range).
fn fraction(z: f64, lo: f64, hi: f64) -> f64 {
    let range = hi - lo;
    if range > 1e-9 * hi.abs().max(1.0) {
        ((z - lo) / range).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The renderer's own land ramp, in linear light.
const TERRAIN: [(f64, [f64; 3]); 5] = [
    (0.0, [0.18, 0.32, 0.14]),
    (0.35, [0.36, 0.52, 0.22]),
    (0.6, [0.52, 0.43, 0.29]),
    (0.82, [0.55, 0.53, 0.50]),
    (0.95, [0.95, 0.95, 0.97]),
];

/// Layer tints in display values (the tints of Wikipedia's topographic map conventions, set
/// over the field's height range rather than at fixed metres).
const HYPSOMETRIC: [(f64, [f64; 3]); 9] = [
    (0.0, srgb(172, 208, 165)),
    (0.1, srgb(148, 191, 139)),
    (0.25, srgb(189, 204, 150)),
    (0.4, srgb(225, 228, 181)),
    (0.55, srgb(222, 214, 163)),
    (0.7, srgb(195, 167, 107)),
    (0.82, srgb(170, 135, 83)),
    (0.92, srgb(186, 174, 154)),
    (1.0, srgb(245, 244, 242)),
];

const fn srgb(r: u8, g: u8, b: u8) -> [f64; 3] {
    [r as f64 / 255.0, g as f64 / 255.0, b as f64 / 255.0]
}

/// The colour at `e` interpolated between the stops around it (the first below `e`, the next
/// above), held at the ends.
fn between_stops(stops: &[(f64, [f64; 3])], e: f64) -> DVec3 {
    let k = stops
        .iter()
        .rposition(|s| s.0 <= e)
        .unwrap_or(0)
        .min(stops.len() - 2);
    let ((e0, c0), (e1, c1)) = (stops[k], stops[k + 1]);
    let f = ((e - e0) / (e1 - e0)).clamp(0.0, 1.0);
    DVec3::from(c0).lerp(DVec3::from(c1), f)
}

/// A display colour in linear light, the inverse of the display gamma the pixels get, so that
/// a surface lit at full strength shows the ramp's own colour.
fn linear(display: DVec3) -> DVec3 {
    display.map(|v| v.powf(2.2))
}

/// A `colorous` gradient at `e`, in linear light.
fn library(gradient: colorous::Gradient, e: f64) -> DVec3 {
    let c = gradient.eval_continuous(e);
    linear(DVec3::from(srgb(c.r, c.g, c.b)))
}

/// The sea at `depth`, from the shore (0) to the deepest point (1): light blue in the
/// shallows to dark blue in the deep (ColorBrewer's blues, from a fifth of the way in, so
/// that the shallows stay blue rather than white).
fn sea(depth: f64) -> DVec3 {
    library(colorous::BLUES, 0.2 + 0.75 * depth)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn span(lo: f64, hi: f64) -> HeightSpan {
        HeightSpan { lo, hi, shore: 0.5 }
    }

    /// Each name parses as itself, and the names are those `name` gives.
    #[test]
    fn every_ramp_parses_by_its_name() {
        for ramp in Ramp::ALL {
            let parsed: Ramp = serde_json::from_str(&format!("\"{}\"", ramp.name())).unwrap();
            assert_eq!(parsed, ramp);
        }
    }

    /// Land ramps go to sea below 0 only on fields that reach below 0; there the shore is the
    /// land ramp's lowest colour and the sea gets darker (less light in every channel) with
    /// depth, and is bluer than it is red or green.
    #[test]
    fn the_sea_is_blue_and_darkens_with_depth() {
        let topobathy = span(-4000.0, 2000.0);
        for ramp in [Ramp::Terrain, Ramp::Hypsometric] {
            assert!(ramp.shows_sea(topobathy));
            assert!(!ramp.shows_sea(span(0.0, 2000.0)));
            assert!(
                !ramp.shows_sea(span(-0.4, 2000.0)),
                "only a quantisation below 0"
            );
            assert_eq!(ramp.colour(-0.4, topobathy), ramp.land(0.0), "sea level");
            assert_eq!(ramp.colour(0.0, topobathy), ramp.land(0.0));
            assert_eq!(ramp.colour(2000.0, topobathy), ramp.land(1.0));
            assert_eq!(ramp.colour(1000.0, topobathy), ramp.land(0.5));
            let mut previous = ramp.colour(-1.0, topobathy);
            for depth in (1..=40).map(|k| -100.0 * f64::from(k)) {
                let c = ramp.colour(depth, topobathy);
                assert!(c.z > c.x && c.z > c.y, "{depth}: {c}");
                assert!(c.cmple(previous).all(), "{depth}: {c} after {previous}");
                previous = c;
            }
        }
        for ramp in [Ramp::Gray, Ramp::Viridis, Ramp::Magma, Ramp::Turbo] {
            assert!(!ramp.shows_sea(topobathy));
            assert_eq!(ramp.colour(-4000.0, topobathy), ramp.land(0.0));
        }
    }

    /// The library ramps are the published colour maps: their ends and middle at full light
    /// show as the reference bytes (matplotlib's viridis and magma, Google's turbo).
    #[test]
    fn library_ramps_show_the_published_colours() {
        let range = span(0.0, 1.0);
        for (ramp, ends) in [
            (Ramp::Viridis, [[68, 1, 84], [33, 145, 140], [253, 231, 37]]),
            (Ramp::Magma, [[0, 0, 4], [183, 55, 121], [252, 253, 191]]),
            (Ramp::Turbo, [[35, 23, 27], [149, 251, 81], [144, 12, 0]]),
        ] {
            for (z, want) in [0.0, 0.5, 1.0].into_iter().zip(ends) {
                let got = ramp.display_rgb(z, range);
                let off = (0..3).map(|k| got[k].abs_diff(want[k])).max();
                assert!(
                    off <= Some(2),
                    "{} at {z}: {got:?}, not {want:?}",
                    ramp.name()
                );
            }
        }
    }
}
