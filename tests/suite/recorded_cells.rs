//! Listing a walk's cells (`trace --cells`) must not change its answer: for every ray of the
//! deterministic hard-case families, every method and arithmetic, the hit with cells recorded
//! is the hit without. In the rounding arithmetics the walk is the same one, so the queries
//! counted are the same too; in exact arithmetic a listing walk leaves out the `f64` walks
//! that certify or clear the way (they list no cells), and counts other queries.

use crate::common::families;
use crate::common::options;
use heightray::{trace, Arith, Method, TraceOptions};

#[test]
fn recording_cells_changes_no_answer() {
    let ariths = [
        Arith::F32,
        Arith::F64,
        Arith::Rational { bound: 1 << 16 },
        Arith::Exact,
    ];
    let mut hits = 0;
    for family in families::all() {
        for ray in &family.rays {
            for method in Method::ALL {
                for arith in ariths {
                    let listed = trace(&family.terrain, ray, &options(method, arith));
                    // (Packets count their node tests in place of the walk's block tests:
                    // their answer is compared, their counters are not.)
                    let quiet = TraceOptions {
                        record_cells: false,
                        packets: false,
                        ..options(method, arith)
                    };
                    let plain = trace(&family.terrain, ray, &quiet);
                    let packed = TraceOptions {
                        packets: true,
                        ..quiet
                    };
                    let at = format!("{} {method} {arith} {ray:?}", family.name);
                    assert_eq!(listed.hit, plain.hit, "{at}");
                    assert_eq!(trace(&family.terrain, ray, &packed).hit, plain.hit, "{at}");
                    if arith != Arith::Exact {
                        assert_eq!(listed.counters, plain.counters, "{at}");
                    }
                    assert!(plain.cells.is_empty(), "{at}");
                    hits += usize::from(plain.hit.is_some());
                }
            }
        }
    }
    // The families hit the surface as well as miss it.
    assert!(hits > 100, "{hits} hits");
}
