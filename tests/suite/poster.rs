//! The poster scene of a real DEM with every annotation, rendered whole and in tiles; scene
//! keys of annotations, contours and vector layers refused with messages that say why.

use crate::common::scenes::{load_scene_text, SMALL_SCENE};
use crate::flight::{arg, heightray};
use std::path::{Path, PathBuf};

fn poster_scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/jacksboro_poster.toml")
}

/// Annotations are drawn at the whole picture's coordinates: tiles merged are the whole render,
/// its labels, bar, arrow and legend included, byte for byte; and they change the picture.
#[test]
fn the_posters_tiles_merge_into_the_whole_annotated_render() {
    let dir = tempfile::tempdir().unwrap();
    let scene = poster_scene();
    let whole = dir.path().join("whole.png");
    heightray(&[
        "render",
        arg(&scene),
        "--size",
        "320x180",
        "-o",
        arg(&whole),
    ]);
    let tiles = dir.path().join("tiles");
    heightray(&[
        "render",
        arg(&scene),
        "--size",
        "320x180",
        "--tiles",
        "3x2",
        "-o",
        arg(&tiles),
    ]);
    let parts: Vec<PathBuf> = std::fs::read_dir(&tiles)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    let merged = dir.path().join("merged.png");
    let mut merge = vec!["merge"];
    merge.extend(parts.iter().map(|p| arg(p)));
    merge.extend(["-o", arg(&merged)]);
    heightray(&merge);
    let read = |path: &Path| image::open(path).unwrap().to_rgb8();
    assert_eq!(read(&merged), read(&whole));

    // The same view without annotations: the marks' corners differ, the middle does not.
    let text = std::fs::read_to_string(&scene).unwrap();
    let plain_text = text.split("[annotations]").next().unwrap().replace(
        "path = \"jacksboro.tif\"",
        &format!("path = {:?}", scene.with_file_name("jacksboro.tif")),
    );
    let plain_scene = dir.path().join("plain.toml");
    std::fs::write(&plain_scene, plain_text).unwrap();
    let plain = dir.path().join("plain.png");
    heightray(&[
        "render",
        arg(&plain_scene),
        "--size",
        "320x180",
        "-o",
        arg(&plain),
    ]);
    let (marked, plain) = (read(&whole), read(&plain));
    let differs = |x0: u32, y0: u32, x1: u32, y1: u32| {
        (y0..y1).any(|y| (x0..x1).any(|x| marked.get_pixel(x, y) != plain.get_pixel(x, y)))
    };
    assert!(differs(0, 0, 120, 20), "no title");
    assert!(differs(0, 150, 110, 180), "no scale bar");
    assert!(differs(280, 0, 320, 40), "no north arrow");
    assert!(differs(290, 90, 320, 170), "no legend");
}

#[test]
fn bad_annotation_contour_and_vector_keys_are_refused_by_name() {
    let refused = |extra: &str, said: &str| {
        let text = format!("{SMALL_SCENE}{extra}");
        match load_scene_text("scene.toml", &text) {
            Ok(_) => panic!("{extra:?} was accepted"),
            Err(message) => assert!(message.contains(said), "{extra:?}: {message}"),
        }
    };
    refused("[annotations]\nscalebar = true\n", "scalebar");
    refused("[overlay]\ncontours = -5.0\n", "[overlay] contours must be");
    refused("[overlay]\ncontours = nan\n", "[overlay] contours must be");
    refused(
        "[[vector]]\npath = \"places.geojson\"\n",
        "places.geojson: No such file",
    );
    refused(
        "[[vector]]\npath = \"places.txt\"\ncoordinates = \"grid\"\n",
        "name a .geojson or .gpx file",
    );
    refused(
        "[[vector]]\npath = \"p.geojson\"\ncoordinates = \"lonlat\"\n",
        "unknown variant",
    );
}

#[test]
fn vector_files_are_checked_as_they_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let scene = |file: &str, body: &str, extra: &str| {
        std::fs::write(dir.path().join(file), body).unwrap();
        let text = format!("{SMALL_SCENE}[[vector]]\npath = {file:?}\n{extra}");
        let path = dir.path().join("scene.toml");
        std::fs::write(&path, text).unwrap();
        heightray::render::Scene::load(&path).map_err(|e| e.to_string())
    };
    let point = r#"{"type": "Feature", "properties": {"name": "A"},
        "geometry": {"type": "Point", "coordinates": [10, 12]}}"#;
    // A plain map has no place for longitudes and latitudes.
    let degrees = scene("p.geojson", point, "").unwrap_err();
    assert!(degrees.contains("no georeferencing"), "{degrees}");
    let loaded = scene("p.geojson", point, "coordinates = \"grid\"\n").unwrap();
    let places = &loaded.annotations.vectors[0].places;
    assert_eq!(places.len(), 1);
    assert_eq!((places[0].name.as_str(), places[0].at), ("A", [10.0, 12.0]));
    let broken = scene(
        "b.geojson",
        "{\"type\": \"Feature\",",
        "coordinates = \"grid\"\n",
    );
    assert!(broken.unwrap_err().contains("not GeoJSON"));
    let colour = scene(
        "p.geojson",
        point,
        "coordinates = \"grid\"\ncolour = \"red\"\n",
    );
    assert!(colour.unwrap_err().contains("is not #RRGGBB"));
    let gpx = scene("t.gpx", "<gpx><trk>", "coordinates = \"grid\"\n");
    assert!(gpx.unwrap_err().contains("not a GPX file"));
    std::fs::create_dir(dir.path().join("d.geojson")).unwrap();
    let text = format!("{SMALL_SCENE}[[vector]]\npath = \"d.geojson\"\ncoordinates = \"grid\"\n");
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let directory = heightray::render::Scene::load(&path)
        .unwrap_err()
        .to_string();
    assert!(directory.contains("it is a directory"), "{directory}");
}

/// The poster's places are given in degrees on a map in degrees: its summit was written at the
/// centre of the sample holding the map's highest height (column 219, row 297 from the top of
/// 344), so it lies at grid point (219, 46), on a 1076 m sample.
#[test]
fn places_in_degrees_land_on_the_samples_they_were_taken_from() {
    let scene = heightray::render::Scene::load(&poster_scene()).unwrap();
    let places = &scene.annotations.vectors[0].places;
    let summit = places.iter().find(|p| p.name == "Summit 1076 m").unwrap();
    let [x, y] = summit.at;
    assert!(
        (x - 219.0).abs() < 0.01 && (y - 46.0).abs() < 0.01,
        "{:?}",
        summit.at
    );
    let field = &scene.field;
    let highest = (0..field.height())
        .flat_map(|j| (0..field.width()).map(move |i| (i, j)))
        .map(|(i, j)| field.z(i, j))
        .fold(f64::MIN, f64::max);
    assert_eq!(field.z(219, 46), highest);
    let metres = heightray::heightfield::place::elevation_metres(field, highest).unwrap();
    assert!((metres - 1076.0).abs() < 1e-6, "{metres}");
}
