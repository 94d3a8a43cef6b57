//! The larger and the smaller of two floats known not to be NaN, as one instruction each
//! (`maxsd`/`minsd`, or their packed forms), where `f64::max` and `f64::min` spend three on
//! the NaN they must handle: for loops that compare crossings and bounds.

/// The larger of two values that are not NaN.
#[inline(always)]
pub fn larger(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// The smaller of two values that are not NaN.
#[inline(always)]
pub fn smaller(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}
