//! Where sub-pixel positions and effect rays point: a 2D low-discrepancy sequence (the first
//! two dimensions of Sobol's sequence, a (0,2)-sequence: every power-of-two prefix is
//! stratified), shifted per pixel or per point by a hash (Cranley-Patterson rotation), so a
//! sample depends only on what it belongs to, never on threads or tile order.

use glam::DVec3;
use std::f64::consts::PI;

/// A 64-bit mix of a value (SplitMix64's finaliser).
pub fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A seed from a ray (its origin's and direction's bits) and a purpose: the same ray gives the
/// same effect samples in every run, on every thread.
pub fn seed_of(origin: [f64; 3], dir: [f64; 3], purpose: u64) -> u64 {
    origin
        .iter()
        .chain(dir.iter())
        .fold(mix(purpose), |h, c| mix(h ^ c.to_bits()))
}

/// Point `index` of the 2D sequence rotated by `seed`'s two offsets, in `[0, 1)^2`.
pub fn point(index: u32, seed: u64) -> (f64, f64) {
    let unit = |bits: u32| f64::from(bits) / 4_294_967_296.0;
    let shift_x = seed as u32;
    let shift_y = (seed >> 32) as u32;
    // Rotation modulo 1 is a wrapping add of the 32-bit fractions.
    (
        unit(index.reverse_bits().wrapping_add(shift_x)),
        unit(sobol_second(index).wrapping_add(shift_y)),
    )
}

/// The second dimension of Sobol's sequence, as a 32-bit fraction.
fn sobol_second(mut index: u32) -> u32 {
    let (mut v, mut r) = (1u32 << 31, 0u32);
    while index != 0 {
        if index & 1 != 0 {
            r ^= v;
        }
        index >>= 1;
        v ^= v >> 1;
    }
    r
}

/// `(u, v)` in the unit square to the unit disc, keeping strata compact (Shirley and Chiu's
/// concentric map).
pub fn disc(u: f64, v: f64) -> (f64, f64) {
    let (a, b) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    if a == 0.0 && b == 0.0 {
        return (0.0, 0.0);
    }
    // The angle is `x` in the first case, `pi/2 - x` in the second, with `|x| <= pi/4`.
    if a.abs() > b.abs() {
        let (sin, cos) = sin_cos_within_quarter(PI / 4.0 * (b / a));
        (a * cos, a * sin)
    } else {
        let (sin, cos) = sin_cos_within_quarter(PI / 4.0 * (a / b));
        (b * sin, b * cos)
    }
}

/// `(sin x, cos x)` for `|x| <= pi/4`, to within a few ulps: their Taylor series, whose first
/// terms left out are below `x^17 / 17! < 6e-17` there. (The library's `sin` and `cos`
/// reduce any argument first, which costs a sky ray more than its bounds' look-up.)
fn sin_cos_within_quarter(x: f64) -> (f64, f64) {
    // `sin x = x * S(x^2)` and `cos x = C(x^2)`, coefficients (signed `1/n!`) highest first.
    const S: [f64; 8] = [
        -1.0 / 1_307_674_368_000.0,
        1.0 / 6_227_020_800.0,
        -1.0 / 39_916_800.0,
        1.0 / 362_880.0,
        -1.0 / 5040.0,
        1.0 / 120.0,
        -1.0 / 6.0,
        1.0,
    ];
    const C: [f64; 9] = [
        1.0 / 20_922_789_888_000.0,
        -1.0 / 87_178_291_200.0,
        1.0 / 479_001_600.0,
        -1.0 / 3_628_800.0,
        1.0 / 40_320.0,
        -1.0 / 720.0,
        1.0 / 24.0,
        -1.0 / 2.0,
        1.0,
    ];
    let y = x * x;
    let horner = |terms: &[f64]| terms.iter().fold(0.0, |sum, &c| sum * y + c);
    (x * horner(&S), horner(&C))
}

/// Two unit vectors completing `n` (a unit vector) to an orthonormal basis.
pub fn basis(n: DVec3) -> (DVec3, DVec3) {
    n.any_orthonormal_pair()
}

/// The hemisphere around a unit vector, with the basis its directions are drawn in, made once
/// for all of a point's directions.
#[derive(Clone, Copy, Debug)]
pub struct Hemisphere {
    n: DVec3,
    a: DVec3,
    b: DVec3,
}

impl Hemisphere {
    /// The hemisphere around the unit vector `n`.
    pub fn around(n: DVec3) -> Hemisphere {
        let (a, b) = basis(n);
        Hemisphere { n, a, b }
    }

    /// `(u, v)` to a direction of the hemisphere, with density proportional to the cosine to
    /// its vector (Malley's method: the disc projected up).
    pub fn cosine(&self, u: f64, v: f64) -> DVec3 {
        let (x, y) = disc(u, v);
        let z = (1.0 - x * x - y * y).max(0.0).sqrt();
        self.a * x + self.b * y + self.n * z
    }
}

/// The directions of a cone, with the basis and radius they are drawn with, made once for
/// all of them (a frame's soft shadows share one).
#[derive(Clone, Copy, Debug)]
pub struct ConeDirections {
    axis: DVec3,
    a: DVec3,
    b: DVec3,
    r: f64,
}

impl ConeDirections {
    /// The cone of half-angle `half` (radians) around the unit vector `axis`.
    pub fn around(axis: DVec3, half: f64) -> ConeDirections {
        let (a, b) = basis(axis);
        ConeDirections {
            axis,
            a,
            b,
            r: half.tan(),
        }
    }

    /// `(u, v)` to a direction inside the cone: the disc of radius `tan(half)` one unit along
    /// the axis (the sun's disc as seen, uniform in area).
    pub fn at(&self, u: f64, v: f64) -> DVec3 {
        let (x, y) = disc(u, v);
        (self.axis + (self.a * x + self.b * y) * self.r).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unrotated, 16 points of the sequence put one point in each 4x4 cell, and one in each
    /// 16x1 and 1x16 strip.
    #[test]
    fn prefixes_are_stratified() {
        let mut grid = [0; 16];
        let (mut rows, mut columns) = ([0; 16], [0; 16]);
        for (x, y) in (0..16).map(|i| point(i, 0)) {
            grid[(x * 4.0) as usize * 4 + (y * 4.0) as usize] += 1;
            columns[(x * 16.0) as usize] += 1;
            rows[(y * 16.0) as usize] += 1;
        }
        assert_eq!(grid, [1; 16]);
        assert_eq!(rows, [1; 16]);
        assert_eq!(columns, [1; 16]);
    }

    /// Cosine-weighted directions: the mean of `cos` over the hemisphere is 2/3 (the integral
    /// of cos^2 over cos), and every direction lies on the normal's side.
    #[test]
    fn cosine_hemisphere_has_the_cosine_mean() {
        let n = DVec3::new(0.3, -0.2, 0.9).normalize();
        let hemisphere = Hemisphere::around(n);
        let count = 4096;
        let mean: f64 = (0..count)
            .map(|i| {
                let (u, v) = point(i, 77);
                let d = hemisphere.cosine(u, v);
                assert!((d.length() - 1.0).abs() < 1e-12);
                assert!(d.dot(n) >= -1e-12, "{d} below the hemisphere");
                d.dot(n)
            })
            .sum::<f64>()
            / f64::from(count);
        assert!((mean - 2.0 / 3.0).abs() < 1e-3, "{mean}");
    }

    /// The series agree with the library's `sin` and `cos` over the quarter turn they serve.
    #[test]
    fn sines_and_cosines_within_a_quarter_match_the_library() {
        for step in -1000..=1000 {
            let x = PI / 4.0 * f64::from(step) / 1000.0;
            let (sin, cos) = sin_cos_within_quarter(x);
            assert!(
                (sin - x.sin()).abs() <= 4e-16,
                "sin {x}: {sin} against {}",
                x.sin()
            );
            assert!(
                (cos - x.cos()).abs() <= 4e-16,
                "cos {x}: {cos} against {}",
                x.cos()
            );
        }
    }

    /// Directions in a cone stay within its half-angle, and reach near its edge.
    #[test]
    fn cone_directions_stay_inside() {
        let axis = DVec3::new(0.4, 0.3, 0.8).normalize();
        let half = 0.01f64;
        let cone = ConeDirections::around(axis, half);
        let widest = (0..256)
            .map(|i| {
                let (u, v) = point(i, 5);
                cone.at(u, v).dot(axis).clamp(-1.0, 1.0).acos()
            })
            .fold(0.0f64, f64::max);
        assert!(
            widest <= half * (1.0 + 1e-9) && widest > 0.9 * half,
            "{widest}"
        );
    }
}
