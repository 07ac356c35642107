//! The one place where float math meets a backend.
//!
//! `std` wins on hosted targets with the `std` feature; otherwise `libm` (the `libm` feature,
//! or any bare-metal target), except for the `f32` square root on an Arm core with a
//! hard-float ABI (a Cortex-M4F, M7, M33...), which is the FPU's `vsqrt.f32`: one instruction
//! (with two moves) instead of libm's software root of about 100 instructions. All are exact
//! (correctly rounded), so every backend gives the same bits. `build.rs` decides.
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
    #[cfg(not(all(target_arch = "arm", target_abi = "eabihf")))]
    #[inline]
    pub fn sqrt_f32(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    /// The FPU's square root (IEEE 754, correctly rounded like libm's): every hard-float Arm
    /// core has VFPv2 or later, which has `vsqrt.f32`. Stable Rust cannot name the FPU's
    /// registers in `cfg` (`vfp2` is not a stable target feature), so the value travels
    /// through a core register and `s14`, declared clobbered: three instructions.
    #[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
    #[inline]
    #[allow(unsafe_code)]
    pub fn sqrt_f32(x: f32) -> f32 {
        let bits: u32;
        // SAFETY: FPU instructions on registers only (no memory, no stack); `s14` is declared
        // clobbered and is caller-saved in the AAPCS.
        unsafe {
            core::arch::asm!(
                "vmov s14, {x}",
                "vsqrt.f32 s14, s14",
                "vmov {root}, s14",
                x = in(reg) x.to_bits(),
                root = lateout(reg) bits,
                out("s14") _,
                options(pure, nomem, nostack)
            );
        }
        f32::from_bits(bits)
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
