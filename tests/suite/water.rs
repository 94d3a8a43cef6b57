//! Water: a plane at a level wherever the terrain lies below it, mirroring by Schlick's
//! Fresnel term. The map is low ground (height 0) for x < 23, a face rising to 8 across cell
//! 23 (`z = 8 (x - 23)`) and a plateau at 8 beyond; the water stands at 1, so it covers
//! x < 23.125. Where rays meet the water and what their reflections meet is worked out by
//! hand below.

use crate::common::top_down::overhead_light;
use heightray::render::effects::{Water, NORMAL_REFLECTANCE};
use heightray::render::Reflection;
use heightray::render::{
    bytes_from_hex, linear_from_bytes, Culling, Lighting, Ramp, Sample, Shader,
    DEFAULT_WATER_COLOUR,
};
use heightray::{Arith, Heightfield, Method, Ray, Terrain};

fn ridge() -> Terrain {
    let field = Heightfield::from_fn(33, 9, 255, 8.0, |i, _| if i >= 24 { 255 } else { 0 });
    Terrain::new(field.unwrap())
}

fn water_colour() -> [f64; 3] {
    linear_from_bytes(bytes_from_hex(DEFAULT_WATER_COLOUR).unwrap())
}

/// The overhead light with water at 1, or none.
fn lighting(water: bool) -> Lighting {
    let mut lighting = overhead_light(Ramp::Gray);
    lighting.effects.water = water.then_some(Water {
        level: 1.0,
        colour: water_colour(),
    });
    lighting
}

fn shade(terrain: &Terrain, water: bool, culling: Culling, ray: &Ray, arith: Arith) -> Sample {
    let shader = Shader::new(terrain, lighting(water), Method::Mipmap, culling);
    shader.traced(ray, arith).0
}

/// The display byte of linear `v` (gamma 2.2).
fn byte(v: f64) -> u32 {
    (v.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0 + 0.5) as u32
}

#[test]
fn water_covers_the_terrain_below_its_level_and_only_there() {
    let terrain = ridge();
    let down = |x: f64| Ray::new([x, 4.0, 20.0], [0.0, 0.0, -1.0]).unwrap();
    // Straight down: the water reflects straight up, the sky's zenith colour
    // (0.28, 0.46, 0.82), by the reflectance at normal incidence; its own colour under the
    // overhead sun at full strength takes the rest.
    let [r, g, b] = water_colour();
    let mix =
        |own: f64, sky: f64| byte(own * (1.0 - NORMAL_REFLECTANCE) + sky * NORMAL_REFLECTANCE);
    let expected = (mix(r, 0.28) << 16) | (mix(g, 0.46) << 8) | mix(b, 0.82);
    for x in [0.5, 10.0, 22.9, 23.05, 23.12] {
        let sample = shade(&terrain, true, Culling::default(), &down(x), Arith::F64);
        assert_eq!(sample.rgb, expected, "x = {x}: {:06x}", sample.rgb);
        assert_eq!(sample.effects.water, Reflection::Clear, "x = {x}");
    }
    // At or above the level (the face reaches 1 at x = 23.125): the terrain, as without water.
    for x in [23.125, 23.2, 24.0, 30.0] {
        let wet = shade(&terrain, true, Culling::default(), &down(x), Arith::F64);
        let dry = shade(&terrain, false, Culling::default(), &down(x), Arith::F64);
        assert_eq!(wet.rgb, dry.rgb, "x = {x}");
        assert_eq!(wet.effects.water, Reflection::NotWater, "x = {x}");
    }
}

#[test]
fn the_reflection_of_the_ridge_appears_where_the_mirror_geometry_puts_it() {
    let terrain = ridge();
    // From (2, 4, 6) along (1, 0, -s): the water at x = 2 + 5 / s, wet for s > 5 / 21.125.
    // The reflected ray (1, 0, s) rises from 1 and passes x = 24 at 1 + s (22 - 5 / s): it
    // meets the face or the plateau's edge while that is at most 8, for s <= 12 / 22.
    let ray = |s: f64| Ray::new([2.0, 4.0, 6.0], [1.0, 0.0, -s]).unwrap();
    for arith in [Arith::F64, Arith::Exact] {
        for culling in [
            Culling::default(),
            Culling {
                horizon_clear: false,
                ..Culling::default()
            },
        ] {
            let at = |s: f64| shade(&terrain, true, culling, &ray(s), arith).effects.water;
            for s in [0.25, 0.3, 0.4, 0.5, 0.54] {
                assert_eq!(at(s), Reflection::Cast { hit: true }, "s = {s}, {arith:?}");
            }
            for s in [0.56, 0.7, 1.0, 3.0] {
                assert!(
                    matches!(at(s), Reflection::Cast { hit: false } | Reflection::Clear),
                    "s = {s}"
                );
            }
            // Dry: the ray meets the terrain before the level.
            assert_eq!(at(0.2), Reflection::NotWater);
        }
    }
    // Culling leaves out only rays that would have seen the sky, and changes no colour.
    for s in [0.25, 0.4, 0.54, 0.56, 0.7, 1.0, 3.0] {
        let culled = shade(&terrain, true, Culling::default(), &ray(s), Arith::F64);
        let off = Culling {
            horizon_clear: false,
            ..Culling::default()
        };
        let traced = shade(&terrain, true, off, &ray(s), Arith::F64);
        assert_eq!(culled.rgb, traced.rgb, "s = {s}");
    }
}
