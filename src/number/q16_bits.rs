//! The raw-bit kernels of [`Q16`]'s products, quotients and roots: each exact form in 64
//! bits, and for cores without a 64-bit multiply or divide (a Cortex-M0) the same result in
//! 32-bit registers, bit for bit (tested against each other).

use super::q16::Q16;

/// `round(a·b / 2¹⁶)` (ties up), saturated: the exact 64-bit form.
#[cfg(any(test, dunas_wide_mul))]
#[inline]
pub(super) fn mul_wide(a: i32, b: i32) -> Q16 {
    let wide = a as i64 * b as i64;
    Q16::saturate((wide + (1 << 15)) >> 16)
}

/// The same product from 16-bit halves and 32-bit multiplies, for cores without a 64-bit
/// multiplier (a Cortex-M0 would call a ~40-instruction library routine for `i64 * i64`).
/// A factor `b` within `±½` (a basis weight, a step length) takes two multiplies;
/// otherwise, when `|a|·|b|` is below about `2³¹` (a product within ±16384 or so) the sum
/// cannot leave 32 bits and is taken there; otherwise in 64 bits, saturated as
/// [`mul_wide`] does. Bit-identical to the 64-bit form (tested on edge cases and 600 000
/// random pairs).
#[cfg(any(test, not(dunas_wide_mul)))]
#[inline]
pub(super) fn mul_halves(a: i32, b: i32) -> Q16 {
    if (b >> 15) == (b >> 31) {
        // -2¹⁵ <= b < 2¹⁵: round(a·b / 2¹⁶) = ah·b + round(al·b / 2¹⁶), where
        // |ah·b| <= 2³⁰ and |al·b + 2¹⁵| < 2³¹; the result is within |a| / 2, so nothing
        // saturates.
        return Q16::from_bits((a >> 16) * b + (((a & 0xffff) * b + (1 << 15)) >> 16));
    }
    // a = ah·2¹⁶ + al with ah signed and al in 0..2¹⁶; the same for b.
    let (ah, al) = (a >> 16, (a & 0xffff) as u32);
    let (bh, bl) = (b >> 16, (b & 0xffff) as u32);
    // round(a·b / 2¹⁶) = ah·bh·2¹⁶ + ah·bl + al·bh + round(al·bl / 2¹⁶), each term within
    // 32 bits (al·bl + 2¹⁵ < 2³²). With |a| <= A·2¹⁶ and |b| <= B·2¹⁶ the result is within
    // A·B·2¹⁶ + 1, so for A·B < 2¹⁵ the wrapping sum is exact.
    let (big_a, big_b) = ((ah ^ (ah >> 31)) + 1, (bh ^ (bh >> 31)) + 1);
    let low = al * bl;
    if big_a * big_b < 1 << 15 {
        let rounded = ((low + (1 << 15)) >> 16) as i32;
        let sum = ((ah * bh) << 16)
            .wrapping_add(ah * bl as i32)
            .wrapping_add(al as i32 * bh)
            .wrapping_add(rounded);
        return Q16::from_bits(sum);
    }
    mul_halves_wide(ah, al, bh, bl)
}

/// [`mul_halves`] past the 32-bit sum: in 64-bit adds only (cheap everywhere), rounded and
/// saturated as [`mul_wide`] does. Out of line: it is rare, and inlined it would cost
/// flash at every product.
#[cfg(any(test, not(dunas_wide_mul)))]
#[cold]
#[inline(never)]
fn mul_halves_wide(ah: i32, al: u32, bh: i32, bl: u32) -> Q16 {
    let high = ah * bh; // |high| <= 2^30
    let mid = (ah * bl as i32) as i64 + (al as i32 * bh) as i64; // each |..| < 2^31
    let sum = ((high as i64) << 32) + (mid << 16) + (al * bl) as i64;
    Q16::saturate((sum + (1 << 15)) >> 16)
}

/// `round(a·2¹⁶ / b)` (half away from zero), saturated: the exact 64-bit form.
#[cfg(any(test, target_pointer_width = "64"))]
#[inline]
pub(super) fn div_wide(a: i32, b: i32) -> Q16 {
    let (a, b) = (a as i64, b as i64);
    if b == 0 {
        return match a.signum() {
            1 => Q16::MAX,
            -1 => Q16::MIN,
            _ => Q16::from_bits(0),
        };
    }
    let num = a << 16;
    let q = num / b;
    let r = num - q * b;
    // Round half away from zero.
    let q = if 2 * r.abs() >= b.abs() {
        q + if (num < 0) == (b < 0) { 1 } else { -1 }
    } else {
        q
    };
    Q16::saturate(q)
}

/// The same quotient in 32-bit registers, for cores without a divider (a Cortex-M0 would
/// call a ~550-instruction library routine for the 64-bit form): the divisor shifted to its
/// top bit, then two 16-bit quotient digits, each estimated from a reciprocal of the
/// divisor's top half ([`reciprocal_top`]) and made exact by its remainder: the same work
/// for any operands, where binary long division took 9 instructions a quotient bit. On a
/// Cortex-M0 it took the catapult's costliest frame (two divisions a link an iteration)
/// from 35 905 to 32 756 instructions (`examples/mcu_catapult.rs`). Bit-identical to
/// [`div_wide`] (tested on edge cases and 600 000 random pairs).
#[cfg(any(test, not(target_pointer_width = "64")))]
#[inline(never)]
pub(super) fn div_long(a: i32, b: i32) -> Q16 {
    let negative = (a < 0) != (b < 0);
    let (big_a, big_b) = (a.unsigned_abs(), b.unsigned_abs());
    let saturated = if negative { Q16::MIN } else { Q16::MAX };
    if big_b == 0 {
        return if a == 0 { Q16::from_bits(0) } else { saturated };
    }
    // `|a|·2¹⁶ / |b| ≥ 2³²`: past every `Q16`.
    if big_a >> 16 >= big_b {
        return saturated;
    }
    // Divisor and dividend `|a|·2¹⁶` shifted left together until the divisor's top bit is
    // set; the dividend is then `high·2³² + low` with `high < divisor`.
    let shift = 32 - width(big_b);
    let divisor = big_b << shift;
    let (high, low) = match 16 + shift {
        s if s >= 32 => (big_a << (s - 32), 0),
        s => (big_a >> (32 - s), big_a << s),
    };
    let z = reciprocal_top(divisor >> 16);
    let (top, rest) = digit(high, low >> 16, divisor, z);
    let (bottom, rem) = digit(rest, low & 0xffff, divisor, z);
    // Round half away from zero (`rem < divisor`, so `2·rem` is compared without overflow),
    // then the sign, saturated.
    let magnitude = u64::from((top << 16) | bottom) + u64::from(rem >= divisor - rem);
    if negative {
        if magnitude > 1 << 31 {
            Q16::MIN
        } else {
            Q16::from_bits((magnitude as i64).wrapping_neg() as i32)
        }
    } else {
        Q16::from_bits(magnitude.min(i32::MAX as u64) as i32)
    }
}

/// One 16-bit digit of a long division: `(rem·2¹⁶ + next) / divisor` and its remainder, for
/// `rem < divisor` and `divisor ≥ 2³¹` (so the digit is below 2¹⁶). The estimate
/// `rem·z / 2³¹` (`z` from [`reciprocal_top`]) is at most 2 off; the remainder,
/// taken exactly in 64 bits from 16-bit products, corrects it.
#[cfg(any(test, not(target_pointer_width = "64")))]
#[inline]
fn digit(rem: u32, next: u32, divisor: u32, z: u32) -> (u32, u32) {
    let estimate = ((rem >> 16) * z + (((rem & 0xffff) * z) >> 16)) >> 15;
    let mut q = estimate.min(0xffff);
    let dividend = (i64::from(rem) << 16) | i64::from(next);
    let product = (i64::from(q * (divisor >> 16)) << 16) + i64::from(q * (divisor & 0xffff));
    let mut r = dividend - product;
    while r < 0 {
        q -= 1;
        r += i64::from(divisor);
    }
    while r >= i64::from(divisor) {
        q += 1;
        r -= i64::from(divisor);
    }
    (q, r as u32)
}

/// `2³¹ / t` at the middle of each 128th of `t ∈ [2¹⁵, 2¹⁶)`: the first guess of
/// [`reciprocal_top`], within 2⁻⁸ relative.
const RECIPROCAL_GUESS: [u16; 128] = {
    let mut table = [0u16; 128];
    let mut i = 0;
    while i < 128 {
        let middle = (128 + i as u32) * 256 + 128;
        table[i] = ((1u32 << 31) / middle) as u16;
        i += 1;
    }
    table
};

/// `z ≈ 2³¹ / t` for the top half `t ∈ [2¹⁵, 2¹⁶)` of a divisor: a guess from
/// [`RECIPROCAL_GUESS`] and one Newton step: at most `2³¹ / t` (Newton's step for a
/// reciprocal lands below it, and each shift rounds down) and within 2⁻¹⁴ of it (tested for
/// every `t`), so a digit's estimate is at most 2 off.
#[inline]
fn reciprocal_top(t: u32) -> u32 {
    let z = u32::from(RECIPROCAL_GUESS[(t >> 8) as usize & 127]);
    // `e = 2³¹ − t·z` is within 2²⁴ (the guess is within 2⁻⁸), so `z·(e / 2¹⁰)` fits an `i32`.
    let e = ((1u32 << 31).wrapping_sub(t * z) as i32) >> 10;
    (z as i32 + ((z as i32 * e) >> 21)) as u32
}

/// `r²` from 16-bit halves and 32-bit multiplies (no 64-bit multiply call on a Cortex-M0).
#[inline]
pub(super) fn square(r: u32) -> u64 {
    let (h, l) = ((r >> 16) as u64, (r & 0xffff) as u64);
    let (hh, hl, ll) = (
        (h as u32 * h as u32) as u64,
        (h as u32 * l as u32) as u64,
        (l as u32 * l as u32) as u64,
    );
    (hh << 32) + (hl << 17) + ll
}

/// The bit width of `x` (0 for 0): five compares, where `leading_zeros` is a library call
/// on a Cortex-M0.
#[inline]
fn width(x: u32) -> u32 {
    let (x, n) = if x >> 16 != 0 { (x >> 16, 16) } else { (x, 0) };
    let (x, n) = if x >> 8 != 0 { (x >> 8, n + 8) } else { (x, n) };
    let (x, n) = if x >> 4 != 0 { (x >> 4, n + 4) } else { (x, n) };
    let (x, n) = if x >> 2 != 0 { (x >> 2, n + 2) } else { (x, n) };
    n + if x >= 2 { 2 } else { x }
}

/// `floor(sqrt(n))`: `n` scaled by a power of four into `[2⁶², 2⁶⁴)`, a root from
/// [`inv_sqrt_unit`] (15 bits), one Newton step through the same inverse (about 29 bits),
/// scaled back and made exact by comparing squares. 32-bit multiplies only: about 200
/// instructions on a Cortex-M0, a third of digit-by-digit's. Equal to `u64::isqrt` for
/// every input (tested).
pub(super) fn isqrt(n: u64) -> u64 {
    u64::from(root_and_inverse(n).0)
}

/// `floor(√n)` as [`isqrt`] finds it, and `2³² / √n` (saturated at `i32::MAX`; 0 for 0) from
/// the same reciprocal estimate, within 2⁻¹⁴ relative or one unit: for `n` the sum of a
/// `Q16` vector's squared raw bits, the raw bits of its length and of its inverse, with no
/// division.
#[inline]
pub(super) fn root_and_inverse(n: u64) -> (u32, u32) {
    if n == 0 {
        return (0, 0);
    }
    let high = (n >> 32) as u32;
    let bits = if high != 0 {
        32 + width(high)
    } else {
        width(n as u32)
    };
    let shift = (64 - bits) & !1;
    // `n << shift` in 32-bit shifts (a 64-bit shift by a variable amount is a library call
    // on a Cortex-M0).
    let (hi, lo) = (high, n as u32);
    let m = match shift {
        0 => n,
        s if s >= 32 => u64::from(lo << (s - 32)) << 32,
        s => (u64::from((hi << s) | (lo >> (32 - s))) << 32) | u64::from(lo << s),
    };
    // `√m ≈ t·z / 2¹⁵` with `t` the top half of `m` and `z ≈ 2¹⁶ / √(t / 2³⁰)`: within
    // `2⁻¹⁴` relative. Each product fits 32 bits (`z ≤ 2¹⁶`, `t >> 16 < 2¹⁶`).
    let t = (m >> 32) as u32;
    let z = inv_sqrt_unit(t);
    let wide = (u64::from((t >> 16) * z) << 16) + u64::from((t & 0xffff) * z);
    let r0 = (wide >> 15).min(u64::from(u32::MAX)) as u32;
    // Newton: `r1 = r0 + (m − r0²) / (2√m)`, with `1 / (2√m) ≈ z / 2⁴⁸`. `|m − r0²| < 2⁵¹`,
    // so `e = (m − r0²) / 2²⁰` fits 32 bits; `e·z` is summed from its 16-bit halves.
    let e = (m.wrapping_sub(square(r0)) as i64 >> 20) as i32;
    let (eh, el) = (e >> 16, (e & 0xffff) as u32);
    let step = ((eh * z as i32) >> 12) + ((el * z) >> 28) as i32;
    let r1 = (i64::from(r0) + i64::from(step)).clamp(0, i64::from(u32::MAX)) as u64;
    // Back to `n`'s scale; a few units off at most (none for most inputs): made exact.
    let mut root = (r1 as u32) >> (shift / 2);
    while square(root) > n {
        root -= 1;
    }
    while root < u32::MAX && square(root + 1) <= n {
        root += 1;
    }
    // `1/√n = 2^(shift/2) / √m` and `1/√m ≈ z / 2⁴⁷`: in units of 2⁻³², `z·2^(shift/2 − 15)`.
    (root, scaled_by(z, shift / 2))
}

/// `z·2^(shift − 15)`, rounded half up and saturated at `i32::MAX`: a reciprocal estimate
/// `z ≤ 2¹⁶` (of a value scaled up by `2^shift`) back at its value's scale, in raw `Q16`
/// bits.
#[inline]
fn scaled_by(z: u32, shift: u32) -> u32 {
    if shift >= 15 {
        let up = shift - 15;
        if up >= 16 || z >> (31 - up) != 0 {
            i32::MAX as u32
        } else {
            z << up
        }
    } else {
        let down = 15 - shift;
        (z + (1 << (down - 1))) >> down
    }
}

/// `2³² / x` for `x > 0` (the raw bits of a `Q16`'s inverse), saturated at `i32::MAX`: the
/// divisor's top half through [`reciprocal_top`], shifted back. Within 2⁻¹³ relative or one
/// unit (tested), with no division.
pub(super) fn reciprocal_bits(x: u32) -> u32 {
    let shift = 32 - width(x);
    let z = reciprocal_top((x << shift) >> 16);
    // `1/x = 2^shift / (x·2^shift)` and `1/(x·2^shift) ≈ z / 2⁴⁷`.
    scaled_by(z, shift)
}

/// `1/√u` at the middle of each eighth of `u ∈ [1, 4)`, in units of 2⁻¹⁶: the first guess of
/// [`inv_sqrt_bits`], within 3% everywhere (tested).
const INV_SQRT_GUESS: [u32; 24] = [
    63579, 60140, 57205, 54661, 52429, 50450, 48679, 47082, 45633, 44310, 43096, 41977, 40940,
    39977, 39078, 38238, 37449, 36708, 36008, 35347, 34722, 34128, 33564, 33027,
];

/// The raw bits of `1/√x` for the raw bits `x > 0` of a `Q16`, in 32-bit arithmetic only (no
/// 64-bit multiply or divide, which a Cortex-M0 calls a library for): `x = u·2³⁰ / 4^k` with
/// `u ∈ [1, 4)`, a guess from [`INV_SQRT_GUESS`] and two Newton steps on `1/√u` in 16
/// fractional bits, shifted back: straight-line code, at most 117 instructions there.
pub(super) fn inv_sqrt_bits(x: u32) -> u32 {
    let (mut m, mut k) = (x, 0u32);
    for (below, shift) in [
        (1u32 << 16, 16u32),
        (1 << 24, 8),
        (1 << 28, 4),
        (1 << 30, 2),
    ] {
        if m < below {
            m <<= shift;
            k += shift / 2;
        }
    }
    let z = inv_sqrt_unit(m);
    // `1/√x = z · 2^(k−7)` in 16 fractional bits.
    if k >= 7 {
        z << (k - 7)
    } else {
        let s = 7 - k;
        (z + (1 << (s - 1))) >> s
    }
}

/// `z ≈ 2¹⁶ / √u` for `u = m / 2³⁰ ∈ [1, 4)` (`m ≥ 2³⁰`), in `(2¹⁵, 2¹⁶]`: a guess from
/// [`INV_SQRT_GUESS`] and two Newton steps, within about `2⁻¹⁵` relative.
#[inline]
fn inv_sqrt_unit(m: u32) -> u32 {
    // `u` in its 16-bit halves, `z` in 16 fractional bits: every product fits 32 bits.
    let (high, low) = (m >> 16, m & 0xffff);
    // `m >> 27` is 8..=31 for any `x > 0`; the clamp only spares a bounds check.
    let mut z = INV_SQRT_GUESS[(m >> 27).saturating_sub(8).min(23) as usize];
    for _ in 0..2 {
        // `z` stays at or below 1 (Newton's steps approach from below), so only `z = 1`
        // would overflow its square.
        let z2 = if z >= 1 << 16 {
            1 << 16
        } else {
            (z * z + (1 << 15)) >> 16
        };
        // `1 − u·z²` in 30 fractional bits, then `z += z·(1 − u·z²)/2`.
        let uz2 = high * z2 + ((low * z2) >> 16);
        let e = ((1u32 << 30) as i32).wrapping_sub(uz2 as i32);
        z = (z as i32 + ((z as i32 * (e >> 12) + (1 << 18)) >> 19)) as u32;
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scalar;

    #[test]
    fn both_multiplications_agree_bit_for_bit() {
        // Edges, then a deterministic spread over the whole range.
        let edges = [
            i32::MIN,
            i32::MIN + 1,
            -65536,
            -65535,
            -32768,
            -1,
            0,
            1,
            32767,
            32768,
            65535,
            65536,
            i32::MAX,
        ];
        for &a in &edges {
            for &b in &edges {
                assert_eq!(mul_halves(a, b), mul_wide(a, b), "{a} {b}");
            }
        }
        // Products at the edge of the range, where rounding decides saturation.
        for a in [
            3i32,
            65537,
            11_863_283,
            -11_863_284,
            1 << 20,
            -(1 << 30) - 7,
        ] {
            for edge in [i32::MAX as i64, i32::MIN as i64] {
                let b0 = ((edge << 16) / a as i64) as i32;
                for b in b0 - 2..=b0 + 2 {
                    assert_eq!(mul_halves(a, b), mul_wide(a, b), "{a} {b}");
                    assert_eq!(mul_halves(-a, b), mul_wide(-a, b), "{a} {b}");
                }
            }
        }
        // Either side of the 32-bit sum's limit (`A·B < 2¹⁵`, `A` = |high half| rounded up),
        // with every sign and the extreme low halves.
        let lows = [0, 1, 0x7fff, 0x8000, 0xffff];
        for big_a in [1, 2, 3, 7, 128, 181, 182, 1000, 16384, 32767, 32768] {
            let edge = (1 << 15) / big_a;
            for big_b in (edge - 2).max(1)..=(edge + 2).min(32768) {
                for (ah, bh) in [
                    (big_a - 1, big_b - 1),
                    (-big_a, big_b - 1),
                    (big_a - 1, -big_b),
                    (-big_a, -big_b),
                ] {
                    for al in lows {
                        for bl in lows {
                            let (a, b) = ((ah << 16) | al, (bh << 16) | bl);
                            assert_eq!(mul_halves(a, b), mul_wide(a, b), "{a} {b}");
                        }
                    }
                }
            }
        }
        // Either side of the two-multiply factor's limit (`-2¹⁵ <= b < 2¹⁵`), against any `a`.
        let factors = [
            -32770, -32769, -32768, -32767, -1, 0, 1, 32766, 32767, 32768, 32769,
        ];
        for &b in &factors {
            for &a in &edges {
                assert_eq!(mul_halves(a, b), mul_wide(a, b), "{a} {b}");
            }
        }
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let (a, b) = (x as i32, (x >> 32) as i32);
            assert_eq!(mul_halves(a, b), mul_wide(a, b), "{a} {b}");
            let (a, b) = (a >> (x % 17), b >> ((x >> 8) % 17)); // smaller magnitudes too
            assert_eq!(mul_halves(a, b), mul_wide(a, b), "{a} {b}");
            let (a, b) = (x as i32, (x >> 32) as i32 >> 16); // any `a`, a factor within ±½
            assert_eq!(mul_halves(a, b), mul_wide(a, b), "{a} {b}");
        }
    }

    #[test]
    fn square_from_halves_is_exact() {
        for r in [
            0u32,
            1,
            0xffff,
            0x1_0000,
            0x8000_0000,
            u32::MAX,
            123_456_789,
        ] {
            assert_eq!(square(r), r as u64 * r as u64, "{r}");
        }
    }

    #[test]
    fn isqrt_matches_core() {
        for n in (0u64..5000).chain([u64::MAX, u64::MAX - 1, 1 << 62, (1 << 62) - 1, 3 << 62]) {
            assert_eq!(isqrt(n), n.isqrt(), "{n}");
        }
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let n = x >> (x % 64);
            assert_eq!(isqrt(n), n.isqrt(), "{n}");
            let sq = (n >> 33) * (n >> 33); // perfect squares and their neighbours
            for m in [sq.saturating_sub(1), sq, sq + 1] {
                assert_eq!(isqrt(m), m.isqrt(), "{m}");
            }
        }
    }

    #[test]
    fn inverse_square_root_holds_its_bound() {
        let (mut worst_rel, mut worst_ulp) = (0.0f64, 0.0f64);
        let mut x: u32 = 1;
        while x < i32::MAX as u32 {
            let got = inv_sqrt_bits(x) as f64;
            let exact = 16_777_216.0 / (x as f64).sqrt();
            let err = (got - exact).abs();
            assert!(
                err <= (exact / 32768.0).max(1.0),
                "x {x}: {got} against {exact}"
            );
            worst_rel = worst_rel.max(err / exact);
            worst_ulp = worst_ulp.max(err);
            x = x + 1 + x / 4099;
        }
        for (i, &g) in INV_SQRT_GUESS.iter().enumerate() {
            let mid = (i as f64 + 8.5) / 8.0;
            assert_eq!(g, (65536.0 / mid.sqrt()).round() as u32);
        }
        assert_eq!(Q16::ONE.inv_sqrt(), Q16::ONE);
        assert_eq!(Q16::from_i16(4).inv_sqrt(), Q16::ratio(1, 2));
        assert_eq!(Q16::ZERO.inv_sqrt(), Q16::ZERO);
        assert_eq!(Q16::from_i16(-3).inv_sqrt(), Q16::ZERO);
        std::println!("worst {worst_rel:e} relative, {worst_ulp} ulp");
    }

    #[test]
    fn long_division_matches_the_wide_one() {
        let edges = [
            0,
            1,
            -1,
            2,
            3,
            0xffff,
            0x1_0000,
            0x1_0001,
            0x7fff_ffff,
            i32::MIN,
            i32::MIN + 1,
            0x4000_0000,
            -0x4000_0000,
            0x8000,
            -0x8000,
            12345,
            -98765,
            // Ties: `1 / 2¹⁷`, `3 / (3·2¹⁷)`, `5 / 2¹⁷`.
            0x2_0000,
            0x6_0000,
            5,
            -0x2_0000,
        ];
        for &a in &edges {
            for &b in &edges {
                assert_eq!(div_long(a, b), div_wide(a, b), "{a} / {b}");
            }
        }
        // Random pairs over every magnitude: raw bits shifted by a random amount.
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for _ in 0..600_000 {
            let r = next();
            let a = (r as i32) >> ((r >> 32) % 32);
            let b = ((r >> 32) as i32) >> ((r >> 40) % 32);
            assert_eq!(div_long(a, b), div_wide(a, b), "{a} / {b}");
        }
        // Quotients next to a saturating one, and divisors at every top-half boundary.
        for b in [1i32, 2, 3, 0x7fff, 0xffff] {
            for a in [b << 15, (b << 15) - 1, i32::MAX, i32::MIN, -(b << 15)] {
                assert_eq!(div_long(a, b), div_wide(a, b), "{a} / {b}");
            }
        }
        for t in (1u32 << 15..1 << 16).step_by(97) {
            for b in [(t << 15) as i32, ((t << 15) | 0x7fff) as i32, t as i32] {
                for a in [1, 0x7fff_ffff, b - 1, -b / 3, 0x1234_5678] {
                    assert_eq!(div_long(a, b), div_wide(a, b), "{a} / {b}");
                }
            }
        }
    }

    #[test]
    fn quick_reciprocal_and_root_inverse_hold_their_bounds() {
        let within = |got: u32, exact: f64, relative: f64| {
            let exact = exact.min(i32::MAX as f64);
            (got as f64 - exact).abs() <= (exact * relative).max(1.0)
        };
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut samples = std::vec::Vec::new();
        for k in 0..31 {
            samples.extend([1u32 << k, (1u32 << k) + 1, (2u32 << k) - 1]);
        }
        for _ in 0..300_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            samples.push((x as u32 >> 1) >> ((x >> 40) % 31));
        }
        for &v in samples.iter().filter(|&&v| v > 0) {
            let exact = 4_294_967_296.0 / v as f64;
            assert!(within(reciprocal_bits(v), exact, 1.0 / 8192.0), "1/{v}");
            // A vector's squared bits: `v²` and sums past 2⁶².
            for n in [square(v), square(v) * 3, u64::from(v)] {
                let (root, inverse) = root_and_inverse(n);
                assert_eq!(u64::from(root), n.isqrt(), "{n}");
                let exact = 4_294_967_296.0 / (n as f64).sqrt();
                assert!(
                    within(inverse, exact, 1.0 / 16384.0),
                    "1/sqrt {n}: {inverse}"
                );
            }
        }
        assert_eq!(root_and_inverse(0), (0, 0));
    }

    #[test]
    fn reciprocal_of_every_top_half_is_a_close_underestimate() {
        for t in 1u32 << 15..1 << 16 {
            let z = u64::from(reciprocal_top(t));
            let product = z * u64::from(t);
            assert!(product <= 1 << 31, "{t}: {z}");
            // Within 2⁻¹⁴ of `2³¹ / t`.
            assert!(product + (1 << 17) > 1 << 31, "{t}: {z}");
        }
    }
}
