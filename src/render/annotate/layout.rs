//! Where the map's measures show in a perspective picture: how long a scale bar is at the
//! depth of the view's target, and where grid north points there.

use crate::render::Camera;
use glam::DVec3;

/// The longest share of the image's width a scale bar takes.
const MOST_BAR_SHARE: f64 = 0.22;

/// A scale bar: a round ground length and how many pixels it spans.
#[derive(Clone, Debug, PartialEq)]
pub struct ScaleBar {
    /// Its ground length, in `unit`s.
    pub length: f64,
    /// Its length in the image, in pixels.
    pub pixels: f64,
    /// What it measures in: `m`, `km`, or `cells` on a map without a ground size.
    pub unit: &'static str,
    /// Its length as written under it ("500 m", "2 km").
    pub label: String,
}

impl ScaleBar {
    /// The scale bar of `camera` (in world coordinates) at the depth of its target: the
    /// longest round length (1, 2 or 5 times a power of ten) within a share of the image's
    /// width, for world units of `metres_per_unit` metres (`None`: a plain image, measured in
    /// cells). `None` where the view has no finite scale.
    pub fn at_target(camera: &Camera, metres_per_unit: Option<f64>) -> Option<ScaleBar> {
        let span = camera.pixel_span_at(camera.target_distance());
        let width = f64::from(camera.whole_size().0);
        let per_pixel = span * metres_per_unit.unwrap_or(1.0);
        let most = MOST_BAR_SHARE * width * per_pixel;
        if !(most.is_finite() && most > 0.0) {
            return None;
        }
        let decade = 10f64.powf(most.log10().floor());
        let round = [5.0, 2.0, 1.0]
            .map(|m| m * decade)
            .into_iter()
            .find(|&l| l <= most)
            .unwrap_or(decade);
        let (length, unit) = match metres_per_unit {
            None => (round, "cells"),
            Some(_) if round >= 1000.0 => (round / 1000.0, "km"),
            Some(_) => (round, "m"),
        };
        Some(ScaleBar {
            length,
            pixels: round / per_pixel,
            unit,
            label: format!("{} {unit}", trimmed(length)),
        })
    }
}

/// A number without trailing zeros: `2`, `0.5`, `1500`.
pub fn trimmed(value: f64) -> String {
    let text = format!("{value:.6}");
    text.trim_end_matches('0').trim_end_matches('.').to_owned()
}

/// The angle of grid north (+y) in the image at the camera's target, in degrees clockwise
/// from the image's up; `None` where north runs along the line of sight.
pub fn north_angle_deg(camera: &Camera) -> Option<f64> {
    let eye = DVec3::from(camera.eye());
    let depth = camera.target_distance();
    let target = eye + DVec3::from(camera.forward()) * depth;
    let step = target + DVec3::Y * (1e-3 * depth);
    let [x0, y0] = camera.project(target.into())?;
    let [x1, y1] = camera.project(step.into())?;
    let (right, up) = (x1 - x0, y0 - y1);
    (right.hypot(up) > 1e-9).then(|| right.atan2(up).to_degrees())
}
