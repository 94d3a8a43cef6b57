//! Ground scale by coordinate system: GeoTIFFs written here with an EPSG code in their
//! GeoKeys (Web Mercator at two latitudes, a Lambert conformal conic State Plane in US feet,
//! UTM away from its central meridian, geographic), their cells in metres checked against
//! Snyder's formulas (*Map Projections: A Working Manual*, USGS 1395) worked here on the
//! ellipsoid; heights in feet converted to metres.

use crate::common::files::{tagged_tiff, TagData};
use heightray::heightfield::{load_bytes, place, relief};
use heightray::{Heightfield, Terrain};
use std::f64::consts::FRAC_PI_4;
use tiff::encoder::colortype::Gray32Float;
use tiff::tags::Tag;

const A: f64 = 6_378_137.0;
/// WGS 84's (and within 1e-10, GRS 80's) first eccentricity squared.
const E2: f64 = 0.006_694_379_990_141_317;
const US_FOOT: f64 = 1200.0 / 3937.0;

/// Meridional and prime-vertical radii of curvature at latitude `phi` (radians).
fn radii(phi: f64) -> (f64, f64) {
    let w = 1.0 - E2 * phi.sin().powi(2);
    (A * (1.0 - E2) / w.powf(1.5), A / w.sqrt())
}

/// A `n` x `n` float DEM of heights `height`, its centre pixel's centre at map point
/// `centre`, `cell` map units a pixel, with these GeoKeys.
fn dem(n: u32, centre: [f64; 2], cell: f64, keys: &[(u16, u16)], height: f32) -> Heightfield {
    let mut directory = vec![1, 1, 0, keys.len() as u16];
    for &(id, value) in keys {
        directory.extend([id, 0, 1, value]);
    }
    let half = 0.5 * f64::from(n) * cell;
    let tiepoint = [0.0, 0.0, 0.0, centre[0] - half, centre[1] + half, 0.0];
    let heights = vec![height; (n * n) as usize];
    let bytes = tagged_tiff::<Gray32Float>(
        n,
        n,
        &heights,
        &[
            (Tag::GeoKeyDirectoryTag, TagData::Shorts(&directory)),
            (
                Tag::ModelPixelScaleTag,
                TagData::Doubles(&[cell, cell, 0.0]),
            ),
            (Tag::ModelTiepointTag, TagData::Doubles(&tiepoint)),
        ],
    );
    load_bytes(&bytes, 1.0, "dem.tif").expect("loads")
}

const PROJECTED: [(u16, u16); 1] = [(1024, 1)];

fn projected(epsg: u16) -> Vec<(u16, u16)> {
    vec![PROJECTED[0], (3072, epsg)]
}

fn close(got: [f64; 2], want: [f64; 2], relative: f64) {
    for axis in 0..2 {
        let error = (got[axis] / want[axis] - 1.0).abs();
        assert!(error < relative, "got {got:?}, want {want:?}");
    }
}

#[test]
fn web_mercator_cells_shrink_by_the_cosine_of_latitude() {
    for lat in [36.6_f64, 60.0] {
        let phi = lat.to_radians();
        // Snyder (7-2): y = R ln tan(pi/4 + phi/2) on the sphere of radius a.
        let y = A * (FRAC_PI_4 + 0.5 * phi).tan().ln();
        let field = dem(101, [-9_380_000.0, y], 100.0, &projected(3857), 0.0);
        // x = R lambda, y as above: dx/dlambda = R, dy/dphi = R / cos(phi); the ground
        // spans N cos(phi) dlambda and M dphi.
        let (m, n) = radii(phi);
        let want = [100.0 * n * phi.cos() / A, 100.0 * m * phi.cos() / A];
        close(field.cell_metres().unwrap(), want, 1e-6);
        let summary = Terrain::new(field).summary();
        assert!(
            summary.contains("WGS 84 / Pseudo-Mercator (EPSG:3857)"),
            "{summary}"
        );
    }
    // At 36.6 N a 100 m cell spans within 0.2% of 100 cos(36.6°) = 80.28 m of ground.
    let y = A * (FRAC_PI_4 + 0.5 * 36.6_f64.to_radians()).tan().ln();
    let [x, _] = dem(5, [0.0, y], 100.0, &projected(3857), 0.0)
        .cell_metres()
        .unwrap();
    assert!((x / 80.28 - 1.0).abs() < 0.002, "{x}");
}

#[test]
fn a_map_spanning_many_degrees_says_its_scale_varies() {
    // 201 cells of 10 km from about 32 N to 44 N: cos(latitude) changes by over 10%.
    let y = A * (FRAC_PI_4 + 0.5 * 38f64.to_radians()).tan().ln();
    let summary = Terrain::new(dem(201, [0.0, y], 10_000.0, &projected(3857), 0.0)).summary();
    assert!(summary.contains("cells vary by"), "{summary}");
    let small = Terrain::new(dem(11, [0.0, y], 100.0, &projected(3857), 0.0)).summary();
    assert!(!small.contains("cells vary by"), "{small}");
}

/// Snyder (15-1 .. 15-9) for EPSG:2274, NAD83 / Tennessee (ftUS): the map point in US feet
/// and the scale factor at longitude `lon`, latitude `lat` (degrees).
fn tennessee(lon: f64, lat: f64) -> ([f64; 2], f64) {
    let e = E2.sqrt();
    let m = |phi: f64| phi.cos() / (1.0 - E2 * phi.sin().powi(2)).sqrt();
    let t = |phi: f64| {
        (FRAC_PI_4 - 0.5 * phi).tan()
            / ((1.0 - e * phi.sin()) / (1.0 + e * phi.sin())).powf(0.5 * e)
    };
    let (phi1, phi2, phi0) = (
        36.416_666_666_666_66_f64.to_radians(),
        35.25_f64.to_radians(),
        34.333_333_333_333_34_f64.to_radians(),
    );
    let n = (m(phi1).ln() - m(phi2).ln()) / (t(phi1).ln() - t(phi2).ln());
    let f = m(phi1) / (n * t(phi1).powf(n));
    let rho = |phi: f64| A * f * t(phi).powf(n);
    let phi = lat.to_radians();
    let theta = n * (lon + 86.0).to_radians();
    let x = 600_000.0 + rho(phi) * theta.sin();
    let y = rho(phi0) - rho(phi) * theta.cos();
    ([x / US_FOOT, y / US_FOOT], rho(phi) * n / (A * m(phi)))
}

#[test]
fn a_state_plane_in_us_feet_has_its_lambert_scale_and_heights_in_feet() {
    // 30 ft cells near Knoxville, north of both standard parallels: k > 1.
    let (centre, k) = tennessee(-84.0, 36.8);
    assert!(k > 1.0 && k < 1.001, "{k}");
    let field = dem(101, centre, 30.0, &projected(2274), 1000.0);
    let want = 30.0 * US_FOOT / k;
    close(field.cell_metres().unwrap(), [want, want], 1e-6);
    let (lat, lon) = place::centre_degrees(&field).unwrap();
    assert!(
        (lat - 36.8).abs() < 1e-6 && (lon + 84.0).abs() < 1e-6,
        "{lat} {lon}"
    );
    // 1000 US ft of height is 304.8006 m, and at true scale that many metres over the cells.
    let z = relief::true_z_scale(&field, 1.0).unwrap();
    let true_scale = field.with_z_scale(z).unwrap();
    let metres = 1000.0 * US_FOOT;
    assert!((true_scale.z(3, 3) * want - metres).abs() < 1e-6);
    let shown = place::elevation_metres(&true_scale, true_scale.z(3, 3)).unwrap();
    assert!((shown - metres).abs() < 1e-9, "{shown}");
    let summary = Terrain::new(true_scale).summary();
    assert!(summary.contains("heights 304.8 .. 304.8 m"), "{summary}");
    assert!(
        summary.contains("heights in US ft (the CRS's unit)"),
        "{summary}"
    );
}

#[test]
fn a_vertical_unit_key_sets_the_height_unit() {
    // UTM in metres, heights in international feet (VerticalUnitsGeoKey 9002).
    let mut keys = projected(32617);
    keys.push((4099, 9002));
    let field = dem(5, [700_000.0, 3_985_000.0], 30.0, &keys, 100.0);
    let shown = place::elevation_metres(&field, field.z(0, 0)).unwrap();
    assert!((shown - 30.48).abs() < 1e-9, "{shown}");
    let summary = Terrain::new(field).summary();
    assert!(
        summary.contains("heights in ft (the file's vertical unit)"),
        "{summary}"
    );
}

#[test]
fn utm_cells_away_from_the_central_meridian_are_smaller_on_the_ground() {
    // 200 km east of zone 17's central meridian near 36 N. Redfearn's series for the scale
    // factor, k = k0 (1 + E^2 / (2 rho nu) + E^4 / (24 rho^2 nu^2)), E = (x - 500 km) / k0.
    let field = dem(101, [700_000.0, 3_985_000.0], 30.0, &projected(32617), 0.0);
    let (lat, _) = place::centre_degrees(&field).unwrap();
    assert!((lat - 36.0).abs() < 0.05, "{lat}");
    let (m, n) = radii(lat.to_radians());
    let e = 200_000.0 / 0.9996;
    let r2 = m * n;
    let k = 0.9996 * (1.0 + e * e / (2.0 * r2) + e.powi(4) / (24.0 * r2 * r2));
    close(field.cell_metres().unwrap(), [30.0 / k, 30.0 / k], 1e-6);
    // On the central meridian: k0 = 0.9996.
    let field = dem(101, [500_000.0, 3_985_000.0], 30.0, &projected(32617), 0.0);
    close(field.cell_metres().unwrap(), [30.0 / 0.9996; 2], 1e-7);
}

#[test]
fn geographic_cells_are_measured_on_the_ellipsoid() {
    let second = 1.0 / 3600.0;
    let keys = [(1024, 2), (2048, 4326)];
    let field = dem(3, [10.0, 60.0], second, &keys, 0.0);
    let phi = 60f64.to_radians();
    let (m, n) = radii(phi);
    let arc = second.to_radians();
    close(
        field.cell_metres().unwrap(),
        [n * phi.cos() * arc, m * arc],
        1e-9,
    );
    // Published lengths of a degree at 60° on WGS 84: 55.80 km of longitude, 111.41 km of
    // latitude.
    let [x, y] = field.cell_metres().unwrap();
    assert!((x * 3600.0 / 55_800.0 - 1.0).abs() < 1e-3, "{x}");
    assert!((y * 3600.0 / 111_412.0 - 1.0).abs() < 1e-4, "{y}");
}
