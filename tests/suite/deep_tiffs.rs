//! `heightray render ... -o out.tif --depth 16`: the TIFF is made from the renderer's linear
//! colours, not from the picture's bytes, so a smooth gradient takes far more than 256 levels
//! a channel; rounded to bytes it is the 8-bit PNG of the same render within a level (one or
//! several samples a pixel, adaptive or not, annotations drawn over it too), with the
//! resolution asked for; the `tiff` crate and GDAL read 16-bit RGB. The same holds of the
//! shaded ortho product. Tiles and frames, which are PNGs, refuse `--depth`.

use crate::products_cli::{dem, gdal_info, gdal_present, heightray, render};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use tiff::decoder::{Decoder, DecodingResult};
use tiff::tags::Tag;

/// The scene with annotations, contours and place labels shipped in `assets/`.
fn poster() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/jacksboro_poster.toml")
}

/// The 16-bit RGB samples of the TIFF at `path`, checked to be 16-bit RGB.
fn words(path: &Path) -> Vec<u16> {
    let mut decoder = Decoder::new(std::fs::File::open(path).unwrap()).unwrap();
    assert_eq!(decoder.colortype().unwrap(), tiff::ColorType::RGB(16));
    let DecodingResult::U16(words) = decoder.read_image().unwrap() else {
        panic!("{}: 16-bit samples", path.display());
    };
    words
}

/// Renders `scene` with `more` arguments to a PNG and to a 16-bit TIFF in `dir`; their
/// samples, the TIFF's as words.
fn both(dir: &Path, name: &str, scene: &Path, more: &[&str]) -> (Vec<u8>, Vec<u16>) {
    let (png, tif) = (
        dir.join(format!("{name}.png")),
        dir.join(format!("{name}.tif")),
    );
    let scene = scene.to_str().unwrap();
    let mut args = vec![scene, "-o", png.to_str().unwrap()];
    args.extend(more);
    render(&args);
    args[2] = tif.to_str().unwrap();
    args.extend(["--depth", "16"]);
    render(&args);
    let picture = image::open(&png).unwrap().to_rgb8().into_raw();
    (picture, words(&tif))
}

/// Asserts that `words` rounded to bytes are `bytes` within one level, sample by sample.
fn rounds_to(words: &[u16], bytes: &[u8], what: &str) {
    assert_eq!(words.len(), bytes.len(), "{what}");
    let worst = words
        .iter()
        .zip(bytes)
        .map(|(&w, &b)| ((u32::from(w) + 128) / 257).abs_diff(u32::from(b)))
        .max();
    assert!(worst <= Some(1), "{what}: {worst:?} levels apart");
}

/// The distinct values of channel `k` of RGB samples.
fn levels<T: Copy + Ord>(samples: &[T], k: usize) -> usize {
    let distinct: BTreeSet<T> = samples.iter().skip(k).step_by(3).copied().collect();
    distinct.len()
}

#[test]
fn a_sixteen_bit_render_has_far_more_levels_and_rounds_to_the_png() {
    let dir = tempfile::tempdir().unwrap();
    let dem = dem(dir.path(), 1);
    // Tall: the sky's gradient and the hill's shading run over hundreds of rows.
    let size = ["--size", "48x600"];
    let (bytes, words) = both(dir.path(), "one", &dem, &size);
    rounds_to(&words, &bytes, "one sample a pixel");
    for k in 0..3 {
        let (narrow, wide) = (levels(&bytes, k), levels(&words, k));
        assert!(
            wide > 256 && wide > 4 * narrow,
            "channel {k}: {wide} levels at 16 bits, {narrow} at 8"
        );
    }
    assert!(words.iter().any(|&w| w % 257 != 0), "finer than bytes");
    // Several samples a pixel, every pixel all of them or adaptively: the words are the mean
    // of the samples' linear colours, the bytes the mean of their bytes'.
    let samples = ["--size", "48x60", "--samples", "4"];
    let (bytes, words) = both(dir.path(), "four", &dem, &samples);
    rounds_to(&words, &bytes, "four samples");
    let adaptive = ["--size", "48x60", "--samples", "4", "--adaptive"];
    let (bytes, words) = both(dir.path(), "adaptive", &dem, &adaptive);
    rounds_to(&words, &bytes, "adaptive samples");
    // Walked in packets: the same picture.
    let packets = ["--size", "48x60", "--packets", "on"];
    let (bytes, words) = both(dir.path(), "packets", &dem, &packets);
    rounds_to(&words, &bytes, "packets");
}

#[test]
fn annotations_are_drawn_into_the_sixteen_bit_picture() {
    let dir = tempfile::tempdir().unwrap();
    let size = ["--size", "480x270"];
    let (bytes, words) = both(dir.path(), "poster", &poster(), &size);
    // Within a level everywhere, the title, legend, scale bar and labels included.
    rounds_to(&words, &bytes, "the poster");
    // The same scene without its annotations and vector layers: the marks are where the two
    // pictures differ, and there are many.
    let text = std::fs::read_to_string(poster()).unwrap();
    let assets = poster().parent().unwrap().display().to_string();
    let bare = text[..text.find("[annotations]").unwrap()]
        .replace("\"jacksboro.tif\"", &format!("\"{assets}/jacksboro.tif\""));
    let scene = dir.path().join("bare.toml");
    std::fs::write(&scene, bare).unwrap();
    let png = dir.path().join("bare.png");
    render(&[
        scene.to_str().unwrap(),
        "--size",
        "480x270",
        "-o",
        png.to_str().unwrap(),
    ]);
    let unmarked = image::open(&png).unwrap().to_rgb8().into_raw();
    let marks = unmarked.iter().zip(&bytes).filter(|(a, b)| a != b).count();
    assert!(marks > 1000, "{marks} samples marked");
}

#[test]
fn sixteen_bit_tiffs_are_rgb_with_the_resolution_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    let dem = dem(dir.path(), 1);
    let tif = dir.path().join("view.tif");
    let (d, t) = (dem.to_str().unwrap(), tif.to_str().unwrap());
    render(&[
        d, "--size", "40x30", "-o", t, "--depth", "16", "--dpi", "300",
    ]);
    let mut decoder = Decoder::new(std::fs::File::open(&tif).unwrap()).unwrap();
    assert_eq!(decoder.colortype().unwrap(), tiff::ColorType::RGB(16));
    assert_eq!(decoder.dimensions().unwrap(), (40, 30));
    assert_eq!(decoder.get_tag_u32_vec(Tag::XResolution).unwrap(), [300, 1]);
    assert_eq!(decoder.get_tag_u32_vec(Tag::YResolution).unwrap(), [300, 1]);
    assert_eq!(
        decoder.get_tag_u32(Tag::ResolutionUnit).unwrap(),
        2,
        "inches"
    );
    if !gdal_present() {
        return;
    }
    let info = gdal_info(&tif);
    assert_eq!(info["size"], serde_json::json!([40, 30]));
    let bands = info["bands"].as_array().unwrap();
    assert_eq!(bands.len(), 3, "RGB, no alpha");
    for (band, colour) in bands.iter().zip(["Red", "Green", "Blue"]) {
        assert_eq!(band["type"], "UInt16");
        assert_eq!(band["colorInterpretation"], colour);
    }
}

#[test]
fn the_shaded_product_at_sixteen_bits_rounds_to_its_eight_bit_twin() {
    let dir = tempfile::tempdir().unwrap();
    let dem = dem(dir.path(), 1);
    let d = dem.to_str().unwrap();
    let (shaded8, shaded16) = (dir.path().join("s8.tif"), dir.path().join("s16.tif"));
    render(&[d, "--ortho", "-o", shaded8.to_str().unwrap()]);
    render(&[
        d,
        "--ortho",
        "-o",
        shaded16.to_str().unwrap(),
        "--depth",
        "16",
    ]);
    let read = |path: &Path| {
        Decoder::new(std::fs::File::open(path).unwrap())
            .unwrap()
            .read_image()
            .unwrap()
    };
    let (DecodingResult::U8(narrow), DecodingResult::U16(wide)) = (read(&shaded8), read(&shaded16))
    else {
        panic!("8- and 16-bit samples");
    };
    // RGBA: the rays' own colours at 16 bits, their bytes' at 8; the coverage the same.
    rounds_to(&wide, &narrow, "shaded relief");
    let coverage = |k: usize| (u32::from(wide[k]) + 128) / 257 == u32::from(narrow[k]);
    assert!(
        (3..wide.len()).step_by(4).all(coverage),
        "the same coverage"
    );
    assert!(wide.iter().any(|&c| c % 257 != 0), "finer than bytes");
}

#[test]
fn tiles_and_frames_refuse_a_depth() {
    let dir = tempfile::tempdir().unwrap();
    let dem = dem(dir.path(), 1);
    let (d, out) = (dem.to_str().unwrap(), dir.path().join("out.tif"));
    let o = out.to_str().unwrap();
    let cases: [&[&str]; 3] = [
        &[d, "--tiles", "2x2", "--tile", "0", "-o", o, "--depth", "16"],
        &[d, "--tiles", "2x2", "-o", o, "--dpi", "300"],
        &[d, "--frames", "all", "-o", o, "--depth", "16"],
    ];
    for args in cases {
        let output = heightray(args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args:?} succeeded");
        assert!(stderr.contains("8-bit PNGs"), "{args:?}: {stderr}");
    }
    assert!(!out.exists());
}
