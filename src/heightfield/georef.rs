//! Where a height field lies on the Earth: the map coordinates of its samples, the units of
//! those coordinates, and the size of its cells in metres.
//!
//! The surface contract stays in grid coordinates (sample `(i, j)` at `x = i`, `y = j`); a
//! georeferenced field adds the map coordinates of sample `(i, j)`,
//! `origin + (i * spacing[0], j * spacing[1])`, north up. Cells may be non-square: a
//! geographic grid's degree of longitude spans `cos(latitude)` of a degree of latitude.

use super::crs::Crs;
use serde::{Deserialize, Serialize};

/// Metres in an international foot (EPSG 9002).
pub const METRES_PER_FOOT: f64 = 0.3048;

/// Metres in a US survey foot (EPSG 9003).
pub const METRES_PER_US_SURVEY_FOOT: f64 = 1200.0 / 3937.0;

/// The finest cells a georeferenced field is shown at true scale with: a micrometre.
pub const FINEST_CELL_METRES: f64 = 1e-6;

/// The coarsest: a quarter of the Earth's circumference.
pub const COARSEST_CELL_METRES: f64 = 1e7;

/// The units of a map's coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum MapUnits {
    /// A projected CRS whose unit is this many metres (1 for metres, 0.3048 for feet).
    Linear {
        /// Metres in one unit.
        metres: f64,
    },
    /// A geographic CRS: x is longitude and y latitude, in degrees.
    Degrees,
}

impl std::fmt::Display for MapUnits {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MapUnits::Linear { metres } if *metres == 1.0 => write!(f, "metres"),
            MapUnits::Linear { metres } => write!(f, "units of {metres} m"),
            MapUnits::Degrees => write!(f, "degrees"),
        }
    }
}

/// The map coordinates of a height field's samples.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Georef {
    /// Map coordinates of sample `(0, 0)`, the south-west sample.
    pub origin: [f64; 2],
    /// Map units from one sample to the next towards east (x) and north (y); both positive.
    pub spacing: [f64; 2],
    /// What the map coordinates measure.
    pub units: MapUnits,
    /// The coordinate system by its EPSG code, where the file names one.
    pub crs: Option<Crs>,
    /// The unit of the heights.
    pub height_unit: HeightUnit,
}

/// The unit of a map's heights, in metres, and who said so.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HeightUnit {
    /// Metres in one unit of height.
    pub metres: f64,
    /// Where the unit comes from.
    pub source: HeightUnitSource,
}

/// Where a map's height unit comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum HeightUnitSource {
    /// The file's vertical unit (GeoTIFF's VerticalUnitsGeoKey).
    VerticalKey,
    /// The projected CRS's linear unit: a map in feet has heights in feet.
    MapUnit,
    /// Metres, the unit of DEMs that say nothing.
    Default,
    /// A scene or the user chose it.
    Chosen,
}

impl HeightUnit {
    /// Metres, by default.
    pub const METRES: HeightUnit = HeightUnit {
        metres: 1.0,
        source: HeightUnitSource::Default,
    };

    /// The unit's short name: `m`, `ft` or `US ft`.
    pub fn symbol(&self) -> &'static str {
        unit_symbol(self.metres)
    }

    /// A unit named `m`, `ft` or `us-ft` (as scenes and the panel say), chosen.
    pub fn named(name: &str) -> Option<HeightUnit> {
        let metres = match name {
            "m" | "metre" | "meter" | "metres" | "meters" => 1.0,
            "ft" | "foot" | "feet" => METRES_PER_FOOT,
            "us-ft" | "us_ft" | "ftUS" | "US ft" => METRES_PER_US_SURVEY_FOOT,
            _ => return None,
        };
        Some(HeightUnit {
            metres,
            source: HeightUnitSource::Chosen,
        })
    }

    /// The key a scene file writes for the unit.
    pub fn key(&self) -> &'static str {
        match self.symbol() {
            "ft" => "ft",
            "US ft" => "us-ft",
            _ => "m",
        }
    }
}

/// The short name of a unit of `metres` metres.
pub fn unit_symbol(metres: f64) -> &'static str {
    // Definitions write the US survey foot to 15 or 16 digits.
    if (metres - METRES_PER_FOOT).abs() < 1e-9 {
        "ft"
    } else if (metres - METRES_PER_US_SURVEY_FOOT).abs() < 1e-9 {
        "US ft"
    } else {
        "m"
    }
}

/// Why numbers do not make a georeferencing.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GeorefError {
    /// An origin coordinate is infinite or NaN.
    #[error("its origin {0:?} is not finite")]
    Origin([f64; 2]),
    /// A sample spacing is not a finite number above 0.
    #[error("its sample spacing {0:?} is not positive (only north-up grids are read)")]
    Spacing([f64; 2]),
    /// The map unit is not a finite length above 0.
    #[error("its unit of {0} metres is not positive")]
    Unit(f64),
}

impl Georef {
    /// A georeferencing with finite coordinates and positive spacings, or why it is not one.
    pub fn new(
        origin: [f64; 2],
        spacing: [f64; 2],
        units: MapUnits,
    ) -> Result<Georef, GeorefError> {
        if !origin.iter().all(|c| c.is_finite()) {
            return Err(GeorefError::Origin(origin));
        }
        if !spacing.iter().all(|s| s.is_finite() && *s > 0.0) {
            return Err(GeorefError::Spacing(spacing));
        }
        if let MapUnits::Linear { metres } = units {
            if !(metres.is_finite() && metres > 0.0) {
                return Err(GeorefError::Unit(metres));
            }
        }
        Ok(Georef {
            origin,
            spacing,
            units,
            crs: None,
            height_unit: match units {
                MapUnits::Linear { metres } if metres != 1.0 => HeightUnit {
                    metres,
                    source: HeightUnitSource::MapUnit,
                },
                _ => HeightUnit::METRES,
            },
        })
    }

    /// The same georeferencing with heights in `height_unit`.
    pub fn with_height_unit(self, height_unit: HeightUnit) -> Georef {
        Georef {
            height_unit,
            ..self
        }
    }

    /// The same georeferencing in coordinate system `crs`.
    pub fn with_crs(self, crs: Option<Crs>) -> Georef {
        let mut georef = Georef { crs, ..self };
        if let (Some(metres), MapUnits::Linear { .. }) =
            (crs.and_then(|c| c.metres_per_unit()), self.units)
        {
            if georef.height_unit.source == HeightUnitSource::Default && metres != 1.0 {
                georef.height_unit = HeightUnit {
                    metres,
                    source: HeightUnitSource::MapUnit,
                };
            }
        }
        georef
    }

    /// The coordinate system in words: its name and code, or its kind of units.
    pub fn crs_label(&self) -> String {
        match (self.crs, self.units) {
            (Some(crs), _) => crs.label(),
            (None, MapUnits::Degrees) => "longitude/latitude".into(),
            (None, MapUnits::Linear { metres }) => {
                format!("a projected CRS in {}", unit_symbol(metres))
            }
        }
    }

    /// The map coordinates of grid point `(x, y)` (fractional sample positions).
    pub fn map_point(&self, x: f64, y: f64) -> [f64; 2] {
        [
            self.origin[0] + x * self.spacing[0],
            self.origin[1] + y * self.spacing[1],
        ]
    }

    /// The grid point (fractional sample positions) at map coordinates `[x, y]`: the inverse
    /// of [`Georef::map_point`].
    pub fn grid_point(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [
            (x - self.origin[0]) / self.spacing[0],
            (y - self.origin[1]) / self.spacing[1],
        ]
    }

    /// The map coordinates of a longitude and latitude in degrees: through the CRS's
    /// projection, or as they are on a map in degrees; `None` on a projected map of unknown
    /// CRS, or where the projection fails.
    pub fn map_of_lonlat(&self, lonlat: [f64; 2]) -> Option<[f64; 2]> {
        match (self.crs, self.units) {
            (Some(crs), _) => crs.to_lonlat().ok()?.map_point(lonlat),
            (None, MapUnits::Degrees) => Some(lonlat),
            (None, MapUnits::Linear { .. }) => None,
        }
    }
}

/// What a file says about its place on the Earth.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Georeferencing {
    /// Nothing: a plain image.
    #[default]
    None,
    /// The map coordinates of the samples.
    Map(Georef),
    /// Georeferencing heightray cannot use (rotated, sheared, unknown units...): the field is
    /// shown as a plain image, and this says why.
    Ignored(String),
}

impl Georeferencing {
    /// The usable georeferencing, if any.
    pub fn georef(&self) -> Option<&Georef> {
        match self {
            Georeferencing::Map(georef) => Some(georef),
            _ => None,
        }
    }

    /// The same, ignored with the reason when a field of `width` x `height` samples would have
    /// cells finer than `FINEST_CELL_METRES` or coarser than `COARSEST_CELL_METRES`: its
    /// true-scale relief would be out of all proportion (or its z scale not even finite).
    pub fn with_cells_checked(self, width: usize, height: usize) -> Georeferencing {
        let Georeferencing::Map(georef) = &self else {
            return self;
        };
        let [x, y] = super::ground::GroundScale::of(georef, width, height).cell_metres;
        let range = FINEST_CELL_METRES..=COARSEST_CELL_METRES;
        if range.contains(&x) && range.contains(&y) {
            return self;
        }
        Georeferencing::Ignored(format!(
            "its cells are {x:.3e} x {y:.3e} m, outside {FINEST_CELL_METRES:e} to \
             {COARSEST_CELL_METRES:e} m"
        ))
    }

    /// Georeferencing from a candidate: used when valid, else ignored with the reason.
    pub fn from_result<E: std::fmt::Display>(result: Result<Georef, E>) -> Georeferencing {
        match result {
            Ok(georef) => Georeferencing::Map(georef),
            Err(reason) => Georeferencing::Ignored(reason.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_points_step_by_the_spacing() {
        let feet = MapUnits::Linear {
            metres: METRES_PER_FOOT,
        };
        let georef = Georef::new([0.0, 0.0], [10.0, 20.0], feet).unwrap();
        assert_eq!(georef.map_point(2.0, 0.5), [20.0, 10.0]);
    }

    #[test]
    fn bad_spacings_and_origins_are_refused_with_a_reason() {
        let metres = MapUnits::Linear { metres: 1.0 };
        let south_up = Georef::new([0.0, 0.0], [1.0, -1.0], metres).unwrap_err();
        assert_eq!(south_up, GeorefError::Spacing([1.0, -1.0]));
        assert!(south_up.to_string().contains("north-up"));
        assert!(matches!(
            Georef::new([f64::NAN, 0.0], [1.0, 1.0], metres),
            Err(GeorefError::Origin(_))
        ));
        assert_eq!(
            Georef::new([0.0, 0.0], [1.0, 1.0], MapUnits::Linear { metres: 0.0 }),
            Err(GeorefError::Unit(0.0))
        );
    }
}
