//! `heightray generate`: the built-in terrain generator as a PNG file.

use super::GenerateArgs;
use heightray::heightfield::landscape;
use heightray::output_file;
use image::{ImageBuffer, Luma};
use std::process::ExitCode;

pub fn run(args: &GenerateArgs) -> anyhow::Result<ExitCode> {
    let format = output_file::check_image(&args.output).map_err(anyhow::Error::msg)?;
    let field = landscape(args.size, args.seed, 1.0)?;
    let (w, h) = (field.width(), field.height());
    // Image row 0 is the northern edge (y = H-1).
    let image = ImageBuffer::from_fn(w as u32, h as u32, |x, r| {
        Luma([field.sample(x as usize, h - 1 - r as usize)])
    });
    output_file::write(&args.output, |out| {
        image
            .write_to(out, format)
            .map_err(|e| format!("cannot write {}: {e}", args.output.display()))
    })
    .map_err(anyhow::Error::msg)?;
    Ok(ExitCode::SUCCESS)
}
