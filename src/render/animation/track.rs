//! A track to follow (`[animation.track]`): the points of a GPX track or route, or of a
//! GeoJSON LineString, in longitude and latitude, placed on a georeferenced map. The camera
//! flies along it at a constant speed, `height` above the ground beneath (interpolated between
//! the points), looking at the track `look_ahead_s` seconds ahead.

use super::view::View;
use crate::heightfield::{world_from_grid, Heightfield};
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The longest track file read: a track of a million points is far smaller.
const MOST_TRACK_BYTES: u64 = 64 << 20;

/// Why a track cannot be flown.
#[derive(Debug, Error)]
pub enum TrackError {
    /// The file gives no points.
    #[error("cannot read track {}: {reason}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why not.
        reason: TrackFileError,
    },
    /// The map has no georeferencing to place longitudes and latitudes on.
    #[error(
        "[animation.track] needs a georeferenced map (a GeoTIFF, .hgt or .asc) to place its \
         longitudes and latitudes on"
    )]
    NotGeoreferenced,
    /// The map's CRS cannot take longitudes and latitudes.
    #[error("[animation.track] cannot place longitude and latitude on this map's {0}")]
    Crs(String),
    /// A point off the map.
    #[error(
        "[animation.track] point {number} (longitude {}, latitude {}) of {} lies off the map",
        point[0],
        point[1],
        path.display()
    )]
    OffMap {
        /// The point's number, from 1.
        number: usize,
        /// Its longitude and latitude.
        point: [f64; 2],
        /// The file.
        path: PathBuf,
    },
    /// All points in one place.
    #[error("[animation.track] {} has fewer than two distinct points", .0.display())]
    Indistinct(PathBuf),
    /// A height, speed or look-ahead out of range.
    #[error("[animation.track] height must be finite, speed above 0, look_ahead_s at least 0")]
    Values,
}

/// Why a track file gives no points.
#[derive(Debug, Error)]
pub enum TrackFileError {
    /// Its text cannot be had.
    #[error(transparent)]
    Text(#[from] TextError),
    /// Not GPX.
    #[error(transparent)]
    Gpx(#[from] NotGpx),
    /// Not JSON.
    #[error("{0}")]
    Json(#[from] serde_json::Error),
    /// A FeatureCollection without a line.
    #[error("its features hold no LineString")]
    NoLineString,
    /// A geometry that is not a line.
    #[error("a {0:?} is not a LineString")]
    NotALine(Option<String>),
    /// A coordinate that is not two numbers.
    #[error("{0} is not a [longitude, latitude] point")]
    NotAPoint(serde_json::Value),
    /// Neither `.gpx` nor `.geojson`.
    #[error("name a .gpx or .geojson file")]
    Extension,
    /// Fewer than two points.
    #[error("it holds fewer than two track points")]
    TooFew,
}

/// Why a track or vector file's text cannot be had.
#[derive(Debug, Error)]
pub enum TextError {
    /// The path names a directory or a device.
    #[error("it is {0}")]
    NotAFile(&'static str),
    /// Reading failed, or the bytes are not UTF-8.
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// A text the `gpx` crate cannot read.
#[derive(Debug, Error)]
#[error("not a GPX file: {0}")]
pub struct NotGpx(#[from] gpx::errors::GpxError);

/// `[animation.track]`.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TrackSection {
    /// A `.gpx` or `.geojson` (`.json`) file, relative to the scene.
    pub path: String,
    /// How high above the ground the eye flies, in world units (grid units up).
    pub height: f64,
    /// World units a second along the track (default: the whole track in 30 s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<f64>,
    /// How far ahead the camera looks, in seconds of travel (default 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub look_ahead_s: Option<f64>,
}

/// A track placed on a map.
#[derive(Clone, Debug, PartialEq)]
pub struct Track {
    /// The points in world x and y, their distance along the track and the ground under them.
    points: Vec<DVec2>,
    along: Vec<f64>,
    ground: Vec<f64>,
    height: f64,
    speed: f64,
    ahead: f64,
}

impl Track {
    /// Reads the track file (relative to `base`) and places it on `field`.
    pub fn load(
        section: &TrackSection,
        base: &Path,
        field: &Heightfield,
    ) -> Result<Track, TrackError> {
        let path = base.join(&section.path);
        let lonlat = read_points(&path).map_err(|reason| TrackError::Read {
            path: path.clone(),
            reason,
        })?;
        let georef = field.georef().ok_or(TrackError::NotGeoreferenced)?;
        let stretch = world_from_grid(field).map_or(1.0, |s| s[0]);
        let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
        let (mut points, mut ground) = (Vec::new(), Vec::new());
        for (n, &point) in lonlat.iter().enumerate() {
            let map = georef
                .map_of_lonlat(point)
                .ok_or_else(|| TrackError::Crs(georef.crs_label()))?;
            let [gx, gy] = georef.grid_point(map);
            if !(gx >= 0.0 && gy >= 0.0 && gx <= w && gy <= h) {
                return Err(TrackError::OffMap {
                    number: n + 1,
                    point,
                    path,
                });
            }
            let i = (gx.floor() as usize).min(field.width() - 2);
            let j = (gy.floor() as usize).min(field.height() - 2);
            ground.push(field.surface_z((i, j), (gx - i as f64, gy - j as f64)));
            points.push(DVec2::new(gx * stretch, gy));
        }
        let mut along = vec![0.0];
        for pair in points.windows(2) {
            along.push(along[along.len() - 1] + pair[0].distance(pair[1]));
        }
        let total = along[along.len() - 1];
        if total.is_nan() || total <= 0.0 {
            return Err(TrackError::Indistinct(path));
        }
        let speed = section.speed.unwrap_or(total / 30.0);
        let look = section.look_ahead_s.unwrap_or(2.0);
        let fine = |v: f64| v.is_finite() && v > 0.0;
        if !(fine(speed) && section.height.is_finite() && look.is_finite() && look >= 0.0) {
            return Err(TrackError::Values);
        }
        Ok(Track {
            points,
            along,
            ground,
            height: section.height,
            speed,
            ahead: (speed * look).max(1e-6 * total),
        })
    }

    /// Seconds from the start to the end of the track.
    pub fn duration(&self) -> f64 {
        self.along[self.along.len() - 1] / self.speed
    }

    /// The view at `time_s`: the eye over the track, looking at it further on.
    pub fn view_at(&self, time_s: f64, fov_y_deg: f64) -> View {
        let s = (self.speed * time_s).max(0.0);
        let (eye, eye_ground) = self.at(s);
        let (mut target, target_ground) = self.at(s + self.ahead);
        if target.distance(eye) < 0.5 * self.ahead {
            // At the end, the last leg's direction carries on.
            let n = self.points.len();
            let last = (self.points[n - 1] - self.points[n - 2]).normalize_or_zero();
            target = eye + last * self.ahead;
        }
        View {
            eye: DVec3::new(eye.x, eye.y, eye_ground + self.height),
            target: DVec3::new(target.x, target.y, target_ground + 0.5 * self.height),
            fov_y_deg,
        }
    }

    /// The point `s` along the track (clamped to it) and the ground there.
    fn at(&self, s: f64) -> (DVec2, f64) {
        let n = self.points.len();
        let s = s.clamp(0.0, self.along[n - 1]);
        let k = self.along.partition_point(|&a| a <= s).clamp(1, n - 1) - 1;
        let span = self.along[k + 1] - self.along[k];
        let u = if span > 0.0 {
            (s - self.along[k]) / span
        } else {
            0.0
        };
        let point = self.points[k].lerp(self.points[k + 1], u);
        let ground = self.ground[k] + (self.ground[k + 1] - self.ground[k]) * u;
        (point, ground)
    }
}

/// The longitude and latitude of every point of a GPX or GeoJSON file, in order.
fn read_points(path: &Path) -> Result<Vec<[f64; 2]>, TrackFileError> {
    let text = read_text(path)?;
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let points = match extension.as_deref() {
        Some("gpx") => gpx_points(&text)?,
        Some("geojson" | "json") => geojson_points(&text)?,
        _ => return Err(TrackFileError::Extension),
    };
    if points.len() < 2 {
        return Err(TrackFileError::TooFew);
    }
    Ok(points)
}

/// A track or vector file's text, at most [`MOST_TRACK_BYTES`] of it; the error says why not.
pub(crate) fn read_text(path: &Path) -> Result<String, TextError> {
    use std::io::Read;
    let (file, _) = crate::regular_file::open(path).map_err(|e| match e {
        crate::regular_file::OpenError::NotAFile(what) => TextError::NotAFile(what),
        crate::regular_file::OpenError::Io(e) => TextError::Io(e),
    })?;
    let mut text = String::new();
    file.take(MOST_TRACK_BYTES).read_to_string(&mut text)?;
    Ok(text)
}

/// The points of a GPX file's tracks (`trkpt`), or else its routes (`rtept`), read by the
/// `gpx` crate: their longitudes and latitudes.
pub(crate) fn gpx_points(text: &str) -> Result<Vec<[f64; 2]>, NotGpx> {
    let gpx = gpx::read(text.as_bytes())?;
    let lon_lat = |w: &gpx::Waypoint| {
        let p = w.point();
        [p.x(), p.y()]
    };
    let track: Vec<[f64; 2]> = gpx
        .tracks
        .iter()
        .flat_map(|t| &t.segments)
        .flat_map(|s| &s.points)
        .map(lon_lat)
        .collect();
    if !track.is_empty() {
        return Ok(track);
    }
    Ok(gpx
        .routes
        .iter()
        .flat_map(|r| &r.points)
        .map(lon_lat)
        .collect())
}

/// The points of a GeoJSON LineString or MultiLineString, alone, in a Feature, or the first in
/// a FeatureCollection.
fn geojson_points(text: &str) -> Result<Vec<[f64; 2]>, TrackFileError> {
    let json: serde_json::Value = serde_json::from_str(text)?;
    let geometry = match json["type"].as_str() {
        Some("FeatureCollection") => json["features"]
            .as_array()
            .and_then(|features| {
                features
                    .iter()
                    .map(|f| &f["geometry"])
                    .find(|g| matches!(g["type"].as_str(), Some("LineString" | "MultiLineString")))
            })
            .ok_or(TrackFileError::NoLineString)?,
        Some("Feature") => &json["geometry"],
        _ => &json,
    };
    let lines: Vec<&serde_json::Value> = match geometry["type"].as_str() {
        Some("LineString") => vec![&geometry["coordinates"]],
        Some("MultiLineString") => geometry["coordinates"]
            .as_array()
            .map(|lines| lines.iter().collect())
            .unwrap_or_default(),
        other => return Err(TrackFileError::NotALine(other.map(str::to_owned))),
    };
    let point = |p: &serde_json::Value| Some([p.get(0)?.as_f64()?, p.get(1)?.as_f64()?]);
    lines
        .into_iter()
        .flat_map(|line| line.as_array().cloned().unwrap_or_default())
        .map(|p| point(&p).ok_or(TrackFileError::NotAPoint(p)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gpx_and_geojson_give_their_points_in_order() {
        let gpx = r#"<gpx version="1.1" creator="t"><trk><trkseg>
            <trkpt lat="45.5" lon="-122.25"><ele>3</ele></trkpt>
            <trkpt lon='-122.5'  lat = "45.75"/></trkseg></trk></gpx>"#;
        assert_eq!(
            gpx_points(gpx).ok(),
            Some(vec![[-122.25, 45.5], [-122.5, 45.75]])
        );
        let route = r#"<gpx version="1.1" creator="t"><rte><rtept lat="1" lon="2"/>
            <rtept lat="3" lon="4"/></rte></gpx>"#;
        assert_eq!(gpx_points(route).ok(), Some(vec![[2.0, 1.0], [4.0, 3.0]]));
        assert!(gpx_points("<gpx version=\"1.1\"><trk><trkseg><trkpt lat=").is_err());
        let feature = r#"{"type": "FeatureCollection", "features": [{"type": "Feature",
            "geometry": {"type": "LineString", "coordinates": [[7, 46, 1200], [7.5, 46.25]]}}]}"#;
        assert_eq!(
            geojson_points(feature).ok(),
            Some(vec![[7.0, 46.0], [7.5, 46.25]])
        );
        assert!(geojson_points(r#"{"type": "Point", "coordinates": [1, 2]}"#).is_err());
    }
}
