//! Soft shadows and sky light against analytic values and brute force: the open sky's mean
//! colour, a V valley's sky-view factor, a straight edge's penumbra, cones settled as blocked;
//! whole frames with effects in [`super::effects_frames`].

use super::*;
use heightray::arith::Plain;
use heightray::render::effects::{Effects, SkyLight};
use heightray::render::Shadow;
use heightray::Ray;

/// A shader over `terrain` with `lighting`, the mipmap walk and every culling rule.
pub(super) fn shader(terrain: &Terrain, lighting: Lighting) -> Shader<'_> {
    Shader::new(terrain, lighting, Method::Mipmap, Culling::default())
}

/// Straight down onto `(x, y)` from above the terrain.
fn down_at(x: f64, y: f64) -> Ray {
    Ray::new([x, y, 500.0], [0.0, 0.0, -1.0]).unwrap()
}

/// Lighting with sky light of `rays` rays per point, looking for terrain without end, and
/// no sun.
fn sky_only(rays: u32) -> Lighting {
    let mut lighting = lighting([0.0, 0.0, 1.0], false);
    lighting.intensity = 0.0;
    lighting.effects = Effects {
        sky_light: true,
        sky_rays: rays,
        sky_distance: f64::INFINITY,
        ..Effects::default()
    };
    lighting
}

#[test]
fn an_open_plane_sees_the_analytic_mean_sky() {
    // The sky's gradient (shade.rs): horizon (0.78, 0.85, 0.93) to zenith (0.28, 0.46, 0.82)
    // by sqrt(sin(elevation)). Under cosine-weighted directions sin(elevation)^2 is uniform on
    // [0, 1], so the mean of sqrt(sin) is E[U^(1/4)] = 4/5.
    let horizon = [0.78, 0.85, 0.93];
    let zenith = [0.28, 0.46, 0.82];
    let mean: [f64; 3] = std::array::from_fn(|k| horizon[k] + 0.8 * (zenith[k] - horizon[k]));
    let brightness = mean.iter().sum::<f64>() / 3.0;
    let terrain = Terrain::new(Heightfield::from_fn(65, 65, 255, 25.5, |_, _| 10).unwrap());
    let (rays, points) = (64, 64);
    let lighting = sky_only(rays);
    let shader = shader(&terrain, lighting);
    let mut sum = [0.0; 3];
    for n in 0..points {
        let (x, y) = (8.0 + f64::from(n % 8) * 6.3, 8.0 + f64::from(n / 8) * 6.1);
        let (light, sky) = SkyLight::at(&shader, &down_at(x, y)).unwrap();
        assert_eq!(
            (sky.open, sky.of),
            (rays as u16, rays as u16),
            "nothing blocks"
        );
        for (k, s) in sum.iter_mut().enumerate() {
            *s += light[k] / lighting.ambient * brightness / f64::from(points);
        }
    }
    // Each ray's colour lies between the zenith's and the horizon's: with N independent rays
    // the standard error is at most (range / 2) / sqrt(N); the points' samples are rotated
    // independently and stratified within a point, which only lowers it. Four of those.
    let n = f64::from(rays * points);
    for k in 0..3 {
        let bound = 4.0 * (horizon[k] - zenith[k]) / 2.0 / n.sqrt();
        assert!(
            (sum[k] - mean[k]).abs() <= bound,
            "channel {k}: {} against {} (bound {bound})",
            sum[k],
            mean[k]
        );
    }
}

/// A valley along x: a flat floor `FLOOR` wide around y = 32, walls rising at 45 degrees for
/// `WALL` cells, plateaus beyond, on a 257 x 65 grid of unit steps and unit heights.
const FLOOR: f64 = 8.0;
const WALL: f64 = 24.0;

fn valley_height(y: f64) -> f64 {
    ((y - 32.0).abs() - FLOOR / 2.0).clamp(0.0, WALL)
}

/// The cosine-weighted sky fraction at floor point `(x, 32)` by brute force: the horizon's
/// elevation in each of 4096 azimuths by marching the analytic surface to the map's edge, or
/// `reach` away, in steps of 1/64, then the mean of `cos^2(horizon)`.
fn valley_sky_fraction(x: f64, reach: f64) -> f64 {
    let azimuths = 4096;
    (0..azimuths)
        .map(|k| {
            let phi = (f64::from(k) + 0.5) / f64::from(azimuths) * std::f64::consts::TAU;
            let (dx, dy) = (phi.cos(), phi.sin());
            let mut tan_horizon = 0.0f64;
            let mut r = 1.0 / 64.0;
            loop {
                let (qx, qy) = (x + r * dx, 32.0 + r * dy);
                let inside = (0.0..=256.0).contains(&qx) && (0.0..=64.0).contains(&qy);
                if !inside || r > reach {
                    break;
                }
                tan_horizon = tan_horizon.max(valley_height(qy) / r);
                r += 1.0 / 64.0;
            }
            1.0 / (1.0 + tan_horizon * tan_horizon)
        })
        .sum::<f64>()
        / f64::from(azimuths)
}

/// The valley's floor seen with sky rays that look `reach` far: the mean open share at 16
/// floor points and the brute-force fraction, and the Monte Carlo bound between them.
fn valley_floor_sky(reach: f64) -> (f64, f64, f64) {
    let field = Heightfield::from_fn(257, 65, 255, 255.0, |_, y| valley_height(y as f64) as u16);
    let terrain = Terrain::new(field.unwrap());
    let rays = 1024;
    let mut lighting = sky_only(rays);
    lighting.effects.sky_distance = reach;
    let shader = shader(&terrain, lighting);
    let xs: Vec<f64> = (0..16).map(|k| 120.0 + f64::from(k) * 1.07).collect();
    let measured = xs
        .iter()
        .map(|&x| {
            SkyLight::at(&shader, &down_at(x, 32.0))
                .unwrap()
                .1
                .open_share()
        })
        .sum::<f64>()
        / xs.len() as f64;
    let reference = xs
        .iter()
        .map(|&x| valley_sky_fraction(x, reach))
        .sum::<f64>()
        / xs.len() as f64;
    // Open or not per ray: the standard error of N independent rays is sqrt(v (1 - v) / N).
    let n = f64::from(rays) * xs.len() as f64;
    let bound = 4.0 * (reference * (1.0 - reference) / n).sqrt();
    (measured, reference, bound)
}

#[test]
fn a_v_valley_floor_sees_the_sky_fraction_of_its_horizon() {
    let (measured, reference, bound) = valley_floor_sky(f64::INFINITY);
    // An infinitely long valley of infinite 45-degree walls would give cos(45) = 0.7071; the
    // finite walls let more sky in.
    assert!(
        reference > std::f64::consts::FRAC_1_SQRT_2 && reference < 0.9,
        "{reference}"
    );
    assert!(
        (measured - reference).abs() <= bound,
        "{measured} against {reference} (bound {bound})"
    );
}

/// Sky rays that look 10 cells far see the walls' lower part only: the horizon of the
/// surface within 10 cells, by brute force; more sky than the whole walls leave.
#[test]
fn sky_rays_look_only_as_far_as_the_sky_distance() {
    let (measured, reference, bound) = valley_floor_sky(10.0);
    let (_, whole, _) = valley_floor_sky(f64::INFINITY);
    assert!(reference > whole + 0.05, "{reference} against {whole}");
    assert!(
        (measured - reference).abs() <= bound,
        "{measured} against {reference} (bound {bound})"
    );
}

/// Ground at height 0 for x up to 60, a plateau 20 high from x = 61 on: its edge at x = 61
/// casts a shadow towards -x from a sun in +x at `elevation_deg`.
fn edge_terrain() -> Terrain {
    Terrain::new(
        Heightfield::from_fn(128, 32, 255, 255.0, |x, _| if x >= 61 { 20 } else { 0 }).unwrap(),
    )
}

/// The share of the sun seen from ground points `x` (at y = 16.3) on [`edge_terrain`].
fn sun_seen(terrain: &Terrain, elevation_deg: f64, angle_deg: f64, xs: &[f64]) -> Vec<f64> {
    let e = elevation_deg.to_radians();
    let mut lighting = lighting([e.cos(), 0.0, e.sin()], true);
    lighting.effects.sun_angle_deg = angle_deg;
    lighting.effects.sun_rays = 256;
    let shader = shader(terrain, lighting);
    xs.iter()
        .map(|&x| {
            match shader
                .recorded::<Plain<f64>>(&down_at(x, 16.3), None)
                .shadow
            {
                Shadow::Soft(soft) => soft.visible(),
                Shadow::Cast { shadowed } => f64::from(u8::from(!shadowed)),
                Shadow::Skipped(_) | Shadow::NotAsked => 1.0,
            }
        })
        .collect()
}

#[test]
fn a_straight_edge_casts_a_penumbra_as_wide_as_the_sun() {
    let terrain = edge_terrain();
    let (elevation, angle, step) = (30.0f64, 2.0f64, 0.02);
    let xs: Vec<f64> = (0..2000).map(|k| 10.0 + f64::from(k) * step).collect();
    // The ground point at distance r from the edge sees it at elevation atan(20 / r): fully
    // lit below the disc's lowest edge, fully shadowed above its highest.
    let half = angle / 2.0;
    let lit_until = 61.0 - 20.0 / (elevation - half).to_radians().tan();
    let dark_from = 61.0 - 20.0 / (elevation + half).to_radians().tan();
    let seen = sun_seen(&terrain, elevation, angle, &xs);
    let first = |f: &dyn Fn(f64) -> bool| {
        xs.iter()
            .zip(&seen)
            .find(|(_, &s)| f(s))
            .map(|(&x, _)| x)
            .unwrap()
    };
    let (penumbra_start, dark_start) = (first(&|s| s < 1.0), first(&|s| s == 0.0));
    // Within a pixel of 0.1 units (five steps): the disc's outermost samples lie just
    // inside its rim.
    let pixel = 0.1;
    assert!(
        (penumbra_start - lit_until).abs() <= pixel,
        "{penumbra_start} against {lit_until}"
    );
    assert!(
        (dark_start - dark_from).abs() <= pixel,
        "{dark_start} against {dark_from}"
    );
    // About the distance along the sun's rays times the angle, seen on the ground.
    let along = 20.0 / elevation.to_radians().sin();
    let width = along * angle.to_radians().tan() / elevation.to_radians().sin();
    assert!(((dark_start - penumbra_start) - width).abs() <= pixel);

    // Angle 0: the hard shadow, whose edge lies where the disc's centre passes the edge.
    let hard = sun_seen(&terrain, elevation, 0.0, &xs);
    let edge = 61.0 - 20.0 / elevation.to_radians().tan();
    for (&x, &h) in xs.iter().zip(&hard) {
        assert!(h == 0.0 || h == 1.0);
        if (x - edge).abs() > step {
            assert_eq!(h == 1.0, x < edge, "hard shadow at {x}, edge at {edge}");
        }
    }
}

/// Soft shadows darken without sky light too: a ground point that sees none of the sun's disc
/// has the colour of a hard shadow's, one that sees all of it the colour of full sun, and a
/// point in the penumbra lies between them.
#[test]
fn soft_shadows_without_sky_light_darken_the_pixel() {
    let terrain = edge_terrain();
    let e = 30.0f64.to_radians();
    let rgb = |angle_deg: f64, shadows: bool, x: f64| {
        let mut lighting = lighting([e.cos(), 0.0, e.sin()], shadows);
        lighting.effects.sun_angle_deg = angle_deg;
        lighting.effects.sun_rays = 256;
        let sample = shader(&terrain, lighting).recorded::<Plain<f64>>(&down_at(x, 16.3), None);
        let [_, r, g, b] = sample.rgb.to_be_bytes();
        u32::from(r) + u32::from(g) + u32::from(b)
    };
    // (Edge at 61, 20 high: hard shadow's edge at 61 - 20 / tan 30° = 26.4; penumbra 25.7..27.1.)
    let (lit, dark, penumbra) = (10.0, 40.0, 26.4);
    assert_eq!(rgb(2.0, true, dark), rgb(0.0, true, dark), "fully shadowed");
    assert!(
        rgb(2.0, true, dark) < rgb(2.0, false, dark),
        "darker than unshadowed"
    );
    assert_eq!(rgb(2.0, true, lit), rgb(2.0, false, lit), "fully lit");
    let between = rgb(2.0, true, penumbra);
    assert!(
        rgb(0.0, true, dark) < between && between < rgb(2.0, true, lit),
        "{between}"
    );
}

/// Behind the plateau's edge, cones settled as blocked whole by one more ray: each point's
/// colour and share of the sun are those of casting every direction, in every arithmetic.
#[test]
fn cones_settled_as_blocked_are_blocked_in_every_arithmetic() {
    let terrain = edge_terrain();
    let e = 30.0f64.to_radians();
    let mut lighting = lighting([e.cos(), 0.0, e.sin()], true);
    lighting.effects.sun_angle_deg = 2.0;
    lighting.effects.sun_rays = 16;
    let settling = shader(&terrain, lighting);
    let culling = Culling {
        cone_blocked: false,
        ..Culling::default()
    };
    let casting = Shader::new(&terrain, lighting, Method::Mipmap, culling);
    // Fully shadowed from x = 61 - 20 / tan(31 degrees) = 27.7 on, lit below 24.9.
    let xs: Vec<f64> = (0..100).map(|k| 20.0 + f64::from(k) * 0.4).collect();
    for arith in [Arith::F32, Arith::F64, Arith::Exact] {
        let mut settled = 0;
        for &x in &xs {
            let ray = down_at(x, 16.3);
            let (with, without) = (
                settling.traced(&ray, arith).0,
                casting.traced(&ray, arith).0,
            );
            assert_eq!(with.rgb, without.rgb, "{arith} at {x}");
            let (Shadow::Soft(a), Shadow::Soft(b)) = (with.shadow, without.shadow) else {
                // Settled as clear by the same rules either way.
                assert_eq!(with.shadow, without.shadow, "{arith} at {x}");
                continue;
            };
            assert_eq!(a.clear, b.clear, "{arith} at {x}");
            assert!(!b.blocked);
            if a.blocked {
                settled += 1;
                assert!(x > 27.7, "{arith}: {x} is in the penumbra");
                assert_eq!((a.cast, b.cast), (1, 16), "{arith} at {x}");
            }
        }
        // Every point from 28 to 59.6 (the cliff's foot at 60).
        assert!(settled >= 78, "{arith}: {settled} settled");
    }
}
