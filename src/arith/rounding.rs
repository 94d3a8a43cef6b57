//! Rounding outwards: `f64` operations whose results are moved to the floats just below and
//! just above the exact value, exactly where error-free transformations (TwoSum, the residual
//! of a product or quotient) show it and by one float otherwise. [`super::Interval`] builds its
//! ends from these.

/// `a + b` rounded down and up: `s + e` is the exact sum (TwoSum).
#[inline]
pub(super) fn sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (
        if e < 0.0 { below(s) } else { s },
        if e > 0.0 { above(s) } else { s },
    )
}

/// Products below this may lose bits of their FMA residual to underflow, and below it the
/// relative step of [`below`] could lose accuracy to underflow.
pub(super) const TINY: f64 = 1e-280;

/// Operands above this could overflow when split for [`product_error`].
const HUGE: f64 = 1e290;

/// A step of `|x| * STEP` moves any normal `x` at least to its neighbour float and no further:
/// a little over half an ulp relative to `x`, never a tie to round back onto `x` (see [`below`]).
const STEP: f64 = f64::EPSILON / 2.0 * (1.0 + 1.0 / 1024.0);

/// Below the exact value `y` of one operation whose result `x` was rounded to nearest: the
/// float just below `x`.
///
/// Why it holds without knowing the rounding error: `|y - x|` is at most half the spacing of
/// the floats on `y`'s side of `x`, and `x - |x| * STEP` lies more than half a spacing and less
/// than one and a half below `x`, so it rounds to `x`'s lower neighbour (the product `|x| *
/// STEP` is accurate: `x` is far from underflow). Ends of intervals that are not points need
/// no more than this; the exact residual is only worth its cost for keeping exact results
/// exact, which [`product_end`] and [`quotient_end`] do where the operands show it.
#[inline]
pub(super) fn below(x: f64) -> f64 {
    if x.abs() >= TINY {
        x - x.abs() * STEP
    } else {
        x.next_down()
    }
}

/// Above the exact value of one operation whose result `x` was rounded to nearest: the float
/// just above `x` (see [`below`]).
#[inline]
pub(super) fn above(x: f64) -> f64 {
    if x.abs() >= TINY {
        x + x.abs() * STEP
    } else {
        x.next_up()
    }
}

/// The fraction bits of an `f64`.
const FRACTION: u64 = (1 << 52) - 1;

/// Whether `x * y` is exact whatever the exponents (barring underflow): one factor is a power of
/// two or zero, or both have at most 26 significant bits. Grid coordinates, halves and
/// quarters of hand-made rays are such numbers, and their products must stay exact for ties
/// between them to settle.
#[inline]
pub(super) fn short_product(x: f64, y: f64) -> bool {
    const LOW: u64 = (1 << 27) - 1;
    let (fx, fy) = (x.to_bits() & FRACTION, y.to_bits() & FRACTION);
    fx == 0 || fy == 0 || (fx | fy) & LOW == 0
}

/// `x * y` moved outwards by `outward` ([`below`] or [`above`]) unless [`short_product`]
/// says it is exact.
#[inline]
pub(super) fn product_end(x: f64, y: f64, outward: fn(f64) -> f64) -> f64 {
    let p = x * y;
    if x == 0.0 || y == 0.0 || (short_product(x, y) && p.abs() >= TINY) {
        p
    } else {
        outward(p)
    }
}

/// `x / y` moved outwards by `outward` unless exact by its operands alone: a zero dividend
/// (a hit at `t = 0`) or a power-of-two divisor.
#[inline]
pub(super) fn quotient_end(x: f64, y: f64, outward: fn(f64) -> f64) -> f64 {
    let q = x / y;
    if x == 0.0 || (y.to_bits() & FRACTION == 0 && q.abs() >= TINY) {
        q
    } else {
        outward(q)
    }
}

/// The rounding error `a*b - p` of the product `p = a*b`, exactly: one fused multiply-add
/// where the target has it, else Dekker's splitting (a library `fma` call is several times
/// slower than the dozen operations of the split).
#[inline]
pub(super) fn product_error(a: f64, b: f64, p: f64) -> f64 {
    if cfg!(target_feature = "fma") || a.abs() > HUGE || b.abs() > HUGE {
        return a.mul_add(b, -p);
    }
    // Veltkamp's split into halves of 26 bits: products of halves are exact.
    let split = |x: f64| {
        let c = 134_217_729.0 * x; // 2^27 + 1
        let hi = c - (c - x);
        (hi, x - hi)
    };
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    ((ah * bh - p) + ah * bl + al * bh) + al * bl
}

/// `a * b` rounded down and up: `p + e` is the exact product, so an exact product stays a
/// point.
#[inline]
pub(super) fn product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    if p.abs() < TINY {
        if a == 0.0 || b == 0.0 {
            return (0.0, 0.0);
        }
        // (Underflow: even a zero `p` is not exact.)
        return (p.next_down().min(0.0), p.next_up().max(0.0));
    }
    let e = product_error(a, b, p);
    (
        if e < 0.0 { below(p) } else { p },
        if e > 0.0 { above(p) } else { p },
    )
}

/// `a / b` (b non-zero) rounded down and up: the residual `a - q*b` gives the side of `q`.
pub(super) fn quotient(a: f64, b: f64) -> (f64, f64) {
    let q = a / b;
    if a == 0.0 {
        return (q, q);
    }
    // The residual is a multiple of the dividend's ulp times 2^-104 or so: near underflow it
    // is not a float. `q` is still rounded to nearest, so its neighbours enclose the quotient.
    if a.abs() < TINY || q.abs() < TINY {
        return (q.next_down(), q.next_up());
    }
    // `a - q*b`: `a - p` is exact (Sterbenz: `p` is within a factor 2 of `a`), so the
    // difference with the product's error has the residual's sign.
    let p = q * b;
    let r = (a - p) - product_error(q, b, p);
    let above = (r > 0.0) == (b > 0.0) && r != 0.0; // exact quotient above q
    let below = r != 0.0 && !above;
    (
        if below { self::below(q) } else { q },
        if above { self::above(q) } else { q },
    )
}
