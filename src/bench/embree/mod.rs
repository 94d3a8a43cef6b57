//! Embree 3, a general-purpose CPU ray tracer and the usual yardstick of CPU ray tracing
//! speed, on the same terrain and view as heightray, so `bench speed --embree` measures both
//! in one run on one machine (built with the `embree` feature, which links Debian's
//! `libembree3`).
//!
//! The terrain goes to Embree as what it is, two triangles per cell with heightray's diagonal
//! (the surface contract, [`crate::geometry`]), its corners the samples in `f32`. A frame does
//! what heightray's does: a ray per pixel through [`Camera::ray`](crate::render::Camera::ray),
//! Embree's single-ray `rtcIntersect1` (one ray at a time, as heightray traces them), the hit
//! shaded by heightray's [`Shader`](crate::render::Shader) from the hit's cell and triangle,
//! and a shadow ray (`rtcOccluded1`) where the surface faces the sun. So the two images can be
//! compared pixel by pixel, and the time differs only in the tracing.

mod ffi;
mod hard_cases;

pub use hard_cases::{hard_cases_in_f32, F32_TOLERANCE};

use crate::render::effects::{Reflection, SkyRays};
use crate::render::{Frame, FrameStats, PixelStats, Renderer, Sample, Shadow, ShadowSkip};
use crate::traverse::Counters;
use crate::{Heightfield, Ray, Terrain};
use glam::DVec3;
use rayon::prelude::*;
use std::ffi::c_void;
use std::sync::atomic::{AtomicIsize, Ordering};
use std::time::{Duration, Instant};
use thiserror::Error;

/// Why Embree's scene could not be made.
#[derive(Debug, Error)]
pub enum EmbreeError {
    /// An Embree call failed.
    #[error("Embree failed to {what} (RTCError {code})")]
    Call {
        /// What the call was to do.
        what: &'static str,
        /// Embree's `RTCError` code.
        code: u32,
    },
    /// The terrain (width and height in samples) is too large for the geometry: more triangles
    /// than a 32-bit primitive id counts, or a side longer than a grid primitive's.
    #[error("a {0}x{1} terrain is too large for Embree's {2}")]
    TooLarge(usize, usize, Geometry),
    /// A grid primitive has no holes, and the terrain has no-data cells.
    #[error("Embree's grid covers every cell; this terrain has cells over no data")]
    Holes,
}

/// How the terrain goes to Embree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Geometry {
    /// Two triangles per cell, as the surface contract ([`crate::geometry`]) defines them,
    /// each with a primitive id.
    Triangles,
    /// Embree's grid primitive over the samples: vertices only, cells split into triangles as
    /// Embree splits them.
    Grid,
}

impl std::fmt::Display for Geometry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Geometry::Triangles => "triangles",
            Geometry::Grid => "grid",
        })
    }
}

/// Where a ray first hits the terrain, as Embree found it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmbreeHit {
    /// The cell `(i, j)` hit.
    pub cell: (usize, usize),
    /// `T0` or `T1` of the cell: 0 or 1 (the surface contract, [`crate::geometry`]).
    pub triangle: u8,
    /// The ray parameter of the hit, as Embree reports it.
    pub t: f64,
    /// The triangle's unit normal, pointing up.
    pub up: DVec3,
}

/// Embree's bounding volume hierarchy over the terrain's triangles, ready to trace.
pub struct EmbreeScene {
    device: ffi::Device,
    scene: ffi::Scene,
    geometry: Geometry,
    /// Cells per row and column (with triangles, the primitive ids run row by row, two
    /// triangles a cell).
    cells: (usize, usize),
    build_time: Duration,
    /// What Embree holds allocated, kept up to date by its memory monitor (boxed: Embree
    /// holds its address).
    allocated: Box<AtomicIsize>,
}

// Embree's scenes may be traced from any number of threads at once once committed, and the
// device and scene are only released on drop.
unsafe impl Send for EmbreeScene {}
unsafe impl Sync for EmbreeScene {}

/// Keeps the count of the bytes Embree holds.
extern "C" fn monitor(user: *mut c_void, bytes: isize, _post: bool) -> bool {
    // SAFETY: `user` is the `AtomicIsize` boxed in the `EmbreeScene`, which outlives its device.
    let allocated = unsafe { &*(user as *const AtomicIsize) };
    allocated.fetch_add(bytes, Ordering::Relaxed);
    true
}

impl EmbreeScene {
    /// Builds the scene on one thread (Embree's own thread pool limited to one, as heightray
    /// builds), at the default build quality.
    pub fn build(terrain: &Terrain, geometry: Geometry) -> Result<EmbreeScene, EmbreeError> {
        let field = terrain.field();
        let (w, h) = (field.width(), field.height());
        let too_large = match geometry {
            Geometry::Triangles => 2 * (w - 1) * (h - 1) > u32::MAX as usize,
            Geometry::Grid => w.max(h) > ffi::GRID_MAX_SIDE,
        };
        if too_large {
            return Err(EmbreeError::TooLarge(w, h, geometry));
        }
        if geometry == Geometry::Grid && field.nodata_count() > 0 {
            return Err(EmbreeError::Holes);
        }
        // SAFETY: the calls follow the API's order (device, geometry with its buffers filled
        // within their sizes, scene committed before use), and every handle is released on
        // drop or before returning an error.
        unsafe {
            let device = ffi::rtcNewDevice(c"threads=1".as_ptr());
            if device.is_null() {
                return Err(EmbreeError::Call {
                    what: "create a device",
                    code: ffi::rtcGetDeviceError(std::ptr::null_mut()),
                });
            }
            let allocated = Box::new(AtomicIsize::new(0));
            let user = &*allocated as *const AtomicIsize as *mut c_void;
            ffi::rtcSetDeviceMemoryMonitorFunction(device, monitor, user);
            let start = Instant::now();
            let kind = match geometry {
                Geometry::Triangles => ffi::GEOMETRY_TYPE_TRIANGLE,
                Geometry::Grid => ffi::GEOMETRY_TYPE_GRID,
            };
            let handle = ffi::rtcNewGeometry(device, kind);
            let filled = fill_vertices(handle, field).and_then(|()| match geometry {
                Geometry::Triangles => fill_triangles(handle, field),
                Geometry::Grid => fill_grid(handle, field),
            });
            if filled.is_none() {
                let code = ffi::rtcGetDeviceError(device);
                ffi::rtcReleaseGeometry(handle);
                ffi::rtcReleaseDevice(device);
                return Err(EmbreeError::Call {
                    what: "allocate the geometry's buffers",
                    code,
                });
            }
            ffi::rtcCommitGeometry(handle);
            let scene = ffi::rtcNewScene(device);
            ffi::rtcAttachGeometry(scene, handle);
            ffi::rtcReleaseGeometry(handle);
            ffi::rtcCommitScene(scene);
            let build_time = start.elapsed();
            let code = ffi::rtcGetDeviceError(device);
            let built = EmbreeScene {
                device,
                scene,
                geometry,
                cells: (w - 1, h - 1),
                build_time,
                allocated,
            };
            if code != ffi::ERROR_NONE {
                return Err(EmbreeError::Call {
                    what: "build the scene",
                    code,
                });
            }
            Ok(built)
        }
    }

    /// The time from the first buffer to the committed hierarchy (filling the buffers
    /// included, as heightray's build includes reading the samples).
    pub fn build_time(&self) -> Duration {
        self.build_time
    }

    /// What Embree holds allocated: vertices, indices and hierarchy.
    pub fn bytes(&self) -> usize {
        self.allocated.load(Ordering::Relaxed).max(0) as usize
    }

    /// The first hit of `ray`.
    pub fn intersect(&self, ray: &Ray) -> Option<EmbreeHit> {
        let mut query = ffi::RayHit {
            ray: segment(ray.origin(), ray.dir()),
            hit: ffi::Hit {
                geom_id: ffi::INVALID_GEOMETRY_ID,
                ..ffi::Hit::default()
            },
        };
        let mut context = ffi::IntersectContext::new();
        // SAFETY: a committed scene, and a context and ray that live through the call.
        unsafe { ffi::rtcIntersect1(self.scene, &mut context, &mut query) };
        if query.hit.geom_id == ffi::INVALID_GEOMETRY_ID {
            return None;
        }
        let t = f64::from(query.ray.tfar);
        let (cell, triangle) = match self.geometry {
            Geometry::Triangles => {
                let prim = query.hit.prim_id as usize;
                let columns = self.cells.0;
                ((prim / 2 % columns, prim / 2 / columns), (prim % 2) as u8)
            }
            // A grid's hit names only the grid: the cell is the one under the hit point, and
            // the triangle heightray's on that side of its diagonal.
            Geometry::Grid => {
                let p = DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * t;
                let floor = |c: f64, cells: usize| (c.floor().max(0.0) as usize).min(cells - 1);
                let (i, j) = (floor(p.x, self.cells.0), floor(p.y, self.cells.1));
                let below_diagonal = p.x - i as f64 >= p.y - j as f64;
                ((i, j), u8::from(!below_diagonal))
            }
        };
        // The surface faces up; Embree's normal may not.
        let normal = DVec3::from(query.hit.ng.map(f64::from)).normalize_or(DVec3::Z);
        Some(EmbreeHit {
            cell,
            triangle,
            t,
            up: normal * normal.z.signum(),
        })
    }

    /// Whether anything lies on the ray from `origin` towards `dir`.
    pub fn occluded(&self, origin: [f64; 3], dir: [f64; 3]) -> bool {
        let mut ray = segment(origin, dir);
        let mut context = ffi::IntersectContext::new();
        // SAFETY: as in `intersect`.
        unsafe { ffi::rtcOccluded1(self.scene, &mut context, &mut ray) };
        // Embree marks an occluded ray by setting its far end to minus infinity.
        ray.tfar < 0.0
    }

    /// Renders `renderer`'s view into `frame` (every pixel, on the current rayon pool): the
    /// same pixels, shading and shadow rays as [`Renderer::render`], traced by Embree.
    pub fn render(&self, renderer: &Renderer<'_>, frame: &mut Frame) {
        let width = frame.width as usize;
        let rows: Vec<FrameStats> = frame
            .pixels
            .par_chunks_mut(width)
            .zip(frame.stats.par_chunks_mut(width))
            .enumerate()
            .map(|(y, (pixels, stats))| {
                let mut totals = FrameStats::default();
                for (x, (pixel, stat)) in pixels.iter_mut().zip(stats).enumerate() {
                    let sample = self.sample(renderer, x as u32, y as u32);
                    totals.add(&sample);
                    (*pixel, *stat) = (sample.rgb, PixelStats::of(&sample));
                }
                totals
            })
            .collect();
        for row in rows {
            frame.totals += row;
        }
        frame.passes_done = crate::render::PASS_BLOCKS.len();
    }

    /// One pixel, shaded as heightray shades it.
    fn sample(&self, renderer: &Renderer<'_>, x: u32, y: u32) -> Sample {
        let shader = &renderer.shader;
        let ray = renderer.camera.ray(x, y);
        let missed = Sample {
            rgb: shader.sky_rgb(&ray),
            hit: false,
            shadow: Shadow::NotAsked,
            primary: Counters::default(),
            secondary: Counters::default(),
            sky: SkyRays::default(),
            reflection: Reflection::NotWater,
            redone: false,
        };
        let Some(hit) = self.intersect(&ray) else {
            return missed;
        };
        let t = hit.t;
        let p = DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * t;
        let facing = shader.facing(hit.cell, hit.triangle, p);
        let shadow = if !shader.lighting.shadows {
            Shadow::NotAsked
        } else if facing <= 0.0 {
            Shadow::Skipped(ShadowSkip::FacingAway)
        } else {
            // Started off the surface by several `f32` roundings of the hit point's size,
            // the usual offset that keeps a shadow ray off the triangle it starts on.
            let room = 1e-6 * p.abs().max_element().max(1.0);
            let start = p + hit.up * room;
            Shadow::Cast {
                shadowed: self.occluded(start.into(), shader.lighting.sun),
            }
        };
        Sample {
            rgb: shader.surface_rgb(&ray, p, t, facing, shadow),
            hit: true,
            shadow,
            ..missed
        }
    }
}

/// Fills the geometry's vertex buffer with the samples (`None` if Embree could not allocate
/// it).
///
/// # Safety
/// `geometry` is a live geometry handle.
unsafe fn fill_vertices(geometry: ffi::Geometry, field: &Heightfield) -> Option<()> {
    let (w, h) = (field.width(), field.height());
    let vertices =
        new_buffer::<[f32; 3]>(geometry, ffi::BUFFER_TYPE_VERTEX, ffi::FORMAT_FLOAT3, w * h)?;
    for j in 0..h {
        for i in 0..w {
            vertices[j * w + i] = [i as f32, j as f32, field.z(i, j) as f32];
        }
    }
    Some(())
}

/// Fills a triangle geometry's index buffer: two triangles per cell, row by row.
///
/// # Safety
/// `geometry` is a live triangle geometry handle.
unsafe fn fill_triangles(geometry: ffi::Geometry, field: &Heightfield) -> Option<()> {
    let (w, h) = (field.width(), field.height());
    let indices = new_buffer::<[u32; 3]>(
        geometry,
        ffi::BUFFER_TYPE_INDEX,
        ffi::FORMAT_UINT3,
        2 * (w - 1) * (h - 1),
    )?;
    for j in 0..h - 1 {
        for i in 0..w - 1 {
            let corner = |di: usize, dj: usize| ((j + dj) * w + i + di) as u32;
            let (p00, p10, p01, p11) = (corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1));
            let cell = 2 * (j * (w - 1) + i);
            // A cell over no data has no surface: degenerate triangles, never hit.
            (indices[cell], indices[cell + 1]) = if field.is_hole_cell(i, j) {
                ([p00; 3], [p00; 3])
            } else {
                ([p00, p10, p11], [p00, p11, p01])
            };
        }
    }
    Some(())
}

/// Sets a grid geometry's one grid: all the samples.
///
/// # Safety
/// `geometry` is a live grid geometry handle, and the field's sides fit a grid.
unsafe fn fill_grid(geometry: ffi::Geometry, field: &Heightfield) -> Option<()> {
    let grid = new_buffer::<ffi::Grid>(geometry, ffi::BUFFER_TYPE_GRID, ffi::FORMAT_GRID, 1)?;
    grid[0] = ffi::Grid {
        start_vertex_id: 0,
        stride: field.width() as u32,
        width: field.width() as u16,
        height: field.height() as u16,
    };
    Some(())
}

/// A new buffer of `count` items of `T` in the geometry, as a slice (`None` if Embree could
/// not allocate it).
///
/// # Safety
/// `geometry` is a live geometry handle, and `T` is laid out as `format` says.
unsafe fn new_buffer<'a, T>(
    geometry: ffi::Geometry,
    kind: u32,
    format: u32,
    count: usize,
) -> Option<&'a mut [T]> {
    let buffer = ffi::rtcSetNewGeometryBuffer(geometry, kind, 0, format, size_of::<T>(), count);
    (!buffer.is_null()).then(|| std::slice::from_raw_parts_mut(buffer as *mut T, count))
}

impl Drop for EmbreeScene {
    fn drop(&mut self) {
        // SAFETY: handles made in `build`, released once; the monitor's box outlives them.
        unsafe {
            ffi::rtcReleaseScene(self.scene);
            ffi::rtcReleaseDevice(self.device);
        }
    }
}

/// An Embree ray from `origin` along `dir` (not normalised, as heightray's).
fn segment(origin: [f64; 3], dir: [f64; 3]) -> ffi::Ray {
    ffi::Ray {
        org: origin.map(|c| c as f32),
        dir: dir.map(|c| c as f32),
        tfar: f32::INFINITY,
        mask: u32::MAX,
        ..ffi::Ray::default()
    }
}

impl super::Reference for EmbreeScene {
    fn name(&self) -> String {
        format!("embree {}", self.geometry)
    }
    fn render(&self, renderer: &Renderer<'_>, frame: &mut Frame) {
        EmbreeScene::render(self, renderer, frame);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{Scene, SceneFile};
    use crate::{trace, Arith, Method, TraceOptions};
    use std::path::Path;

    /// Embree's scene is heightray's surface: the camera rays of every built-in scene hit the
    /// same cell and triangle at the same `t` as heightray's exact answer (a 64x64 image
    /// each), but for rays within `f32` rounding of an edge, where either neighbour may win.
    #[test]
    fn embree_hits_what_the_exact_trace_hits() {
        let exact = TraceOptions::new(Method::Mipmap, Arith::Exact);
        for (name, mut file) in SceneFile::builtins().unwrap() {
            file.size = Some((64, 64));
            let scene = Scene::from_file(&file, Path::new(""), Path::new(name)).unwrap();
            let terrain = Terrain::new(scene.field.clone());
            let embree = EmbreeScene::build(&terrain, Geometry::Triangles).unwrap();
            let (mut rays, mut hits, mut near_edges) = (0, 0, 0);
            for ray in scene.camera.rays() {
                rays += 1;
                let ours = trace(&terrain, &ray, &exact).hit;
                let theirs = embree.intersect(&ray);
                match (&ours, &theirs) {
                    (Some(ours), Some(theirs))
                        if ours.cell == [theirs.cell.0, theirs.cell.1]
                            && ours.triangle == theirs.triangle =>
                    {
                        hits += 1;
                        let off = (ours.t - theirs.t).abs() / ours.t;
                        assert!(off < 1e-5, "{name}: t {} against {}", ours.t, theirs.t);
                    }
                    (None, None) => {}
                    _ => {
                        // Only where the exact hit point lies within rounding of a cell's
                        // or triangle's edge (the diagonal `x - i = y - j`).
                        let p = ours.as_ref().map(|h| h.point).or(theirs.map(|h| {
                            (DVec3::from(ray.origin()) + DVec3::from(ray.dir()) * h.t).into()
                        }));
                        let [x, y, _] = p.unwrap();
                        let near = |v: f64| (v - v.round()).abs() < 1e-3;
                        let diagonal = (x - x.floor()) - (y - y.floor());
                        assert!(
                            near(x) || near(y) || diagonal.abs() < 1e-3,
                            "{name}: {ray:?}: exact {ours:?}, Embree {theirs:?}"
                        );
                        near_edges += 1;
                    }
                }
            }
            assert!(hits > rays / 4, "{name}: {hits} of {rays} rays hit");
            assert!(near_edges * 100 < rays, "{name}: {near_edges} near edges");
        }
    }

    /// Embree's grid splits cells its own way, so on a tilted plane, where either diagonal
    /// gives the same surface, its hits are heightray's exact ones: every ray from above
    /// aimed at a point of the plane hits it there, at the cell and triangle under the point
    /// (away from edges, where either neighbour may answer).
    #[test]
    fn grid_hits_a_plane_where_the_exact_trace_does() {
        // z = (3i + 2j) * 100 / 1000: a plane through every sample.
        let sample = |i: usize, j: usize| (3 * i + 2 * j) as u16;
        let field = Heightfield::from_fn(40, 30, 1000, 100.0, sample).unwrap();
        let terrain = Terrain::new(field);
        let grid = EmbreeScene::build(&terrain, Geometry::Grid).unwrap();
        let exact = TraceOptions::new(Method::Mipmap, Arith::Exact);
        for k in 0..200 {
            // Points inside cells, clear of their edges and diagonals.
            let (i, j) = (1 + k % 37, 1 + (k * 7) % 27);
            let (u, v) = if k % 2 == 0 { (0.7, 0.2) } else { (0.2, 0.7) };
            let (x, y) = (i as f64 + u, j as f64 + v);
            let target = [x, y, (3.0 * x + 2.0 * y) * 0.1];
            let dir = [0.3 - 0.01 * (k % 5) as f64, -0.2, -1.0];
            let origin = [0, 1, 2].map(|a| target[a] - 20.0 * dir[a]);
            let ray = Ray::new(origin, dir).unwrap();
            let ours = trace(&terrain, &ray, &exact).hit.unwrap();
            let theirs = grid.intersect(&ray).unwrap();
            assert_eq!(ours.cell, [i, j], "{ray:?}");
            assert_eq!([theirs.cell.0, theirs.cell.1], ours.cell, "{ray:?}");
            assert_eq!(theirs.triangle, ours.triangle, "{ray:?}");
            assert!(
                (theirs.t - 20.0).abs() < 1e-4 && (ours.t - 20.0).abs() < 1e-9,
                "{ray:?}"
            );
        }
        assert!(
            matches!(
                EmbreeScene::build(&terrain_with_hole(), Geometry::Grid),
                Err(EmbreeError::Holes)
            ),
            "a grid over no data is refused"
        );
    }

    /// A small terrain with one no-data sample.
    fn terrain_with_hole() -> Terrain {
        let mut hole = crate::heightfield::NoDataMask::new(16);
        hole.insert(5);
        let maxval = crate::heightfield::Quantisation::Maxval(255);
        let field = Heightfield::new(4, 4, vec![5u16; 16], maxval, 1.0, Some(hole));
        Terrain::new(field.unwrap())
    }

    /// A shadow ray is blocked by the terrain exactly where heightray's exact trace says:
    /// rays from above the highest sample down onto the terrain are occluded, rays rising
    /// from above it are not.
    #[test]
    fn occlusion_follows_the_surface() {
        let field = crate::heightfield::landscape(33, 1, 8.0).unwrap();
        let terrain = Terrain::new(field);
        let embree = EmbreeScene::build(&terrain, Geometry::Triangles).unwrap();
        let (_, top) = terrain.z_range();
        for k in 0..64 {
            // Inside the grid, and still inside where the downward rays reach the ground.
            let (x, y) = (1.0 + 0.45 * k as f64, 29.0 - 0.36 * k as f64);
            let origin = [x, y, top + 1.0];
            assert!(embree.occluded(origin, [0.1, 0.2, -1.0]), "{origin:?} down");
            assert!(!embree.occluded(origin, [0.1, 0.2, 1.0]), "{origin:?} up");
        }
        assert!(embree.bytes() > 33 * 33 * 12, "{} bytes", embree.bytes());
    }
}
