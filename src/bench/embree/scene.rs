//! Embree's scene of a terrain: its triangles (or its grid) in Embree's buffers, the
//! hierarchy built on one thread, what the build took and what Embree holds.

use super::{ffi, EmbreeError, Geometry};
use crate::{Heightfield, Terrain};
use std::ffi::c_void;
use std::sync::atomic::{AtomicIsize, Ordering};
use std::time::{Duration, Instant};

/// Embree's bounding volume hierarchy over the terrain's triangles, ready to trace.
pub struct EmbreeScene {
    pub(super) device: ffi::Device,
    pub(super) scene: ffi::Scene,
    pub(super) geometry: Geometry,
    /// Cells per row and column (with triangles, the primitive ids run row by row, two
    /// triangles a cell).
    pub(super) cells: (usize, usize),
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

    /// Whether this build of Embree on this processor traces `width`-wide packets natively
    /// (8 or 16; otherwise `rtcIntersect16` and the like fall back to single rays).
    pub fn native_packets(&self, width: usize) -> bool {
        let property = match width {
            8 => ffi::DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED,
            16 => ffi::DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED,
            _ => return false,
        };
        // SAFETY: a live device.
        unsafe { ffi::rtcGetDeviceProperty(self.device, property) == 1 }
    }

    /// Embree's version, as `3.13.5`.
    pub fn version(&self) -> String {
        // SAFETY: a live device.
        let v = unsafe { ffi::rtcGetDeviceProperty(self.device, ffi::DEVICE_PROPERTY_VERSION) };
        format!("{}.{}.{}", v / 10000, v / 100 % 100, v % 100)
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
