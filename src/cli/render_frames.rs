//! `heightray render SCENE --frames SPEC -o DIR/`: a flythrough's frames as
//! `DIR/frame-00042.png`, each written whole or not at all. A frame whose file already holds a
//! whole image of the right size is skipped (an interrupted run resumes; `--force` renders it
//! again), and `--frame-of I/N` takes every N-th frame from the I-th: what a scheduler's task
//! runs.

use super::render::Setup;
use super::render_progress::Progress;
use super::RenderArgs;
use heightray::batch::{frame_file, Share};
use heightray::output_file;
use heightray::render::{Frame, Window};
use std::path::Path;
use std::process::ExitCode;

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    let Some(spec) = args.frames else {
        anyhow::bail!("--frames is needed to render frames");
    };
    let folder = &args.output;
    output_folder(folder)?;
    let setup = Setup::new(args)?;
    let Some(animation) = &setup.animation else {
        anyhow::bail!(
            "{} has no [animation] to take frames from; add one (README, 'Flythroughs and \
             posters'), or leave out --frames to render the scene's still",
            args.scene.display()
        );
    };
    let frames = spec
        .frames(animation.frames())
        .map_err(anyhow::Error::msg)?;
    let share = args.frame_of.unwrap_or(Share::ALL);
    let mine = share.of(&frames);
    let size = setup.camera.size();
    let (width, height) = size;
    let to_do: Vec<u64> = mine
        .iter()
        .copied()
        .filter(|&k| args.force || !is_whole_image(&frame_file(folder, k), size))
        .collect();
    eprintln!(
        "frames {spec} of {} ({} frames at {} fps), share {share}: {} frames, {} already \
         written, {} to render at {width}x{height}",
        args.scene.display(),
        animation.frames(),
        animation.fps(),
        mine.len(),
        mine.len() - to_do.len(),
        to_do.len()
    );
    let progress = Progress::new(to_do.len() as u64 * u64::from(width) * u64::from(height));
    for &k in &to_do {
        let path = frame_file(folder, k);
        let camera = animation
            .camera(k, &setup.terrain, size)
            .map_err(|e| anyhow::anyhow!("frame {k}: the camera: {e}"))?;
        let renderer = setup.renderer(camera);
        let mut frame = Frame::new(width, height);
        setup
            .pool
            .install(|| progress.render(&renderer, &mut frame));
        let whole = Window {
            x: 0,
            y: 0,
            width,
            height,
        };
        setup.annotate(camera, &mut frame.pixels, whole)?;
        output_file::save_rgb(&path, &frame.pixels, size).map_err(anyhow::Error::msg)?;
        progress.finished(&path.display().to_string());
    }
    progress.done();
    Ok(ExitCode::SUCCESS)
}

/// Makes the output folder if it is missing; refuses a file.
pub fn output_folder(folder: &Path) -> anyhow::Result<()> {
    if folder.exists() && !folder.is_dir() {
        anyhow::bail!(
            "-o {}: frames and tiles go into a folder, and this is a file; give a folder \
             such as frames/",
            folder.display()
        );
    }
    std::fs::create_dir_all(folder)
        .map_err(|e| anyhow::anyhow!("cannot make the folder {}: {e}", folder.display()))
}

/// Whether `path` holds a whole image of `size` (a file cut short by a crash or a full disk
/// does not decode, and is rendered again).
pub fn is_whole_image(path: &Path, size: (u32, u32)) -> bool {
    image::ImageReader::open(path)
        .ok()
        .and_then(|reader| reader.decode().ok())
        .is_some_and(|image| (image.width(), image.height()) == size)
}
