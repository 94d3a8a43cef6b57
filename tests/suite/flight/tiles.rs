//! A poster in tiles: merged, the exact bytes of the whole render, adaptive samples included,
//! whose decisions near a tile's edge look across it (tiles are rendered with a margin as wide
//! as they reach, and without it they differ).

use super::{arg, heightray, orbit_scene, run};
use heightray::batch::TileGrid;
use heightray::render::reach;
use heightray::render::{Culling, Frame, Renderer, Scene, SceneFile, Shader, Window};
use heightray::Terrain;
use std::path::PathBuf;

/// Adaptive samples, soft shadows: a picture whose pixels near an edge depend on the next.
const SAMPLED: &str = "[render]\nsamples = 16\nadaptive = true\n[sun]\nangle_deg = 2.0\n";

#[test]
fn sixteen_tiles_and_three_bands_merge_into_the_whole_render() {
    let dir = tempfile::tempdir().unwrap();
    let scene = orbit_scene(dir.path(), SAMPLED);
    let whole = dir.path().join("whole.png");
    heightray(&["render", arg(&scene), "-o", arg(&whole)]);
    let tiles = dir.path().join("tiles");
    heightray(&[
        "render",
        arg(&scene),
        "--tiles",
        "4x4",
        "-o",
        arg(&tiles),
        "--threads",
        "1",
    ]);
    let mut parts: Vec<PathBuf> = std::fs::read_dir(&tiles)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(parts.len(), 16);
    parts.reverse(); // (any order)
    let poster = dir.path().join("poster.png");
    let mut merge = vec!["merge"];
    merge.extend(parts.iter().map(|p| arg(p)));
    merge.extend(["-o", arg(&poster)]);
    heightray(&merge);
    assert_eq!(
        std::fs::read(&poster).unwrap(),
        std::fs::read(&whole).unwrap()
    );

    let bands: Vec<PathBuf> = (0..3)
        .map(|i| dir.path().join(format!("band{i}.png")))
        .collect();
    for (i, band) in bands.iter().enumerate() {
        heightray(&[
            "render",
            arg(&scene),
            "--tile",
            &format!("{i}/3"),
            "-o",
            arg(band),
        ]);
    }
    let joined = dir.path().join("joined.png");
    heightray(&[
        "merge",
        arg(&bands[2]),
        arg(&bands[0]),
        arg(&bands[1]),
        "-o",
        arg(&joined),
    ]);
    assert_eq!(
        std::fs::read(&joined).unwrap(),
        std::fs::read(&whole).unwrap()
    );

    // Parts that are not one whole picture are refused.
    let refused = |args: &[&str], said: &str| {
        let output = run(args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success() && stderr.contains(said),
            "{args:?}: {stderr}"
        );
    };
    let out = arg(&joined);
    refused(
        &["merge", arg(&bands[0]), arg(&bands[1]), "-o", out],
        "uncovered",
    );
    refused(
        &[
            "merge",
            arg(&bands[0]),
            arg(&bands[0]),
            arg(&bands[1]),
            arg(&bands[2]),
            "-o",
            out,
        ],
        "overlaps",
    );
    refused(&["merge", arg(&whole), "-o", out], "not a tile");
}

#[test]
fn a_tile_needs_its_margin_to_be_the_whole_pictures() {
    let dir = tempfile::tempdir().unwrap();
    // Large enough that some pixel beside a tile's edge stops early only when it cannot see
    // an edge in the picture across it.
    let path = orbit_scene(dir.path(), SAMPLED);
    let mut file = SceneFile::read(&path).unwrap();
    file.size = Some((256, 192));
    let scene = Scene::from_file(&file, dir.path(), &path).unwrap();
    let terrain = Terrain::new(scene.field);
    let renderer = |camera| Renderer {
        shader: Shader::new(&terrain, scene.lighting, scene.method, Culling::default()),
        camera,
        arith: scene.arith,
    };
    let (w, h) = scene.camera.size();
    let mut whole = Frame::new(w, h);
    renderer(scene.camera).render(&mut whole);
    let margin = reach(&scene.lighting.effects);
    assert_eq!(margin, 8, "16 samples in batches of 2");
    let mut differ_without = 0;
    for index in 0..16 {
        let place = TileGrid {
            columns: 4,
            rows: 4,
        }
        .tile(index, (w, h))
        .unwrap();
        for grow in [0, margin] {
            let grown = place.grown(grow);
            let mut frame = Frame::new(grown.width, grown.height);
            renderer(scene.camera.window(grown).unwrap()).render(&mut frame);
            let Window {
                x,
                y,
                width,
                height,
            } = place.window;
            let differing = (y..y + height)
                .flat_map(|py| (x..x + width).map(move |px| (px, py)))
                .filter(|&(px, py)| {
                    let inside = ((py - grown.y) * grown.width + (px - grown.x)) as usize;
                    frame.pixels[inside] != whole.pixels[(py * w + px) as usize]
                })
                .count();
            if grow == margin {
                assert_eq!(differing, 0, "tile {index} with its margin");
            } else {
                differ_without += differing;
            }
        }
    }
    assert!(
        differ_without > 0,
        "no pixel near a tile's edge depends on the next tile"
    );
}
