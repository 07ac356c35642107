//! The number formats every algorithm is written against: `f32`, `f64` and [`Q16`](crate::Q16).
//!
//! Each algorithm in the crate is generic over [`Scalar`], so a rope runs in `f64` on a
//! desktop, in `f32` on a Cortex-M4F and in Q16.16 on a Cortex-M0 without a second copy of
//! the code. Float math (square roots) goes through one private module that picks `std` or
//! `libm`; the fast approximations of `micromath` are only reached through the explicitly
//! named `approx_*` methods.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// A real number format: `f32`, `f64` or [`Q16`](crate::Q16).
///
/// Arithmetic operators never panic. Floats follow IEEE 754; `Q16` saturates at its range
/// and reports saturation through [`is_finite`](Scalar::is_finite).
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not a dunas `Scalar` in this build",
    note = "`f32` and `f64` are `Scalar`s with the `std` or the `libm` feature (a bare-metal build always has `libm`); `Q16` with the `fixed` feature"
)]
pub trait Scalar:
    Copy
    + Default
    + Debug
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// Largest coordinate magnitude constructors accept.
    ///
    /// Inside this range the differences, second differences and lengths the crate computes
    /// cannot overflow: `1e18` for `f32`, `1e150` for `f64`, `16383` for `Q16` (so that the
    /// difference of two coordinates still fits in Q16.16's ±32768).
    const SAFE_RANGE: Self;
    /// Spacing of representable numbers just above 1 (the unit of rounding error).
    const EPSILON: Self;
    /// `true` for fixed-point formats, where multiplications are costly on the target and
    /// parameters should be dyadic; picks the default sampler.
    const FIXED_POINT: bool;

    /// Converts from `f64`, rounding to nearest; out-of-range values saturate (`Q16`) and NaN
    /// becomes 0 in `Q16`. Meant for setup code, not the per-frame path on FPU-less chips.
    fn from_f64(x: f64) -> Self;
    /// Converts to `f64` (exact for all three formats).
    fn to_f64(self) -> f64;
    /// The value's bits, as a key: equal exactly when the two values are the same number in
    /// the same encoding (a float's `0` and `−0` differ). The default goes through
    /// [`to_f64`](Self::to_f64); the crate's formats read their bits directly.
    #[inline]
    fn bits(self) -> u64 {
        self.to_f64().to_bits()
    }
    /// `num / den` rounded to nearest; `den == 0` gives 0.
    fn ratio(num: u32, den: u32) -> Self;
    /// Square root; negative inputs give 0. Exact to the format's rounding.
    fn sqrt(self) -> Self;
    /// Square root that may trade accuracy for speed: micromath's approximation for `f32`
    /// when the `micromath` feature is on (at most 6.1%, measured over 1e-3..1e3), otherwise [`sqrt`](Self::sqrt).
    #[inline]
    fn approx_sqrt(self) -> Self {
        self.sqrt()
    }
    /// `1 / sqrt(self)`, possibly approximate: micromath's (at most 3.5%, measured over 1e-3..1e3) for `f32`
    /// with the `micromath` feature. Non-positive input gives 0.
    #[inline]
    fn approx_inv_sqrt(self) -> Self {
        let s = self.sqrt();
        if s > Self::ZERO {
            Self::ONE / s
        } else {
            Self::ZERO
        }
    }
    /// `1 / sqrt(self)`, for a direction and a length from one squared length; non-positive
    /// or NaN input gives 0. Floats: a square root and a division, exact to their rounding.
    /// `Q16`: 32-bit integer steps only, within 2⁻¹⁵ relative or one unit of 2⁻¹⁶.
    #[inline]
    fn inv_sqrt(self) -> Self {
        if self > Self::ZERO {
            Self::ONE / self.sqrt()
        } else {
            Self::ZERO
        }
    }
    /// `1 / self` for `self > 0`, possibly approximate; 0 otherwise. Floats: a division,
    /// exact to its rounding. `Q16`: a table and one Newton step in 32-bit integers, within
    /// 2⁻¹³ relative or one unit of 2⁻¹⁶ (no division: for a solve's pivots, where the last
    /// bits change no result that matters).
    #[inline]
    fn approx_recip(self) -> Self {
        if self > Self::ZERO {
            Self::ONE / self
        } else {
            Self::ZERO
        }
    }
    /// Absolute value (saturating for `Q16`).
    fn abs(self) -> Self;
    /// `false` for NaN and infinities, and for a `Q16` that has saturated to its range.
    fn is_finite(self) -> bool;
    /// `(a + b) / 2` without intermediate overflow. Exact in floats; in `Q16` rounded to
    /// nearest (ties up) by a shift, with no multiply.
    fn midpoint(a: Self, b: Self) -> Self;
    /// Euclidean norm `sqrt(sum xs[i]^2)` of up to 3 coordinates, computed so that it does
    /// not overflow for coordinates inside the format's range (`Q16` uses a 64-bit
    /// accumulator, so vectors longer than 181 are fine).
    fn norm(xs: &[Self]) -> Self;
    /// Whether [`norm`](Self::norm)`(xs)` is below `limit`, without its root: floats
    /// compare the sum of squares with `limit²` (to rounding), `Q16` its exact 64-bit sum.
    #[inline]
    fn norm_below(xs: &[Self], limit: Self) -> bool {
        Self::norm(xs) < limit
    }
    /// Whether [`norm`](Self::norm)`(xs)` is above `norm(ys)`, without the roots: floats
    /// compare the sums of squares (to rounding), `Q16` its exact 64-bit sums (the longer by
    /// them has a root at least as large).
    #[inline]
    fn norm_above(xs: &[Self], ys: &[Self]) -> bool {
        Self::norm(xs) > Self::norm(ys)
    }
    /// [`norm`](Self::norm) and its inverse (0 for a zero norm), for a length and a
    /// direction at once. Floats: a division, exact to its rounding. `Q16`: the norm as
    /// exact as [`norm`](Self::norm)'s, the inverse from the root's own reciprocal estimate,
    /// within 2⁻¹⁴ relative or one unit of 2⁻¹⁶ (no division).
    #[inline]
    fn norm_and_inverse(xs: &[Self]) -> (Self, Self) {
        let n = Self::norm(xs);
        (n, n.approx_recip())
    }
    /// `ceil(self)` as a `usize`, clamped to `0..=max`; NaN gives `max`.
    fn ceil_usize(self, max: usize) -> usize;
    /// `floor(self)` as an `i32`, saturating at the `i32` range; NaN gives 0.
    fn floor_i32(self) -> i32;

    /// The larger of two values (`other` if they are unordered).
    #[inline]
    fn max(self, other: Self) -> Self {
        if self > other { self } else { other }
    }
    /// The smaller of two values (`other` if they are unordered).
    #[inline]
    fn min(self, other: Self) -> Self {
        if self < other { self } else { other }
    }
    /// A small integer as a scalar (exact for `|i| <= 16383` in every format).
    fn from_i16(i: i16) -> Self;
    /// `self`, or 0 when `|self| < tiny`: the flush of values that decay towards a float's
    /// subnormals. Floats compare their bits, in integer steps, for a `tiny` from `+0` to
    /// `+∞` (any other compares as floats do).
    #[inline]
    fn flush_tiny(self, tiny: Self) -> Self {
        if self.abs() < tiny { Self::ZERO } else { self }
    }
    /// `|self| ≤ limit`, `false` for NaN. Floats compare their bits, in integer steps (a
    /// subtraction whose sign says it), for a `limit` from `+0` to `+∞` (any other compares
    /// as floats do).
    #[inline]
    fn within(self, limit: Self) -> bool {
        self.abs() <= limit
    }
    /// `true` when the value is finite and `|self| <= SAFE_RANGE`.
    #[inline]
    fn in_safe_range(self) -> bool {
        self.is_finite() && self.abs() <= Self::SAFE_RANGE
    }
}

#[cfg(dunas_floats)]
macro_rules! impl_float {
    ($t:ty, $sqrt:path, $range:expr, { $($extra:tt)* }) => {
        impl Scalar for $t {
            $($extra)*

            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const SAFE_RANGE: Self = $range;
            const EPSILON: Self = <$t>::EPSILON;
            const FIXED_POINT: bool = false;

            #[inline]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn bits(self) -> u64 {
                u64::from(self.to_bits())
            }
            #[inline]
            fn ratio(num: u32, den: u32) -> Self {
                if den == 0 { 0.0 } else { num as $t / den as $t }
            }
            #[inline]
            fn sqrt(self) -> Self {
                if self > 0.0 { $sqrt(self) } else { 0.0 }
            }
            #[inline]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
            #[inline]
            fn midpoint(a: Self, b: Self) -> Self {
                a * 0.5 + b * 0.5
            }
            #[inline]
            fn norm_below(xs: &[Self], limit: Self) -> bool {
                let mut s = 0.0;
                for &x in xs {
                    s += x * x;
                }
                limit > 0.0 && s < limit * limit
            }
            #[inline]
            fn norm_above(xs: &[Self], ys: &[Self]) -> bool {
                let squares = |v: &[Self]| v.iter().fold(0.0, |s, &x| s + x * x);
                squares(xs) > squares(ys)
            }
            #[inline]
            fn norm(xs: &[Self]) -> Self {
                // Coordinates are bounded by SAFE_RANGE, whose square fits the format.
                let mut s = 0.0;
                for &x in xs {
                    s += x * x;
                }
                Scalar::sqrt(s)
            }
            #[inline]
            fn ceil_usize(self, max: usize) -> usize {
                if self.is_nan() || self >= max as $t {
                    return max;
                }
                if self <= 0.0 {
                    return 0;
                }
                let n = self as usize; // truncation, self is in 0..max
                if (n as $t) < self { n + 1 } else { n }
            }
            #[inline]
            fn from_i16(i: i16) -> Self {
                i as $t
            }
            // A float's magnitude is its bits without the sign: ordered as the values, NaN
            // above infinity. A bound from +0 to +∞ has the bits of its magnitude (−0 is
            // made +0 by adding +0); a negative or NaN one holds nothing.
            #[inline]
            fn flush_tiny(self, tiny: Self) -> Self {
                let sign = (-0.0 as $t).to_bits();
                let bound = (tiny + 0.0).to_bits();
                let small = self.to_bits() & !sign < bound;
                if small && bound <= <$t>::INFINITY.to_bits() { 0.0 } else { self }
            }
            #[inline]
            fn within(self, limit: Self) -> bool {
                let sign = (-0.0 as $t).to_bits();
                let bound = (limit + 0.0).to_bits();
                let inside = bound.wrapping_sub(self.to_bits() & !sign) & sign == 0;
                inside & (bound <= <$t>::INFINITY.to_bits())
            }
            #[inline]
            fn floor_i32(self) -> i32 {
                // `as` saturates and maps NaN to 0; step down for negative non-integers.
                let t = self as i32;
                if (t as $t) > self { t.saturating_sub(1) } else { t }
            }
        }
    };
}

#[cfg(dunas_floats)]
impl_float!(f32, crate::number::math::sqrt_f32, 1e18, {
    #[inline]
    fn approx_sqrt(self) -> Self {
        approx_f32::sqrt(self)
    }
    #[inline]
    fn approx_inv_sqrt(self) -> Self {
        approx_f32::inv_sqrt(self)
    }
});
#[cfg(dunas_floats)]
impl_float!(f64, crate::number::math::sqrt_f64, 1e150, {});

/// Fast approximate roots for `f32` (see the `micromath` feature).
#[cfg(dunas_floats)]
mod approx_f32 {
    /// Approximate `sqrt`.
    #[inline]
    pub fn sqrt(x: f32) -> f32 {
        if x > 0.0 {
            crate::number::math::approx_sqrt_f32(x)
        } else {
            0.0
        }
    }
    /// Approximate `1 / sqrt`.
    #[inline]
    pub fn inv_sqrt(x: f32) -> f32 {
        if x > 0.0 {
            crate::number::math::approx_inv_sqrt_f32(x)
        } else {
            0.0
        }
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;

    /// The floats' `norm_below` answers as the root would, but at the rounding of a limit
    /// within a few ulps of the norm: 3-4-5 triangles exactly, and random vectors in `f64`.
    #[test]
    fn norm_below_answers_as_the_root() {
        assert!(!f32::norm_below(&[3.0, 4.0], 5.0) && f32::norm_below(&[3.0, 4.0], 5.0001));
        assert!(!f64::norm_below(&[0.0, 0.0], 0.0) && !f64::norm_below(&[1.0], -2.0));
        let mut x = 0.5f64;
        for _ in 0..10_000 {
            let mut next = || {
                x = (x * 3.9 * (1.0 - x)).clamp(1e-9, 1.0 - 1e-9);
                (x - 0.5) * 200.0
            };
            let (xs, limit) = ([next(), next(), next()], next().abs());
            let norm = f64::norm(&xs);
            if (norm - limit).abs() > 1e-12 * limit {
                assert_eq!(f64::norm_below(&xs, limit), norm < limit, "{xs:?} {limit}");
            }
        }
    }

    /// Floats' `norm_above` answers as the roots do, for vectors whose norms are apart by
    /// more than their rounding: 3-4-5 triangles exactly, and random vectors in `f64`.
    #[test]
    fn norm_above_answers_as_the_roots() {
        assert!(!f32::norm_above(&[3.0, 4.0], &[0.0, 5.0]));
        assert!(f32::norm_above(&[3.0, 4.0], &[0.0, 4.999]));
        let mut x = 0.3f64;
        for _ in 0..10_000 {
            let mut next = || {
                x = (x * 3.9 * (1.0 - x)).clamp(1e-9, 1.0 - 1e-9);
                (x - 0.5) * 200.0
            };
            let (xs, ys) = ([next(), next(), next()], [next(), next(), next()]);
            let (a, b) = (f64::norm(&xs), f64::norm(&ys));
            if (a - b).abs() > 1e-12 * a.max(b) {
                assert_eq!(f64::norm_above(&xs, &ys), a > b, "{xs:?} {ys:?}");
            }
        }
    }

    /// The floats' bit tests of `flush_tiny` and `within` answer as the float comparisons
    /// do, for every pair of edge values: signed zeros, subnormals, infinities, NaN, and
    /// negative bounds.
    #[test]
    fn bit_tests_agree_with_the_comparisons() {
        let edges = [
            0.0f32,
            -0.0,
            f32::MIN_POSITIVE / 4.0,
            -f32::MIN_POSITIVE,
            f32::EPSILON * f32::EPSILON,
            1.0,
            -1.0,
            1e18,
            -3e38,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
        ];
        for &x in &edges {
            for &bound in &edges {
                let flushed = if x.abs() < bound { 0.0 } else { x };
                assert_eq!(
                    x.flush_tiny(bound).to_bits(),
                    flushed.to_bits(),
                    "{x} {bound}"
                );
                assert_eq!(x.within(bound), x.abs() <= bound, "{x} {bound}");
                let (x, bound) = (f64::from(x), f64::from(bound));
                let flushed = if x.abs() < bound { 0.0 } else { x };
                assert_eq!(
                    x.flush_tiny(bound).to_bits(),
                    flushed.to_bits(),
                    "{x} {bound}"
                );
                assert_eq!(x.within(bound), x.abs() <= bound, "{x} {bound}");
            }
        }
    }

    #[test]
    fn ratio_is_correctly_rounded() {
        assert_eq!(<f32 as Scalar>::ratio(1, 3), 1.0f32 / 3.0);
        assert_eq!(<f64 as Scalar>::ratio(7, 1023), 7.0 / 1023.0);
        assert_eq!(<f64 as Scalar>::ratio(7, 0), 0.0);
    }

    #[test]
    fn ceil_usize_clamps_and_rounds_up() {
        assert_eq!(2.0f64.ceil_usize(100), 2);
        assert_eq!(2.0001f64.ceil_usize(100), 3);
        assert_eq!((-5.0f32).ceil_usize(100), 0);
        assert_eq!(f32::NAN.ceil_usize(100), 100);
        assert_eq!(f64::INFINITY.ceil_usize(100), 100);
        assert_eq!(1e30f32.ceil_usize(100), 100);
    }

    #[test]
    fn floor_i32_rounds_down_and_saturates() {
        assert_eq!(2.7f32.floor_i32(), 2);
        assert_eq!((-2.2f64).floor_i32(), -3);
        assert_eq!((-2.0f64).floor_i32(), -2);
        assert_eq!(f32::NAN.floor_i32(), 0);
        assert_eq!(1e30f32.floor_i32(), i32::MAX);
        assert_eq!((-1e30f64).floor_i32(), i32::MIN);
    }

    #[test]
    fn sqrt_of_negative_is_zero_not_nan() {
        assert_eq!(Scalar::sqrt(-4.0f32), 0.0);
        assert_eq!(Scalar::sqrt(f64::NAN), 0.0);
        assert_eq!(Scalar::sqrt(9.0f64), 3.0);
    }

    #[test]
    fn norm_does_not_overflow_at_safe_range() {
        let r = <f32 as Scalar>::SAFE_RANGE;
        let n = <f32 as Scalar>::norm(&[r, r, r]);
        assert!(n.is_finite());
        assert!((n / r - 3f32.sqrt()).abs() < 1e-6);
    }

    /// The documented worst cases of the approximate roots: exact without `micromath`, within
    /// 6.1% (sqrt) and 3.5% (inverse sqrt) with it, over six decades.
    #[test]
    fn approximate_roots_hold_their_documented_error() {
        let (mut worst_sqrt, mut worst_inv) = (0.0f64, 0.0f64);
        let mut x = 1e-3f32;
        while x < 1e3 {
            let exact = (x as f64).sqrt();
            worst_sqrt = worst_sqrt.max((x.approx_sqrt() as f64 / exact - 1.0).abs());
            worst_inv = worst_inv.max((x.approx_inv_sqrt() as f64 * exact - 1.0).abs());
            x *= 1.001;
        }
        std::eprintln!("approx sqrt {worst_sqrt:.4}, inverse sqrt {worst_inv:.4}");
        if cfg!(feature = "micromath") {
            assert!(
                worst_sqrt < 0.061 && worst_inv < 0.035,
                "{worst_sqrt} {worst_inv}"
            );
            assert!(worst_sqrt > 0.01, "micromath is really in use");
        } else {
            assert!(worst_sqrt < 1e-7 && worst_inv < 2e-7);
        }
        assert_eq!((-1.0f32).approx_sqrt(), 0.0);
        assert_eq!(0.0f32.approx_inv_sqrt(), 0.0);
    }

    #[test]
    fn from_i16_is_exact() {
        assert_eq!(<f32 as Scalar>::from_i16(-16383), -16383.0);
        assert_eq!(<f64 as Scalar>::from_i16(7), 7.0);
    }
}
