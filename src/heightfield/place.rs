//! Words for where a georeferenced field lies: its cells and extent in metres and kilometres,
//! and a grid point's map coordinates and elevation.

use super::{relief, Georeferencing, HeightUnitSource, Heightfield, MapUnits};

/// A field's georeferencing in a line: cell size, extent, coordinate system and scale,
/// height unit, exaggeration; or why a file's georeferencing is not used; `None` for a plain
/// image.
pub fn describe_georeferencing(field: &Heightfield) -> Option<String> {
    let georef = match field.georeferencing() {
        Georeferencing::None => return None,
        Georeferencing::Ignored(why) => {
            return Some(format!(
                "georeferencing not used ({why}): shown as a plain image"
            ))
        }
        Georeferencing::Map(georef) => georef,
    };
    let ground = field.ground()?;
    let [cx, cy] = ground.cell_metres;
    let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
    let unit = georef.height_unit;
    let heights = match unit.source {
        HeightUnitSource::Default => String::new(),
        HeightUnitSource::VerticalKey => {
            format!("heights in {} (the file's vertical unit), ", unit.symbol())
        }
        HeightUnitSource::MapUnit => format!("heights in {} (the CRS's unit), ", unit.symbol()),
        HeightUnitSource::Chosen => format!("heights in {} (chosen), ", unit.symbol()),
    };
    let exaggeration = relief::exaggeration(field).unwrap_or(1.0);
    Some(format!(
        "cells {cx:.2} x {cy:.2} m, {:.2} x {:.2} km ({}), {heights}shown x{exaggeration:.2}",
        w * cx / 1000.0,
        h * cy / 1000.0,
        ground.describe()
    ))
}

/// Latitude and longitude in degrees of the centre of a map in longitude and latitude, or in
/// a projected CRS known by its EPSG code.
pub fn centre_degrees(field: &Heightfield) -> Option<(f64, f64)> {
    let georef = field.georef()?;
    let (w, h) = (field.width() - 1, field.height() - 1);
    let centre = georef.map_point(0.5 * w as f64, 0.5 * h as f64);
    let [lon, lat] = match (georef.crs, georef.units) {
        (Some(crs), _) => crs.to_lonlat().ok()?.lonlat(centre)?,
        (None, MapUnits::Degrees) => centre,
        (None, MapUnits::Linear { .. }) => return None,
    };
    Some((lat, lon))
}

/// The elevation in metres of grid height `z` on a georeferenced field.
pub fn elevation_metres(field: &Heightfield, z: f64) -> Option<f64> {
    field.georef()?;
    (field.z_scale() > 0.0).then(|| z * relief::metres_per_z_scale(field) / field.z_scale())
}

/// Grid point `(x, y, z)` as map coordinates and elevation, e.g. `E 500015.0 m, N 4599950.0
/// m, 123.4 m` or `60.00012° N, 10.00005° E, 312.0 m`; `None` on a plain image.
pub fn describe_point(field: &Heightfield, [x, y, z]: [f64; 3]) -> Option<String> {
    let georef = field.georef()?;
    let [mx, my] = georef.map_point(x, y);
    let position = match georef.units {
        MapUnits::Degrees => format!(
            "{:.5}° {}, {:.5}° {}",
            my.abs(),
            if my < 0.0 { 'S' } else { 'N' },
            mx.abs(),
            if mx < 0.0 { 'W' } else { 'E' }
        ),
        MapUnits::Linear { metres } => {
            let unit = if metres == 1.0 { "m" } else { "ft" };
            format!("E {mx:.1} {unit}, N {my:.1} {unit}")
        }
    };
    Some(match elevation_metres(field, z) {
        Some(metres) => format!("{position}, elevation {metres:.1} m"),
        None => position,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightfield::{Georef, NoDataMask, Quantisation};

    #[test]
    fn a_point_reads_as_its_map_coordinates_and_elevation() {
        let q = Quantisation::Offset {
            lowest: 100.0,
            step: 1.0,
        };
        let georef = Georef::new([10.0, -45.0], [0.5, 0.25], MapUnits::Degrees).unwrap();
        let field = Heightfield::new(2, 2, vec![0, 10, 20, 30], q, 0.5, Some(NoDataMask::new(0)))
            .unwrap()
            .with_georeferencing(Georeferencing::Map(georef));
        // Grid height 60 at z scale 0.5 is 120 m.
        assert_eq!(
            describe_point(&field, [1.0, 1.0, 60.0]).unwrap(),
            "44.75000° S, 10.50000° E, elevation 120.0 m"
        );
        let plain = field.with_georeferencing(Georeferencing::None);
        assert_eq!(describe_point(&plain, [1.0, 1.0, 60.0]), None);
    }
}
