//! The packet walk on the SIMD path picked at run time ([`SimdPath`]): one binary uses
//! AVX-512 or AVX2 where the processor has them, plain `x86-64` (SSE2) elsewhere. The lanes'
//! steps are the same in each (additions, multiplications and comparisons, never fused), so
//! every path gives the same answers.

use super::lanes::{Kernel, Lanes, NodeTest, Packet};
use super::walk::walk as walk_inline;
#[cfg(target_arch = "x86_64")]
use super::x86;
use super::PacketClearance;
use crate::arith::SimdPath;

/// Walks the packet on `path`, which the processor must have.
pub(super) fn walk(path: SimdPath, p: &Packet<'_>, out: &mut PacketClearance) {
    match path {
        // SAFETY: the caller picks a path the processor has the instructions of.
        #[cfg(target_arch = "x86_64")]
        SimdPath::Avx512 => unsafe { walk_avx512(p, out) },
        #[cfg(target_arch = "x86_64")]
        SimdPath::Avx2 => unsafe { walk_avx2(p, out) },
        _ => walk_inline::<Portable>(p, out),
    }
}

/// The portable test, SIMD as far as the compiler makes it.
struct Portable;

impl Kernel for Portable {
    #[inline(always)]
    fn test(lanes: &Lanes, room: f64, faces: [f64; 4], highest: f64) -> NodeTest {
        lanes.test(room, faces, highest)
    }
}

#[cfg(target_arch = "x86_64")]
struct Avx2;

#[cfg(target_arch = "x86_64")]
impl Kernel for Avx2 {
    #[inline(always)]
    fn test(lanes: &Lanes, room: f64, faces: [f64; 4], highest: f64) -> NodeTest {
        // SAFETY: only `walk_avx2` walks with this kernel, on a processor with AVX2.
        unsafe { x86::test_avx2(lanes, room, faces, highest) }
    }
}

#[cfg(target_arch = "x86_64")]
struct Avx512;

#[cfg(target_arch = "x86_64")]
impl Kernel for Avx512 {
    #[inline(always)]
    fn test(lanes: &Lanes, room: f64, faces: [f64; 4], highest: f64) -> NodeTest {
        // SAFETY: only `walk_avx512` walks with this kernel, on a processor with AVX-512.
        unsafe { x86::test_avx512(lanes, room, faces, highest) }
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx2")]
fn walk_avx512(p: &Packet<'_>, out: &mut PacketClearance) {
    walk_inline::<Avx512>(p, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn walk_avx2(p: &Packet<'_>, out: &mut PacketClearance) {
    walk_inline::<Avx2>(p, out);
}
