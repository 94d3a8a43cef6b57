//! The part of Embree 3's C API (`rtcore.h`, 3.13) the comparison uses, declared by hand: a
//! score of functions, the single-ray structures and the 8- and 16-wide packets, laid out as
//! the header lays them out for `RTC_MAX_INSTANCE_LEVEL_COUNT` 1 and `RTC_MIN_WIDTH` 0
//! (Debian's `libembree-dev` build).

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
/// `RTC_DEVICE_PROPERTY_VERSION`: the version as one number, 31305 for 3.13.5.
pub const DEVICE_PROPERTY_VERSION: u32 = 0;
/// `RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED`; the 16-wide one follows it.
pub const DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED: u32 = 33;
pub const DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED: u32 = 34;
/// `RTC_INTERSECT_CONTEXT_FLAG_COHERENT`: the rays of a call are coherent.
const INTERSECT_CONTEXT_FLAG_COHERENT: u32 = 1;

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

    /// A context for coherent rays (`RTC_INTERSECT_CONTEXT_FLAG_COHERENT`).
    pub fn coherent() -> Self {
        IntersectContext {
            flags: INTERSECT_CONTEXT_FLAG_COHERENT,
            ..IntersectContext::new()
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

/// `RTCRay8` and `RTCRay16`: `N` rays, one array per field. 64-byte aligned, as the 16-wide
/// packet must be (the 8-wide needs 32): every field array of either is a multiple of 32
/// bytes, so the fields sit where the header puts them.
#[repr(C, align(64))]
#[derive(Clone, Copy)]
pub struct RayN<const N: usize> {
    pub org: [[f32; N]; 3],
    pub tnear: [f32; N],
    pub dir: [[f32; N]; 3],
    pub time: [f32; N],
    pub tfar: [f32; N],
    pub mask: [u32; N],
    pub id: [u32; N],
    pub flags: [u32; N],
}

/// `RTCHit8` and `RTCHit16`.
#[repr(C, align(64))]
#[derive(Clone, Copy)]
pub struct HitN<const N: usize> {
    pub ng: [[f32; N]; 3],
    pub u: [f32; N],
    pub v: [f32; N],
    pub prim_id: [u32; N],
    pub geom_id: [u32; N],
    pub inst_id: [[u32; N]; 1],
}

/// `RTCRayHit8` and `RTCRayHit16`.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct RayHitN<const N: usize> {
    pub ray: RayN<N>,
    pub hit: HitN<N>,
}

/// A packet's valid mask: -1 for a lane to trace, 0 for one to leave alone, aligned as its
/// packet.
#[repr(C, align(64))]
#[derive(Clone, Copy)]
pub struct Valid<const N: usize>(pub [i32; N]);

/// The packet calls of one width.
pub trait Packet<const N: usize> {
    /// `rtcIntersect8` or `rtcIntersect16`.
    ///
    /// # Safety
    /// A committed scene.
    unsafe fn intersect(
        valid: &Valid<N>,
        scene: Scene,
        context: &mut IntersectContext,
        rayhit: &mut RayHitN<N>,
    );
    /// `rtcOccluded8` or `rtcOccluded16`.
    ///
    /// # Safety
    /// A committed scene.
    unsafe fn occluded(
        valid: &Valid<N>,
        scene: Scene,
        context: &mut IntersectContext,
        ray: &mut RayN<N>,
    );
}

/// The packet width `N` as a type, to pick its calls.
pub struct Width<const N: usize>;

/// Embree's calls of one packet width, and `Packet<N>` for `Width<N>` made of them.
macro_rules! packet_calls {
    ($n:literal, $intersect:ident, $occluded:ident) => {
        #[link(name = "embree3")]
        extern "C" {
            fn $intersect(
                valid: *const i32,
                scene: Scene,
                context: *mut IntersectContext,
                rayhit: *mut RayHitN<$n>,
            );
            fn $occluded(
                valid: *const i32,
                scene: Scene,
                context: *mut IntersectContext,
                ray: *mut RayN<$n>,
            );
        }

        impl Packet<$n> for Width<$n> {
            unsafe fn intersect(
                valid: &Valid<$n>,
                scene: Scene,
                context: &mut IntersectContext,
                rayhit: &mut RayHitN<$n>,
            ) {
                $intersect(valid.0.as_ptr(), scene, context, rayhit);
            }
            unsafe fn occluded(
                valid: &Valid<$n>,
                scene: Scene,
                context: &mut IntersectContext,
                ray: &mut RayN<$n>,
            ) {
                $occluded(valid.0.as_ptr(), scene, context, ray);
            }
        }
    };
}

packet_calls!(8, rtcIntersect8, rtcOccluded8);
packet_calls!(16, rtcIntersect16, rtcOccluded16);

/// `RTCMemoryMonitorFunction`: told of every allocation (`bytes` > 0) and release (< 0).
pub type MemoryMonitor = extern "C" fn(user: *mut c_void, bytes: isize, post: bool) -> bool;

#[link(name = "embree3")]
extern "C" {
    pub fn rtcNewDevice(config: *const c_char) -> Device;
    pub fn rtcReleaseDevice(device: Device);
    pub fn rtcGetDeviceError(device: Device) -> u32;
    pub fn rtcGetDeviceProperty(device: Device, property: u32) -> isize;
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

    /// `RTCRayHit8` and `RTCRayHit16`: twelve and eight arrays of `N` four-byte fields, the
    /// hit right after the ray, 32- and 64-byte aligned at least.
    #[test]
    fn packets_are_laid_out_as_the_header_says() {
        assert_eq!(size_of::<RayN<8>>(), 12 * 8 * 4);
        assert_eq!(size_of::<HitN<8>>(), 8 * 8 * 4);
        assert_eq!(offset_of!(RayHitN<8>, hit), 384);
        assert_eq!(size_of::<RayHitN<8>>(), 640);
        assert_eq!(size_of::<RayHitN<16>>(), 1280);
        assert_eq!(offset_of!(RayHitN<16>, hit), 768);
        assert_eq!(offset_of!(RayN<8>, tnear), 96);
        assert_eq!(offset_of!(RayN<8>, tfar), 256);
        assert_eq!(offset_of!(RayN<16>, flags), 704);
        assert_eq!(offset_of!(HitN<16>, prim_id), 320);
        assert_eq!(offset_of!(HitN<8>, inst_id), 224);
        assert!(align_of::<RayHitN<8>>() >= 32 && align_of::<RayHitN<16>>() >= 64);
        assert!(align_of::<Valid<8>>() >= 32 && align_of::<Valid<16>>() >= 64);
    }
}
