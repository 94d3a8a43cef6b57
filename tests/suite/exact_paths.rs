//! Exact mode has two paths: intervals that settle almost every decision, and rationals for
//! the rays they cannot settle. Both must give the same answers and counters; here the
//! rational path is run on its own (through `Tracer::trace::<Exact>`) against `trace` in exact
//! mode, on random rays that favour degenerate cases (so both paths are taken).

use crate::common::random::field_and_ray;
use heightray::arith::{settled, Exact, Interval, Scalar};
use heightray::traverse::Tracer;
use heightray::{trace, Arith, Method, TraceOptions};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, rng_seed: RngSeed::Fixed(7), ..ProptestConfig::default() })]

    #[test]
    fn interval_path_and_rational_path_agree((field, ray) in field_and_ray()) {
        let terrain = heightray::Terrain::new(field);
        for method in Method::ALL {
            let combined = trace(&terrain, &ray, &TraceOptions::new(method, Arith::Exact));
            let rational = Tracer::new(&terrain, method).trace::<Exact>(&ray, None);
            prop_assert_eq!(combined.counters, rational.counters, "{}", method);
            let combined_hit = combined.hit.map(|h| (h.t_exact, h.cell, h.triangle));
            let rational_hit = rational.hit.map(|f| (f.t.to_exact(), [f.cell.0, f.cell.1], f.triangle));
            prop_assert_eq!(combined_hit, rational_hit, "{}", method);
        }
    }
}

/// The interval path settles ordinary rays: a generic ray over a hilly field takes it.
#[test]
fn ordinary_rays_are_settled_by_intervals() {
    let field = heightray::heightfield::landscape(33, 5, 10.0).unwrap();
    let terrain = heightray::Terrain::new(field);
    let ray = heightray::Ray::new([-3.1234, -2.71, 14.2], [1.0, 0.8377, -0.4123]).unwrap();
    let tracer = Tracer::new(&terrain, Method::Runs);
    let (answer, is_settled) = settled(|| tracer.trace::<Interval>(&ray, None));
    assert!(is_settled);
    assert!(answer.hit.is_some());
}
