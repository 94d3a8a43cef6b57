//! A map's coordinate reference system by its EPSG code, with the projection behind it
//! (`proj4rs`, definitions from `crs-definitions`): its name, its unit, and the longitude
//! and latitude of any map point.

use proj4rs::Proj;
use thiserror::Error;

/// Radians to degrees and back happen here only; `proj4rs` works in radians.
const WGS84_LONLAT: &str = "+proj=longlat +datum=WGS84 +no_defs";

/// Why a CRS's projection cannot be used.
#[derive(Debug, Error)]
pub enum CrsError {
    /// The definitions hold the code, but `proj4rs` cannot use its definition.
    #[error("the definition of EPSG:{epsg} is not usable ({source})")]
    Definition {
        /// The EPSG code.
        epsg: u16,
        /// What `proj4rs` said.
        source: proj4rs::errors::Error,
    },
    /// WGS 84's own longitude and latitude would not parse.
    #[error("WGS 84 longitude and latitude are not usable ({0})")]
    Wgs84(proj4rs::errors::Error),
}

/// A coordinate reference system known by its EPSG code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Crs {
    /// The EPSG code, e.g. 3857 for Web Mercator, 32617 for UTM zone 17 N.
    pub epsg: u16,
}

impl Crs {
    /// The CRS of an EPSG code, if the definitions hold it.
    pub fn from_epsg(epsg: u16) -> Option<Crs> {
        crs_definitions::from_code(epsg).map(|_| Crs { epsg })
    }

    /// The CRS's name from its definition, e.g. `WGS 84 / Pseudo-Mercator`.
    pub fn name(&self) -> &'static str {
        crs_definitions::from_code(self.epsg)
            .and_then(|def| def.wkt.split('"').nth(1))
            .unwrap_or("unnamed")
    }

    /// The name and code, e.g. `WGS 84 / UTM zone 17N (EPSG:32617)`.
    pub fn label(&self) -> String {
        format!("{} (EPSG:{})", self.name(), self.epsg)
    }

    /// Whether coordinates are longitude and latitude.
    pub fn is_geographic(&self) -> bool {
        self.proj().is_ok_and(|p| p.is_latlong())
    }

    /// Metres in one unit of a projected CRS's coordinates (0.3048006 for US survey feet).
    pub fn metres_per_unit(&self) -> Option<f64> {
        self.proj()
            .ok()
            .filter(|p| !p.is_latlong())
            .map(|p| p.to_meter())
    }

    /// The projection, parsed from the definition.
    fn proj(&self) -> Result<Proj, CrsError> {
        Proj::from_epsg_code(self.epsg).map_err(|source| CrsError::Definition {
            epsg: self.epsg,
            source,
        })
    }

    /// A converter between this CRS's coordinates and WGS 84 longitude and latitude.
    pub fn to_lonlat(&self) -> Result<LonLat, CrsError> {
        let wgs84 = Proj::from_proj_string(WGS84_LONLAT).map_err(CrsError::Wgs84)?;
        Ok(LonLat {
            map: self.proj()?,
            wgs84,
        })
    }
}

/// Map coordinates to WGS 84 longitude and latitude in degrees, and back.
pub struct LonLat {
    map: Proj,
    wgs84: Proj,
}

impl LonLat {
    /// Longitude and latitude in degrees of map point `[x, y]` (in the CRS's units; degrees
    /// for a geographic CRS).
    pub fn lonlat(&self, [x, y]: [f64; 2]) -> Option<[f64; 2]> {
        let (x, y) = if self.map.is_latlong() {
            (x.to_radians(), y.to_radians())
        } else {
            (x, y)
        };
        let mut point = (x, y, 0.0);
        proj4rs::transform::transform(&self.map, &self.wgs84, &mut point).ok()?;
        let out = [point.0.to_degrees(), point.1.to_degrees()];
        out.iter().all(|c| c.is_finite()).then_some(out)
    }

    /// Map point of longitude and latitude `[lon, lat]` in degrees.
    pub fn map_point(&self, [lon, lat]: [f64; 2]) -> Option<[f64; 2]> {
        let mut point = (lon.to_radians(), lat.to_radians(), 0.0);
        proj4rs::transform::transform(&self.wgs84, &self.map, &mut point).ok()?;
        let out = if self.map.is_latlong() {
            [point.0.to_degrees(), point.1.to_degrees()]
        } else {
            [point.0, point.1]
        };
        out.iter().all(|c| c.is_finite()).then_some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn web_mercator_is_named_and_inverts_to_degrees() {
        let crs = Crs::from_epsg(3857).unwrap();
        assert_eq!(crs.name(), "WGS 84 / Pseudo-Mercator");
        assert!(!crs.is_geographic());
        // x = R * lon on the sphere of radius 6378137 m.
        let r = 6_378_137.0_f64;
        let lonlat = crs.to_lonlat().unwrap();
        let [lon, lat] = lonlat.lonlat([r * 10f64.to_radians(), 0.0]).unwrap();
        assert!((lon - 10.0).abs() < 1e-9 && lat.abs() < 1e-9, "{lon} {lat}");
        assert!(Crs::from_epsg(1).is_none());
    }
}
