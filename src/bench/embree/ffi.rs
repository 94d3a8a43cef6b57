//! The part of Embree 3's C API (`rtcore.h`, 3.13) the comparison uses, declared by hand: a
//! dozen functions and the single-ray structures, laid out as the header lays them out for
//! `RTC_MAX_INSTANCE_LEVEL_COUNT` 1 and `RTC_MIN_WIDTH` 0 (Debian's `libembree-dev` build).

use std::ffi::{c_char, c_void};

pub type Device = *mut c_void;
pub type Scene = *mut c_void;
pub type Geometry = *mut c_void;

pub const GEOMETRY_TYPE_TRIANGLE: u32 = 0;
pub const GEOMETRY_TYPE_GRID: u32 = 2;
pub const BUFFER_TYPE_INDEX: u32 = 0;
pub const BUFFER_TYPE_VERTEX: u32 = 1;
pub const BUFFER_TYPE_GRID: u32 = 8;
pub const FORMAT_UINT3: u32 = 0x5003;
pub const FORMAT_FLOAT3: u32 = 0x9003;
pub const FORMAT_GRID: u32 = 0xA001;
/// The most vertices a side of a grid primitive may have.
pub const GRID_MAX_SIDE: usize = 32767;
pub const ERROR_NONE: u32 = 0;
pub const INVALID_GEOMETRY_ID: u32 = u32::MAX;

/// `RTCGrid`: a `width` x `height` block of the vertex buffer, rows `stride` vertices apart.
#[repr(C)]
pub struct Grid {
    pub start_vertex_id: u32,
    pub stride: u32,
    pub width: u16,
    pub height: u16,
}

/// `RTCIntersectContext`, as `rtcInitIntersectContext` sets it (incoherent rays, no filter).
#[repr(C)]
pub struct IntersectContext {
    flags: u32,
    filter: *const c_void,
    inst_id: [u32; 1],
}

impl IntersectContext {
    pub fn new() -> Self {
        IntersectContext {
            flags: 0,
            filter: std::ptr::null(),
            inst_id: [INVALID_GEOMETRY_ID],
        }
    }
}

/// `RTCRay`.
#[repr(C, align(16))]
#[derive(Clone, Copy, Default)]
pub struct Ray {
    pub org: [f32; 3],
    pub tnear: f32,
    pub dir: [f32; 3],
    pub time: f32,
    pub tfar: f32,
    pub mask: u32,
    pub id: u32,
    pub flags: u32,
}

/// `RTCHit`.
#[repr(C, align(16))]
#[derive(Clone, Copy, Default)]
pub struct Hit {
    pub ng: [f32; 3],
    pub u: f32,
    pub v: f32,
    pub prim_id: u32,
    pub geom_id: u32,
    pub inst_id: [u32; 1],
}

/// `RTCRayHit`.
#[repr(C, align(16))]
#[derive(Clone, Copy, Default)]
pub struct RayHit {
    pub ray: Ray,
    pub hit: Hit,
}

/// `RTCMemoryMonitorFunction`: told of every allocation (`bytes` > 0) and release (< 0).
pub type MemoryMonitor = extern "C" fn(user: *mut c_void, bytes: isize, post: bool) -> bool;

#[link(name = "embree3")]
extern "C" {
    pub fn rtcNewDevice(config: *const c_char) -> Device;
    pub fn rtcReleaseDevice(device: Device);
    pub fn rtcGetDeviceError(device: Device) -> u32;
    pub fn rtcSetDeviceMemoryMonitorFunction(device: Device, f: MemoryMonitor, user: *mut c_void);
    pub fn rtcNewScene(device: Device) -> Scene;
    pub fn rtcReleaseScene(scene: Scene);
    pub fn rtcCommitScene(scene: Scene);
    pub fn rtcAttachGeometry(scene: Scene, geometry: Geometry) -> u32;
    pub fn rtcNewGeometry(device: Device, kind: u32) -> Geometry;
    pub fn rtcReleaseGeometry(geometry: Geometry);
    pub fn rtcCommitGeometry(geometry: Geometry);
    pub fn rtcSetNewGeometryBuffer(
        geometry: Geometry,
        kind: u32,
        slot: u32,
        format: u32,
        byte_stride: usize,
        count: usize,
    ) -> *mut c_void;
    pub fn rtcIntersect1(scene: Scene, context: *mut IntersectContext, rayhit: *mut RayHit);
    pub fn rtcOccluded1(scene: Scene, context: *mut IntersectContext, ray: *mut Ray);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::mem::{offset_of, size_of};

    /// The layouts `rtcore_ray.h` and `rtcore_common.h` give on x86-64.
    #[test]
    fn structures_are_laid_out_as_the_header_says() {
        assert_eq!(size_of::<Ray>(), 48);
        assert_eq!(size_of::<Hit>(), 32);
        assert_eq!(size_of::<RayHit>(), 80);
        assert_eq!(offset_of!(RayHit, hit), 48);
        assert_eq!(offset_of!(Ray, tfar), 32);
        assert_eq!(offset_of!(Hit, prim_id), 20);
        assert_eq!(size_of::<IntersectContext>(), 24);
        assert_eq!(size_of::<Grid>(), 12);
        assert_eq!(offset_of!(IntersectContext, inst_id), 16);
    }
}
