//! How the viewer shows a map read from a tile store: first from its preview, made of the
//! mipmap levels held in memory, and on more threads than cores, so that walks waiting on the
//! disk leave them to others.

use crate::heightfield::{store, Preview};
use crate::render::effects::Effects;
use crate::render::{Camera, Culling, Lighting, Renderer, Shader};
use crate::{Arith, Method, Terrain};
use std::sync::OnceLock;

/// A renderer of `camera`'s view (world coordinates) of a map's `preview`: lit with `lighting`
/// (fog and the floor's depth scaled with the preview), the sun's hard shadow and no other
/// effect.
pub fn preview_renderer(
    preview: &Preview,
    camera: Camera,
    mut lighting: Lighting,
    method: Method,
) -> Renderer<'_> {
    let scale = preview.world_from_grid[2];
    lighting.effects = Effects {
        sun_angle_deg: 0.0,
        sky_light: false,
        samples: 1,
        water: None,
        ..lighting.effects
    };
    lighting.fog *= scale;
    lighting.base.depth = lighting.base.depth.map(|d| d / scale);
    Renderer {
        shader: Shader::new(&preview.terrain, lighting, method, Culling::default()),
        camera: camera.in_grid(Some(preview.world_from_grid)),
        arith: Arith::F64,
    }
}

/// The threads that trace `terrain` where it is mapped from a tile store (made once): more
/// than the cores (see [`store::threads`]).
pub fn store_pool(terrain: &Terrain) -> Option<&'static rayon::ThreadPool> {
    static POOL: OnceLock<Option<rayon::ThreadPool>> = OnceLock::new();
    if !terrain.field().is_mapped() {
        return None;
    }
    let pool = || {
        rayon::ThreadPoolBuilder::new()
            .num_threads(store::threads())
            .thread_name(|k| format!("heightray-store-{k}"))
            .build()
            .ok()
    };
    POOL.get_or_init(pool).as_ref()
}
