//! Place names in a perspective picture never overlap: where two collide, the one with the
//! higher GeoJSON `priority` (else the nearer to the eye) keeps the upper-right corner, the
//! other takes a free corner or, with none, loses its name but keeps its marker; names that do
//! not collide are all drawn where they always were, and names keep off the legend. Seen straight down on a flat map, so the
//! place under the eye is the nearest.

use heightray::render::annotate::{
    Annotations, Coordinates, PlacedName, Sheet, VectorLayer, VectorSection,
};
use heightray::render::{Camera, Ramp};
use heightray::{Arith, Heightfield, Method, Terrain};

const LONG: &str = "A long name under the eye";

fn flat() -> Terrain {
    Terrain::new(Heightfield::from_fn(64, 64, 1000, 1000.0, |_, _| 0).unwrap())
}

/// The names drawn for `places` (name, grid point, priority if any), seen straight down from
/// above the map's centre, and the SVG they are drawn in.
fn names(terrain: &Terrain, places: &[(&str, [f64; 2], Option<f64>)]) -> (Vec<PlacedName>, String) {
    names_with(terrain, places, Annotations::default())
}

/// [`names`] over the marks of `marks` (a legend, a title...).
fn names_with(
    terrain: &Terrain,
    places: &[(&str, [f64; 2], Option<f64>)],
    marks: Annotations,
) -> (Vec<PlacedName>, String) {
    let features: Vec<String> = places
        .iter()
        .map(|(name, [x, y], priority)| {
            let priority = priority.map_or(String::new(), |p| format!(", \"priority\": {p}"));
            format!(
                "{{\"type\": \"Feature\", \"properties\": {{\"name\": \"{name}\"{priority}}}, \
                 \"geometry\": {{\"type\": \"Point\", \"coordinates\": [{x}, {y}]}}}}"
            )
        })
        .collect();
    let dir = tempfile::tempdir().unwrap();
    let text = format!(
        "{{\"type\": \"FeatureCollection\", \"features\": [{}]}}",
        features.join(",")
    );
    std::fs::write(dir.path().join("places.geojson"), text).unwrap();
    let section = VectorSection {
        path: "places.geojson".into(),
        coordinates: Coordinates::Grid,
        colour: None,
        lift: Some(0.0),
    };
    let layer = VectorLayer::load(&section, dir.path(), terrain.field()).unwrap();
    let camera = Camera::look_at(
        [32.0, 32.0, 60.0],
        [32.0, 32.0, 0.0],
        [0.0, 1.0, 0.0],
        60.0,
        (640, 480),
    );
    let sheet = Sheet {
        terrain,
        camera: camera.unwrap(),
        ramp: Ramp::Terrain,
        method: Method::Mipmap,
        arith: Arith::F64,
    };
    let annotations = Annotations {
        vectors: vec![layer],
        ..marks
    };
    (annotations.place_names(&sheet), annotations.svg(&sheet))
}

fn assert_apart(names: &[PlacedName]) {
    for (k, a) in names.iter().enumerate() {
        for b in &names[k + 1..] {
            assert!(!a.overlaps(b), "{a:?} overlaps {b:?}");
        }
    }
}

/// A place 60 pixels right of the centre and 8 up (about 8.7 and 1.2 cells at this view's
/// 6.9 pixels a cell): inside the long name's box, so every corner of its own name collides
/// with the long name at the upper right.
const BESIDE: [f64; 2] = [32.0 + 60.0 / 6.93, 32.0 + 8.0 / 6.93];

#[test]
fn the_nearer_place_keeps_its_name_where_names_collide() {
    let terrain = flat();
    let (drawn, svg) = names(
        &terrain,
        &[("Beside", BESIDE, None), (LONG, [32.0, 32.0], None)],
    );
    // Exactly one name: the nearer's, at the upper right; both markers.
    assert_eq!(drawn.len(), 1, "{drawn:?}");
    assert_eq!((drawn[0].name.as_str(), drawn[0].ends_at), (LONG, false));
    assert!(svg.contains(&format!(">{LONG}<")) && !svg.contains(">Beside<"));
    assert_eq!(svg.matches("<circle").count(), 2);
}

#[test]
fn a_higher_priority_keeps_its_name_and_the_other_moves_to_a_free_corner() {
    let terrain = flat();
    let places = [
        ("Beside", BESIDE, Some(2.0)),
        (LONG, [32.0, 32.0], Some(1.0)),
    ];
    let (drawn, _) = names(&terrain, &places);
    assert_eq!(drawn.len(), 2, "{drawn:?}");
    // The farther place outranks the nearer: its name at the upper right; the long name,
    // blocked there, at the upper left of its marker.
    assert_eq!(
        (drawn[0].name.as_str(), drawn[0].ends_at),
        ("Beside", false)
    );
    assert_eq!((drawn[1].name.as_str(), drawn[1].ends_at), (LONG, true));
    assert_apart(&drawn);
    // Without the priorities, the nearer wins and the other has no room (as above).
    let places = [("Beside", BESIDE, None), (LONG, [32.0, 32.0], None)];
    assert_eq!(names_of(&names(&terrain, &places).0), [LONG]);
}

#[test]
fn names_that_do_not_collide_are_all_drawn_at_the_upper_right() {
    let terrain = flat();
    let places = [
        ("North", [32.0, 50.0], None),
        ("Centre", [32.0, 32.0], Some(1.0)),
        ("South-west", [12.0, 14.0], None),
    ];
    let (drawn, _) = names(&terrain, &places);
    let mut which = names_of(&drawn);
    which.sort_unstable();
    assert_eq!(which, ["Centre", "North", "South-west"]);
    assert!(drawn.iter().all(|n| !n.ends_at), "{drawn:?}");
    assert_apart(&drawn);
}

fn names_of(names: &[PlacedName]) -> Vec<&str> {
    names.iter().map(|n| n.name.as_str()).collect()
}

#[test]
fn a_name_moves_off_the_legend() {
    let terrain = flat();
    // A marker at pixel (500, 380) of 640x480: its name at the upper right would run into the
    // legend, which takes x from 640 - 7 em (em = 14 pixels here) between y 283 and 455.
    let place = [(
        "Near the legend",
        [32.0 + 180.0 / 6.928, 32.0 - 140.0 / 6.928],
        None,
    )];
    let (free, _) = names(&terrain, &place);
    assert!(!free[0].ends_at && free[0].bounds[2] > 542.0, "{free:?}");
    let legend = Annotations {
        legend: true,
        ..Annotations::default()
    };
    let (moved, _) = names_with(&terrain, &place, legend);
    assert_eq!(moved.len(), 1);
    assert!(moved[0].ends_at && moved[0].bounds[2] <= 542.0, "{moved:?}");
}
