//! `heightray video`: an MP4 that ffprobe reads as H.264 in yuv420p with every frame at the
//! rate asked; a gap in the frames is named.

use super::{arg, have_tool, heightray, orbit_scene, run};

#[test]
fn frames_become_an_mp4_with_their_count_and_rate() {
    if !have_tool("ffmpeg", "HEIGHTRAY_REQUIRE_FFMPEG") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let scene = orbit_scene(dir.path(), "");
    let frames = dir.path().join("frames");
    heightray(&[
        "render",
        arg(&scene),
        "--frames",
        "2..12",
        "-o",
        arg(&frames),
    ]);
    let video = dir.path().join("fly.mp4");
    heightray(&["video", arg(&frames), "-o", arg(&video), "--fps", "12"]);
    let (count, rate, format) = probe(&video);
    assert_eq!(
        (count, rate.as_str(), format.as_str()),
        (10, "12/1", "h264 yuv420p 64x48")
    );

    std::fs::remove_file(frames.join("frame-00006.png")).unwrap();
    let output = run(&["video", arg(&frames), "-o", arg(&video)]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains("frame 6 is missing"),
        "{stderr}"
    );
}

/// The frames counted in `video`'s first video stream, its rate, and its codec, pixel format
/// and size.
pub fn probe(video: &std::path::Path) -> (u64, String, String) {
    let output = std::process::Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args([
            "-show_entries",
            "stream=nb_read_frames,r_frame_rate,codec_name,pix_fmt,width,height",
        ])
        .args(["-of", "default=noprint_wrappers=1"])
        .arg(video)
        .output()
        .expect("run ffprobe");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8_lossy(&output.stdout).into_owned();
    let field = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(&format!("{key}=")))
            .unwrap_or_else(|| panic!("no {key} in {text}"))
            .to_owned()
    };
    let count = field("nb_read_frames").parse().expect("a frame count");
    let format = format!(
        "{} {} {}x{}",
        field("codec_name"),
        field("pix_fmt"),
        field("width"),
        field("height")
    );
    (count, field("r_frame_rate"), format)
}
