//! What each effect costs, and how several samples per pixel converge: frames of one scene
//! with each effect alone and all together, and images against a supersampled reference.

use crate::render::effects::{Around, Effects, Summary, Water};
use crate::render::{Culling, Frame, FrameStats, Renderer, Scene, Shader};
use crate::traverse::Method;
use crate::Terrain;
use std::time::{Duration, Instant};

/// One configuration's frame: its time and statistics.
#[derive(Clone, Debug)]
pub struct EffectRow {
    /// What the frame had ("plain", "soft shadows", ...).
    pub label: String,
    /// The effects it had.
    pub effects: Effects,
    /// Time of the faster of two frames one after the other (steady state, as the viewer
    /// renders).
    pub time: Duration,
    /// Time of the first, which makes what is kept across frames as rays first ask for it
    /// (the sky's bounds, kept for the terrain's lifetime).
    pub first: Duration,
    /// Its statistics.
    pub totals: FrameStats,
    /// Its pixels.
    pub pixels: Vec<u32>,
}

impl EffectRow {
    /// Pixels of the frame.
    pub fn pixel_count(&self) -> f64 {
        self.totals.effects.samples.pixels.max(1) as f64
    }

    /// Each effect of the list as the frame counted it: its rays, and the share of the rays
    /// it could have cast that it left out.
    pub fn each_effect(&self) -> Vec<Summary> {
        let around = Around {
            asked: &self.effects,
            shadow_rays: self.totals.shadow_rays,
            settled: self.totals.skipped.settled(),
        };
        self.totals.effects.each(&around)
    }
}

/// The renderer of `scene` with `effects` (the scene's shadows, fog and shading).
pub fn renderer_with<'a>(scene: &Scene, terrain: &'a Terrain, effects: Effects) -> Renderer<'a> {
    let mut lighting = scene.lighting;
    lighting.effects = effects;
    Renderer {
        shader: Shader::new(terrain, lighting, Method::Mipmap, Culling::default()),
        camera: scene.camera,
        arith: scene.arith,
    }
}

/// Renders `scene` with `effects` (the scene's shadows, fog and shading) twice, timed (see
/// [`EffectRow::time`]).
pub fn frame_with(scene: &Scene, terrain: &Terrain, effects: Effects, label: &str) -> EffectRow {
    let renderer = renderer_with(scene, terrain, effects);
    let (w, h) = scene.camera.size();
    let timed = || {
        let mut frame = Frame::new(w, h);
        let start = Instant::now();
        renderer.render(&mut frame);
        (frame, start.elapsed())
    };
    let (_, first) = timed();
    let (frame, again) = timed();
    EffectRow {
        label: label.into(),
        effects,
        time: first.min(again),
        first,
        totals: frame.totals,
        pixels: frame.pixels,
    }
}

/// Each effect alone and all together, after the plain frame: soft shadows of a sun
/// `sun_angle_deg` wide, sky light, `samples` per pixel uniform and adaptive, and `water`.
pub fn configurations(
    base: Effects,
    sun_angle_deg: f64,
    samples: u32,
    water: Water,
) -> Vec<(String, Effects)> {
    let plain = Effects {
        sun_angle_deg: 0.0,
        sky_light: false,
        samples: 1,
        adaptive: false,
        water: None,
        ..base
    };
    let soft = Effects {
        sun_angle_deg,
        ..plain
    };
    let sky = Effects {
        sky_light: true,
        ..plain
    };
    let uniform = Effects { samples, ..plain };
    let adaptive = Effects {
        adaptive: true,
        ..uniform
    };
    let all = Effects {
        sun_angle_deg,
        sky_light: true,
        ..adaptive
    };
    vec![
        ("plain".into(), plain),
        (format!("soft shadows {sun_angle_deg} deg"), soft),
        ("sky light".into(), sky),
        (format!("{samples} samples"), uniform),
        (format!("{samples} samples adaptive"), adaptive),
        ("all (adaptive)".into(), all),
        (
            format!("water at {:.1}", water.level),
            Effects {
                water: Some(water),
                ..plain
            },
        ),
    ]
}

/// Linear light of 0x00RRGGBB pixels, by the display formula (`(byte / 255)^2.2`).
fn linear(rgb: u32) -> [f64; 3] {
    [16, 8, 0].map(|shift| (f64::from((rgb >> shift) as u8) / 255.0).powf(2.2))
}

/// A `factor` times larger frame's pixels averaged over blocks of `factor x factor`, in
/// linear light: the reference of a box filter.
pub fn block_average(pixels: &[u32], width: u32, factor: u32) -> Vec<[f64; 3]> {
    let (w, f) = (width as usize, factor as usize);
    let small_w = w / f;
    let small_h = pixels.len() / w / f;
    let mut out = vec![[0.0; 3]; small_w * small_h];
    for (k, &rgb) in pixels.iter().enumerate() {
        let (x, y) = (k % w / f, k / w / f);
        let l = linear(rgb);
        for c in 0..3 {
            out[y * small_w + x][c] += l[c] / (f * f) as f64;
        }
    }
    out
}

/// The root mean square difference of `pixels` from `reference` in linear light, over every
/// channel.
pub fn rms_error(pixels: &[u32], reference: &[[f64; 3]]) -> f64 {
    let sum: f64 = pixels
        .iter()
        .zip(reference)
        .map(|(&rgb, r)| {
            let l = linear(rgb);
            (0..3).map(|c| (l[c] - r[c]).powi(2)).sum::<f64>()
        })
        .sum();
    (sum / (3 * pixels.len()) as f64).sqrt()
}
