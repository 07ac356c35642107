//! Q16.16 fixed point for chips without an FPU (feature `fixed`).
//!
//! [`Q16`] wraps [`fixed::types::I16F16`] (range ±32768, resolution 2⁻¹⁶ ≈ 1.5e-5) and
//! gives it the arithmetic a game loop can rely on:
//!
//! - products are computed in 64 bits and rounded to nearest before the shift back;
//! - `+ - * /` saturate at the range instead of wrapping; a saturated value reports
//!   `is_finite() == false`, so the same guard that catches NaN in floats catches overflow
//!   here; division by zero saturates (0 / 0 gives 0);
//! - halving and [`midpoint`](crate::Scalar::midpoint) are shifts with no multiply.
//!
//! # Safe range
//!
//! A squared length overflows Q16.16 once a vector is longer than about 181 (181² > 32768).
//! The crate never squares a coordinate on its own: [`Scalar::norm`] sums squares of the raw
//! bits in a 64-bit accumulator and takes an integer square root, so lengths are exact up
//! to the full range. Constructors accept coordinates up to `±16383` ([`Scalar::SAFE_RANGE`])
//! so that the difference of any two stays representable. Keep a scene inside that range by
//! working relative to an anchor (the rope's pin, the sail's mast) and in screen-sized units.

use core::fmt;
use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use fixed::types::I16F16;

#[cfg(not(target_pointer_width = "64"))]
use super::q16_bits::div_long;
#[cfg(target_pointer_width = "64")]
use super::q16_bits::div_wide;
#[cfg(not(dunas_wide_mul))]
use super::q16_bits::mul_halves;
#[cfg(dunas_wide_mul)]
use super::q16_bits::mul_wide;
use super::q16_bits::{inv_sqrt_bits, isqrt, reciprocal_bits, root_and_inverse, square};
use crate::Scalar;

/// A Q16.16 fixed-point number with saturating, round-to-nearest arithmetic.
///
/// ```
/// use dunas::{Q16, Scalar};
/// let a = Q16::from_f64(1.5);
/// assert_eq!((a * a).to_f64(), 2.25);
/// assert!(!(Q16::from_f64(30000.0) * a).is_finite()); // saturated, and says so
///
/// const DT: Q16 = Q16::ratio(1, 60); // constants, of either sign
/// const GRAVITY: Q16 = Q16::ratio(-981, 100);
/// const LIMIT: Q16 = Q16::from_int(100);
/// assert_eq!(DT.to_bits(), 1092);
/// assert_eq!(GRAVITY.to_bits(), -642_908); // -9.81 · 65 536, rounded
/// assert_eq!(LIMIT.max(DT), LIMIT); // no ambiguity between Ord and Scalar
/// ```
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct Q16(pub I16F16);

impl Q16 {
    /// The largest value, `32767.99998`; also the saturation marker.
    pub const MAX: Q16 = Q16(I16F16::MAX);
    /// The smallest value, `-32768`; also the saturation marker.
    pub const MIN: Q16 = Q16(I16F16::MIN);

    /// Builds a value from its raw bits (`value * 65536`).
    #[inline]
    pub const fn from_bits(bits: i32) -> Q16 {
        Q16(I16F16::from_bits(bits))
    }

    /// The raw bits (`value * 65536`).
    #[inline]
    pub const fn to_bits(self) -> i32 {
        self.0.to_bits()
    }

    /// `n` as a `Q16`, in `const` context: `const LIMIT: Q16 = Q16::from_int(100);`.
    #[inline]
    pub const fn from_int(n: i16) -> Q16 {
        Q16::from_bits((n as i32) << 16)
    }

    /// `num / den` rounded to nearest (halves away from zero), saturated at the range, in
    /// `const` context and for either sign: `const DT: Q16 = Q16::ratio(1, 60);`,
    /// `Q16::ratio(-981, 100)`. A zero `den` gives 0. (This inherent `ratio` takes signed
    /// numbers; generic code calls [`Scalar::ratio`], which takes unsigned ones.)
    #[inline]
    pub const fn ratio(num: i32, den: i32) -> Q16 {
        if den == 0 {
            return Q16::from_bits(0);
        }
        let negative = (num < 0) != (den < 0);
        let (n, d) = (
            (num as i64).unsigned_abs() << 16,
            (den as i64).unsigned_abs(),
        );
        let q = ((n + d / 2) / d) as i64;
        Q16::saturate(if negative { -q } else { q })
    }

    /// The larger of two values. (Inherent, so `a.max(b)` is not ambiguous between
    /// [`Ord::max`] and [`Scalar::max`]; all three agree.)
    #[inline]
    pub const fn max(self, other: Q16) -> Q16 {
        if self.to_bits() >= other.to_bits() {
            self
        } else {
            other
        }
    }

    /// The smaller of two values (inherent, as [`max`](Self::max)).
    #[inline]
    pub const fn min(self, other: Q16) -> Q16 {
        if self.to_bits() <= other.to_bits() {
            self
        } else {
            other
        }
    }

    #[inline]
    pub(super) const fn saturate(wide: i64) -> Q16 {
        if wide > i32::MAX as i64 {
            Q16::MAX
        } else if wide < i32::MIN as i64 {
            Q16::MIN
        } else {
            Q16::from_bits(wide as i32)
        }
    }
}

impl From<I16F16> for Q16 {
    #[inline]
    fn from(x: I16F16) -> Q16 {
        Q16(x)
    }
}

impl From<Q16> for I16F16 {
    #[inline]
    fn from(x: Q16) -> I16F16 {
        x.0
    }
}

impl fmt::Debug for Q16 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&self.0, f)
    }
}

impl fmt::Display for Q16 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

impl Add for Q16 {
    type Output = Q16;
    #[inline]
    fn add(self, rhs: Q16) -> Q16 {
        Q16::from_bits(self.to_bits().saturating_add(rhs.to_bits()))
    }
}

impl Sub for Q16 {
    type Output = Q16;
    #[inline]
    fn sub(self, rhs: Q16) -> Q16 {
        Q16::from_bits(self.to_bits().saturating_sub(rhs.to_bits()))
    }
}

impl Neg for Q16 {
    type Output = Q16;
    #[inline]
    fn neg(self) -> Q16 {
        Q16::from_bits(self.to_bits().saturating_neg())
    }
}

impl Mul for Q16 {
    type Output = Q16;
    /// Product rounded to nearest (ties up), saturated. 64-bit multiply where the core has
    /// one, 32-bit halves elsewhere; the results are identical bit for bit.
    #[inline]
    fn mul(self, rhs: Q16) -> Q16 {
        #[cfg(dunas_wide_mul)]
        {
            mul_wide(self.to_bits(), rhs.to_bits())
        }
        #[cfg(not(dunas_wide_mul))]
        {
            mul_halves(self.to_bits(), rhs.to_bits())
        }
    }
}

impl Div for Q16 {
    type Output = Q16;
    /// Quotient rounded to nearest (ties away from zero), saturated; `x / 0` saturates by the
    /// sign of `x`. A 64-bit division where the core has one; elsewhere (a Cortex-M0) two
    /// 16-bit quotient digits in 32-bit registers, each estimated from a 128-entry table of
    /// reciprocals and made exact by its remainder; the results are identical bit for bit.
    #[inline]
    fn div(self, rhs: Q16) -> Q16 {
        #[cfg(target_pointer_width = "64")]
        {
            div_wide(self.to_bits(), rhs.to_bits())
        }
        #[cfg(not(target_pointer_width = "64"))]
        {
            div_long(self.to_bits(), rhs.to_bits())
        }
    }
}

impl AddAssign for Q16 {
    #[inline]
    fn add_assign(&mut self, rhs: Q16) {
        *self = *self + rhs;
    }
}

impl SubAssign for Q16 {
    #[inline]
    fn sub_assign(&mut self, rhs: Q16) {
        *self = *self - rhs;
    }
}

/// Logged as its value (`defmt`'s `f32` formatting: 24 bits, exact for every `Q16` below 256).
#[cfg(feature = "defmt")]
impl defmt::Format for Q16 {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(f, "{=f32}", self.0.to_num::<f32>());
    }
}

/// The sum of the coordinates' squared raw bits (Q32.32 values below 2⁶² each), saturated.
#[inline]
fn squared_bits(xs: &[Q16]) -> u64 {
    xs.iter().fold(0u64, |acc, x| {
        acc.saturating_add(square(x.to_bits().unsigned_abs()))
    })
}

impl Scalar for Q16 {
    const ZERO: Self = Q16::from_bits(0);
    const ONE: Self = Q16::from_bits(1 << 16);
    const SAFE_RANGE: Self = Q16::from_bits(16383 << 16);
    const EPSILON: Self = Q16::from_bits(1);
    const FIXED_POINT: bool = true;

    #[inline]
    fn bits(self) -> u64 {
        u64::from(self.to_bits() as u32)
    }

    fn from_f64(x: f64) -> Self {
        if x.is_nan() {
            return Self::ZERO;
        }
        Q16(I16F16::saturating_from_num(x))
    }

    #[inline]
    fn to_f64(self) -> f64 {
        self.to_bits() as f64 / 65536.0
    }

    #[inline]
    fn ratio(num: u32, den: u32) -> Self {
        if den == 0 {
            return Self::ZERO;
        }
        let (n, d) = ((num as u64) << 16, den as u64);
        let q = (n + d / 2) / d;
        Q16::saturate(q.min(i64::MAX as u64) as i64)
    }

    #[inline]
    fn sqrt(self) -> Self {
        if self.to_bits() <= 0 {
            Self::ZERO
        } else {
            Q16(self.0.sqrt())
        }
    }

    /// In 32-bit arithmetic (see `inv_sqrt_bits`): within 2⁻¹⁵ of `1/√x` relative, or
    /// one unit of 2⁻¹⁶ where that is larger (tested over the whole range).
    #[inline]
    fn inv_sqrt(self) -> Self {
        let x = self.to_bits();
        if x <= 0 {
            Self::ZERO
        } else {
            Q16::from_bits(inv_sqrt_bits(x as u32) as i32)
        }
    }

    #[inline]
    fn abs(self) -> Self {
        Q16::from_bits(self.to_bits().saturating_abs())
    }

    #[inline]
    fn is_finite(self) -> bool {
        // Neither MIN nor MAX, in one subtraction and one unsigned compare (no branch).
        (self.to_bits().wrapping_sub(i32::MIN + 1) as u32) < u32::MAX - 1
    }

    #[inline]
    fn midpoint(a: Self, b: Self) -> Self {
        // Sum in 64 bits, then a rounding shift: no overflow, no multiply.
        let s = a.to_bits() as i64 + b.to_bits() as i64;
        Q16::from_bits(((s + 1) >> 1) as i32)
    }

    fn norm(xs: &[Self]) -> Self {
        Q16::saturate(isqrt(squared_bits(xs)) as i64)
    }

    #[inline]
    fn norm_below(xs: &[Self], limit: Self) -> bool {
        limit > Q16::ZERO && squared_bits(xs) < square(limit.to_bits().unsigned_abs())
    }

    #[inline]
    fn norm_above(xs: &[Self], ys: &[Self]) -> bool {
        squared_bits(xs) > squared_bits(ys)
    }

    #[inline]
    fn norm_and_inverse(xs: &[Self]) -> (Self, Self) {
        let (root, inverse) = root_and_inverse(squared_bits(xs));
        (
            Q16::saturate(i64::from(root)),
            Q16::from_bits(inverse as i32),
        )
    }

    #[inline]
    fn approx_recip(self) -> Self {
        match self.to_bits() {
            x if x > 0 => Q16::from_bits(reciprocal_bits(x as u32) as i32),
            _ => Self::ZERO,
        }
    }

    #[inline]
    fn floor_i32(self) -> i32 {
        self.to_bits() >> 16
    }

    #[inline]
    fn from_i16(i: i16) -> Self {
        Q16::from_bits((i as i32) << 16)
    }

    #[inline]
    fn ceil_usize(self, max: usize) -> usize {
        let bits = self.to_bits();
        if bits <= 0 {
            return 0;
        }
        let n = ((bits as i64 + 0xFFFF) >> 16) as usize;
        n.min(max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(x: f64) -> Q16 {
        Q16::from_f64(x)
    }

    #[test]
    fn multiply_rounds_to_nearest_and_saturates() {
        assert_eq!(q(1.5) * q(1.5), q(2.25));
        // 3 * 2^-16 times 0.5 is 1.5 ulp: rounds to 2 ulp (ties up).
        assert_eq!((Q16::from_bits(3) * q(0.5)).to_bits(), 2);
        assert_eq!(q(200.0) * q(200.0), Q16::MAX);
        assert_eq!(q(-200.0) * q(200.0), Q16::MIN);
        assert!(!(q(200.0) * q(200.0)).is_finite());
    }

    #[test]
    fn add_saturates_instead_of_wrapping() {
        assert_eq!(q(30000.0) + q(30000.0), Q16::MAX);
        assert_eq!(q(-30000.0) - q(30000.0), Q16::MIN);
        assert_eq!(-Q16::MIN, Q16::MAX);
    }

    #[test]
    fn divide_rounds_and_handles_zero() {
        assert_eq!(q(1.0) / q(4.0), q(0.25));
        assert_eq!((q(1.0) / q(3.0)).to_bits(), 21845); // 65536/3 = 21845.33
        assert_eq!((q(2.0) / q(3.0)).to_bits(), 43691); // 43690.67
        assert_eq!((q(-2.0) / q(3.0)).to_bits(), -43691);
        assert_eq!(q(1.0) / q(0.0), Q16::MAX);
        assert_eq!(q(-1.0) / q(0.0), Q16::MIN);
        assert_eq!(q(0.0) / q(0.0), Q16::ZERO);
        assert_eq!(q(30000.0) / q(0.01), Q16::MAX);
    }

    #[test]
    fn ratio_is_exact_at_dyadic_and_rounded_elsewhere() {
        assert_eq!(Q16::ratio(3, 8), q(0.375));
        assert_eq!(Q16::ratio(1, 3).to_bits(), 21845);
        assert_eq!(Q16::ratio(1, 0), Q16::ZERO);
        assert_eq!(<Q16 as Scalar>::ratio(u32::MAX, 1), Q16::MAX);
        // The inherent, signed `ratio` agrees with the unsigned one and mirrors it.
        for (n, d) in [(1, 60), (981, 100), (7, 3), (65535, 65536), (32767, 1)] {
            let unsigned = <Q16 as Scalar>::ratio(n as u32, d as u32);
            assert_eq!(Q16::ratio(n, d), unsigned);
            assert_eq!(Q16::ratio(-n, d), -unsigned);
            assert_eq!(Q16::ratio(n, -d), -unsigned);
        }
        assert_eq!(Q16::ratio(i32::MAX, 1), Q16::MAX);
        assert_eq!(Q16::ratio(i32::MIN, 1), Q16::MIN);
        assert_eq!(Q16::from_int(-3), q(-3.0));
        assert_eq!(q(2.0).max(q(-1.0)), q(2.0));
        assert_eq!(q(2.0).min(q(-1.0)), q(-1.0));
    }

    #[test]
    fn norm_is_exact_beyond_181() {
        // 3-4-5 scaled far past the point where the squares overflow Q16.16.
        let n = Q16::norm(&[q(3000.0), q(4000.0)]);
        assert_eq!(n, q(5000.0));
        let n = Q16::norm(&[q(16383.0), q(16383.0), q(16383.0)]);
        assert!((n.to_f64() - 16383.0 * 3f64.sqrt()).abs() < 2e-5);
        assert_eq!(Q16::norm(&[Q16::MIN, Q16::MIN]), Q16::MAX);
    }

    /// Random numbers of `bits` significant bits (signed, from units of 2⁻¹⁶), the same
    /// from the same `seed` (a 32-bit linear congruential generator).
    fn random_bits(mut seed: u32) -> impl FnMut(u32) -> Q16 {
        move |bits| {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            Q16::from_bits((seed >> (32 - bits)) as i32 - (1 << (bits - 1)))
        }
    }

    /// `norm_below` answers exactly: against the sum of squares of the coordinates' bits in
    /// `f64` (exact below 2²⁶ bits a coordinate), and as `norm`'s root does.
    #[test]
    fn norm_below_is_exact() {
        let mut next = random_bits(0x2545_f491);
        let (mut below, mut above) = (0, 0);
        for round in 0..20_000 {
            let bits = if round % 2 == 0 { 12 } else { 24 };
            let xs = [next(bits), next(bits), next(bits)];
            let limit = Q16::norm(&xs[..2]) + Q16::from_bits(next(4).to_bits());
            let exact = xs[..2]
                .iter()
                .map(|x| f64::from(x.to_bits()).powi(2))
                .sum::<f64>();
            let answer = Q16::norm_below(&xs[..2], limit);
            assert_eq!(
                answer,
                limit > Q16::ZERO && exact < f64::from(limit.to_bits()).powi(2)
            );
            assert_eq!(answer, Q16::norm(&xs[..2]) < limit, "{xs:?} {limit:?}");
            (below, above) = if answer {
                (below + 1, above)
            } else {
                (below, above + 1)
            };
            assert!(!Q16::norm_below(&xs, Q16::ZERO));
        }
        assert!(below > 1000 && above > 1000, "{below} {above}");
    }

    /// `norm_above` answers exactly: against the sums of squares of the coordinates' bits in
    /// `f64` (exact below 2²⁶ bits a coordinate), and the longer by it never has the shorter
    /// root; equal vectors are not above each other.
    #[test]
    fn norm_above_is_exact() {
        let mut next = random_bits(0x1b87_3593);
        let exact = |v: &[Q16]| {
            v.iter()
                .map(|x| f64::from(x.to_bits()).powi(2))
                .sum::<f64>()
        };
        let (mut above, mut not) = (0, 0);
        for round in 0..20_000 {
            let bits = if round % 2 == 0 { 12 } else { 24 };
            let xs = [next(bits), next(bits)];
            // Every third pair one unit apart in a coordinate, where the roots often tie.
            let ys = if round % 3 == 0 {
                [xs[0] + Q16::EPSILON, xs[1]]
            } else {
                [next(bits), next(bits)]
            };
            let answer = Q16::norm_above(&xs, &ys);
            assert_eq!(answer, exact(&xs) > exact(&ys), "{xs:?} {ys:?}");
            assert!(!answer || Q16::norm(&xs) >= Q16::norm(&ys), "{xs:?} {ys:?}");
            assert!(!Q16::norm_above(&xs, &xs));
            (above, not) = if answer {
                (above + 1, not)
            } else {
                (above, not + 1)
            };
        }
        assert!(above > 1000 && not > 1000, "{above} {not}");
    }

    #[test]
    fn midpoint_and_sqrt() {
        assert_eq!(Q16::midpoint(Q16::MAX, Q16::MAX), Q16::MAX);
        assert_eq!(Q16::midpoint(q(-3.0), q(4.0)), q(0.5));
        assert_eq!(q(2.25).sqrt(), q(1.5));
        assert_eq!(q(-1.0).sqrt(), Q16::ZERO);
    }

    #[test]
    fn conversions() {
        assert_eq!(q(f64::NAN), Q16::ZERO);
        assert_eq!(q(1e9), Q16::MAX);
        assert_eq!(q(-0.5).to_f64(), -0.5);
        assert_eq!(q(2.5).ceil_usize(10), 3);
        assert_eq!(q(2.0).ceil_usize(10), 2);
        assert_eq!(q(-2.0).ceil_usize(10), 0);
        assert_eq!(Q16::from_i16(-16383).to_f64(), -16383.0);
        assert_eq!(q(2.5).floor_i32(), 2);
        assert_eq!(q(-2.5).floor_i32(), -3);
    }
}
