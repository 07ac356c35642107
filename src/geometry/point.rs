//! 2D and 3D points ([`Vec2`], [`Vec3`]) and the [`Point`] trait the geometry is written on.

use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use crate::Scalar;

/// A position or displacement in 2 or 3 dimensions over a [`Scalar`].
///
/// Curves, patches and samplers are generic over `Point`, so the same code draws a 2D rope
/// in `Vec2<Q16>` and a 3D sail in `Vec3<f32>`. Samplers work one coordinate lane at a time
/// through [`coord`](Point::coord) / [`set_coord`](Point::set_coord).
pub trait Point:
    Copy
    + Default
    + PartialEq
    + core::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
    + Mul<<Self as Point>::Scalar, Output = Self>
    + AddAssign
    + SubAssign
{
    /// The number format of the coordinates.
    type Scalar: Scalar;
    /// Number of coordinates (2 or 3).
    const DIM: usize;

    /// Coordinate `axis` (0 = x, 1 = y, 2 = z); 0 for an axis the point does not have.
    fn coord(self, axis: usize) -> Self::Scalar;
    /// Sets coordinate `axis`; ignored for an axis the point does not have.
    fn set_coord(&mut self, axis: usize, value: Self::Scalar);
    /// A point with every coordinate equal to `value`.
    fn splat(value: Self::Scalar) -> Self;

    /// Euclidean length, overflow-free inside the format's range (see [`Scalar::norm`]).
    fn length(self) -> Self::Scalar;

    /// Whether [`length`](Self::length) is below `limit`, without a root (see
    /// [`Scalar::norm_below`]).
    ///
    /// ```
    /// use dunas::prelude::*;
    /// let d = Vec2::new(3.0f32, 4.0);
    /// assert!(!d.shorter_than(5.0) && d.shorter_than(5.001));
    /// ```
    #[inline]
    fn shorter_than(self, limit: Self::Scalar) -> bool {
        self.length() < limit
    }

    /// Whether this vector is longer than `other`, without the roots (see
    /// [`Scalar::norm_above`]): in `Q16` the longer by it has a [`length`](Self::length) at
    /// least as large.
    ///
    /// ```
    /// use dunas::prelude::*;
    /// let (a, b) = (Vec2::new(3.0f32, 4.0), Vec2::new(0.0, 5.0));
    /// assert!(!a.longer_than(b) && a.longer_than(Vec2::new(4.9, 0.0)));
    /// ```
    #[inline]
    fn longer_than(self, other: Self) -> bool {
        self.length() > other.length()
    }

    /// [`length`](Self::length) and its inverse (0 for a zero vector), for a length and a
    /// direction at once: see [`Scalar::norm_and_inverse`] (in `Q16`, no division).
    #[inline]
    fn length_and_inverse(self) -> (Self::Scalar, Self::Scalar) {
        let l = self.length();
        (l, l.approx_recip())
    }

    /// Dot product. In `Q16` it saturates once `|a|·|b|` passes 32768.
    fn dot(self, other: Self) -> Self::Scalar;

    /// Distance to `other`.
    #[inline]
    fn distance(self, other: Self) -> Self::Scalar {
        (other - self).length()
    }

    /// `self + (other - self) * t`: one multiply per coordinate.
    #[inline]
    fn lerp(self, other: Self, t: Self::Scalar) -> Self {
        self + (other - self) * t
    }

    /// The midpoint, by [`Scalar::midpoint`] (a shift in `Q16`).
    #[inline]
    fn midpoint(self, other: Self) -> Self {
        let mut p = self;
        for d in 0..Self::DIM {
            p.set_coord(d, Scalar::midpoint(self.coord(d), other.coord(d)));
        }
        p
    }

    /// Coordinate-wise minimum.
    #[inline]
    fn min_coords(self, other: Self) -> Self {
        let mut p = self;
        for d in 0..Self::DIM {
            p.set_coord(d, self.coord(d).min(other.coord(d)));
        }
        p
    }

    /// Coordinate-wise maximum.
    #[inline]
    fn max_coords(self, other: Self) -> Self {
        let mut p = self;
        for d in 0..Self::DIM {
            p.set_coord(d, self.coord(d).max(other.coord(d)));
        }
        p
    }

    /// `true` when every coordinate is finite and within [`Scalar::SAFE_RANGE`].
    #[inline]
    fn in_safe_range(self) -> bool {
        (0..Self::DIM).all(|d| self.coord(d).in_safe_range())
    }

    /// `true` when every coordinate is finite (not NaN, not infinite, not saturated).
    #[inline]
    fn is_finite(self) -> bool {
        // `&`, not `&&`: no branch per coordinate in the per-spring checks of fixed point.
        (0..Self::DIM).fold(true, |ok, d| ok & self.coord(d).is_finite())
    }
}

/// A 2D point or vector: screen-space ropes, side-on sails.
#[derive(Clone, Copy, Default, PartialEq, Debug)]
pub struct Vec2<S = f32> {
    /// Horizontal coordinate.
    pub x: S,
    /// Vertical coordinate.
    pub y: S,
}

/// A 3D point or vector: sails, flags, cloth.
#[derive(Clone, Copy, Default, PartialEq, Debug)]
pub struct Vec3<S = f32> {
    /// First coordinate.
    pub x: S,
    /// Second coordinate.
    pub y: S,
    /// Third coordinate.
    pub z: S,
}

impl<S> Vec2<S> {
    /// A point from its coordinates.
    #[inline]
    pub const fn new(x: S, y: S) -> Self {
        Vec2 { x, y }
    }
}

impl<S> Vec3<S> {
    /// A point from its coordinates.
    #[inline]
    pub const fn new(x: S, y: S, z: S) -> Self {
        Vec3 { x, y, z }
    }
}

impl<S: Scalar> Vec2<S> {
    /// A point from `f64` coordinates (setup code; see [`Scalar::from_f64`]).
    #[inline]
    pub fn from_f64(x: f64, y: f64) -> Self {
        Vec2::new(S::from_f64(x), S::from_f64(y))
    }

    /// The z component of the 3D cross product (twice the signed triangle area).
    #[inline]
    pub fn cross(self, o: Self) -> S {
        self.x * o.y - self.y * o.x
    }
}

impl<S: Scalar> Vec3<S> {
    /// A point from `f64` coordinates (setup code; see [`Scalar::from_f64`]).
    #[inline]
    pub fn from_f64(x: f64, y: f64, z: f64) -> Self {
        Vec3::new(S::from_f64(x), S::from_f64(y), S::from_f64(z))
    }

    /// Cross product.
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
}

macro_rules! impl_ops {
    (@scalar $f:ident) => { S };
    ($V:ident { $($f:ident),+ }, $dim:expr, [$($axis:literal => $g:ident),+]) => {
        impl<S: Scalar> Add for $V<S> {
            type Output = Self;
            #[inline]
            fn add(self, o: Self) -> Self {
                $V { $($f: self.$f + o.$f),+ }
            }
        }
        impl<S: Scalar> Sub for $V<S> {
            type Output = Self;
            #[inline]
            fn sub(self, o: Self) -> Self {
                $V { $($f: self.$f - o.$f),+ }
            }
        }
        impl<S: Scalar> Neg for $V<S> {
            type Output = Self;
            #[inline]
            fn neg(self) -> Self {
                $V { $($f: -self.$f),+ }
            }
        }
        impl<S: Scalar> Mul<S> for $V<S> {
            type Output = Self;
            #[inline]
            fn mul(self, s: S) -> Self {
                $V { $($f: self.$f * s),+ }
            }
        }
        impl<S: Scalar> Div<S> for $V<S> {
            type Output = Self;
            /// Each coordinate divided by `s` (in `Q16`, saturating for a tiny `s`).
            #[inline]
            fn div(self, s: S) -> Self {
                $V { $($f: self.$f / s),+ }
            }
        }
        impl<S: Scalar> From<[S; $dim]> for $V<S> {
            #[inline]
            fn from([$($f),+]: [S; $dim]) -> Self {
                $V { $($f),+ }
            }
        }
        impl<S: Scalar> From<$V<S>> for [S; $dim] {
            #[inline]
            fn from(v: $V<S>) -> Self {
                [$(v.$f),+]
            }
        }
        impl<S: Scalar> From<($(impl_ops!(@scalar $f)),+)> for $V<S> {
            #[inline]
            fn from(($($f),+): ($(impl_ops!(@scalar $f)),+)) -> Self {
                $V { $($f),+ }
            }
        }
        impl<S: Scalar + core::fmt::Display> core::fmt::Display for $V<S> {
            /// `(x, y)` / `(x, y, z)`, each coordinate with the formatter's precision.
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                let mut sep = "(";
                $(
                    f.write_str(sep)?;
                    core::fmt::Display::fmt(&self.$f, f)?;
                    sep = ", ";
                )+
                let _ = sep;
                f.write_str(")")
            }
        }
        impl<S: Scalar> $V<S> {
            /// The unit vector in this direction, or `None` for a zero (or non-finite) vector.
            ///
            /// One norm and one division, to the format's rounding for any other vector: one whose
            /// largest coordinate is below ½ or from 256 up is first scaled by powers of two (exact
            /// in floats, so their result is unchanged), since in `Q16` a tiny vector's length has
            /// few significant bits and a long one's saturates, and in floats the inverse of a
            /// subnormal length overflows.
            #[inline]
            pub fn normalize(self) -> Option<Self> {
                let (v, _) = self.scaled()?;
                Some(v * (S::ONE / v.length()))
            }

            /// This vector scaled by a power of two until its largest coordinate `m` is in
            /// `[½, 256)`, with `m`; `None` for a zero (or non-finite) vector.
            #[inline]
            fn scaled(self) -> Option<(Self, S)> {
                let largest = S::ZERO $(.max(self.$f.abs()))+;
                if !(largest > S::ZERO && largest.is_finite()) {
                    return None;
                }
                let (mut v, mut m) = (self, largest);
                let (up, down) = (S::from_i16(256), S::ratio(1, 256));
                while m >= up {
                    (v, m) = (v * down, m * down);
                }
                while m < down {
                    (v, m) = (v * up, m * up);
                }
                let (two, half) = (S::from_i16(2), S::ratio(1, 2));
                while m < half {
                    (v, m) = (v * two, m * two);
                }
                Some((v, m))
            }
        }
        impl<S: Scalar> AddAssign for $V<S> {
            #[inline]
            fn add_assign(&mut self, o: Self) {
                $(self.$f += o.$f;)+
            }
        }
        impl<S: Scalar> SubAssign for $V<S> {
            #[inline]
            fn sub_assign(&mut self, o: Self) {
                $(self.$f -= o.$f;)+
            }
        }
        impl<S: Scalar> Point for $V<S> {
            type Scalar = S;
            const DIM: usize = $dim;
            #[inline]
            fn coord(self, axis: usize) -> S {
                match axis {
                    $($axis => self.$g,)+
                    _ => S::ZERO,
                }
            }
            #[inline]
            fn set_coord(&mut self, axis: usize, value: S) {
                match axis {
                    $($axis => self.$g = value,)+
                    _ => {}
                }
            }
            #[inline]
            fn splat(value: S) -> Self {
                $V { $($f: value),+ }
            }
            #[inline]
            fn length(self) -> S {
                S::norm(&[$(self.$f),+])
            }
            #[inline]
            fn shorter_than(self, limit: S) -> bool {
                S::norm_below(&[$(self.$f),+], limit)
            }
            #[inline]
            fn longer_than(self, other: Self) -> bool {
                S::norm_above(&[$(self.$f),+], &[$(other.$f),+])
            }
            #[inline]
            fn length_and_inverse(self) -> (S, S) {
                S::norm_and_inverse(&[$(self.$f),+])
            }
            #[inline]
            fn dot(self, o: Self) -> S {
                let mut s = S::ZERO;
                $(s += self.$f * o.$f;)+
                s
            }
        }
    };
}

impl_ops!(Vec2 { x, y }, 2, [0 => x, 1 => y]);
impl_ops!(Vec3 { x, y, z }, 3, [0 => x, 1 => y, 2 => z]);

impl<S: Scalar> Vec3<S> {
    /// This vector scaled by a power of two until its largest coordinate is in `[½, 2)`, or
    /// `None` for a zero (or non-finite) vector: a direction whose cross products stay in
    /// `Q16`'s range, for a fraction of [`normalize`](Self::normalize)'s cost (no root, no
    /// division).
    #[inline]
    pub(crate) fn balanced(self) -> Option<Self> {
        let (mut v, mut m) = self.scaled()?;
        let half = S::ratio(1, 2);
        while m >= S::from_i16(2) {
            (v, m) = (v * half, m * half);
        }
        Some(v)
    }
}

/// `s * v` for each format (a generic `S * Vec2<S>` cannot be written for foreign `S`).
macro_rules! scalar_times {
    ($($S:ty),+) => {$(
        impl Mul<Vec2<$S>> for $S {
            type Output = Vec2<$S>;
            #[inline]
            fn mul(self, v: Vec2<$S>) -> Vec2<$S> {
                v * self
            }
        }
        impl Mul<Vec3<$S>> for $S {
            type Output = Vec3<$S>;
            #[inline]
            fn mul(self, v: Vec3<$S>) -> Vec3<$S> {
                v * self
            }
        }
    )+};
}

#[cfg(dunas_floats)]
scalar_times!(f32, f64);

/// Conversions to and from `mint`, which glam, nalgebra and cgmath convert to and from:
/// `Vec2::from(glam_vec2.into())`-style bridges with no copy of the math.
#[cfg(feature = "mint")]
mod mint_bridge {
    use super::{Vec2, Vec3};
    use crate::Scalar;

    macro_rules! bridge {
        ($V:ident { $($f:ident),+ }: $M:ident) => {
            impl<S: Scalar> From<mint::$M<S>> for $V<S> {
                #[inline]
                fn from(m: mint::$M<S>) -> Self {
                    $V { $($f: m.$f),+ }
                }
            }
            impl<S: Scalar> From<$V<S>> for mint::$M<S> {
                #[inline]
                fn from(v: $V<S>) -> Self {
                    mint::$M { $($f: v.$f),+ }
                }
            }
        };
    }

    bridge!(Vec2 { x, y }: Vector2);
    bridge!(Vec2 { x, y }: Point2);
    bridge!(Vec3 { x, y, z }: Vector3);
    bridge!(Vec3 { x, y, z }: Point3);
}
#[cfg(feature = "fixed")]
scalar_times!(crate::Q16);

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_and_lanes() {
        let a = Vec2::new(1.0f64, 2.0);
        let b = Vec2::new(3.0, -1.0);
        assert_eq!(a + b, Vec2::new(4.0, 1.0));
        assert_eq!(a.lerp(b, 0.5), Vec2::new(2.0, 0.5));
        assert_eq!(a.midpoint(b), Vec2::new(2.0, 0.5));
        assert_eq!(a.coord(1), 2.0);
        assert_eq!(a.coord(2), 0.0);
        assert_eq!(Vec2::new(3.0f32, 4.0).length(), 5.0);
        assert_eq!(a.min_coords(b), Vec2::new(1.0, -1.0));
    }

    #[test]
    fn operators_and_conversions() {
        let a = Vec2::new(3.0f32, 4.0);
        assert_eq!(a / 2.0, Vec2::new(1.5, 2.0));
        assert_eq!(2.0 * a, a * 2.0);
        assert_eq!(Vec2::from([3.0, 4.0]), a);
        assert_eq!(Vec2::from((3.0, 4.0)), a);
        assert_eq!(<[f32; 2]>::from(a), [3.0, 4.0]);
        assert_eq!(a.normalize(), Some(Vec2::new(0.6, 0.8)));
        assert_eq!(Vec2::<f32>::default().normalize(), None);
        assert_eq!(std::format!("{a:.1}"), "(3.0, 4.0)");
        assert_eq!(std::format!("{}", Vec3::new(1.0f64, 2.0, 3.0)), "(1, 2, 3)");
        assert_eq!(Vec3::from((1.0, 2.0, 3.0)), Vec3::from([1.0, 2.0, 3.0]));
        #[cfg(feature = "mint")]
        {
            let m: mint::Vector2<f32> = a.into();
            assert_eq!((m.x, m.y), (3.0, 4.0));
            assert_eq!(
                Vec3::from(mint::Point3 {
                    x: 1.0,
                    y: 2.0,
                    z: 3.0
                }),
                Vec3::new(1.0, 2.0, 3.0)
            );
        }
    }

    #[test]
    fn normalize_and_cross() {
        let x = Vec3::new(2.0f64, 0.0, 0.0);
        let y = Vec3::new(0.0, 3.0, 0.0);
        assert_eq!(x.cross(y).normalize(), Some(Vec3::new(0.0, 0.0, 1.0)));
        assert_eq!(Vec3::<f32>::default().normalize(), None);
        assert_eq!(Vec3::new(f32::NAN, 0.0, 0.0).normalize(), None);
        // Subnormal and huge vectors, whose inverse length or length overflows unscaled.
        for x in [1e-310f64, f64::MIN_POSITIVE, 1e300, f64::MAX] {
            assert_eq!(
                Vec3::new(0.0, -x, 0.0).normalize(),
                Some(Vec3::new(0.0, -1.0, 0.0))
            );
        }
    }

    /// In `Q16`, tiny vectors (a few units of the last place) and long ones (whose length
    /// is past the range) normalize to unit length too.
    #[cfg(feature = "fixed")]
    #[test]
    fn q16_normalizes_tiny_and_long_vectors() {
        use crate::Q16;
        let ulp = Q16::from_bits(1);
        let q = |x: f64| Q16::from_f64(x);
        for v in [
            Vec3::new(ulp, ulp, Q16::ZERO),
            Vec3::new(Q16::ZERO, Q16::ZERO, -ulp),
            Vec3::new(q(0.01), q(-0.003), q(0.002)),
            Vec3::new(q(30000.0), q(30000.0), q(-30000.0)),
        ] {
            let n = v.normalize().unwrap();
            assert!((n.length().to_f64() - 1.0).abs() < 1e-3, "{v:?}: {n:?}");
            // The same direction: parallel to `v` (in `f64`).
            let w = [v.x, v.y, v.z].map(|c| c.to_f64());
            let norm = w.iter().map(|c| c * c).sum::<f64>().sqrt();
            for (c, e) in [n.x, n.y, n.z].iter().zip(w) {
                assert!((c.to_f64() - e / norm).abs() < 1e-3, "{v:?}: {n:?}");
            }
        }
    }

    #[test]
    fn safe_range() {
        assert!(Vec2::new(1e4f32, -1e4).in_safe_range());
        assert!(!Vec2::new(f32::INFINITY, 0.0).in_safe_range());
        assert!(!Vec2::new(1e30f32, 0.0).in_safe_range());
    }
}
