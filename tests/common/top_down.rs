//! A render looking straight down with the light from straight above, no ambient and no
//! shadows: every pixel over the terrain shows its height's ramp colour at full light.

use heightray::render::effects::Effects;
use heightray::render::{Camera, Culling, Frame, Lighting, Normals, Ramp, Renderer, Shader};
use heightray::{Arith, Method, Terrain};

/// A 16x16 frame of `terrain` seen from `(4, 4, eye_height)` with a vertical field of view of
/// `fov_y_deg`, coloured by `ramp`.
pub fn render_top_down(terrain: &Terrain, ramp: Ramp, eye_height: f64, fov_y_deg: f64) -> Frame {
    let lighting = overhead_light(ramp);
    let camera = Camera::look_at(
        [4.0, 4.0, eye_height],
        [4.0, 4.0, 0.0],
        [0.0, 1.0, 0.0],
        fov_y_deg,
        (16, 16),
    )
    .expect("a valid camera");
    let renderer = Renderer {
        shader: Shader::new(terrain, lighting, Method::Runs, Culling::default()),
        camera,
        arith: Arith::F64,
    };
    let mut frame = Frame::new(16, 16);
    renderer.render(&mut frame);
    frame
}

/// The sun straight above, no ambient light, no shadows, flat normals: a flat surface shows its
/// height's `ramp` colour at full light.
pub fn overhead_light(ramp: Ramp) -> Lighting {
    Lighting {
        sun: [0.0, 0.0, 1.0],
        intensity: 1.0,
        ambient: 0.0,
        shadows: false,
        fog: 0.0,
        normals: Normals::Flat,
        ramp,
        effects: Effects::default(),
        base: heightray::render::BaseStyle::default(),
    }
}
