//! The one place where float math meets a backend.
//!
//! `std` wins on hosted targets with the `std` feature; otherwise `libm` (the `libm` feature,
//! or any bare-metal target). Both are exact (correctly rounded sqrt). `build.rs` decides.
//! `micromath` is only used by the `approx_*` functions, which callers choose explicitly.

#[cfg(dunas_std)]
mod backend {
    #[inline]
    pub fn sqrt_f32(x: f32) -> f32 {
        x.sqrt()
    }
    #[inline]
    pub fn sqrt_f64(x: f64) -> f64 {
        x.sqrt()
    }
}

#[cfg(not(dunas_std))]
mod backend {
    #[inline]
    pub fn sqrt_f32(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    #[inline]
    pub fn sqrt_f64(x: f64) -> f64 {
        libm::sqrt(x)
    }
}

pub use backend::{sqrt_f32, sqrt_f64};

/// Approximate f32 square root: micromath's (at most 6.1%, measured over 1e-3..1e3) when the feature is on,
/// exact otherwise.
#[inline]
pub fn approx_sqrt_f32(x: f32) -> f32 {
    #[cfg(feature = "micromath")]
    {
        micromath::F32(x).sqrt().0
    }
    #[cfg(not(feature = "micromath"))]
    {
        sqrt_f32(x)
    }
}

/// Approximate f32 inverse square root: micromath's (at most 3.5%, measured over 1e-3..1e3) when the
/// feature is on, exact otherwise.
#[inline]
pub fn approx_inv_sqrt_f32(x: f32) -> f32 {
    #[cfg(feature = "micromath")]
    {
        micromath::F32(x).invsqrt().0
    }
    #[cfg(not(feature = "micromath"))]
    {
        1.0 / sqrt_f32(x)
    }
}
