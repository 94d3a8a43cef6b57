//! The water surface a scene asks for: a flat plane at a level wherever the terrain lies below
//! it, where camera rays meet it, and how much light it reflects.

use crate::heightfield::Heightfield;

/// A scene's water, validated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Water {
    /// The water's height (`z`, as the terrain's heights).
    pub level: f64,
    /// The water's own colour in linear light.
    pub colour: [f64; 3],
}

/// Water's reflectance at normal incidence: `((n - 1) / (n + 1))^2` for `n = 1.333`.
pub const NORMAL_REFLECTANCE: f64 = 0.0204;

/// Schlick's approximation of the share of light water reflects at an angle whose cosine to
/// the surface's normal is `cos`.
pub fn schlick(cos: f64) -> f64 {
    let r0 = NORMAL_REFLECTANCE;
    r0 + (1.0 - r0) * (1.0 - cos.clamp(0.0, 1.0)).powi(5)
}

impl Water {
    /// Where the ray `o + t d` (grid coordinates) meets the water: its `t`, if it crosses
    /// the level from above over a cell of `field` that is not a hole (no data holds no
    /// water), before the terrain's hit at `terrain_t` if any (a terrain hit at the level or
    /// above it is dry land).
    pub fn crossing(
        &self,
        o: [f64; 3],
        d: [f64; 3],
        terrain_t: Option<f64>,
        field: &Heightfield,
    ) -> Option<f64> {
        if !(d[2] < 0.0 && o[2] > self.level) {
            return None;
        }
        let t = (self.level - o[2]) / d[2];
        if terrain_t.is_some_and(|hit| hit <= t) {
            return None;
        }
        let (x, y) = (o[0] + t * d[0], o[1] + t * d[1]);
        let cells = (field.width() - 1, field.height() - 1);
        let over = |v: f64, cells: usize| (0.0..=cells as f64).contains(&v);
        if !(over(x, cells.0) && over(y, cells.1)) {
            return None;
        }
        // (The far edges belong to the last cells.)
        let cell = |v: f64, cells: usize| (v as usize).min(cells - 1);
        let (i, j) = (cell(x, cells.0), cell(y, cells.1));
        if field.is_hole_cell(i, j) {
            return None;
        }
        // A ray that came in under the surface through the map's side crosses the level
        // beneath dry land, where there is no water to see.
        let under_land = field.surface_z((i, j), (x - i as f64, y - j as f64)) >= self.level;
        (!under_land).then_some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schlick_is_the_normal_reflectance_head_on_and_total_at_grazing() {
        assert_eq!(schlick(1.0), NORMAL_REFLECTANCE);
        assert_eq!(schlick(0.0), 1.0);
        // Half way: r0 + (1 - r0) / 32.
        let half = NORMAL_REFLECTANCE + (1.0 - NORMAL_REFLECTANCE) / 32.0;
        assert!((schlick(0.5) - half).abs() < 1e-15);
    }

    #[test]
    fn rays_meet_the_water_only_from_above_over_the_map_before_dry_land() {
        let water = Water {
            level: 2.0,
            colour: [0.0; 3],
        };
        let down = [1.0, 0.0, -1.0];
        let field = |side| Heightfield::from_fn(side, side, 1, 1.0, |_, _| 0).unwrap();
        let (large, small) = (field(9), field(3));
        // From (0, 1, 5) down at 45 degrees: the level at t = 3, over x = 3.
        assert_eq!(
            water.crossing([0.0, 1.0, 5.0], down, None, &large),
            Some(3.0)
        );
        assert_eq!(
            water.crossing([0.0, 1.0, 5.0], down, Some(4.0), &large),
            Some(3.0)
        );
        // The terrain at the level or above it first: dry land.
        assert_eq!(
            water.crossing([0.0, 1.0, 5.0], down, Some(3.0), &large),
            None
        );
        // Off the map (x = 3 past a 3-sample map's x = 2), from below, and rising.
        assert_eq!(water.crossing([0.0, 1.0, 5.0], down, None, &small), None);
        assert_eq!(water.crossing([0.0, 1.0, 1.0], down, None, &large), None);
        assert_eq!(
            water.crossing([0.0, 1.0, 5.0], [1.0, 0.0, 1.0], None, &large),
            None
        );
        // Land 3 high everywhere: a ray in through the map's side at height 2.5 crosses the
        // level at x = 1 under the surface, with no terrain hit, and sees no water.
        let high = Heightfield::from_fn(9, 9, 1, 3.0, |_, _| 1).unwrap();
        let shallow = [1.0, 0.0, -0.125];
        assert_eq!(water.crossing([-3.0, 1.0, 2.5], shallow, None, &high), None);
        // The same ray over the flat map at height 0 meets the water there.
        assert_eq!(
            water.crossing([-3.0, 1.0, 2.5], shallow, None, &large),
            Some(4.0)
        );
    }
}
