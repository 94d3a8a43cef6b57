//! A view rendered in several arithmetics against its exact render: how many pixels each
//! colours otherwise, and how long each frame takes (the fastest of repeated renders). The
//! accuracy benchmark and the viewer's accuracy panel both measure with it.

use super::timing::{fastest_cancellable, timed, TIMING_BUDGET};
use super::{Camera, Culling, Frame, Lighting, Renderer, Shader};
use crate::arith::Arith;
use crate::traverse::Method;
use crate::Terrain;
use std::time::Duration;

/// A scene rendered in one method and arithmetic, against the exact render.
#[derive(Clone, Debug)]
pub struct PixelRow {
    /// The traversal method.
    pub method: Method,
    /// The arithmetic rendered in.
    pub arith: Arith,
    /// Pixels whose colour differs from the exact render's.
    pub differing: u64,
    /// The largest difference of a colour channel from the exact render's, in display bytes.
    pub largest_difference: u8,
    /// Pixels in the frame.
    pub pixels: u64,
    /// Wall time of the frame (all threads of the pool), the fastest of its renders.
    pub time: Duration,
}

/// What a view shows: the terrain through a camera, lit, walked with one method.
#[derive(Clone, Copy)]
pub struct View<'a> {
    /// The terrain seen.
    pub terrain: &'a Terrain,
    /// The camera it is seen through.
    pub camera: Camera,
    /// The sun, shading and effects.
    pub lighting: Lighting,
    /// The traversal method.
    pub method: Method,
}

/// Renders `view` exactly, then in each arithmetic (on the current rayon pool), and counts the
/// pixels that differ from the exact render. Each render's row goes to `rendered` as soon as
/// it is done, the exact reference first (for a caller showing progress or a growing table).
/// `cancelled` is asked between bands of rows; once it says yes, the result is None.
pub fn view_pixel_differences(
    view: &View<'_>,
    ariths: &[Arith],
    cancelled: &(dyn Fn() -> bool + Sync),
    rendered: &mut dyn FnMut(&PixelRow),
) -> Option<Vec<PixelRow>> {
    let render = |arith| {
        let renderer = Renderer {
            shader: Shader::new(view.terrain, view.lighting, view.method, Culling::default()),
            camera: view.camera.in_grid(view.terrain.world_from_grid()),
            arith,
        };
        let (w, h) = view.camera.size();
        let measured = fastest_cancellable(TIMING_BUDGET, || {
            let mut frame = Frame::new(w, h);
            let (complete, time) = timed(|| renderer.render_cancellable(&mut frame, cancelled));
            complete.then_some((frame.pixels, time))
        })?;
        Some((measured.out, measured.fastest))
    };
    let row = |arith, pixels: &[u32], exact: &[u32], time| PixelRow {
        method: view.method,
        arith,
        differing: differing_pixels(pixels, exact).count() as u64,
        largest_difference: largest_difference(pixels, exact),
        pixels: pixels.len() as u64,
        time,
    };
    let (exact, exact_time) = render(Arith::Exact)?;
    rendered(&row(Arith::Exact, &exact, &exact, exact_time));
    let mut rows = Vec::new();
    for &arith in ariths {
        let measured = if arith == Arith::Exact {
            row(arith, &exact, &exact, exact_time)
        } else {
            let (pixels, time) = render(arith)?;
            row(arith, &pixels, &exact, time)
        };
        rendered(&measured);
        rows.push(measured);
    }
    Some(rows)
}

/// Indices of the pixels whose colour differs between two renders of one view.
pub fn differing_pixels<'a>(
    pixels: &'a [u32],
    exact: &'a [u32],
) -> impl Iterator<Item = usize> + 'a {
    pixels
        .iter()
        .zip(exact)
        .enumerate()
        .filter(|(_, (a, b))| a != b)
        .map(|(k, _)| k)
}

/// The largest difference of a colour channel between two renders of one view, in display
/// bytes (0 where they are equal).
pub fn largest_difference(pixels: &[u32], exact: &[u32]) -> u8 {
    let channels = |rgb: u32| [16, 8, 0].map(|shift| (rgb >> shift) as u8);
    let pairs = pixels.iter().zip(exact);
    let per_pixel = pairs.flat_map(|(&a, &b)| channels(a).into_iter().zip(channels(b)));
    per_pixel.map(|(a, b)| a.abs_diff(b)).max().unwrap_or(0)
}
