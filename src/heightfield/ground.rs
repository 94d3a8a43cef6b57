//! How large a map's cells are on the ground: a projected map's units are metres on the
//! projection's plane, which a conformal projection stretches by its scale factor (Web
//! Mercator by 1/cos(latitude), transverse Mercator away from its central meridian, a
//! Lambert conic away from its standard parallels); a geographic map's degree of longitude
//! narrows with cos(latitude).
//!
//! A cell is measured where it lies: the map points of its two ends along each axis are
//! taken to longitude and latitude by the CRS's own projection, and the step between them is
//! measured on the WGS 84 ellipsoid by its radii of curvature (other datums' ellipsoids
//! differ from it by under 0.01% in scale). The map's centre stands for the whole map; where
//! cells elsewhere differ from the centre's by more than 1%, the summary says so.

use super::crs::LonLat;
use super::{Georef, MapUnits};

/// WGS 84's semi-major axis in metres and first eccentricity squared.
const WGS84_A: f64 = 6_378_137.0;
const WGS84_E2: f64 = 0.006_694_379_990_141_317;

/// Cells differing from the centre's by more than this share are worth a word.
pub const SPREAD_NOTED: f64 = 0.01;

/// The ground size of a georeferenced map's cells.
#[derive(Clone, Debug, PartialEq)]
pub struct GroundScale {
    /// Metres a cell spans along x and y at the map's centre.
    pub cell_metres: [f64; 2],
    /// Map units per metre of ground along x and y at the centre, in metres of the map's
    /// unit (1 on a projection's true-scale lines); `None` for longitude and latitude, or
    /// where the projection is not known.
    pub map_scale: Option<[f64; 2]>,
    /// The largest share by which a cell anywhere on the map differs from the centre's.
    pub spread: f64,
    /// What the sizes rest on, e.g. `WGS 84 / Pseudo-Mercator (EPSG:3857)`.
    pub basis: String,
}

impl GroundScale {
    /// The ground scale of a field of `width` x `height` samples placed by `georef`.
    pub fn of(georef: &Georef, width: usize, height: usize) -> GroundScale {
        let measure = Measure::new(georef);
        let (w, h) = ((width.max(2) - 1) as f64, (height.max(2) - 1) as f64);
        let centre = measure.cell(georef, 0.5 * w, 0.5 * h);
        let map_metres = match georef.units {
            MapUnits::Linear { metres } => Some(metres),
            MapUnits::Degrees => None,
        };
        let flat = |metres: f64| GroundScale {
            cell_metres: georef.spacing.map(|s| s * metres),
            map_scale: None,
            spread: 0.0,
            basis: measure.basis.clone(),
        };
        let Some(centre) = centre else {
            return flat(map_metres.unwrap_or(1.0));
        };
        let mut spread: f64 = 0.0;
        for fx in [0.0, 0.5, 1.0] {
            for fy in [0.0, 0.5, 1.0] {
                if let Some(cell) = measure.cell(georef, fx * w, fy * h) {
                    for axis in 0..2 {
                        spread = spread.max((cell[axis] / centre[axis] - 1.0).abs());
                    }
                }
            }
        }
        GroundScale {
            cell_metres: centre,
            map_scale: map_metres.map(|m| [0, 1].map(|a| georef.spacing[a] * m / centre[a])),
            spread,
            basis: measure.basis,
        }
    }

    /// Words for the scale, e.g. `WGS 84 / Pseudo-Mercator (EPSG:3857), map scale 1.2452 at
    /// the centre; cells vary by 2.1% across the map`.
    pub fn describe(&self) -> String {
        let mut words = self.basis.clone();
        if let Some([sx, sy]) = self.map_scale {
            if (sx / sy - 1.0).abs() < 5e-5 {
                words += &format!(", map scale {sx:.5} at the centre");
            } else {
                words += &format!(", map scale {sx:.5} (x) {sy:.5} (y) at the centre");
            }
        }
        if self.spread > SPREAD_NOTED {
            words += &format!(
                "; cells vary by {:.1}% across the map (sizes are the centre's)",
                100.0 * self.spread
            );
        }
        words
    }
}

/// How map points become longitude and latitude, and what that rests on.
struct Measure {
    lonlat: Option<LonLat>,
    basis: String,
}

impl Measure {
    fn new(georef: &Georef) -> Measure {
        match (georef.crs, georef.units) {
            (Some(crs), _) => match crs.to_lonlat() {
                Ok(lonlat) => Measure {
                    lonlat: Some(lonlat),
                    basis: crs.label(),
                },
                Err(why) => Measure {
                    lonlat: None,
                    basis: format!("{}: {why}; scale factor taken as 1", crs.label()),
                },
            },
            (None, MapUnits::Degrees) => Measure {
                lonlat: None,
                basis: "longitude/latitude".into(),
            },
            (None, MapUnits::Linear { metres }) => Measure {
                lonlat: None,
                basis: format!(
                    "projected, {}, CRS without an EPSG code: scale factor taken as 1",
                    if metres == 1.0 { "metres" } else { "feet" }
                ),
            },
        }
    }

    /// Metres a cell spans along x and y at grid point `(x, y)`.
    fn cell(&self, georef: &Georef, x: f64, y: f64) -> Option<[f64; 2]> {
        let to_degrees = |p: [f64; 2]| match &self.lonlat {
            Some(lonlat) => lonlat.lonlat(p),
            None if georef.units == MapUnits::Degrees => Some(p),
            None => None,
        };
        let step = |dx: f64, dy: f64| {
            let a = to_degrees(georef.map_point(x - dx, y - dy))?;
            let b = to_degrees(georef.map_point(x + dx, y + dy))?;
            Some(ellipsoid_distance(a, b))
        };
        Some([step(0.5, 0.0)?, step(0.0, 0.5)?])
    }
}

/// Metres between two nearby points given as longitude and latitude in degrees, on the WGS 84
/// ellipsoid by its meridional and prime-vertical radii at their mean latitude.
pub fn ellipsoid_distance([lon_a, lat_a]: [f64; 2], [lon_b, lat_b]: [f64; 2]) -> f64 {
    let phi = (0.5 * (lat_a + lat_b)).to_radians();
    let w = 1.0 - WGS84_E2 * phi.sin().powi(2);
    let meridional = WGS84_A * (1.0 - WGS84_E2) / w.powf(1.5);
    let prime_vertical = WGS84_A / w.sqrt();
    let mut dlon = (lon_b - lon_a).to_radians();
    if dlon.abs() > std::f64::consts::PI {
        dlon -= dlon.signum() * std::f64::consts::TAU;
    }
    let dlat = (lat_b - lat_a).to_radians();
    (meridional * dlat).hypot(prime_vertical * phi.cos() * dlon)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_degree_of_latitude_at_45_degrees_is_111_131_metres() {
        // The published series for a degree of latitude on WGS 84, 111 132.954 - 559.822
        // cos 2φ + 1.175 cos 4φ metres, is 111 131.78 m at 45°.
        let d = ellipsoid_distance([0.0, 44.5], [0.0, 45.5]);
        assert!((d - 111_131.78).abs() < 0.05, "{d}");
    }
}
