//! What the panels edit besides the camera: light, shading, effects, traversal, display.

use crate::arith::DEFAULT_BOUND;
use crate::render::effects::Effects;
use crate::render::sun_position::SunPosition;
use crate::render::{BaseStyle, Lighting, Normals, Ramp};
use crate::{Arith, Method};

/// Which arithmetic, with the rational bound kept apart so switching away and back keeps it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArithKind {
    F32,
    F64,
    Rational,
    Exact,
}

impl ArithKind {
    pub const ALL: [ArithKind; 4] = [
        ArithKind::F32,
        ArithKind::F64,
        ArithKind::Rational,
        ArithKind::Exact,
    ];

    pub fn label(self) -> &'static str {
        match self {
            ArithKind::F32 => "f32",
            ArithKind::F64 => "f64",
            ArithKind::Rational => "rational (bounded)",
            ArithKind::Exact => "exact",
        }
    }
}

/// Which per-pixel counter the heat map shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeatMode {
    Off,
    Cells,
    Triangles,
    Blocks,
    Runs,
    Samples,
}

impl HeatMode {
    pub const ALL: [HeatMode; 6] = [
        HeatMode::Off,
        HeatMode::Cells,
        HeatMode::Triangles,
        HeatMode::Blocks,
        HeatMode::Runs,
        HeatMode::Samples,
    ];

    pub fn label(self) -> &'static str {
        match self {
            HeatMode::Off => "off (shaded image)",
            HeatMode::Cells => "cell queries",
            HeatMode::Triangles => "triangle queries",
            HeatMode::Blocks => "block queries (mipmap)",
            HeatMode::Runs => "run queries",
            HeatMode::Samples => "samples per pixel",
        }
    }

    /// The name of its entry in the heat-map list, for scripted tests.
    pub fn widget_name(self) -> &'static str {
        match self {
            HeatMode::Off => "heat_off",
            HeatMode::Cells => "heat_cells",
            HeatMode::Triangles => "heat_triangles",
            HeatMode::Blocks => "heat_blocks",
            HeatMode::Runs => "heat_runs",
            HeatMode::Samples => "heat_samples",
        }
    }

    /// Why `method` leaves this map empty, if it does: only the mipmap asks block queries,
    /// only the run methods ask run queries.
    pub fn unavailable(self, method: Method) -> Option<&'static str> {
        match (self, method) {
            (HeatMode::Blocks, Method::Mipmap) => None,
            (HeatMode::Blocks, _) => Some("only the mipmap method makes block queries"),
            (HeatMode::Runs, Method::Runs | Method::HierarchicalRuns) => None,
            (HeatMode::Runs, _) => {
                Some("only the runs and hierarchical runs methods make run queries")
            }
            _ => None,
        }
    }
}

/// Fog as the viewer's slider shows it: the distance, in map units, at which contrast falls to
/// 5% (e^-3). Scene files keep the density, `3 / distance`.
pub mod fog {
    /// Density for a visibility distance.
    pub fn density(distance: f64) -> f64 {
        3.0 / distance.max(f64::MIN_POSITIVE)
    }

    /// Visibility distance for a density (infinite when the fog is off).
    pub fn distance(density: f64) -> f64 {
        if density > 0.0 {
            3.0 / density
        } else {
            f64::INFINITY
        }
    }

    /// The slider's range for a map `size` across seen from `eye_distance` away: from twice
    /// the distance to the point looked at, where that point keeps a fifth of its contrast
    /// and the far side is nearly gone, to twenty times the far side's distance, where fog
    /// only tints the horizon. A shorter visibility would wash out the whole view.
    pub fn range(size: f64, eye_distance: f64) -> std::ops::RangeInclusive<f64> {
        let size = size.max(1.0);
        let near = eye_distance.max(0.01 * size);
        2.0 * near..=20.0 * (near + size)
    }
}

/// Everything the panels edit besides the camera and the height map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Sun direction: compass bearing (0 north, 90 east, 0 to 360), elevation above the
    /// horizon.
    pub sun_azimuth_deg: f64,
    /// A direction given as such (a scene's), with the angles it was shown at.
    pub sun_given: Option<([f64; 3], f64, f64)>,
    pub sun_elevation_deg: f64,
    pub intensity: f64,
    pub ambient: f64,
    pub shadows: bool,
    /// Fog density per unit of distance; 0 is off.
    pub fog: f64,
    pub normals: Normals,
    pub ramp: Ramp,
    /// The base under the map: walls or not, and the floor's depth.
    pub base: BaseStyle,
    pub method: Method,
    pub arith: ArithKind,
    pub rational_bound: u32,
    /// Rendered pixels per physical window pixel along each axis (1 = full resolution).
    pub render_scale: f32,
    pub heat: HeatMode,
    /// Soft shadows, sky light and samples per pixel.
    pub effects: Effects,
}

impl Default for Settings {
    fn default() -> Self {
        let mut settings = Settings {
            sun_azimuth_deg: 0.0,
            sun_given: None,
            sun_elevation_deg: 0.0,
            intensity: 1.0,
            ambient: 0.25,
            shadows: true,
            fog: 0.0,
            normals: Normals::Flat,
            ramp: Ramp::Terrain,
            base: BaseStyle::default(),
            method: Method::Mipmap,
            arith: ArithKind::F64,
            rational_bound: DEFAULT_BOUND,
            render_scale: 1.0,
            heat: HeatMode::Off,
            effects: Effects::default(),
        };
        // The scene files' default sun.
        settings.set_sun([0.4, 0.3, 0.8]);
        settings
    }
}

impl Settings {
    /// Takes a scene's lighting, traversal and arithmetic.
    pub fn adopt_scene(&mut self, lighting: &Lighting, method: Method, arith: Arith) {
        self.set_sun(lighting.sun);
        self.intensity = lighting.intensity;
        self.ambient = lighting.ambient;
        self.shadows = lighting.shadows;
        self.fog = lighting.fog;
        self.normals = lighting.normals;
        self.ramp = lighting.ramp;
        self.base = lighting.base;
        self.effects = lighting.effects;
        self.method = method;
        self.arith = match arith {
            Arith::F32 => ArithKind::F32,
            Arith::F64 => ArithKind::F64,
            Arith::Exact => ArithKind::Exact,
            Arith::Rational { bound } => {
                self.rational_bound = bound;
                ArithKind::Rational
            }
        };
    }

    /// Sets azimuth and elevation from a direction towards the sun.
    pub fn set_sun(&mut self, towards_sun: [f64; 3]) {
        let sun = SunPosition::from_direction(towards_sun);
        self.sun_azimuth_deg = sun.azimuth_deg;
        self.sun_elevation_deg = sun.elevation_deg;
        self.sun_given = Some((towards_sun, sun.azimuth_deg, sun.elevation_deg));
    }

    /// The direction a scene gave, while the sliders have not moved the sun from it: kept
    /// as given, since angles and back would change its last bits and so the image.
    pub fn given_sun(&self) -> Option<[f64; 3]> {
        self.sun_given
            .filter(|&(_, az, el)| az == self.sun_azimuth_deg && el == self.sun_elevation_deg)
            .map(|(direction, _, _)| direction)
    }

    /// Vector towards the sun.
    pub fn sun(&self) -> [f64; 3] {
        self.given_sun().unwrap_or_else(|| {
            SunPosition {
                azimuth_deg: self.sun_azimuth_deg,
                elevation_deg: self.sun_elevation_deg,
            }
            .direction()
        })
    }

    /// The renderer's lighting; a sun below the horizon (set by a date and time) lights
    /// nothing and casts no shadows ([`Lighting::after_dark`]).
    pub fn lighting(&self) -> Lighting {
        Lighting {
            sun: Lighting::unit(self.sun()),
            intensity: self.intensity,
            ambient: self.ambient,
            shadows: self.shadows,
            fog: self.fog,
            normals: self.normals,
            ramp: self.ramp,
            effects: self.effects,
            base: self.base,
        }
        .after_dark()
    }

    /// The traversal arithmetic.
    pub fn arith(&self) -> Arith {
        match self.arith {
            ArithKind::F32 => Arith::F32,
            ArithKind::F64 => Arith::F64,
            ArithKind::Exact => Arith::Exact,
            ArithKind::Rational => Arith::Rational {
                bound: self.rational_bound.clamp(1, 1 << 30),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sun_angles_round_trip() {
        let mut settings = Settings::default();
        let towards = [0.4, 0.3, 0.8];
        let length = (0.16f64 + 0.09 + 0.64).sqrt();
        settings.set_sun(towards);
        // A given direction is kept as given; the sliders' angles give the same within
        // rounding.
        assert_eq!(settings.lighting().sun, Lighting::unit(towards));
        let angles = SunPosition {
            azimuth_deg: settings.sun_azimuth_deg,
            elevation_deg: settings.sun_elevation_deg,
        }
        .direction();
        for (got, want) in angles.iter().zip(towards) {
            assert!((got - want / length).abs() < 1e-12);
        }
        // North-east is bearing 45.
        settings.set_sun([1.0, 1.0, 0.0]);
        assert!((settings.sun_azimuth_deg - 45.0).abs() < 1e-12);
    }

    #[test]
    fn scene_arithmetic_is_kept_with_its_bound() {
        let mut settings = Settings::default();
        let lighting = settings.lighting();
        settings.adopt_scene(&lighting, Method::Dda, Arith::Rational { bound: 77 });
        assert_eq!(settings.arith(), Arith::Rational { bound: 77 });
        assert_eq!(settings.method, Method::Dda);
    }

    #[test]
    fn fog_distance_and_density_round_trip() {
        assert_eq!(fog::density(300.0), 0.01);
        assert!((fog::distance(fog::density(1234.5)) - 1234.5).abs() < 1e-9);
        assert_eq!(fog::distance(0.0), f64::INFINITY);
        // At the visibility distance 5% of the contrast is left.
        let left = (-fog::density(500.0) * 500.0).exp();
        assert!((left - 0.0498).abs() < 1e-3);
    }

    #[test]
    fn heat_maps_a_method_cannot_fill_are_refused_with_a_reason() {
        assert_eq!(HeatMode::Blocks.unavailable(Method::Mipmap), None);
        assert!(HeatMode::Blocks.unavailable(Method::Runs).is_some());
        assert_eq!(HeatMode::Runs.unavailable(Method::HierarchicalRuns), None);
        assert!(HeatMode::Runs.unavailable(Method::Mipmap).is_some());
        for method in [Method::Mipmap, Method::Runs, Method::Dda] {
            assert_eq!(HeatMode::Cells.unavailable(method), None);
        }
    }
}
