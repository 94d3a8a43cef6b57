//! Embree's packet API: `rtcIntersect8` or `rtcIntersect16` for the camera rays of a tile of
//! 4x2 or 4x4 pixels, and `rtcOccluded8` or `rtcOccluded16` for shadow rays 8 or 16 at a
//! time, gathered in the order of the tiles from a band of them, all in a context for coherent
//! rays. Lanes past the frame's edge or past a band's last shadow ray are masked off.

use super::ffi::{self, Packet, RayHitN, RayN, Valid, Width};
use super::pixel::{render_in_bands, Pixel};
use super::{EmbreeHit, EmbreeScene};
use crate::render::{Frame, Renderer};
use crate::Ray;

/// Pixels across a tile of camera rays; a packet of `N` rays is `N / 4` rows of them.
const TILE_WIDTH: u32 = 4;

impl EmbreeScene {
    /// The first hits of up to `N` rays, traced as one packet (lanes past `rays` are masked
    /// off and answer `None`).
    pub(super) fn intersect_packet<const N: usize>(&self, rays: &[Ray]) -> [Option<EmbreeHit>; N]
    where
        Width<N>: Packet<N>,
    {
        let (valid, ray) = packet::<N>(rays.iter().map(|r| r.origin()), |k| rays[k].dir());
        let hit = ffi::HitN {
            ng: [[0.0; N]; 3],
            u: [0.0; N],
            v: [0.0; N],
            prim_id: [0; N],
            geom_id: [ffi::INVALID_GEOMETRY_ID; N],
            inst_id: [[ffi::INVALID_GEOMETRY_ID; N]],
        };
        let mut query = RayHitN { ray, hit };
        let mut context = ffi::IntersectContext::coherent();
        // SAFETY: a committed scene; the mask and packet are aligned as the call needs and
        // live through it.
        unsafe { Width::<N>::intersect(&valid, self.scene, &mut context, &mut query) };
        let (out, hit) = (&query.ray, &query.hit);
        let mut hits = [None; N];
        for (k, ray) in rays.iter().enumerate() {
            let ng = [hit.ng[0][k], hit.ng[1][k], hit.ng[2][k]];
            hits[k] = self.hit(ray, hit.geom_id[k], hit.prim_id[k], out.tfar[k], ng);
        }
        hits
    }

    /// Whether anything lies on each of up to `N` rays from `starts` towards `dir`, traced as
    /// one packet (lanes past `starts` are masked off and answer `false`).
    pub(super) fn occluded_packet<const N: usize>(
        &self,
        starts: &[[f64; 3]],
        dir: [f64; 3],
    ) -> [bool; N]
    where
        Width<N>: Packet<N>,
    {
        let (valid, mut ray) = packet::<N>(starts.iter().copied(), |_| dir);
        let mut context = ffi::IntersectContext::coherent();
        // SAFETY: as in `intersect_packet`.
        unsafe { Width::<N>::occluded(&valid, self.scene, &mut context, &mut ray) };
        let mut blocked = [false; N];
        for (k, blocked) in blocked.iter_mut().enumerate().take(starts.len()) {
            // Embree marks an occluded ray by setting its far end to minus infinity.
            *blocked = ray.tfar[k] < 0.0;
        }
        blocked
    }

    /// Renders `renderer`'s view into `frame` (every pixel, on the current rayon pool) as
    /// [`EmbreeScene::render`] does, its rays traced `N` at a time.
    pub(super) fn render_packets<const N: usize>(&self, renderer: &Renderer<'_>, frame: &mut Frame)
    where
        Width<N>: Packet<N>,
    {
        let shader = &renderer.shader;
        let rows = N as u32 / TILE_WIDTH;
        let (width, height) = (frame.width, frame.height);
        render_in_bands(frame, rows, |y0, put| {
            let y1 = (y0 + rows).min(height);
            let mut pixels = Vec::with_capacity((width * rows) as usize);
            let (mut lanes, mut rays) = (Vec::with_capacity(N), Vec::with_capacity(N));
            for x0 in (0..width).step_by(TILE_WIDTH as usize) {
                lanes.clear();
                rays.clear();
                for y in y0..y1 {
                    for x in x0..(x0 + TILE_WIDTH).min(width) {
                        lanes.push((x, y));
                        rays.push(renderer.camera.ray(x, y));
                    }
                }
                let hits = self.intersect_packet::<N>(&rays);
                for ((&(x, y), &ray), hit) in lanes.iter().zip(&rays).zip(hits) {
                    pixels.push((x, y, Pixel::new(shader, ray, hit)));
                }
            }
            let casting: Vec<(usize, [f64; 3])> = (pixels.iter().enumerate())
                .filter_map(|(k, (_, _, pixel))| Some((k, pixel.shadow_start()?)))
                .collect();
            let mut shadowed = vec![false; pixels.len()];
            let mut starts = Vec::with_capacity(N);
            for packet in casting.chunks(N) {
                starts.clear();
                starts.extend(packet.iter().map(|&(_, start)| start));
                let blocked = self.occluded_packet::<N>(&starts, shader.lighting.sun);
                for (&(k, _), blocked) in packet.iter().zip(blocked) {
                    shadowed[k] = blocked;
                }
            }
            for ((x, y, pixel), shadowed) in pixels.iter().zip(shadowed) {
                put(*x, *y, pixel.sample(shader, shadowed));
            }
        });
    }
}

/// A packet of up to `N` rays from `origins`, ray `k` along `dir(k)`, with the mask of its
/// lanes in use.
fn packet<const N: usize>(
    origins: impl ExactSizeIterator<Item = [f64; 3]>,
    dir: impl Fn(usize) -> [f64; 3],
) -> (Valid<N>, RayN<N>) {
    assert!(
        origins.len() <= N,
        "{} rays for a packet of {N}",
        origins.len()
    );
    let mut valid = Valid([0; N]);
    let mut ray = RayN {
        org: [[0.0; N]; 3],
        tnear: [0.0; N],
        dir: [[0.0; N]; 3],
        time: [0.0; N],
        tfar: [f32::INFINITY; N],
        mask: [u32::MAX; N],
        id: [0; N],
        flags: [0; N],
    };
    for (k, origin) in origins.enumerate() {
        let dir = dir(k);
        valid.0[k] = -1;
        for axis in 0..3 {
            ray.org[axis][k] = origin[axis] as f32;
            ray.dir[axis][k] = dir[axis] as f32;
        }
    }
    (valid, ray)
}
