//! Which SIMD instructions the lane kernels (the packet walk's node test, the cell kernel)
//! run on, picked at run time: one binary uses AVX-512 or AVX2 where the processor has them,
//! plain `x86-64` (SSE2) elsewhere.

use std::fmt;
use std::sync::OnceLock;

/// The environment variable that forces a path (`scalar`, `avx2` or `avx512`): one the
/// processor lacks falls back to the best it has below it.
pub const SIMD_VARIABLE: &str = "HEIGHTRAY_SIMD";

/// An instruction set the lane kernels are compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SimdPath {
    /// The baseline instructions (SSE2 on `x86-64`), two lanes per instruction.
    Scalar,
    /// AVX2: four `f64` lanes per instruction.
    Avx2,
    /// AVX-512: eight `f64` lanes per instruction.
    Avx512,
}

impl SimdPath {
    /// The best path this processor runs.
    pub fn detected() -> SimdPath {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx512f")
                && std::arch::is_x86_feature_detected!("avx512vl")
            {
                return SimdPath::Avx512;
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                return SimdPath::Avx2;
            }
        }
        SimdPath::Scalar
    }

    /// The path asked for in [`SIMD_VARIABLE`], if any; an error names a value it does not
    /// know.
    pub fn requested() -> Result<Option<SimdPath>, UnknownSimdPath> {
        match std::env::var(SIMD_VARIABLE) {
            Err(_) => Ok(None),
            Ok(value) => value.parse().map(Some),
        }
    }

    /// The path the lane kernels run on: the one requested (where the processor has it, else
    /// the best below it it has), else the best detected. Decided once per process.
    pub fn active() -> SimdPath {
        static ACTIVE: OnceLock<SimdPath> = OnceLock::new();
        *ACTIVE.get_or_init(|| {
            let detected = SimdPath::detected();
            match SimdPath::requested() {
                Ok(Some(asked)) => asked.min(detected),
                _ => detected,
            }
        })
    }
}

impl fmt::Display for SimdPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SimdPath::Scalar => "scalar",
            SimdPath::Avx2 => "avx2",
            SimdPath::Avx512 => "avx512",
        })
    }
}

/// A name that is not a SIMD path's.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{SIMD_VARIABLE}={0} is not a SIMD path: use scalar, avx2 or avx512")]
pub struct UnknownSimdPath(pub String);

impl std::str::FromStr for SimdPath {
    type Err = UnknownSimdPath;
    fn from_str(s: &str) -> Result<Self, UnknownSimdPath> {
        match s {
            "scalar" => Ok(SimdPath::Scalar),
            "avx2" => Ok(SimdPath::Avx2),
            "avx512" => Ok(SimdPath::Avx512),
            _ => Err(UnknownSimdPath(s.to_owned())),
        }
    }
}
