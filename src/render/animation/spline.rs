//! A centripetal Catmull-Rom spline through points given at times (Yuksel, Schaefer & Keyser
//! 2011): it passes through every point, its tangent turns smoothly at each, and it makes no
//! cusp or loop between close points. Each segment is the Barry-Goldman pyramid over knots
//! spaced by the square root of the distance between points; its knot interval is mapped
//! linearly onto the segment's time interval. The ends are extended by reflecting the second
//! point through the first (and the last but one through the last).

use glam::DVec3;

/// Where a spline through `points` (in order of `times`, which increase) is at `time`;
/// before the first time the first point, after the last the last.
pub fn at(times: &[f64], points: &[DVec3], time: f64) -> DVec3 {
    let n = points.len();
    match n {
        0 => return DVec3::ZERO,
        1 => return points[0],
        _ => {}
    }
    if time <= times[0] {
        return points[0];
    }
    if time >= times[n - 1] {
        return points[n - 1];
    }
    // The segment from point `i` to `i + 1` holds `time`.
    let i = times.partition_point(|&t| t <= time).clamp(1, n - 1) - 1;
    let (p1, p2) = (points[i], points[i + 1]);
    let p0 = if i == 0 { 2.0 * p1 - p2 } else { points[i - 1] };
    let p3 = if i + 2 == n {
        2.0 * p2 - p1
    } else {
        points[i + 2]
    };
    let u = (time - times[i]) / (times[i + 1] - times[i]);
    segment([p0, p1, p2, p3], u)
}

/// Knot spacing between two points: the square root of their distance (centripetal), never
/// zero, so that a point repeated (a pause) leaves the pyramid defined.
fn spacing(a: DVec3, b: DVec3) -> f64 {
    a.distance(b).sqrt().max(1e-12)
}

/// The point at fraction `u` of the way from `p[1]` to `p[2]` in knot parameter.
fn segment(p: [DVec3; 4], u: f64) -> DVec3 {
    if p[1] == p[2] {
        return p[1];
    }
    let t0 = 0.0;
    let t1 = t0 + spacing(p[0], p[1]);
    let t2 = t1 + spacing(p[1], p[2]);
    let t3 = t2 + spacing(p[2], p[3]);
    let t = t1 + u * (t2 - t1);
    let lerp = |a: DVec3, b: DVec3, ta: f64, tb: f64| a + (b - a) * ((t - ta) / (tb - ta));
    let a1 = lerp(p[0], p[1], t0, t1);
    let a2 = lerp(p[1], p[2], t1, t2);
    let a3 = lerp(p[2], p[3], t2, t3);
    let b1 = lerp(a1, a2, t0, t2);
    let b2 = lerp(a2, a3, t1, t3);
    lerp(b1, b2, t1, t2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_on_a_line_at_even_spacing_move_evenly() {
        // Collinear, evenly spaced points at even times: the spline is the line itself, at
        // constant speed (every knot interval is the same, so the pyramid is linear).
        let points = [0.0, 1.0, 2.0, 3.0].map(|x| DVec3::new(x, 0.0, 0.0));
        let times = [0.0, 1.0, 2.0, 3.0];
        for k in 0..=30 {
            let t = f64::from(k) / 10.0;
            let p = at(&times, &points, t);
            assert!((p - DVec3::new(t, 0.0, 0.0)).length() < 1e-12, "{t}: {p}");
        }
    }
}
