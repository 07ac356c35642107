//! Bézier curves of any degree: evaluation, tangents, splitting, bounds and arc length.

use crate::curves::power::Power;
use crate::error::check_points;
use crate::{Aabb, Error, Point, Scalar};

/// A Bézier curve with `N` control points (degree `N - 1`), stored inline.
///
/// Construction checks the control points once (finite, inside
/// [`Scalar::SAFE_RANGE`]); after that every method is total: no panics, no NaN out.
/// `N < 2` is rejected at compile time:
///
/// ```compile_fail
/// use dunas::{Bezier, Vec2};
/// let c = Bezier::new([Vec2::new(0.0f32, 0.0)]); // a single point is not a curve
/// ```
///
/// ```
/// use dunas::{Bezier, Vec2};
/// let c = Bezier::new([
///     Vec2::new(0.0f32, 0.0),
///     Vec2::new(1.0, 2.0),
///     Vec2::new(3.0, 2.0),
///     Vec2::new(4.0, 0.0),
/// ])?;
/// assert_eq!(c.eval(0.5), Vec2::new(2.0, 1.5));
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bezier<P, const N: usize> {
    points: [P; N],
}

/// A quadratic Bézier curve (3 control points).
pub type Quadratic<P> = Bezier<P, 3>;
/// A cubic Bézier curve (4 control points).
pub type Cubic<P> = Bezier<P, 4>;

/// Deepest recursion of [`Bezier::arclen`]: at most `2^16` leaf pieces.
const ARCLEN_MAX_DEPTH: u32 = 16;

impl<P: Point, const N: usize> Bezier<P, N> {
    /// A curve through these control points.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN, infinite or saturated coordinate;
    /// [`Error::OutOfRange`] for one beyond [`Scalar::SAFE_RANGE`].
    pub fn new(points: [P; N]) -> Result<Self, Error> {
        const { assert!(N >= 2, "a Bézier curve needs at least 2 control points") };
        check_points(&points, "points")?;
        Ok(Bezier { points })
    }

    /// A curve from points the caller has already checked (convex combinations of checked
    /// points, for instance).
    #[inline]
    pub(crate) fn new_unchecked(points: [P; N]) -> Self {
        Bezier { points }
    }

    /// The control points.
    #[inline]
    pub fn points(&self) -> &[P; N] {
        &self.points
    }

    /// The polynomial degree, `N - 1`.
    #[inline]
    pub const fn degree(&self) -> usize {
        N - 1
    }

    /// The first control point, where the curve starts.
    #[inline]
    pub fn start(&self) -> P {
        self.points[0]
    }

    /// The last control point, where the curve ends.
    #[inline]
    pub fn end(&self) -> P {
        self.points[N - 1]
    }

    /// The point at parameter `t` by de Casteljau's algorithm.
    ///
    /// `t` is clamped to `[0, 1]` and NaN counts as 0; the ends are returned exactly.
    /// Cost: `N(N-1)/2` lerps (one multiply each per coordinate). Error: a few units of
    /// rounding times the largest coordinate, since every step is a convex combination.
    pub fn eval(&self, t: P::Scalar) -> P {
        point_at(&self.points, t)
    }

    /// The derivative `dP/dt` at `t` (clamped to `[0, 1]`, NaN as 0): the direction of
    /// travel, with length equal to the speed in units per unit of `t`.
    ///
    /// Cost: `N(N-1)/2 - 1` lerps. In `Q16` the result saturates (and reports it through
    /// [`Point::is_finite`]) when the speed exceeds the range.
    pub fn tangent(&self, t: P::Scalar) -> P {
        tangent_points(&self.points, clamp_unit(t))
    }

    /// The hodograph: the curve of `dP/dt`, with `M = N - 1` control points.
    ///
    /// Stable Rust cannot write `N - 1` in a return type, so `M` is a separate parameter
    /// checked at compile time:
    ///
    /// ```
    /// use dunas::{Bezier, Vec2};
    /// let c = Bezier::new([Vec2::new(0.0f64, 0.0), Vec2::new(1.0, 1.0), Vec2::new(2.0, 0.0)])?;
    /// let d: Bezier<_, 2> = c.derivative()?;
    /// assert_eq!(d.eval(0.5), c.tangent(0.5));
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::OutOfRange`] / [`Error::NonFinite`] when the derivative's control points
    /// (`(N-1)·(P[i+1] - P[i])`) leave the format's safe range, which happens in `Q16` for
    /// large, high-degree curves.
    pub fn derivative<const M: usize>(&self) -> Result<Bezier<P, M>, Error> {
        const {
            assert!(
                M + 1 == N,
                "the derivative of an N-point curve has N - 1 points"
            )
        };
        let k = degree_scalar::<P::Scalar>(N - 1);
        let mut d = [P::default(); M];
        for (i, di) in d.iter_mut().enumerate() {
            *di = (self.points[i + 1] - self.points[i]) * k;
        }
        Bezier::new(d)
    }

    /// Splits at `t` (clamped to `[0, 1]`, NaN as 0) into the pieces before and after.
    ///
    /// Together the two halves trace exactly the original curve. Cost: `N(N-1)/2` lerps.
    pub fn split(&self, t: P::Scalar) -> (Self, Self) {
        let t = clamp_unit(t);
        self.split_with(|a, b| a.lerp(b, t))
    }

    /// Splits at `t = 1/2` with [`Point::midpoint`]: exact in floats, shifts and adds in `Q16`.
    pub fn split_half(&self) -> (Self, Self) {
        self.split_with(|a, b| a.midpoint(b))
    }

    /// The parameter in `[0, 1]` whose point has the least `key` (a distance, or anything
    /// that orders points like one): the best of `2^L + 1` evenly spaced points (`L` = 2 up
    /// to a cubic, 3 up to degree 7, else 4), then 8 rounds that halve the bracket around the
    /// best point, to `2^-(L+8)` (under 1/1000 of the curve). Halving only: in `Q16` shifts
    /// and additions, with no multiplication. Cost: `2^L + 17` keys and `2^L + 2L + 15`
    /// [`split_half`](Self::split_half)s. Finds the least of a key with one minimum near the
    /// best sample; a key with several minima gets the one nearest the best sample.
    pub(crate) fn deepest(&self, key: impl Fn(P) -> P::Scalar) -> P::Scalar {
        let levels: u32 = match N {
            0..=4 => 2,
            5..=8 => 3,
            _ => 4,
        };
        let count = 1u32 << levels;
        // The evenly spaced points are the ends of the pieces of `levels` halvings; piece `i`
        // alone takes `levels` splits.
        let piece = |i: u32| {
            let mut c = *self;
            for bit in (0..levels).rev() {
                let (l, r) = c.split_half();
                c = if i >> bit & 1 == 0 { l } else { r };
            }
            c
        };
        let mut keys = [key(self.start()); 17];
        self.leaves(levels, 0, &mut |i, c| keys[i as usize + 1] = key(c.end()));
        let mut best = 0;
        for i in 1..=count {
            if keys[i as usize] < keys[best as usize] {
                best = i;
            }
        }
        // The bracket: the two pieces that meet at the best inner point.
        let junction = best.clamp(1, count - 1);
        let (mut left, mut right) = (piece(junction - 1), piece(junction));
        let at = |j: u32| P::Scalar::ratio(j, count);
        let (mut t, mut width, mut middle) = (at(junction), at(1), keys[junction as usize]);
        let mut found = (at(best), keys[best as usize]);
        let half = P::Scalar::ratio(1, 2);
        for _ in 0..8 {
            width = width * half;
            let (l0, l1) = left.split_half();
            let (r0, r1) = right.split_half();
            let (ka, kb) = (key(l0.end()), key(r0.end()));
            if ka < middle && ka <= kb {
                (left, right, t, middle) = (l0, l1, t - width, ka);
            } else if kb < middle {
                (left, right, t, middle) = (r0, r1, t + width, kb);
            } else {
                (left, right) = (l1, r0);
            }
            if middle < found.1 {
                found = (t, middle);
            }
        }
        found.0
    }

    /// The parameter in `[0, 1]` where the curve reaches farthest against `normal` (least
    /// `normal · p(t)`, the deepest point in a half-space whose outward normal it is). Exact
    /// for a segment (an end) and a cubic: an end, or a root of the derivative's quadratic,
    /// scaled to at most 1 so that `Q16` neither saturates nor divides by zero; other degrees
    /// by [`deepest`](Self::deepest). Cost of a cubic: 4 dot products, a square root and up
    /// to 4 divisions.
    pub(crate) fn lowest(&self, normal: P) -> P::Scalar {
        let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
        let h = |i: usize| self.points[i].dot(normal);
        match N {
            2 => return if h(1) < h(0) { one } else { zero },
            4 => {}
            _ => return self.deepest(|p| p.dot(normal)),
        }
        // The height in power form, g(t) = g0 + t·(3·d0 + t·(3·(d1 - d0) + t·a)), and its
        // slope's quadratic a·t² + b·t + c (a third of it).
        let (g0, d0, d1, d2) = (h(0), h(1) - h(0), h(2) - h(1), h(3) - h(2));
        let three = P::Scalar::from_i16(3);
        let (a, b, c) = (d0 - d1 - d1 + d2, (d1 - d0) * P::Scalar::from_i16(2), d0);
        let height = |t: P::Scalar| g0 + t * (d0 * three + t * ((d1 - d0) * three + t * a));
        let mut best = if h(3) < g0 { (one, h(3)) } else { (zero, g0) };
        let largest = a.abs().max(b.abs()).max(c.abs());
        if largest == zero {
            return best.0;
        }
        let unit = one / largest;
        let (a, b, c) = (a * unit, b * unit, c * unit);
        let disc = b * b - (a * c) * P::Scalar::from_i16(4);
        if disc < zero {
            return best.0;
        }
        // The roots q/a and c/q, with q of b's sign (no cancellation); each taken only where
        // it lies inside (-1, 1), so that no division overflows.
        let root = disc.sqrt();
        let q = (if b < zero { root - b } else { -(b + root) }) * P::Scalar::ratio(1, 2);
        let roots = [
            (q.abs() < a.abs()).then(|| q / a),
            (c.abs() < q.abs()).then(|| c / q),
        ];
        for t in roots.into_iter().flatten().filter(|&t| t > zero) {
            let g = height(t);
            if g < best.1 {
                best = (t, g);
            }
        }
        best.0
    }

    /// The parameter in `[0, 1]` of the point nearest `c` (the deepest in a ball centred
    /// there): a cubic in floats by Newton steps on its power form
    /// ([`Power::nearest`](crate::curves::power::Power)), to the format's precision; other
    /// degrees, and fixed point, by [`deepest`](Self::deepest) on the squared distance.
    pub(crate) fn nearest(&self, c: P) -> P::Scalar {
        match <[P; 4]>::try_from(&self.points[..]) {
            Ok(cubic) if !P::Scalar::FIXED_POINT => Power::of(cubic).nearest(c),
            _ => self.deepest(|p| (p - c).dot(p - c)),
        }
    }

    /// Calls `visit(first + i, piece)` for the `2^levels` pieces of `levels` halvings, in
    /// order: `2^levels - 1` splits in all.
    fn leaves(&self, levels: u32, first: u32, visit: &mut impl FnMut(u32, &Self)) {
        if levels == 0 {
            return visit(first, self);
        }
        let (l, r) = self.split_half();
        l.leaves(levels - 1, 2 * first, visit);
        r.leaves(levels - 1, 2 * first + 1, visit);
    }

    #[inline]
    fn split_with(&self, mix: impl Fn(P, P) -> P) -> (Self, Self) {
        let mut work = self.points;
        let mut left = self.points;
        let mut right = self.points;
        for r in 1..N {
            for i in 0..N - r {
                work[i] = mix(work[i], work[i + 1]);
            }
            left[r] = work[0];
            right[N - 1 - r] = work[N - 1 - r];
        }
        // Convex combinations of checked points stay inside the safe range.
        (Bezier { points: left }, Bezier { points: right })
    }

    /// The box around the control points, which contains the whole curve (convex hull
    /// property). Cost: `N` compares per coordinate.
    pub fn bounding_box(&self) -> Aabb<P> {
        let mut b = Aabb::point(self.points[0]);
        for &p in &self.points[1..] {
            b = b.including(p);
        }
        b
    }

    /// Length of the control polygon, an upper bound on the arc length.
    pub fn polygon_length(&self) -> P::Scalar {
        let mut len = P::Scalar::ZERO;
        for w in self.points.windows(2) {
            len += w[0].distance(w[1]);
        }
        len
    }

    /// Arc length within `accuracy` (absolute, in coordinate units).
    ///
    /// Recursive halving until the control polygon and the chord of each piece agree to
    /// the piece's share of `accuracy`, then Gravesen's estimate
    /// `(2·chord + (N-2)·polygon) / N` per piece. The curve lies between chord and
    /// polygon, so the error of each piece is below their gap. A non-positive or NaN
    /// `accuracy` asks for the best the format gives. Cost: `N²/2` midpoints per piece,
    /// at most `2^16` pieces; in practice about `sqrt(length / accuracy)` pieces.
    pub fn arclen(&self, accuracy: P::Scalar) -> P::Scalar {
        let acc = if accuracy > P::Scalar::ZERO {
            accuracy
        } else {
            P::Scalar::EPSILON
        };
        arclen_rec(self, acc, 0)
    }
}

/// [`Bezier::eval`] of a bare control polygon: `t` clamped (NaN as 0), the ends exact.
#[inline]
pub(crate) fn point_at<P: Point, const N: usize>(points: &[P; N], t: P::Scalar) -> P {
    let t = clamp_unit(t);
    if t == P::Scalar::ZERO {
        points[0]
    } else if t == P::Scalar::ONE {
        points[N - 1]
    } else {
        eval_points(points, t)
    }
}

/// De Casteljau on a bare control polygon (no clamping): `N(N-1)/2` lerps.
#[inline]
pub(crate) fn eval_points<P: Point, const N: usize>(points: &[P; N], t: P::Scalar) -> P {
    let mut b = *points;
    for r in 1..N {
        for i in 0..N - r {
            b[i] = b[i].lerp(b[i + 1], t);
        }
    }
    b[0]
}

/// `dP/dt` of a bare control polygon: de Casteljau to the second-last level.
#[inline]
pub(crate) fn tangent_points<P: Point, const N: usize>(points: &[P; N], t: P::Scalar) -> P {
    let mut b = *points;
    for r in 1..N - 1 {
        for i in 0..N - r {
            b[i] = b[i].lerp(b[i + 1], t);
        }
    }
    (b[1] - b[0]) * degree_scalar::<P::Scalar>(N - 1)
}

fn arclen_rec<P: Point, const N: usize>(c: &Bezier<P, N>, acc: P::Scalar, depth: u32) -> P::Scalar {
    let chord = c.start().distance(c.end());
    let poly = c.polygon_length();
    if poly - chord <= acc || depth >= ARCLEN_MAX_DEPTH {
        // Gravesen: (2·chord + (n-1)·polygon) / (n+1) with n = N - 1, a convex combination.
        let two = P::Scalar::ONE + P::Scalar::ONE;
        return (chord * two + poly * degree_scalar(N - 2)) / degree_scalar(N);
    }
    let (l, r) = c.split_half();
    let half = Scalar::midpoint(acc, P::Scalar::ZERO);
    arclen_rec(&l, half, depth + 1) + arclen_rec(&r, half, depth + 1)
}

/// `t` clamped to `[0, 1]`, NaN mapped to 0.
#[inline]
pub(crate) fn clamp_unit<S: Scalar>(t: S) -> S {
    match (t.partial_cmp(&S::ZERO), t.partial_cmp(&S::ONE)) {
        (Some(core::cmp::Ordering::Greater), Some(core::cmp::Ordering::Less)) => t,
        (Some(core::cmp::Ordering::Greater), _) => S::ONE,
        _ => S::ZERO,
    }
}

/// A small integer (a degree or a binomial) as a scalar. Saturates past `i16::MAX`,
/// which no supported degree reaches.
#[inline]
pub(crate) fn degree_scalar<S: Scalar>(n: usize) -> S {
    S::from_i16(n.min(i16::MAX as usize) as i16)
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::{Q16, Vec2};

    fn cubic() -> Cubic<Vec2<f64>> {
        Bezier::new([
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 3.0),
            Vec2::new(4.0, 3.0),
            Vec2::new(5.0, 0.0),
        ])
        .unwrap()
    }

    /// `lowest` is the least height of a dense sampling (f64, 20 001 points) or lower, on
    /// cubics with their lowest point at an end, inside, in a flat stretch and on a line;
    /// in `Q16` within 1/1000 of a metre of it.
    #[test]
    fn the_lowest_point_is_found_exactly() {
        let mut next = crate::curves::power::tests::uniform(12345);
        let mut cubics: std::vec::Vec<[f64; 8]> =
            (0..500).map(|_| [(); 8].map(|_| next())).collect();
        cubics.push([0.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0, 1.0]);
        cubics.push([0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0]);
        cubics.push([0.0, 1.0, 1.0, -1.0, 2.0, -1.0, 3.0, 1.0]);
        for c in cubics {
            let p = |i: usize| Vec2::new(c[2 * i], c[2 * i + 1]);
            let curve = Bezier::new([p(0), p(1), p(2), p(3)]).unwrap();
            let normal = Vec2::new(0.6, 0.8);
            let height = |t: f64| curve.eval(t).dot(normal);
            let sampled = (0..=20_000)
                .map(|i| height(i as f64 / 20_000.0))
                .fold(f64::INFINITY, f64::min);
            let t = curve.lowest(normal);
            assert!(
                (0.0..=1.0).contains(&t) && height(t) <= sampled + 1e-12,
                "{c:?}"
            );
            let q = |v: Vec2<f64>| Vec2::new(Q16::from_f64(v.x), Q16::from_f64(v.y));
            let fixed = Bezier::new([q(p(0)), q(p(1)), q(p(2)), q(p(3))]).unwrap();
            let t = fixed.lowest(q(normal)).to_f64();
            assert!(
                height(t) <= sampled + 1e-3,
                "{c:?}: {}",
                height(t) - sampled
            );
        }
    }

    #[test]
    fn eval_matches_bernstein_form() {
        let c = cubic();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let s = 1.0 - t;
            let p = c.points();
            let b = p[0] * (s * s * s)
                + p[1] * (3.0 * s * s * t)
                + p[2] * (3.0 * s * t * t)
                + p[3] * (t * t * t);
            assert!((c.eval(t) - b).length() < 1e-12);
        }
        assert_eq!(c.eval(f64::NAN), c.start());
        assert_eq!(c.eval(7.0), c.end());
    }

    #[test]
    fn tangent_matches_closed_form_and_derivative() {
        let c = cubic();
        let d: Bezier<_, 3> = c.derivative().unwrap();
        for i in 0..=8 {
            let t = i as f64 / 8.0;
            let s = 1.0 - t;
            let p = c.points();
            let exact = (p[1] - p[0]) * (3.0 * s * s)
                + (p[2] - p[1]) * (6.0 * s * t)
                + (p[3] - p[2]) * (3.0 * t * t);
            assert!((c.tangent(t) - exact).length() < 1e-12);
            assert!((d.eval(t) - exact).length() < 1e-12);
        }
    }

    #[test]
    fn rejects_bad_control_points() {
        let nan = Bezier::new([Vec2::new(0.0f32, f32::NAN), Vec2::new(1.0, 1.0)]);
        assert!(matches!(nan, Err(Error::NonFinite { .. })));
        let far = Bezier::new([Vec2::new(0.0f32, 1e30), Vec2::new(1.0, 1.0)]);
        assert!(matches!(far, Err(Error::OutOfRange { .. })));
    }

    #[test]
    fn arclen_of_a_line_and_a_parabola() {
        let line = Bezier::new([
            Vec2::new(0.0f64, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(3.0, 3.0),
        ])
        .unwrap();
        assert!((line.arclen(1e-9) - 18f64.sqrt()).abs() < 1e-9);
        // y = x^2 on [0, 1] as a quadratic Bézier: length = sqrt(5)/2 + asinh(2)/4.
        let par = Bezier::new([
            Vec2::new(0.0f64, 0.0),
            Vec2::new(0.5, 0.0),
            Vec2::new(1.0, 1.0),
        ])
        .unwrap();
        let exact = 5f64.sqrt() / 2.0 + 2f64.asinh() / 4.0;
        for acc in [1e-2, 1e-4, 1e-6, 1e-9] {
            let err = (par.arclen(acc) - exact).abs();
            assert!(err <= acc, "accuracy {acc}: error {err}");
        }
    }
}
