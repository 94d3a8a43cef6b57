//! Where a height field lies on the Earth: the map coordinates of its samples, the units of
//! those coordinates, and the size of its cells in metres.
//!
//! The surface contract stays in grid coordinates (sample `(i, j)` at `x = i`, `y = j`); a
//! georeferenced field adds the map coordinates of sample `(i, j)`,
//! `origin + (i * spacing[0], j * spacing[1])`, north up. Cells may be non-square: a
//! geographic grid's degree of longitude spans `cos(latitude)` of a degree of latitude.

/// Metres in one degree of a great circle on the sphere of the Earth's mean radius
/// (6 371 008.8 m, IUGG): `pi * R / 180`.
pub const METRES_PER_DEGREE: f64 = std::f64::consts::PI * 6_371_008.8 / 180.0;

/// Metres in an international foot (EPSG 9002).
pub const METRES_PER_FOOT: f64 = 0.3048;

/// Metres in a US survey foot (EPSG 9003).
pub const METRES_PER_US_SURVEY_FOOT: f64 = 1200.0 / 3937.0;

/// The finest cells a georeferenced field is shown at true scale with: a micrometre.
pub const FINEST_CELL_METRES: f64 = 1e-6;

/// The coarsest: a quarter of the Earth's circumference.
pub const COARSEST_CELL_METRES: f64 = 1e7;

/// The units of a map's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
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
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Georef {
    /// Map coordinates of sample `(0, 0)`, the south-west sample.
    pub origin: [f64; 2],
    /// Map units from one sample to the next towards east (x) and north (y); both positive.
    pub spacing: [f64; 2],
    /// What the map coordinates measure.
    pub units: MapUnits,
}

impl Georef {
    /// A georeferencing with finite coordinates and positive spacings, or why it is not one.
    pub fn new(origin: [f64; 2], spacing: [f64; 2], units: MapUnits) -> Result<Georef, String> {
        if !origin.iter().all(|c| c.is_finite()) {
            return Err(format!("its origin {origin:?} is not finite"));
        }
        if !spacing.iter().all(|s| s.is_finite() && *s > 0.0) {
            return Err(format!(
                "its sample spacing {spacing:?} is not positive (only north-up grids are read)"
            ));
        }
        if let MapUnits::Linear { metres } = units {
            if !(metres.is_finite() && metres > 0.0) {
                return Err(format!("its unit of {metres} metres is not positive"));
            }
        }
        Ok(Georef {
            origin,
            spacing,
            units,
        })
    }

    /// The map coordinates of grid point `(x, y)` (fractional sample positions).
    pub fn map_point(&self, x: f64, y: f64) -> [f64; 2] {
        [
            self.origin[0] + x * self.spacing[0],
            self.origin[1] + y * self.spacing[1],
        ]
    }

    /// The size of a cell in metres along x and y, at the centre of a field of `width` x
    /// `height` samples (a geographic grid's cells narrow towards the poles; the centre's
    /// latitude stands for the whole field).
    pub fn cell_metres(&self, width: usize, height: usize) -> [f64; 2] {
        match self.units {
            MapUnits::Linear { metres } => self.spacing.map(|s| s * metres),
            MapUnits::Degrees => {
                let centre = self.map_point(0.5 * (width - 1) as f64, 0.5 * (height - 1) as f64);
                let across = centre[1].to_radians().cos().max(0.0);
                [
                    self.spacing[0] * METRES_PER_DEGREE * across,
                    self.spacing[1] * METRES_PER_DEGREE,
                ]
            }
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
    /// cells finer than [`FINEST_CELL_METRES`] or coarser than [`COARSEST_CELL_METRES`]: its
    /// true-scale relief would be out of all proportion (or its z scale not even finite).
    pub fn with_cells_checked(self, width: usize, height: usize) -> Georeferencing {
        let Georeferencing::Map(georef) = &self else {
            return self;
        };
        let [x, y] = georef.cell_metres(width, height);
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
    pub fn from_result(result: Result<Georef, String>) -> Georeferencing {
        match result {
            Ok(georef) => Georeferencing::Map(georef),
            Err(reason) => Georeferencing::Ignored(reason),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_degree_of_longitude_at_60_north_spans_half_a_degree_of_latitude() {
        // 3x3 samples a second apart, centred on 60 N.
        let second = 1.0 / 3600.0;
        let georef =
            Georef::new([10.0, 60.0 - second], [second, second], MapUnits::Degrees).unwrap();
        let [x, y] = georef.cell_metres(3, 3);
        assert!((x / y - 0.5).abs() < 1e-12, "{x} / {y}");
        // A second of latitude on the mean sphere: 6371008.8 m * pi / 648000.
        assert!((y - 6_371_008.8 * std::f64::consts::PI / 648_000.0).abs() < 1e-9);
    }

    #[test]
    fn projected_cells_are_their_spacing_in_metres() {
        let feet = MapUnits::Linear {
            metres: METRES_PER_FOOT,
        };
        let georef = Georef::new([0.0, 0.0], [10.0, 20.0], feet).unwrap();
        assert_eq!(georef.cell_metres(5, 5), [3.048, 6.096]);
        assert_eq!(georef.map_point(2.0, 0.5), [20.0, 10.0]);
    }

    #[test]
    fn bad_spacings_and_origins_are_refused_with_a_reason() {
        let metres = MapUnits::Linear { metres: 1.0 };
        assert!(Georef::new([0.0, 0.0], [1.0, -1.0], metres)
            .unwrap_err()
            .contains("north-up"));
        assert!(Georef::new([f64::NAN, 0.0], [1.0, 1.0], metres).is_err());
        assert!(Georef::new([0.0, 0.0], [1.0, 1.0], MapUnits::Linear { metres: 0.0 }).is_err());
    }
}
