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

/// `(cos, sin)` of `k/n` of a turn in `f64`, the same bits on every target (IEEE arithmetic
/// only, no backend): the angle is folded into the nearest quarter turn's `±π/4` and summed
/// by Taylor series to within 1e-16. For building shapes (a ring of particles), not per frame.
pub fn turn(k: usize, n: usize) -> (f64, f64) {
    let (n, k) = (n.max(1), k % n.max(1));
    // The angle is q quarter turns and x: q = round(4k/n), x = (4k - q·n)/n quarter turns.
    let q = (8 * k + n) / (2 * n);
    let x = (4 * k) as f64 - (q * n) as f64;
    let x = x / n as f64 * core::f64::consts::FRAC_PI_2;
    let (mut c, mut s, mut term_c, mut term_s) = (1.0, x, 1.0, x);
    for i in 1..12 {
        let (a, b) = ((2 * i) as f64, (2 * i + 1) as f64);
        term_c *= -x * x / ((a - 1.0) * a);
        term_s *= -x * x / (a * b);
        c += term_c;
        s += term_s;
    }
    match q % 4 {
        0 => (c, s),
        1 => (-s, c),
        2 => (-c, -s),
        _ => (s, -c),
    }
}

#[cfg(test)]
mod tests {
    use super::turn;

    /// Exact at the quarter turns; on the unit circle, and at the angles with known values,
    /// within 2e-16 (on the circle within 1e-15).
    #[test]
    fn turn_is_exact_at_quarters_and_accurate_between() {
        assert_eq!(turn(0, 8), (1.0, 0.0));
        assert_eq!(turn(2, 8), (0.0, 1.0));
        assert_eq!(turn(4, 8), (-1.0, 0.0));
        assert_eq!(turn(6, 8), (0.0, -1.0));
        assert_eq!(turn(9, 8), turn(1, 8));
        let half = 0.5f64;
        let root_half = 0.707_106_781_186_547_5_f64;
        let root_three_halves = 0.866_025_403_784_438_6_f64;
        for ((k, n), (c, s)) in [
            ((1, 8), (root_half, root_half)),
            ((1, 6), (half, root_three_halves)),
            ((1, 12), (root_three_halves, half)),
            ((5, 12), (-root_three_halves, half)),
            ((7, 12), (-root_three_halves, -half)),
        ] {
            let (tc, ts) = turn(k, n);
            assert!((tc - c).abs() < 2e-16 && (ts - s).abs() < 2e-16, "{k}/{n}");
        }
        for n in 1..200 {
            for k in 0..n {
                let (c, s) = turn(k, n);
                assert!((c * c + s * s - 1.0).abs() < 1e-15, "{k}/{n}");
            }
        }
    }
}
