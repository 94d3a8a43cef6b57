//! `heightray generate`: the built-in terrain generator as a PNG file.

use super::GenerateArgs;
use anyhow::Context;
use heightray::heightfield::landscape;
use image::{ImageBuffer, Luma};
use std::process::ExitCode;

pub fn run(args: &GenerateArgs) -> anyhow::Result<ExitCode> {
    let field = landscape(args.size, args.seed, 1.0)?;
    let (w, h) = (field.width(), field.height());
    // Image row 0 is the northern edge (y = H-1).
    let image = ImageBuffer::from_fn(w as u32, h as u32, |x, r| {
        Luma([field.sample(x as usize, h - 1 - r as usize)])
    });
    image
        .save(&args.output)
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    Ok(ExitCode::SUCCESS)
}
