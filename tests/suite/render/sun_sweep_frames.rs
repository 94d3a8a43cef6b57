//! Hard shadow rays the sun's sweep settles: frames with the rule on and off are the same in
//! `f32`, `f64` and exact arithmetic, with flat and smooth normals, for suns along an axis and
//! a diagonal, low, just below the steepest slope and at random; and the sweep settles a share
//! of the rays both ways.

use super::*;
use crate::common::random::Rng;

#[test]
fn sun_sweep_on_or_off_gives_the_same_image() {
    let scene = builtin_scene("small49", 40);
    let terrain = Terrain::new(scene.field.clone());
    let steepest = terrain.max_slope();
    let mut rng = Rng(0x0500_0bad_5eed);
    let a = rng.within(0.0, std::f64::consts::TAU);
    let suns = [
        [1.0, 0.0, 0.3],
        [0.0, -1.0, 0.15],
        [1.0, 1.0, 0.4],
        [-0.6, 0.8, 0.05],
        // Just below the steepest slope: few points are shadowed, and only by steep faces.
        [0.6, -0.8, steepest * 0.95],
        [a.cos(), a.sin(), rng.within(0.05, 1.0)],
    ];
    let (mut lit, mut shadowed) = (0, 0);
    for arith in [Arith::F32, Arith::F64, Arith::Exact] {
        for normals in [Normals::Flat, Normals::Smooth] {
            for sun in suns {
                let lighting = Lighting {
                    normals,
                    ..lighting(sun, true)
                };
                let frame = |culling| {
                    render_by(
                        Method::Mipmap,
                        &terrain,
                        scene.camera,
                        lighting,
                        arith,
                        culling,
                        2,
                    )
                };
                let on = frame(Culling::default());
                let off = frame(Culling {
                    sun_sweep: false,
                    ..Culling::default()
                });
                let what = format!("{arith} {normals:?} sun {sun:?}");
                assert_eq!(on.pixels, off.pixels, "{what}");
                let settled = on.totals.skipped.sun_lit + on.totals.skipped.sun_shadowed;
                assert_eq!(
                    off.totals.skipped.sun_lit + off.totals.skipped.sun_shadowed,
                    0
                );
                // Each settled ray is one the walk would have cast (or found above the terrain).
                assert_eq!(
                    on.totals.shadow_rays + on.totals.skipped.above_terrain + settled,
                    off.totals.shadow_rays + off.totals.skipped.above_terrain,
                    "{what}"
                );
                lit += on.totals.skipped.sun_lit;
                shadowed += on.totals.skipped.sun_shadowed;
            }
        }
    }
    assert!(lit > 1000, "{lit} settled lit");
    assert!(shadowed > 0, "{shadowed} settled in shadow");
}
