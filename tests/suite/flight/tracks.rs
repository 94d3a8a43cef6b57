//! A track to follow on a georeferenced map: the eye over each point of a GeoJSON line at its
//! height above the ground there (checked through the map's own georeferencing and surface),
//! looking ahead along it; a GPX file of the same points flies the same path.

use super::{arg, heightray};
use heightray::render::framing::surface_z;
use heightray::render::{Scene, SceneFile};
use heightray::Terrain;
use std::path::Path;

/// A 21x21 grid of 0.001-degree cells from 7 E, 46 N with a hill, and a scene flying `track`
/// 5 units above it at 4 units a second, in `dir`.
fn write_scene(dir: &Path, track: &str) -> std::path::PathBuf {
    let mut grid =
        String::from("ncols 21\nnrows 21\nxllcorner 7.0\nyllcorner 46.0\ncellsize 0.001\n");
    for r in 0..21i32 {
        let row: Vec<String> = (0..21i32)
            .map(|c| (300 - ((c - 10).pow(2) + (r - 8).pow(2))).to_string())
            .collect();
        grid += &(row.join(" ") + "\n");
    }
    std::fs::write(dir.join("hill.asc"), grid).unwrap();
    let path = dir.join(format!("{track}.toml"));
    std::fs::write(
        &path,
        format!(
            "[heightmap]\npath = \"hill.asc\"\n[camera]\neye = [0.0, 0.0, 400.0]\n\
             target = [10.0, 10.0, 300.0]\nwidth = 32\nheight = 24\n[animation]\nfps = 10\n\
             [animation.track]\npath = \"{track}\"\nheight = 5.0\nspeed = 4.0\n"
        ),
    )
    .unwrap();
    path
}

const POINTS: [[f64; 2]; 3] = [[7.0025, 46.0035], [7.0165, 46.0035], [7.0165, 46.0155]];

#[test]
fn the_camera_flies_over_the_track_looking_ahead() {
    let dir = tempfile::tempdir().unwrap();
    let line: Vec<String> = POINTS.iter().map(|[x, y]| format!("[{x}, {y}]")).collect();
    std::fs::write(
        dir.path().join("route.geojson"),
        format!(
            "{{\"type\": \"Feature\", \"geometry\": {{\"type\": \"LineString\", \
             \"coordinates\": [{}]}}}}",
            line.join(", ")
        ),
    )
    .unwrap();
    let path = write_scene(dir.path(), "route.geojson");
    let file = SceneFile::read(&path).unwrap();
    let scene = Scene::from_file(&file, dir.path(), &path).unwrap();
    let path_of = scene.animation.expect("a track");
    let field = scene.field.clone();
    let georef = *field.georef().expect("degrees");
    let terrain = Terrain::new(scene.field);
    // Where a world point lies, in longitude and latitude, by the map's own georeferencing.
    let lonlat = |p: glam::DVec3| {
        let [gx, gy, _] = terrain.grid_point(p.into());
        georef.map_point(gx, gy)
    };
    let first = path_of.view_at(0.0);
    let [lon, lat] = lonlat(first.eye);
    assert!(
        (lon - POINTS[0][0]).abs() < 1e-9 && (lat - POINTS[0][1]).abs() < 1e-9,
        "{lon} {lat}"
    );
    let ground = surface_z(&terrain, first.eye.x, first.eye.y);
    assert!(
        (first.eye.z - ground - 5.0).abs() < 1e-9,
        "{} over {ground}",
        first.eye.z
    );
    // Looking ahead: east along the first leg.
    let ahead = first.target - first.eye;
    assert!(ahead.x > 0.0 && ahead.y.abs() < 1e-9, "{ahead}");
    // The last frame is over the last point, looking on to the north.
    let end = path_of.view_at((path_of.frames() - 1) as f64 / 10.0 + 1.0);
    let [lon, lat] = lonlat(end.eye);
    assert!(
        (lon - POINTS[2][0]).abs() < 1e-9 && (lat - POINTS[2][1]).abs() < 1e-9,
        "{lon} {lat}"
    );
    assert!(end.target.y > end.eye.y);

    // The same points as a GPX track: the same frames.
    let gpx: String = POINTS
        .iter()
        .map(|[lon, lat]| format!("<trkpt lat=\"{lat}\" lon=\"{lon}\"></trkpt>"))
        .collect();
    std::fs::write(
        dir.path().join("route.gpx"),
        format!("<gpx version=\"1.1\" creator=\"test\"><trk><trkseg>{gpx}</trkseg></trk></gpx>"),
    )
    .unwrap();
    let other = write_scene(dir.path(), "route.gpx");
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    heightray(&["render", arg(&path), "--frames", "0..30/7", "-o", arg(&a)]);
    heightray(&["render", arg(&other), "--frames", "0..30/7", "-o", arg(&b)]);
    for k in [0, 7, 14, 21, 28] {
        let name = format!("frame-{k:05}.png");
        assert_eq!(
            std::fs::read(a.join(&name)).unwrap(),
            std::fs::read(b.join(&name)).unwrap()
        );
    }
}
