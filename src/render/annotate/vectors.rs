//! Vector layers (`[[vector]]`): named places and lines read from a GeoJSON file (the
//! `geojson` crate) or a GPX file (the `gpx` crate: waypoints, and the track the camera paths
//! read), placed on the map's grid.

use crate::heightfield::Heightfield;
use crate::render::animation::{gpx_points, read_text, NotGpx, TextError};
use crate::render::bytes_from_hex;
use geojson::{GeoJson, Geometry, Value};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why a `[[vector]]` layer cannot be shown.
#[derive(Debug, Error)]
#[error("[[vector]] {}: {reason}", path.display())]
pub struct VectorError {
    /// The file.
    pub path: PathBuf,
    /// What is wrong.
    pub reason: VectorProblem,
}

/// What is wrong with a `[[vector]]` layer.
#[derive(Debug, Error)]
pub enum VectorProblem {
    /// The file gives no places or lines.
    #[error(transparent)]
    File(#[from] VectorFileError),
    /// Longitudes and latitudes or map coordinates on a map without georeferencing.
    #[error(
        "the map has no georeferencing to place longitudes and latitudes or map coordinates \
         on: give coordinates = \"grid\" (sample positions)"
    )]
    NotGeoreferenced,
    /// Not `#RRGGBB`.
    #[error("colour {0:?} is not #RRGGBB")]
    Colour(String),
    /// A negative or infinite lift.
    #[error("lift must be a finite number >= 0, got {0}")]
    Lift(f64),
}

/// Why a vector file gives no places or lines.
#[derive(Debug, Error)]
pub enum VectorFileError {
    /// Neither `.geojson` nor `.gpx`.
    #[error("name a .geojson or .gpx file")]
    Extension,
    /// Its text cannot be had.
    #[error(transparent)]
    Text(#[from] TextError),
    /// Not GeoJSON.
    #[error("not GeoJSON: {0}")]
    GeoJson(#[from] Box<geojson::Error>),
    /// Not GPX.
    #[error(transparent)]
    Gpx(#[from] NotGpx),
}

/// A scene file's `[[vector]]` section.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct VectorSection {
    /// A `.geojson` (`.json`) or `.gpx` file, relative to the scene.
    pub path: String,
    /// What its coordinates are: `degrees` (longitude and latitude, as GeoJSON and GPX
    /// define them; the default), `map` (the map's own CRS) or `grid` (sample positions, for
    /// a map without georeferencing).
    #[serde(default)]
    pub coordinates: Coordinates,
    /// The lines' colour, `#RRGGBB` (default a bright red).
    #[serde(default)]
    pub colour: Option<String>,
    /// How high above the ground a place's marker stands, in world units: the point whose
    /// sight from the eye decides whether the place shows (default 0.5).
    #[serde(default)]
    pub lift: Option<f64>,
}

/// What a vector file's coordinates are.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Coordinates {
    /// Longitude and latitude in degrees, converted to the map's CRS.
    #[default]
    Degrees,
    /// The map's own coordinates.
    Map,
    /// Grid sample positions: column `x`, row from the south `y`.
    Grid,
}

/// A named point on the map.
#[derive(Clone, Debug, PartialEq)]
pub struct Place {
    /// Its name, as its label shows it.
    pub name: String,
    /// Where it lies, in grid coordinates (in a [`VectorFile`], the file's own).
    pub at: [f64; 2],
    /// Where labels collide, the higher priority keeps its label (GeoJSON's numeric `priority`
    /// property; 0 without it).
    pub priority: f64,
}

/// A layer's places and lines on the map's grid.
#[derive(Clone, Debug, PartialEq)]
pub struct VectorLayer {
    /// Named points (points without a name are left out).
    pub places: Vec<Place>,
    /// Lines, each at least two points, in grid coordinates; parts off the map are cut out.
    pub lines: Vec<Vec<[f64; 2]>>,
    /// The lines' colour, display bytes.
    pub colour: [u8; 3],
    /// A marker's height above the ground, in world units.
    pub lift: f64,
    /// The section it was read from, its path made absolute (a scene saved elsewhere keeps it).
    pub section: VectorSection,
}

/// The default line colour.
const LINE_COLOUR: [u8; 3] = [0xe0, 0x30, 0x20];
/// The default marker height.
const DEFAULT_LIFT: f64 = 0.5;

/// What a vector file holds, in its own coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VectorFile {
    /// Named points.
    pub places: Vec<Place>,
    /// Lines and polygon rings.
    pub lines: Vec<Vec<[f64; 2]>>,
}

impl VectorLayer {
    /// Reads the section's file (relative to `base`) and places it on `field`.
    pub fn load(
        section: &VectorSection,
        base: &Path,
        field: &Heightfield,
    ) -> Result<Self, VectorError> {
        let path = base.join(&section.path);
        let key = |reason: VectorProblem| VectorError {
            path: path.clone(),
            reason,
        };
        let file = read(&path).map_err(|e| key(e.into()))?;
        let to_grid = grid_of(section.coordinates, field).map_err(key)?;
        let colour = match &section.colour {
            None => LINE_COLOUR,
            Some(text) => {
                bytes_from_hex(text).ok_or_else(|| key(VectorProblem::Colour(text.clone())))?
            }
        };
        let lift = section.lift.unwrap_or(DEFAULT_LIFT);
        if !(lift.is_finite() && lift >= 0.0) {
            return Err(key(VectorProblem::Lift(lift)));
        }
        let (w, h) = ((field.width() - 1) as f64, (field.height() - 1) as f64);
        let on_map = |p: &[f64; 2]| p[0] >= 0.0 && p[1] >= 0.0 && p[0] <= w && p[1] <= h;
        let places = file
            .places
            .into_iter()
            .filter_map(|place| {
                let at = to_grid(place.at).filter(on_map)?;
                Some(Place { at, ..place })
            })
            .collect();
        let mut lines = Vec::new();
        for line in file.lines {
            // Runs of points on the map, each a line of its own.
            let mut run: Vec<[f64; 2]> = Vec::new();
            for point in line.into_iter().map(|p| to_grid(p).filter(on_map)) {
                match point {
                    Some(p) => run.push(p),
                    None => lines.push(std::mem::take(&mut run)),
                }
            }
            lines.push(run);
        }
        lines.retain(|line| line.len() >= 2);
        Ok(VectorLayer {
            places,
            lines,
            colour,
            lift,
            section: VectorSection {
                path: std::path::absolute(&path)
                    .unwrap_or(path)
                    .display()
                    .to_string(),
                ..section.clone()
            },
        })
    }
}

/// How a file's coordinates become grid coordinates on `field`.
fn grid_of(
    coordinates: Coordinates,
    field: &Heightfield,
) -> Result<impl Fn([f64; 2]) -> Option<[f64; 2]> + '_, VectorProblem> {
    let georef = field.georef();
    if coordinates != Coordinates::Grid && georef.is_none() {
        return Err(VectorProblem::NotGeoreferenced);
    }
    Ok(move |p: [f64; 2]| {
        let finite = p.iter().all(|c| c.is_finite());
        match (coordinates, georef) {
            _ if !finite => None,
            (Coordinates::Grid, _) => Some(p),
            (Coordinates::Map, Some(g)) => Some(g.grid_point(p)),
            (Coordinates::Degrees, Some(g)) => Some(g.grid_point(g.map_of_lonlat(p)?)),
            (_, None) => None,
        }
    })
}

/// The places and lines of a GeoJSON or GPX file, by its extension.
pub fn read(path: &Path) -> Result<VectorFile, VectorFileError> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let read: fn(&str) -> Result<VectorFile, VectorFileError> = match extension.as_deref() {
        Some("gpx") => from_gpx,
        Some("geojson" | "json") => from_geojson,
        _ => return Err(VectorFileError::Extension),
    };
    read(&read_text(path)?)
}

/// A GeoJSON text's named points (the `name` property, and `priority` if it is a number) and
/// lines (LineStrings and polygon rings).
pub fn from_geojson(text: &str) -> Result<VectorFile, VectorFileError> {
    let json: GeoJson = text.parse().map_err(Box::new)?;
    let mut file = VectorFile::default();
    match json {
        GeoJson::FeatureCollection(collection) => {
            for feature in &collection.features {
                add_feature(feature, &mut file);
            }
        }
        GeoJson::Feature(feature) => add_feature(&feature, &mut file),
        GeoJson::Geometry(geometry) => add_geometry(&geometry, None, &mut file),
    }
    Ok(file)
}

/// Adds a feature's geometry to `file`, its points named by its `name` property.
fn add_feature(feature: &geojson::Feature, file: &mut VectorFile) {
    let name = feature.property("name").map(name_text).map(|name| {
        let priority = feature
            .property("priority")
            .and_then(serde_json::Value::as_f64);
        (name, priority.filter(|p| p.is_finite()).unwrap_or(0.0))
    });
    if let Some(geometry) = &feature.geometry {
        let named = name.as_ref().map(|(n, p)| (n.as_str(), *p));
        add_geometry(geometry, named, file);
    }
}

/// A `name` property as text: a string as it is, anything else as JSON.
fn name_text(value: &serde_json::Value) -> String {
    match value {
        serde_json::Value::String(text) => text.clone(),
        other => other.to_string(),
    }
}

/// Adds a geometry's points (if named, with their priority) and lines to `file`.
fn add_geometry(geometry: &Geometry, name: Option<(&str, f64)>, file: &mut VectorFile) {
    let place = |(name, priority): (&str, f64), at| Place {
        name: name.to_owned(),
        at,
        priority,
    };
    let xy = |p: &Vec<f64>| [p.first().copied(), p.get(1).copied()];
    let point = |p: &Vec<f64>| match xy(p) {
        [Some(x), Some(y)] => Some([x, y]),
        _ => None,
    };
    let line = |l: &Vec<Vec<f64>>| l.iter().filter_map(point).collect::<Vec<_>>();
    match &geometry.value {
        Value::Point(p) => file
            .places
            .extend(name.zip(point(p)).map(|(n, p)| place(n, p))),
        Value::MultiPoint(points) => {
            for p in points.iter().filter_map(point) {
                file.places.extend(name.map(|n| place(n, p)));
            }
        }
        Value::LineString(l) => file.lines.push(line(l)),
        Value::MultiLineString(ls) | Value::Polygon(ls) => file.lines.extend(ls.iter().map(line)),
        Value::MultiPolygon(polygons) => file
            .lines
            .extend(polygons.iter().flat_map(|rings| rings.iter().map(line))),
        Value::GeometryCollection(geometries) => {
            for g in geometries {
                add_geometry(g, name, file);
            }
        }
    }
}

/// A GPX text's waypoints (named ones) and its track (or route), as the camera paths read it.
pub fn from_gpx(text: &str) -> Result<VectorFile, VectorFileError> {
    let gpx = gpx::read(text.as_bytes()).map_err(NotGpx::from)?;
    let places = gpx
        .waypoints
        .iter()
        .filter_map(|w| {
            let p = w.point();
            Some(Place {
                name: w.name.clone()?,
                at: [p.x(), p.y()],
                priority: 0.0,
            })
        })
        .collect();
    let track = gpx_points(text)?;
    Ok(VectorFile {
        places,
        lines: vec![track],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn geojson_gives_named_points_and_lines() {
        let text = r#"{"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": {"name": "Summit"},
             "geometry": {"type": "Point", "coordinates": [7.5, 46.25, 3000]}},
            {"type": "Feature", "properties": {},
             "geometry": {"type": "Point", "coordinates": [1, 2]}},
            {"type": "Feature", "properties": {"name": "Trail"},
             "geometry": {"type": "LineString", "coordinates": [[7, 46], [7.5, 46.5]]}}]}"#;
        let file = from_geojson(text).unwrap();
        let summit = Place {
            name: "Summit".into(),
            at: [7.5, 46.25],
            priority: 0.0,
        };
        assert_eq!(file.places, vec![summit]);
        assert_eq!(file.lines, vec![vec![[7.0, 46.0], [7.5, 46.5]]]);
        assert!(from_geojson("{\"type\": \"Feature\"").is_err());
    }

    #[test]
    fn gpx_gives_waypoints_and_its_track() {
        let text = r#"<gpx version="1.1" creator="t"><wpt lat="45.5" lon="-122.25">
            <name>Hut</name></wpt><trk><trkseg><trkpt lat="1" lon="2"/><trkpt lat="3" lon="4"/>
            </trkseg></trk></gpx>"#;
        let file = from_gpx(text).unwrap();
        let hut = Place {
            name: "Hut".into(),
            at: [-122.25, 45.5],
            priority: 0.0,
        };
        assert_eq!(file.places, vec![hut]);
        assert_eq!(file.lines, vec![vec![[2.0, 1.0], [4.0, 3.0]]]);
    }
}
