//! How high the terrain rises around a point of the surface, along one horizontal direction:
//! the horizon a sky-view factor and a sunrise are measured against.
//!
//! Along a vertical plane through the point, the surface is a polyline: straight within each
//! triangle, bending only where the line crosses a cell's edge (`x` or `y` whole) or its
//! diagonal (`x - y` whole). Over a straight piece `z = a + b*d` the rise `(z - z0) / d` is
//! monotone in the distance `d`, so its greatest value is at a piece's end: walking those
//! crossings in order and taking the rise at each finds the horizon of the triangulated
//! surface itself, not of samples near the line. Holes have no surface and add nothing.

use crate::heightfield::Terrain;

/// The steepest rise seen from a point of the surface along one direction.
pub struct Horizon<'a> {
    terrain: &'a Terrain,
    /// World units per grid unit along x, y and z.
    scale: [f64; 3],
}

impl<'a> Horizon<'a> {
    /// Horizons over `terrain`, measured in its world coordinates (true proportions on a
    /// georeferenced map shown unexaggerated).
    pub fn new(terrain: &'a Terrain) -> Self {
        Horizon {
            terrain,
            scale: terrain.world_from_grid().unwrap_or([1.0, 1.0, 1.0]),
        }
    }

    /// The surface height (grid units) at grid point `(x, y)`, on a cell that is not a hole;
    /// `None` off the map or where every cell holding the point is a hole.
    pub fn surface_z(&self, [x, y]: [f64; 2]) -> Option<f64> {
        let field = self.terrain.field();
        let (last_i, last_j) = ((field.width() - 2) as f64, (field.height() - 2) as f64);
        if !(x >= 0.0 && y >= 0.0 && x <= last_i + 1.0 && y <= last_j + 1.0) {
            return None;
        }
        // A point on a cell's edge belongs to the cells on both sides.
        let candidates = |v: f64, last: f64| {
            let below = v.floor().min(last);
            [
                below,
                if v == below && below > 0.0 {
                    below - 1.0
                } else {
                    below
                },
            ]
        };
        for i in candidates(x, last_i) {
            for j in candidates(y, last_j) {
                let (i, j) = (i as usize, j as usize);
                if !field.is_hole_cell(i, j) {
                    return Some(field.surface_z((i, j), (x - i as f64, y - j as f64)));
                }
            }
        }
        None
    }

    /// The greatest rise `(z - z0) / d` (world units, `d` horizontal) of the surface seen from
    /// grid point `from` at height `z0` (grid units) towards the compass direction `toward`
    /// (a horizontal unit vector in the world, x east, y north), over distances `0 < d <=
    /// reach` (world units); `None` where no surface lies that way within reach.
    pub fn rise(&self, from: [f64; 2], z0: f64, toward: [f64; 2], reach: f64) -> Option<f64> {
        let field = self.terrain.field();
        let (cells_x, cells_y) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
        let g = [toward[0] / self.scale[0], toward[1] / self.scale[1]];
        let at = |d: f64| [from[0] + d * g[0], from[1] + d * g[1]];
        let mut lines = [
            Crossings::new(from[0], g[0]),
            Crossings::new(from[1], g[1]),
            Crossings::new(from[0] - from[1], g[0] - g[1]),
        ];
        let z_top = self.terrain.z_range().1;
        let mut best: Option<f64> = None;
        let mut d = 0.0;
        while d < reach {
            let next = lines.iter().map(Crossings::next).fold(reach, f64::min);
            for line in &mut lines {
                line.pass(next);
            }
            let [mx, my] = at(0.5 * (d + next));
            if !(mx >= 0.0 && my >= 0.0 && mx <= cells_x && my <= cells_y) {
                break; // off the map, which is convex: nothing further on.
            }
            let (i, j) = (
                (mx.floor() as usize).min(field.width() - 2),
                (my.floor() as usize).min(field.height() - 2),
            );
            if !field.is_hole_cell(i, j) {
                let lower = mx - i as f64 >= my - j as f64;
                for end in [d, next] {
                    if end > 0.0 {
                        let [x, y] = at(end);
                        let z = triangle_z(field, (i, j), lower, (x - i as f64, y - j as f64));
                        let rise = (z - z0) * self.scale[2] / end;
                        best = Some(best.map_or(rise, |b| b.max(rise)));
                    }
                }
            }
            d = next;
            // Nothing further on can rise more steeply than the highest terrain at this distance.
            if best.is_some_and(|b| (z_top - z0) * self.scale[2] <= b * d) {
                break;
            }
        }
        best
    }
}

/// The height on the lower (`P00, P10, P11`, where `fx >= fy`) or upper triangle of cell
/// `(i, j)` at fractions `(fx, fy)`: a crossing at a piece's end is on the piece's triangle.
fn triangle_z(
    field: &crate::Heightfield,
    (i, j): (usize, usize),
    lower: bool,
    (fx, fy): (f64, f64),
) -> f64 {
    let [z00, z10, z01, z11] = [
        field.z(i, j),
        field.z(i + 1, j),
        field.z(i, j + 1),
        field.z(i + 1, j + 1),
    ];
    if lower {
        z00 + fx * (z10 - z00) + fy * (z11 - z10)
    } else {
        z00 + fy * (z01 - z00) + fx * (z11 - z01)
    }
}

/// Where a line `v(d) = v0 + d * rate` next takes a whole value, beyond the distance passed.
struct Crossings {
    v0: f64,
    rate: f64,
    /// The next whole value the line reaches.
    next_value: f64,
}

impl Crossings {
    fn new(v0: f64, rate: f64) -> Self {
        let next_value = if rate > 0.0 {
            v0.floor() + 1.0
        } else {
            v0.ceil() - 1.0
        };
        Crossings {
            v0,
            rate,
            next_value,
        }
    }

    /// The distance of the next crossing (infinite for a line parallel to these).
    fn next(&self) -> f64 {
        if self.rate == 0.0 {
            f64::INFINITY
        } else {
            (self.next_value - self.v0) / self.rate
        }
    }

    /// Moves past every crossing up to distance `d`.
    fn pass(&mut self, d: f64) {
        while self.rate != 0.0 && self.next() <= d {
            self.next_value += self.rate.signum();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Heightfield;

    /// A plane rising 0.5 per cell towards the east, 9 x 9 samples.
    fn ramp() -> Terrain {
        Terrain::new(Heightfield::from_fn(9, 9, 8, 4.0, |i, _| i as u16).unwrap())
    }

    #[test]
    fn a_plane_rises_by_its_slope_uphill_and_falls_downhill() {
        let terrain = ramp();
        let horizon = Horizon::new(&terrain);
        let z0 = horizon.surface_z([4.0, 4.0]).unwrap();
        assert_eq!(z0, 2.0);
        let east = horizon.rise([4.0, 4.0], z0, [1.0, 0.0], 10.0).unwrap();
        assert!((east - 0.5).abs() < 1e-12, "{east}");
        let west = horizon.rise([4.0, 4.0], z0, [-1.0, 0.0], 10.0).unwrap();
        assert!((west + 0.5).abs() < 1e-12, "{west}");
        // North-east, 45 degrees off the slope: it rises by 0.5 * cos 45.
        let s = 0.5f64.sqrt();
        let ne = horizon.rise([4.0, 4.0], z0, [s, s], 10.0).unwrap();
        assert!((ne - 0.5 * s).abs() < 1e-12, "{ne}");
    }

    #[test]
    fn a_point_off_the_map_has_no_surface() {
        let terrain = ramp();
        let horizon = Horizon::new(&terrain);
        assert_eq!(horizon.surface_z([-0.1, 2.0]), None);
        assert_eq!(horizon.surface_z([8.0, 8.0]), Some(4.0));
        assert_eq!(horizon.rise([8.0, 4.0], 4.0, [1.0, 0.0], 10.0), None);
    }
}
