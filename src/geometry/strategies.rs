//! Proptest strategies shared by the tests of ray and triangle geometry.

use proptest::prelude::*;

/// A ray direction's component: zero, small integers (rays along grid lines, diagonals and
/// through lattice points), arbitrary, and tiny (nearly parallel to an axis).
pub fn component() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        (-4i32..5).prop_map(f64::from),
        -1.0f64..1.0,
        (-1.0f64..1.0).prop_map(|x| x * 1e-9),
    ]
}
