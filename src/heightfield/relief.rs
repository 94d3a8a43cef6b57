//! How high relief is shown: a georeferenced field at its true proportions (heights in metres
//! over cells in metres) times an exaggeration; a plain image, whose cells have no size, with
//! its relief scaled to a quarter of its larger side.
//!
//! Grid units are cells; on a georeferenced field one unit of height is one cell along y, so
//! a height of `h` metres over cells `cell_y` metres high is `h * exaggeration / cell_y` units.
//! Heights in feet are taken to metres by the map's height unit first.

use super::{Heightfield, Quantisation};

/// The z scale of the field's default view: true scale for a georeferenced field, else a
/// quarter of the larger side for the relief.
pub fn default_z_scale(field: &Heightfield) -> f64 {
    true_z_scale(field, 1.0).unwrap_or_else(|| plain_z_scale(field))
}

/// The z scale that shows a georeferenced field's heights, in metres, `exaggeration` times
/// their true proportion to its cells.
pub fn true_z_scale(field: &Heightfield, exaggeration: f64) -> Option<f64> {
    let [_, cell_y] = field.cell_metres()?;
    Some(exaggeration * metres_per_z_scale(field) / cell_y)
}

/// How many times a georeferenced field's heights are exaggerated at its z scale.
pub fn exaggeration(field: &Heightfield) -> Option<f64> {
    exaggeration_at(field, field.z_scale())
}

/// How many times a georeferenced field's heights are exaggerated at `z_scale`.
pub fn exaggeration_at(field: &Heightfield, z_scale: f64) -> Option<f64> {
    let [_, cell_y] = field.cell_metres()?;
    Some(z_scale * cell_y / metres_per_z_scale(field))
}

/// The z scale at which heights are metres on the map: the raster's values (1 for values in
/// their own units, the maxval for integer samples) times metres in its height unit.
pub(super) fn metres_per_z_scale(field: &Heightfield) -> f64 {
    let values = match field.quantisation() {
        Quantisation::Maxval(maxval) => f64::from(maxval),
        Quantisation::Offset { .. } => 1.0,
    };
    values * field.georef().map_or(1.0, |g| g.height_unit.metres)
}

/// A z scale that makes a plain image's relief visible whatever its size: an integer raster's
/// largest value (its heights have no unit) becomes a quarter of the larger side, and heights
/// in their own units (floats, signed, decoded terrain-RGB: metres over cells of unknown size)
/// are scaled so that their range spans as much.
fn plain_z_scale(field: &Heightfield) -> f64 {
    let relief = 0.25 * field.width().max(field.height()) as f64;
    match field.quantisation() {
        Quantisation::Maxval(_) => relief,
        Quantisation::Offset { step, .. } => {
            // The lowest valid value is sample 0.
            let top = field.samples().iter().copied().max().unwrap_or(0);
            let range = step * f64::from(top);
            if range > 0.0 {
                relief / range
            } else {
                1.0
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::{Georef, Georeferencing, MapUnits, NoDataMask};

    /// A 3x3 field of heights 0 .. 80 metres over `cell` metre cells.
    fn field(cell: [f64; 2]) -> Heightfield {
        let samples = (0..9).map(|k| k * 10).collect();
        let q = Quantisation::Offset {
            lowest: 0.0,
            step: 1.0,
        };
        let metres = MapUnits::Linear { metres: 1.0 };
        let georef = Georef::new([0.0, 0.0], cell, metres).unwrap();
        Heightfield::new(3, 3, samples, q, 1.0, Some(NoDataMask::new(0)))
            .unwrap()
            .with_georeferencing(Georeferencing::Map(georef))
    }

    #[test]
    fn true_scale_puts_metres_of_height_over_metres_of_cell() {
        // 80 m of relief over 20 m cells is 4 cells high at true scale, 8 at exaggeration 2.
        let f = field([30.0, 20.0]);
        let z = true_z_scale(&f, 2.0).unwrap();
        let scaled = f.with_z_scale(z).unwrap();
        assert_eq!(scaled.z(2, 2), 8.0);
        assert_eq!(exaggeration(&scaled), Some(2.0));
        assert_eq!(default_z_scale(&f), 1.0 / 20.0);
    }

    #[test]
    fn a_plain_image_keeps_a_quarter_of_its_side() {
        let f = Heightfield::from_fn(9, 5, 255, 1.0, |i, _| i as u16).unwrap();
        assert_eq!(default_z_scale(&f), 9.0 / 4.0);
        assert_eq!(exaggeration(&f), None);
    }
}
