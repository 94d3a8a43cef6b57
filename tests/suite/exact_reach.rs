//! Exact shadow rays with a reach (a sky ray's distance, the part kept bounds leave to walk):
//! every method answers alike from an exact start on the surface, and every answer holds
//! against the exact reference: a ray touching the surface up to the reach is blocked, and one
//! touching nothing up to a cell's diagonal past it is clear. (Between the two, a touch counts
//! where the walk's last cells hold it, the same for every method.)

use crate::common::options;
use crate::common::random::Rng;
use crate::common::reference::{first_touch, q, ExactField, ExactRay, Q};
use crate::far_bounds::{field, SUNS};
use heightray::arith::Exact;
use heightray::traverse::{Start, Tracer};
use heightray::{trace, Arith, Heightfield, Method, Ray, Terrain};

/// The least `t > 0` at which the ray from the exact point `o` towards `dir` touches a
/// triangle, exactly (a line meets the plane of a triangle it starts on only there).
fn first_touch_after_start(field: &Heightfield, o: &[Q; 3], dir: [f64; 3]) -> Option<Q> {
    let exact = ExactField::new(field);
    let ray = ExactRay {
        o: o.clone(),
        d: dir.map(q),
        dir,
    };
    let zero = q(0.0);
    (0..field.height() - 1)
        .flat_map(|j| (0..field.width() - 1).map(move |i| [i, j]))
        .flat_map(|cell| [0, 1].map(|k| (cell, k)))
        .filter_map(|(cell, k)| first_touch(&exact, &ray, cell, k).filter(|t| *t > zero))
        .min()
}

#[test]
fn reach_limited_exact_shadow_rays_agree_across_methods_and_with_the_reference() {
    let mut rng = Rng(0x7eac_4ed5_0bad);
    let (mut blocked, mut clear, mut past_reach) = (0, 0, 0);
    for _ in 0..24 {
        let n = 20 + rng.below(12);
        let field = field(&mut rng, n);
        let terrain = Terrain::new(field.clone());
        let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
        for _ in 0..12 {
            // A camera ray from high above onto a random point: its exact hit is the start.
            let target = [rng.within(0.5, w - 0.5), rng.within(0.5, h - 0.5), 0.0];
            let eye = [target[0] + rng.within(-3.0, 3.0), target[1], 400.0];
            let down = [0, 1, 2].map(|k| target[k] - eye[k]);
            let ray = Ray::new(eye, down).expect("a ray");
            let Some(t) = trace(&terrain, &ray, &options(Method::Runs, Arith::Exact))
                .hit
                .and_then(|hit| hit.t_exact)
            else {
                continue;
            };
            let (o, d) = (ray.origin(), ray.dir());
            let point: [Q; 3] = [0, 1, 2].map(|k| q(o[k]) + q(d[k]) * t.clone());
            let start = point.clone().map(Exact);
            let sun = match rng.below(3) {
                0 => SUNS[rng.below(SUNS.len())],
                _ => [
                    rng.within(-1.0, 1.0),
                    rng.within(-1.0, 1.0),
                    rng.within(-0.2, 1.0),
                ],
            };
            let across = sun[0].hypot(sun[1]);
            let touch = first_touch_after_start(&field, &point, sun);
            for _ in 0..4 {
                let reach = rng.within(0.02, 12.0) / across.max(0.05);
                let answers: Vec<_> = Method::ALL
                    .iter()
                    .map(|&method| {
                        let tracer = Tracer::new(&terrain, method).within(reach);
                        tracer.occluded(&Start::Point(&start), sun, false).occluded
                    })
                    .collect();
                let what = format!("start {point:?} sun {sun:?} reach {reach} touch {touch:?}");
                assert!(
                    answers.iter().all(|a| *a == answers[0]),
                    "{what}: {answers:?}"
                );
                let last_cell = reach + std::f64::consts::SQRT_2 * 1.001 / across;
                match &touch {
                    Some(t) if *t <= q(reach) => {
                        assert_eq!(answers[0], Some(true), "{what}");
                        blocked += 1;
                    }
                    Some(t) if *t <= q(last_cell) => past_reach += 1,
                    _ => {
                        assert_eq!(answers[0], Some(false), "{what}");
                        clear += 1;
                    }
                }
            }
        }
    }
    assert!(
        blocked > 100 && clear > 100 && past_reach > 0,
        "{blocked} blocked, {clear} clear, {past_reach} touched just past the reach"
    );
}

/// A hand-worked ray whose reach ends a hair short of the cell it would touch next: from
/// `(1/3, 1/2, 0)` (no `f64`) on flat ground nearly along `+x`, climbing 0.1 a cell, towards
/// a cell whose far side stands 10 high. The reach, 2/3 rounded down to an `f64`, ends the
/// path 3.7e-17 before `x = 1`, within the `f64` walk's room for the start but outside that
/// cell: the touch just past it (at `t` near 0.673) is not in the way, for every method.
#[test]
fn a_touch_in_the_cell_just_past_the_reach_is_not_in_the_way() {
    let terrain =
        crate::common::families::terrain(16, 16, 10, 10.0, |x, _| if x >= 2 { 10 } else { 0 });
    let third = Q::new(1.into(), 3.into());
    let start = [third, Q::new(1.into(), 2.into()), q(0.0)].map(Exact);
    let dir = [1.0, 0.01, 0.1];
    let reach = 2.0f64 / 3.0;
    assert!(q(reach) < Q::new(2.into(), 3.into()));
    for method in Method::ALL {
        let tracer = Tracer::new(&terrain, method).within(reach);
        let answer = tracer.occluded(&Start::Point(&start), dir, false).occluded;
        assert_eq!(answer, Some(false), "{method}");
        // Reaching on into the cell, the touch is in the way.
        let further = Tracer::new(&terrain, method).within(0.7);
        let answer = further.occluded(&Start::Point(&start), dir, false).occluded;
        assert_eq!(answer, Some(true), "{method}");
    }
}
