//! `heightray submit slurm` on a real Slurm cluster (`.ci/slurm-up` makes one of this machine):
//! a 12-frame, 4-task job array and the video job after it make every frame byte for byte as a
//! local render does, and the MP4; submitted again after frames are lost, the array renders
//! only those.

use super::video::probe;
use super::{arg, have_tool, heightray, orbit_scene};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// How long the jobs may take: far more than the seconds they take on an idle node.
const PATIENCE: Duration = Duration::from_secs(300);

#[test]
fn a_job_array_makes_the_frames_of_a_local_render_and_the_video() {
    let slurm = have_tool("sbatch", "HEIGHTRAY_REQUIRE_SLURM");
    if !(slurm && have_tool("ffmpeg", "HEIGHTRAY_REQUIRE_FFMPEG")) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let scene = orbit_scene(dir.path(), "[render]\nsamples = 4\n");
    let (out, local) = (dir.path().join("out"), dir.path().join("local"));
    let video = out.join("fly.mp4");
    heightray(&[
        "render",
        arg(&scene),
        "--frames",
        "0..12",
        "-o",
        arg(&local),
    ]);
    let submit = [
        "submit",
        "slurm",
        arg(&scene),
        "--frames",
        "0..12",
        "--tasks",
        "4",
        "-o",
        arg(&out),
        "--video",
        arg(&video),
        "--time",
        "00:05:00",
    ];
    let jobs = submitted(&heightray(&submit).stdout);
    wait_for(&jobs, &out);
    let frame = |folder: &Path, k: u64| std::fs::read(folder.join(format!("frame-{k:05}.png")));
    for k in 0..12 {
        assert_eq!(
            frame(&out, k).unwrap(),
            frame(&local, k).unwrap(),
            "frame {k}"
        );
    }
    let (count, rate, _) = probe(&video);
    assert_eq!((count, rate.as_str()), (12, "12/1"));

    // Two frames and the video lost: submitted again, the tasks render those two alone.
    for k in [3, 10] {
        std::fs::remove_file(out.join(format!("frame-{k:05}.png"))).unwrap();
    }
    std::fs::remove_file(&video).unwrap();
    let again = submitted(&heightray(&submit).stdout);
    wait_for(&again, &out);
    let rendered: u64 = (0..4)
        .map(|task| {
            let log = out.join(format!("slurm/render-{}_{task}.out", again[0]));
            let text = std::fs::read_to_string(&log).unwrap_or_default();
            let count = text
                .split(" to render")
                .next()
                .and_then(|s| s.rsplit(", ").next());
            count
                .and_then(|c| c.trim().parse::<u64>().ok())
                .unwrap_or_else(|| panic!("{text}"))
        })
        .sum();
    assert_eq!(rendered, 2);
    for k in 0..12 {
        assert_eq!(
            frame(&out, k).unwrap(),
            frame(&local, k).unwrap(),
            "frame {k}"
        );
    }
    assert_eq!(probe(&video).0, 12);
}

/// The job ids `submit slurm` printed: the array's, then the video job's.
fn submitted(stdout: &[u8]) -> Vec<String> {
    let text = String::from_utf8_lossy(stdout);
    let ids: Vec<String> = text
        .lines()
        .filter_map(|l| {
            l.strip_prefix("submitted job array ")
                .or(l.strip_prefix("submitted job "))
        })
        .filter_map(|rest| rest.split_whitespace().next().map(str::to_owned))
        .collect();
    assert_eq!(ids.len(), 2, "{text}");
    ids
}

/// Waits until none of `jobs` is queued or running; fails with the jobs' logs if they take
/// longer than [`PATIENCE`] or a job waits on one that failed.
fn wait_for(jobs: &[String], out: &Path) {
    let list = jobs.join(",");
    let start = Instant::now();
    loop {
        let queue = Command::new("squeue")
            .args(["-h", "-o", "%i %T %r", "-j", &list])
            .output()
            .expect("run squeue");
        let text = String::from_utf8_lossy(&queue.stdout).into_owned();
        // (squeue refuses ids it has forgotten: those jobs have long ended.)
        if text.trim().is_empty() {
            return;
        }
        let stuck = text.contains("DependencyNeverSatisfied");
        if stuck || start.elapsed() > PATIENCE {
            let _ = Command::new("scancel").args(jobs).status();
            panic!("the jobs did not finish: {text}\n{}", logs(out));
        }
        std::thread::sleep(Duration::from_millis(500));
    }
}

/// Every log in `out/slurm`, for a failure's message.
fn logs(out: &Path) -> String {
    let Ok(entries) = std::fs::read_dir(out.join("slurm")) else {
        return "no logs".into();
    };
    entries
        .filter_map(|e| {
            let path = e.ok()?.path();
            let text = std::fs::read_to_string(&path).ok()?;
            Some(format!("--- {}\n{text}", path.display()))
        })
        .collect()
}
