//! The sky's colour towards a direction, by day and by night: graded from the horizon's up to
//! the zenith's.

use glam::DVec3;

/// The sky's colour towards `dir`: from the horizon's up to the zenith's, by the square root
/// of the sine of the elevation.
pub(super) fn sky_colour(dir: DVec3) -> DVec3 {
    let d = dir.normalize_or(DVec3::Z);
    horizon().lerp(zenith(), d.z.clamp(0.0, 1.0).sqrt())
}

/// The night sky's colour towards `dir`, graded as the day's.
pub(super) fn night_sky_colour(dir: DVec3) -> DVec3 {
    let d = dir.normalize_or(DVec3::Z);
    NIGHT_HORIZON.lerp(NIGHT_ZENITH, d.z.clamp(0.0, 1.0).sqrt())
}

/// The night sky's colour at the horizon: a faint glow.
pub(super) const NIGHT_HORIZON: DVec3 = DVec3::new(0.012, 0.016, 0.035);

/// The night sky's colour at the zenith.
const NIGHT_ZENITH: DVec3 = DVec3::new(0.002, 0.003, 0.010);

/// The sky's colour at the horizon.
pub(super) fn horizon() -> DVec3 {
    DVec3::new(0.78, 0.85, 0.93)
}

/// The sky's colour at the zenith.
pub(super) fn zenith() -> DVec3 {
    DVec3::new(0.28, 0.46, 0.82)
}
