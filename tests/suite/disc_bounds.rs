//! The sun's strip bounds for a disc of directions around the sun (soft shadows): every ray
//! of the disc they call clear beyond a point, and every disc they call clear as a whole
//! beyond a distance (the look-up before any of its rays), touches no triangle from there
//! on, by the exact reference; a ray that drifts across the strips meets what they hold.

use crate::common::random::Rng;
use crate::common::reference::ExactField;
use crate::far_bounds::{field, start_on, touches, SUNS};
use heightray::heightfield::{landscape, Quantisation, StripBounds};
use heightray::Heightfield;

/// A low flat field with a few tall single samples: rays of a disc that drift across the
/// strips meet spikes that the strips along the axis never hold.
fn spikes(rng: &mut Rng, n: usize) -> Heightfield {
    let mut samples = vec![0u16; n * n];
    for _ in 0..n / 3 {
        samples[rng.below(n * n)] = 40 + rng.below(200) as u16;
    }
    Heightfield::new(n, n, samples, Quantisation::Maxval(255), 20.0, None).unwrap()
}

/// The field of round `round` of the discs' checks: a landscape, then spiky and random ones
/// of growing size.
fn strip_field(round: usize, rng: &mut Rng) -> Heightfield {
    match round {
        0 => landscape(33, 3, 12.0).unwrap(),
        _ if round.is_multiple_of(2) => spikes(rng, 24 + round),
        _ => field(rng, 8 + round),
    }
}

/// A direction at angle `atan(r)` from `axis`, turned `turn` about it.
fn in_disc(axis: [f64; 3], r: f64, turn: f64) -> [f64; 3] {
    let norm = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / l)
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let a = norm(axis);
    let across = norm(cross(a, [0.0, 0.0, 1.0]));
    let up = cross(across, a);
    let (c, s) = (turn.cos() * r, turn.sin() * r);
    norm([0, 1, 2].map(|k| a[k] + across[k] * c + up[k] * s))
}

#[test]
fn rays_of_the_suns_disc_called_clear_beyond_a_point_touch_nothing_from_there_on() {
    let mut rng = Rng(0x0d15_c0f5_a7e5);
    let (mut asked, mut clear, mut built) = (0, 0, 0);
    let (mut discs, mut discs_clear) = (0, 0);
    for round in 0..12 {
        let field = strip_field(round, &mut rng);
        let exact = ExactField::new(&field);
        for sun in SUNS {
            for half in [0.0046, 0.02, 0.1] {
                let Some(bounds) = StripBounds::build(&field, sun, half) else {
                    // Only a disc that dips to the horizon (or under it), or one near the
                    // zenith that spans most azimuths, is refused.
                    let elevation = sun[2].atan2(sun[0].hypot(sun[1]));
                    let wide = half.sin() / elevation.cos() > 0.8;
                    assert!(elevation - half < 0.01 || wide, "sun {sun:?}, half {half}");
                    continue;
                };
                built += 1;
                for _ in 0..12 {
                    let start = start_on(&field, &mut rng);
                    discs += 1;
                    if let Some(distance) = bounds.disc_clear_beyond(start, 0.0) {
                        discs_clear += 1;
                        // The rim all round, the axis and points inside, from `distance` on.
                        for k in 0..24 {
                            let r = half.tan() * [1.0, 0.0, rng.within(0.0, 1.0)][k % 3];
                            let dir = in_disc(sun, r, rng.within(0.0, std::f64::consts::TAU));
                            let t = distance / dir[0].hypot(dir[1]);
                            assert!(
                                !touches(&field, &exact, (start, dir), t, f64::INFINITY),
                                "round {round}, sun {sun:?}, half {half}, dir {dir:?}, start {start:?}: the disc touches the surface beyond {distance} cells"
                            );
                        }
                    }
                    // Inside the disc, its rim included.
                    let r = half.tan() * [1.0, rng.within(0.0, 1.0)][rng.below(2)];
                    let dir = in_disc(sun, r, rng.within(0.0, std::f64::consts::TAU));
                    asked += 1;
                    let Some(t) = bounds.clear_beyond(start, dir, 0.0) else {
                        continue;
                    };
                    clear += 1;
                    assert!(
                        !touches(&field, &exact, (start, dir), t, f64::INFINITY),
                        "round {round}, sun {sun:?}, half {half}, dir {dir:?}, start {start:?}: touches the surface beyond t = {t}"
                    );
                }
            }
        }
    }
    assert!(built > 250, "{built} discs bounded");
    // A good share of the rays is settled: the test is not vacuous.
    assert!(clear * 3 > asked, "{clear} of {asked} rays called clear");
    assert!(
        discs_clear * 4 > discs,
        "{discs_clear} of {discs} discs called clear"
    );
}

/// A field flat but for one spike 3 rows across from the start `[2, 10]` of the spike
/// checks, and a disc along x whose rim reaches the spike while its axis passes it by.
fn one_spike() -> (Heightfield, ([f64; 3], f64)) {
    let (w, h) = (48, 16);
    let mut samples = vec![0u16; w * h];
    samples[7 * w + 30] = 200;
    let field = Heightfield::new(w, h, samples, Quantisation::Maxval(255), 25.5, None).unwrap();
    (field, ([1.0, 0.0, 0.3], 0.1))
}

#[test]
fn a_ray_of_the_disc_that_drifts_into_another_strip_meets_its_spike() {
    let (field, (axis, half)) = one_spike();
    let bounds = StripBounds::build(&field, axis, half).expect("the disc climbs");
    // Worked by hand: at the rim, turned towards -y, the ray is 2.9 rows across and 8.5 high
    // at x = 30, where the spike's triangles stand about 18 high.
    let dir = in_disc(axis, half.tan() * 0.999, 0.0);
    let start = [2.0, 10.0, 0.05];
    let exact = ExactField::new(&field);
    assert!(touches(&field, &exact, (start, dir), 0.0, f64::INFINITY));
    // Called clear only from a column line past the spike (x = 33, the first whose blocks
    // hold none of its vertices): the part left to walk holds the touch.
    let t = bounds
        .clear_beyond(start, dir, 0.0)
        .expect("clear past the spike");
    assert!(
        start[0] + t * dir[0] > 31.0,
        "called clear before the spike"
    );
    assert!(touches(&field, &exact, (start, dir), 0.0, t));
    // The axis itself passes the spike by: its own strip is clear.
    assert!(bounds.clear_beyond(start, axis, 0.0).is_some());
}

#[test]
fn a_disc_whose_rim_drifts_into_another_strip_is_not_called_clear_before_its_spike() {
    // The spike of the single rays' check: the disc's rim meets it, its axis passes it by.
    let (field, (axis, half)) = one_spike();
    let bounds = StripBounds::build(&field, axis, half).expect("the disc climbs");
    let start = [2.0, 10.0, 0.05];
    let distance = bounds
        .disc_clear_beyond(start, 0.0)
        .expect("clear past the spike");
    assert!(
        start[0] + distance > 31.0,
        "called clear {distance} cells on, before the spike at x = 30"
    );
}
