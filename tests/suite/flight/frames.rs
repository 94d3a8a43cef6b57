//! Frames of a flythrough: the same bytes whether rendered alone, in a range or in a share, on
//! one thread or two; seeded per frame; an interrupted run resumes, replacing a cut-off file.

use super::{arg, heightray, orbit_scene, run};
use std::os::unix::fs::MetadataExt;
use std::path::Path;

/// The bytes of frame `k` in `folder`.
fn frame(folder: &Path, k: u64) -> Vec<u8> {
    std::fs::read(folder.join(format!("frame-{k:05}.png"))).expect("the frame")
}

#[test]
fn a_frame_is_the_same_alone_in_a_range_and_in_a_share() {
    let dir = tempfile::tempdir().unwrap();
    // Adaptive samples and soft shadows: every seeded choice a frame makes.
    let scene = orbit_scene(
        dir.path(),
        "[render]\nsamples = 8\nadaptive = true\n[sun]\nangle_deg = 2.0\n",
    );
    let (range, alone, shares) = (
        dir.path().join("range"),
        dir.path().join("alone"),
        dir.path().join("shares"),
    );
    heightray(&[
        "render",
        arg(&scene),
        "--frames",
        "0..12",
        "-o",
        arg(&range),
        "--threads",
        "2",
    ]);
    heightray(&[
        "render",
        arg(&scene),
        "--frames",
        "5",
        "-o",
        arg(&alone),
        "--threads",
        "1",
    ]);
    for k in 0..3 {
        let share = format!("{k}/3");
        heightray(&[
            "render",
            arg(&scene),
            "--frames",
            "all",
            "--frame-of",
            &share,
            "-o",
            arg(&shares),
            "--threads",
            "1",
        ]);
    }
    assert_eq!(frame(&alone, 5), frame(&range, 5));
    for k in 0..12 {
        assert_eq!(frame(&shares, k), frame(&range, k), "frame {k}");
    }
    assert_eq!(std::fs::read_dir(&alone).unwrap().count(), 1);
    assert_ne!(frame(&range, 0), frame(&range, 5), "the camera turns");
}

#[test]
fn samples_are_seeded_per_frame_and_frame_zero_is_the_still() {
    let dir = tempfile::tempdir().unwrap();
    // Two keys of one view: every frame has the same camera, and differs only by its seed.
    let scene = dir.path().join("still.toml");
    heightray(&[
        "generate",
        "--size",
        "33",
        "--seed",
        "5",
        "-o",
        arg(&dir.path().join("map.png")),
    ]);
    let view = "eye = [-10.0, -12.0, 20.0]\ntarget = [16.0, 16.0, 2.0]\n";
    std::fs::write(
        &scene,
        format!(
            "[heightmap]\npath = \"map.png\"\nz_scale = 8.0\n[camera]\n{view}width = 48\n\
             height = 32\n[render]\nsamples = 4\n[animation]\nfps = 10\n\
             [[animation.key]]\ntime_s = 0.0\n{view}[[animation.key]]\ntime_s = 1.0\n{view}"
        ),
    )
    .unwrap();
    let frames = dir.path().join("frames");
    heightray(&[
        "render",
        arg(&scene),
        "--frames",
        "0..3",
        "-o",
        arg(&frames),
    ]);
    let still = dir.path().join("still.png");
    heightray(&["render", arg(&scene), "-o", arg(&still)]);
    let pixels = |bytes: &[u8]| image::load_from_memory(bytes).unwrap().to_rgb8();
    assert_eq!(
        pixels(&frame(&frames, 0)),
        image::open(&still).unwrap().to_rgb8()
    );
    assert_ne!(pixels(&frame(&frames, 0)), pixels(&frame(&frames, 1)));
    assert_ne!(pixels(&frame(&frames, 1)), pixels(&frame(&frames, 2)));
}

#[test]
fn an_interrupted_run_resumes_and_replaces_a_cut_off_frame() {
    let dir = tempfile::tempdir().unwrap();
    let scene = orbit_scene(dir.path(), "");
    let out = dir.path().join("out");
    heightray(&["render", arg(&scene), "--frames", "0..6", "-o", arg(&out)]);
    let first: Vec<Vec<u8>> = (0..6).map(|k| frame(&out, k)).collect();
    let path = |k: u64| out.join(format!("frame-{k:05}.png"));
    let inode = |k: u64| std::fs::metadata(path(k)).unwrap().ino();
    let inodes: Vec<u64> = (0..6).map(inode).collect();
    // Frame 2 cut off half way, frame 4 never written.
    std::fs::write(path(2), &first[2][..first[2].len() / 2]).unwrap();
    std::fs::remove_file(path(4)).unwrap();
    let resumed = heightray(&["render", arg(&scene), "--frames", "0..6", "-o", arg(&out)]);
    let said = String::from_utf8_lossy(&resumed.stderr);
    assert!(said.contains("4 already written, 2 to render"), "{said}");
    for k in 0..6 {
        assert_eq!(frame(&out, k), first[k as usize], "frame {k}");
        if ![2, 4].contains(&k) {
            assert_eq!(inode(k), inodes[k as usize], "frame {k} was written again");
        }
    }
    heightray(&[
        "render",
        arg(&scene),
        "--frames",
        "0..6",
        "-o",
        arg(&out),
        "--force",
    ]);
    assert_ne!(inode(0), inodes[0], "--force renders again");
    assert_eq!(frame(&out, 0), first[0]);
    // Nothing but the frames is left in the folder.
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 6);
}

#[test]
fn frames_that_cannot_be_rendered_say_why() {
    let dir = tempfile::tempdir().unwrap();
    let scene = orbit_scene(dir.path(), "");
    let out = dir.path().join("out");
    let cases: [(&[&str], &str); 4] = [
        (&["--frames", "10..20"], "0..12"),
        (&["--frames", "3..1"], "after the start"),
        (&["--frames", "0..4", "--frame-of", "4/4"], "I/N"),
        (&["--frame-of", "0/2"], "--frames"),
    ];
    for (args, said) in cases {
        let mut all = vec!["render", arg(&scene), "-o", arg(&out)];
        all.extend_from_slice(args);
        let output = run(&all);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success() && stderr.contains(said),
            "{args:?}: {stderr}"
        );
    }
    let plain = dir.path().join("plain.toml");
    std::fs::write(&plain, "[heightmap]\npath = \"map.png\"\n").unwrap();
    let output = run(&["render", arg(&plain), "--frames", "0", "-o", arg(&out)]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains("no [animation]"),
        "{stderr}"
    );
}
