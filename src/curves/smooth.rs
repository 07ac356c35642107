//! Smoothing a row of particles into a curve: the step between the physics and the screen.
//!
//! A rope simulated with `K` particles is drawn as a smooth curve with as many points as
//! the screen needs. Four ways, chosen with [`Smoothing`]:
//!
//! - [`Smoothing::Bezier`]: one Bézier curve with the particles as control points (the
//!   thesis's way). Smoothest (C∞), passes through the two ends only, and each particle
//!   pulls the whole curve. De Casteljau costs `K²/2` lerps a point, so keep `K` small (≤ 16).
//! - [`Smoothing::BSpline`]: the uniform cubic B-spline of the particles, written as `K - 1`
//!   cubic Bézier pieces with C² joins. Passes through the ends, follows the particles
//!   closely without touching the inner ones; 6 lerps a point whatever `K`.
//! - [`Smoothing::CatmullRom`]: the Catmull-Rom spline, `K - 1` cubic pieces with C¹ joins
//!   that pass through every particle. 6 lerps a point.
//! - [`Smoothing::NaturalSpline`]: the C² cubic spline through every particle (natural
//!   ends): a B-spline whose control points solve one tridiagonal system, `O(K)` when the
//!   curve is built, then 6 lerps a point.
//! - [`Smoothing::Polyline`]: straight segments between the particles, the unsmoothed
//!   reference. 1 lerp a point.
//!
//! [`Smoothed`] holds the pieces a smoothing makes of a row ([`Smoothed::open`]) or a ring
//! ([`Smoothed::closed`]) of particles: one Bézier curve, cubic spans or straight segments.
//! It samples them with any [`Sampler`] through one engine, [`Sampler::sample_joined`]: every
//! span gets the same number of points and a particle's joint falls on a sample. The format's
//! default sampler ([`DefaultSampler`]) walks dyadic parameters in `Q16` (shifts and additions
//! only); a [`BernsteinTable`](crate::curves::sampler::BernsteinTable) of the span size makes the float
//! path a few multiply-adds a point. A rope draws itself with [`Rope::sample`](crate::Rope::sample).
//!
//! ```
//! use dunas::{Vec2, smooth::{Smoothed, Smoothing}};
//! let rope = [Vec2::new(0.0f32, 0.0), Vec2::new(1.0, -1.0), Vec2::new(2.0, -1.0), Vec2::new(3.0, 0.0)];
//! let mut out = [Vec2::default(); 31];
//! let n = Smoothed::open(Smoothing::CatmullRom, &rope)?.sample(&mut out)?;
//! assert_eq!(n, 31); // 3 spans of 10 segments
//! assert_eq!(out[10], rope[1]); // Catmull-Rom passes through every particle
//! # Ok::<(), dunas::Error>(())
//! ```

use crate::curves::natural::{natural_controls, natural_open};
use crate::curves::sampler::{DefaultSampler, Sampler};
use crate::curves::spans::{
    Fractions, bspline_span, bspline_spans, catmull_rom_span, catmull_rom_spans, ring_segment,
    ring_span, segment, segments,
};
use crate::error::check_points;
use crate::error::invalid;
use crate::{Aabb, Bezier, Error, Point, Scalar};

/// How a row of particles becomes a curve. See the [module docs](self).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Smoothing {
    /// One Bézier curve of degree `K - 1` over all the particles.
    #[default]
    Bezier,
    /// Uniform cubic B-spline, C² (ends clamped by reflected phantom points).
    BSpline,
    /// Catmull-Rom spline through every particle, C¹. Its spans overshoot the particles by up
    /// to a sixth of the distance between a particle's neighbours, so with particles at the
    /// edge of [`Scalar::SAFE_RANGE`] the drawn points reach at most 4/3 of it (finite in
    /// every format). The other smoothings stay inside the particles' convex hull.
    CatmullRom,
    /// Straight lines between the particles.
    Polyline,
    /// The natural cubic spline through every particle, C²: the uniform B-spline whose
    /// control points `c` solve `c[i-1] + 4·c[i] + c[i+1] = 6·p[i]` (zero curvature at open
    /// ends, wrapping on a loop). Each particle pulls the whole curve, by a weight that falls
    /// by `2 - √3 ≈ 0.27` a particle. The spans bulge past the particles by at most
    /// `max |p[i-1] - 2·p[i] + p[i+1]| / 2` (the control points' offset); the drawn velocity
    /// is at most 1.55 times the fastest particle's (`Σ|w| < 1.55`).
    NaturalSpline,
}

/// The curve a [`Smoothing`] makes of `K` particles, ready to sample or measure.
///
/// Built in `O(K)` from checked particles; sampling and measuring then cannot fail on the
/// curve, only on the buffer. Size: `K` cubic spans (`32·K` bytes for `Vec2<f32>`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smoothed<P, const K: usize> {
    pieces: Pieces<P, K>,
    method: Smoothing,
    /// The particles it is drawn through: the first `len` of the `K`.
    len: usize,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Pieces<P, const K: usize> {
    /// One Bézier curve over all the particles.
    Whole(Bezier<P, K>),
    /// The first `count` cubic spans.
    Cubic([Bezier<P, 4>; K], usize),
    /// The first `count` straight segments.
    Straight([Bezier<P, 2>; K], usize),
}

impl<P: Point, const K: usize> Smoothed<P, K> {
    /// The open curve through a row of particles: `K - 1` spans from the first particle to
    /// the last, which it starts and ends on.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] when a particle is NaN, infinite,
    /// saturated or beyond [`Scalar::SAFE_RANGE`].
    // Inlined so that a constant `method` folds away the other methods' code (flash on a device).
    #[inline]
    pub fn open(method: Smoothing, particles: &[P; K]) -> Result<Self, Error> {
        const { assert!(K >= 2, "smoothing needs at least 2 particles") };
        check_points(particles, "particles")?;
        let pieces = match method {
            Smoothing::Bezier => Pieces::Whole(Bezier::new_unchecked(*particles)),
            Smoothing::BSpline => Pieces::Cubic(bspline_spans(particles, K), K - 1),
            Smoothing::CatmullRom => Pieces::Cubic(catmull_rom_spans(particles, K), K - 1),
            Smoothing::NaturalSpline => {
                let mut controls = *particles;
                natural_open(&mut controls, K);
                Pieces::Cubic(bspline_spans(&controls, K), K - 1)
            }
            Smoothing::Polyline => Pieces::Straight(segments(particles, K), K - 1),
        };
        Ok(Smoothed {
            pieces,
            method,
            len: K,
        })
    }

    /// The open curve through the first `n` particles (`2 ≤ n ≤ K`, clamped): a piece of a
    /// broken rope. One Bézier repeats the `n`-th particle up to degree `K - 1`. Its
    /// [`weights`](Self::weights) are those of the piece (0 past its `n` particles).
    pub(crate) fn open_first(
        method: Smoothing,
        particles: &[P; K],
        n: usize,
    ) -> Result<Self, Error> {
        let n = n.clamp(2.min(K), K);
        let mut row = *particles;
        for p in &mut row[n..] {
            *p = particles[n - 1];
        }
        check_points(&row, "particle")?;
        let pieces = match method {
            Smoothing::Bezier => Pieces::Whole(Bezier::new_unchecked(row)),
            Smoothing::BSpline => Pieces::Cubic(bspline_spans(&row, n), n - 1),
            Smoothing::CatmullRom => Pieces::Cubic(catmull_rom_spans(&row, n), n - 1),
            Smoothing::NaturalSpline => {
                natural_open(&mut row, n);
                Pieces::Cubic(bspline_spans(&row, n), n - 1)
            }
            Smoothing::Polyline => Pieces::Straight(segments(&row, n), n - 1),
        };
        Ok(Smoothed {
            pieces,
            method,
            len: n,
        })
    }

    /// The closed curve through a ring of particles (a loop topology): `K` spans, wrapping
    /// from the last particle back to the first with no seam. [`Smoothing::BSpline`] is C²
    /// all round, [`Smoothing::CatmullRom`] passes through every particle,
    /// [`Smoothing::Polyline`] joins them straight. The samples start and end on the same
    /// point, so a polyline through them closes.
    ///
    /// ```
    /// use dunas::{Vec2, smooth::{Smoothed, Smoothing}};
    /// let square = [Vec2::new(0.0f32, 0.0), Vec2::new(1.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0)];
    /// let mut out = [Vec2::default(); 17];
    /// assert_eq!(Smoothed::closed(Smoothing::CatmullRom, &square)?.sample(&mut out), Ok(17));
    /// assert_eq!(out[0], out[16]);
    /// assert_eq!(out[4], square[1]); // 4 segments per span: particle k at sample 4k
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`open`](Self::open); [`Error::InvalidParameter`] for [`Smoothing::Bezier`], since
    /// one Bézier curve cannot close smoothly.
    pub fn closed(method: Smoothing, particles: &[P; K]) -> Result<Self, Error> {
        const { assert!(K >= 3, "a closed loop needs at least 3 particles") };
        Self::ring(method, particles)
    }

    /// [`closed`](Self::closed) for any `K`: [`Error::InvalidParameter`] below 3 particles.
    pub(crate) fn ring(method: Smoothing, particles: &[P; K]) -> Result<Self, Error> {
        if K < 3 {
            return Err(invalid("particle count", "at least 3 for a closed curve"));
        }
        check_points(particles, "particles")?;
        let mut controls = *particles;
        if method == Smoothing::NaturalSpline {
            natural_controls(&mut controls, true);
        }
        let pieces = match method {
            Smoothing::Bezier => {
                return Err(invalid(
                    "smoothing",
                    "a spline or the polyline (one Bezier cannot close)",
                ));
            }
            Smoothing::Polyline => {
                Pieces::Straight(core::array::from_fn(|i| ring_segment(&controls, i)), K)
            }
            _ => {
                let f = Fractions::new();
                Pieces::Cubic(
                    core::array::from_fn(|i| ring_span(method, &controls, i, f)),
                    K,
                )
            }
        };
        Ok(Smoothed {
            pieces,
            method,
            len: K,
        })
    }

    /// Draws again, after particles `lo..=hi` of those it is drawn through moved, the spans
    /// they weigh in (a cubic spline's span weighs the particles from one before it to two
    /// after, a segment its two ends), checking only the moved particles; one Bézier and
    /// the natural spline, whose every span each particle weighs in, are drawn again whole.
    /// Returns the spans drawn again, `(first, count)`, counted round a loop: the same
    /// spans as drawing it again whole, at the cost of those.
    ///
    /// # Errors
    /// As [`open`](Self::open), for the moved particles.
    pub(crate) fn redraw(
        &mut self,
        particles: &[P; K],
        moved: (usize, usize),
    ) -> Result<(usize, usize), Error> {
        match self.outdated(particles, moved)? {
            Some(spans) => {
                self.redraw_spans(particles, spans);
                Ok(spans)
            }
            None => Ok((0, self.span_count())),
        }
    }

    /// What [`redraw`](Self::redraw) would draw again after particles `lo..=hi` moved,
    /// `(first, count)` round a loop (at most every span), left to
    /// [`redraw_spans`](Self::redraw_spans); `None` for one Bézier or a natural spline, whose
    /// every span each particle weighs in, and for particles past the curve's, which this
    /// draws again at once.
    ///
    /// # Errors
    /// As [`open`](Self::open), for the moved particles.
    pub(crate) fn outdated(
        &mut self,
        particles: &[P; K],
        (lo, hi): (usize, usize),
    ) -> Result<Option<(usize, usize)>, Error> {
        let spans = self.span_count();
        let closed = spans == K;
        // How many spans before the first moved particle and after the last it weighs in.
        let (before, after) = match self.method {
            Smoothing::Polyline => (1, 0),
            Smoothing::BSpline | Smoothing::CatmullRom => (2, 1),
            Smoothing::Bezier | Smoothing::NaturalSpline => (K, K),
        };
        let count = (hi.min(K - 1) + 1).saturating_sub(lo) + before + after;
        if before >= K || lo > hi || hi >= self.len {
            *self = if closed {
                Self::ring(self.method, particles)
            } else {
                Self::open_first(self.method, particles, self.len)
            }?;
            return Ok(None);
        }
        check_points(&particles[lo..=hi], "particles")?;
        Ok(Some(if closed {
            ((lo + K - before) % K, count.min(spans))
        } else {
            let first = lo.saturating_sub(before);
            (first, (hi + after).min(spans - 1) + 1 - first)
        }))
    }

    /// Draws spans `first..first + count` (round a loop) again from `particles`, as
    /// [`outdated`](Self::outdated) gave them.
    pub(crate) fn redraw_spans(&mut self, particles: &[P; K], (first, count): (usize, usize)) {
        let spans = self.span_count();
        let closed = spans == K;
        let (method, n, f) = (self.method, self.len, Fractions::new());
        // Round a loop without a division a span.
        let start = first.checked_rem(spans).unwrap_or(0);
        let index = |j: usize| match start + j {
            i if i >= spans => i - spans,
            i => i,
        };
        let count = count.min(spans);
        match &mut self.pieces {
            Pieces::Cubic(s, _) => (0..count).map(index).for_each(|i| {
                s[i] = match (closed, method) {
                    (true, _) => ring_span(method, particles, i, f),
                    (false, Smoothing::CatmullRom) => catmull_rom_span(particles, n, i, f),
                    _ => bspline_span(particles, n, i, f),
                };
            }),
            Pieces::Straight(s, _) => (0..count).map(index).for_each(|i| {
                s[i] = if closed {
                    ring_segment(particles, i)
                } else {
                    segment(particles, n, i)
                };
            }),
            Pieces::Whole(_) => {}
        }
    }

    /// Samples the curve with the format's [`DefaultSampler`]; returns the count. One
    /// Bézier writes what [`Bezier::sample`] writes. Spans write `spans·s + 1` points,
    /// `s` segments a span: `s = ⌊(out.len() - 1) / spans⌋` in floats, the largest power of
    /// two up to that in `Q16` (dyadic parameters, no multiplication).
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] when `out` holds fewer than `spans + 1` points.
    #[inline]
    pub fn sample(&self, out: &mut [P]) -> Result<usize, Error> {
        self.sample_with(&DefaultSampler, out)
    }

    /// Samples the curve with `sampler` for its cubic spans ([`Smoothing::BSpline`] and
    /// [`Smoothing::CatmullRom`]); one Bézier and straight segments use the
    /// [`DefaultSampler`]. See [`Sampler::sample_joined`] for the count.
    ///
    /// ```
    /// use dunas::{Vec2, sampler::BernsteinTable, smooth::{Smoothed, Smoothing}};
    /// let rope = [Vec2::new(0.0f32, 0.0), Vec2::new(1.0, -1.0), Vec2::new(2.0, -1.0), Vec2::new(3.0, 0.0)];
    /// let table = BernsteinTable::<f32, 4, 9>::new(); // 8 segments a span, built once
    /// let mut out = [Vec2::default(); 64];
    /// let n = Smoothed::open(Smoothing::BSpline, &rope)?.sample_with(&table, &mut out)?;
    /// assert_eq!(n, 25);
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Sampler::sample_joined`].
    pub fn sample_with(&self, sampler: &impl Sampler<P, 4>, out: &mut [P]) -> Result<usize, Error> {
        match &self.pieces {
            Pieces::Whole(curve) => DefaultSampler.sample_joined(core::slice::from_ref(curve), out),
            Pieces::Cubic(spans, count) => sampler.sample_joined(&spans[..*count], out),
            Pieces::Straight(segments, count) => {
                DefaultSampler.sample_joined(&segments[..*count], out)
            }
        }
    }

    /// The cubic spans (empty for one Bézier or straight segments).
    pub(crate) fn cubic_spans(&self) -> &[Bezier<P, 4>] {
        match &self.pieces {
            Pieces::Cubic(spans, count) => &spans[..*count],
            _ => &[],
        }
    }

    /// The smoothing that draws it.
    pub(crate) fn method(&self) -> Smoothing {
        self.method
    }

    /// Number of spans: 1 for one Bézier, `K - 1` open, `K` closed.
    pub fn span_count(&self) -> usize {
        match self.pieces {
            Pieces::Whole(_) => 1,
            Pieces::Cubic(_, count) | Pieces::Straight(_, count) => count,
        }
    }

    /// The point of span `span` at `t` in `[0, 1]` (`t` clamped; a span past the last is the
    /// last). De Casteljau on the span: 6 lerps for a cubic span, `K²/2` for one Bézier.
    pub fn point(&self, span: usize, t: P::Scalar) -> P {
        let t = crate::curves::curve::clamp_unit(t);
        match &self.pieces {
            Pieces::Whole(curve) => curve.eval(t),
            Pieces::Cubic(spans, count) => spans[span.min(count - 1)].eval(t),
            Pieces::Straight(segments, count) => segments[span.min(count - 1)].eval(t),
        }
    }

    /// The derivative `dP/dt` of span `span` at `t` (as [`point`](Self::point)): 5 lerps
    /// for a cubic span.
    pub(crate) fn tangent(&self, span: usize, t: P::Scalar) -> P {
        match &self.pieces {
            Pieces::Whole(curve) => curve.tangent(t),
            Pieces::Cubic(spans, count) => spans[span.min(count - 1)].tangent(t),
            Pieces::Straight(segments, count) => segments[span.min(count - 1)].tangent(t),
        }
    }

    /// The parameter of span `span` whose point has the least `key`: see
    /// [`Bezier::deepest`](crate::Bezier). Halving only (no multiplication in `Q16`).
    pub(crate) fn deepest(&self, span: usize, key: impl Fn(P) -> P::Scalar) -> P::Scalar {
        match &self.pieces {
            Pieces::Whole(curve) => curve.deepest(key),
            Pieces::Cubic(spans, count) => spans[span.min(count - 1)].deepest(key),
            Pieces::Straight(segments, count) => segments[span.min(count - 1)].deepest(key),
        }
    }

    /// The parameter of span `span` where it reaches farthest against `normal`: see
    /// [`Bezier::lowest`](crate::Bezier).
    pub(crate) fn lowest(&self, span: usize, normal: P) -> P::Scalar {
        match &self.pieces {
            Pieces::Whole(curve) => curve.lowest(normal),
            Pieces::Cubic(spans, count) => spans[span.min(count - 1)].lowest(normal),
            Pieces::Straight(segments, count) => segments[span.min(count - 1)].lowest(normal),
        }
    }

    /// The parameter of span `span` nearest `c`: see [`Bezier::nearest`](crate::Bezier).
    pub(crate) fn nearest(&self, span: usize, c: P) -> P::Scalar {
        match &self.pieces {
            Pieces::Whole(curve) => curve.nearest(c),
            Pieces::Cubic(spans, count) => spans[span.min(count - 1)].nearest(c),
            Pieces::Straight(segments, count) => segments[span.min(count - 1)].nearest(c),
        }
    }

    /// The box of span `span`'s control points, which holds the span (convex hull property).
    pub fn span_bounds(&self, span: usize) -> Aabb<P> {
        Aabb::from_points(self.span_points(span)).unwrap_or(Aabb::point(P::default()))
    }

    /// Span `span`'s control points: 4 for a cubic span, 2 for a segment, every particle for
    /// one Bézier (a span past the last is the last).
    pub(crate) fn span_points(&self, span: usize) -> &[P] {
        match &self.pieces {
            Pieces::Whole(curve) => curve.points(),
            Pieces::Cubic(spans, count) => spans[span.min(count - 1)].points(),
            Pieces::Straight(segments, count) => segments[span.min(count - 1)].points(),
        }
    }

    /// How much each particle weighs in the point of span `span` at `t`: the point is
    /// `Σ weights[i] · particles[i]`, and the weights sum to 1. At most 4 are non-zero for the
    /// splines, 2 for the polyline, all `K` for one Bézier; Catmull-Rom's can be negative
    /// (down to -1/16, with `Σ|w| <= 5/4`). A force or a correction at that point reaches the
    /// particles through these weights.
    pub fn weights(&self, span: usize, t: P::Scalar, weights: &mut [P::Scalar; K]) {
        let closed = self.span_count() == K;
        self.method.row_weights(closed, self.len, span, t, weights);
    }

    /// [`weights`](Self::weights) of an open curve's cubic or straight span: the first of
    /// the 4 particles that can weigh in and their weights; `None` on a loop, for one
    /// Bézier, the natural spline and fewer than 4 particles.
    pub(crate) fn window(&self, span: usize, t: P::Scalar) -> Option<(usize, [P::Scalar; 4])> {
        (self.span_count() != K)
            .then(|| self.method.window(self.len, span, t))
            .flatten()
    }

    /// Length of the curve within `accuracy` (see [`Bezier::arclen`]), shared between the
    /// spans; a polyline's length is exact.
    pub fn length(&self, accuracy: P::Scalar) -> P::Scalar {
        let share = accuracy / P::Scalar::from_i16(self.span_count().min(i16::MAX as usize) as i16);
        let mut len = P::Scalar::ZERO;
        match &self.pieces {
            Pieces::Whole(curve) => len = curve.arclen(accuracy),
            Pieces::Cubic(spans, count) => {
                for span in &spans[..*count] {
                    len += span.arclen(share);
                }
            }
            Pieces::Straight(segments, count) => {
                for s in &segments[..*count] {
                    len += s.start().distance(s.end());
                }
            }
        }
        len
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;

    fn zigzag() -> [Vec2<f64>; 6] {
        core::array::from_fn(|i| Vec2::new(i as f64, if i % 2 == 0 { 0.0 } else { 1.0 }))
    }

    #[test]
    fn every_method_hits_the_ends() {
        let p = zigzag();
        for m in [
            Smoothing::Bezier,
            Smoothing::BSpline,
            Smoothing::CatmullRom,
            Smoothing::Polyline,
            Smoothing::NaturalSpline,
        ] {
            let mut out = [Vec2::default(); 18];
            let n = Smoothed::open(m, &p).unwrap().sample(&mut out).unwrap();
            // 5 spans of 3 segments, or one Bézier filling the buffer.
            assert_eq!(n, if m == Smoothing::Bezier { 18 } else { 16 }, "{m:?}");
            assert_eq!(out[0], p[0], "{m:?}");
            assert_eq!(out[n - 1], p[5], "{m:?}");
        }
    }

    #[test]
    fn catmull_rom_and_polyline_pass_through_particles() {
        let p = zigzag();
        let mut out = [Vec2::default(); 26]; // 5 spans × 5 + 1: particle k at sample 5k
        for m in [
            Smoothing::CatmullRom,
            Smoothing::Polyline,
            Smoothing::NaturalSpline,
        ] {
            Smoothed::open(m, &p).unwrap().sample(&mut out).unwrap();
            for (k, &pk) in p.iter().enumerate() {
                assert!((out[5 * k] - pk).length() < 1e-12, "{m:?} particle {k}");
            }
        }
    }

    #[test]
    fn bspline_joins_are_c2() {
        let p = zigzag();
        let s = bspline_spans(&p, p.len());
        for i in 0..p.len() - 2 {
            let (a, b) = (*s[i].points(), *s[i + 1].points());
            assert_eq!(a[3], b[0]);
            // C1: equal first derivatives; C2: equal second derivatives at the join.
            assert!(((a[3] - a[2]) - (b[1] - b[0])).length() < 1e-12);
            let a2 = a[3] - a[2] * 2.0 + a[1];
            let b2 = b[2] - b[1] * 2.0 + b[0];
            assert!((a2 - b2).length() < 1e-12);
        }
    }

    /// The natural spline passes through every particle of a row and of a ring, is C² at
    /// every joint (it is a B-spline), has no curvature at open ends, and its particle
    /// weights stay within the documented `Σ|w| < 1.55`.
    #[test]
    fn natural_spline_interpolates_with_c2_joins() {
        let p = zigzag();
        for closed in [false, true] {
            let curve = if closed {
                Smoothed::closed(Smoothing::NaturalSpline, &p).unwrap()
            } else {
                Smoothed::open(Smoothing::NaturalSpline, &p).unwrap()
            };
            let Pieces::Cubic(s, count) = curve.pieces else {
                panic!("cubic spans")
            };
            for i in 0..count {
                let a = *s[i].points();
                assert!((a[0] - p[i]).length() < 1e-12, "{closed} {i}");
                assert!((a[3] - p[(i + 1) % 6]).length() < 1e-12, "{closed} {i}");
                if i + 1 < count || closed {
                    let b = *s[(i + 1) % count].points();
                    let a2 = a[3] - a[2] * 2.0 + a[1];
                    let b2 = b[2] - b[1] * 2.0 + b[0];
                    assert!((a2 - b2).length() < 1e-12, "{closed} {i}");
                }
            }
            if !closed {
                let a = *s[0].points();
                assert!((a[2] - a[1] * 2.0 + a[0]).length() < 1e-12);
            }
            let mut w = [0.0; 6];
            for span in 0..count {
                for k in 0..=16 {
                    curve.weights(span, k as f64 / 16.0, &mut w);
                    assert!(w.iter().map(|w| w.abs()).sum::<f64>() < 1.55, "{w:?}");
                }
            }
        }
    }

    #[test]
    fn catmull_rom_joins_are_c1() {
        let p = zigzag();
        let s = catmull_rom_spans(&p, p.len());
        for i in 0..p.len() - 2 {
            let (a, b) = (*s[i].points(), *s[i + 1].points());
            assert!(((a[3] - a[2]) - (b[1] - b[0])).length() < 1e-12);
        }
    }

    #[test]
    fn closed_loops_have_no_seam() {
        let ring: [Vec2<f64>; 6] = core::array::from_fn(|i| {
            let a = i as f64 * core::f64::consts::TAU / 6.0;
            Vec2::new(a.cos(), a.sin())
        });
        let mut out = [Vec2::default(); 6 * 8 + 1];
        for m in [
            Smoothing::BSpline,
            Smoothing::CatmullRom,
            Smoothing::NaturalSpline,
        ] {
            Smoothed::closed(m, &ring)
                .unwrap()
                .sample(&mut out)
                .unwrap();
            // The same distance from the centre all round, and rotating the ring only
            // rotates the curve: the seam at particle 0 is like every other joint.
            let r0 = out[0].length();
            for o in &out {
                assert!((o.length() - r0).abs() < 0.05, "{m:?}");
            }
            let rotated: [Vec2<f64>; 6] = core::array::from_fn(|i| ring[(i + 1) % 6]);
            let mut out2 = [Vec2::default(); 6 * 8 + 1];
            Smoothed::closed(m, &rotated)
                .unwrap()
                .sample(&mut out2)
                .unwrap();
            for k in 0..out.len() - 8 {
                assert!((out[k + 8] - out2[k]).length() < 1e-12, "{m:?} {k}");
            }
        }
        assert!(matches!(
            Smoothed::closed(Smoothing::Bezier, &ring),
            Err(Error::InvalidParameter { .. })
        ));
    }

    #[test]
    fn weights_rebuild_every_drawn_point() {
        let p = zigzag();
        for closed in [false, true] {
            for m in [
                Smoothing::Bezier,
                Smoothing::BSpline,
                Smoothing::CatmullRom,
                Smoothing::Polyline,
                Smoothing::NaturalSpline,
            ] {
                let Ok(curve) = (if closed {
                    Smoothed::closed(m, &p)
                } else {
                    Smoothed::open(m, &p)
                }) else {
                    continue;
                };
                let mut w = [0.0; 6];
                for span in 0..curve.span_count() {
                    for k in 0..=8 {
                        let t = k as f64 / 8.0;
                        curve.weights(span, t, &mut w);
                        let rebuilt = p
                            .iter()
                            .zip(&w)
                            .fold(Vec2::default(), |acc, (&pi, &wi)| acc + pi * wi);
                        let drawn = curve.point(span, t);
                        assert!(
                            (rebuilt - drawn).length() < 1e-12,
                            "{m:?} {closed} {span} {t}"
                        );
                        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
                    }
                }
            }
        }
    }

    #[test]
    fn bad_input_is_an_error() {
        let mut p = zigzag();
        let mut out = [Vec2::default(); 8];
        let curve = Smoothed::open(Smoothing::BSpline, &p).unwrap();
        assert_eq!(
            curve.sample(&mut out[..5]),
            Err(Error::BufferTooSmall { needed: 6, got: 5 })
        );
        p[3].y = f64::NAN;
        assert!(matches!(
            Smoothed::open(Smoothing::Polyline, &p),
            Err(Error::NonFinite { .. })
        ));
    }

    #[test]
    fn straight_particles_give_a_straight_curve() {
        let p: [Vec2<f64>; 5] = core::array::from_fn(|i| Vec2::new(2.0 * i as f64, 0.0));
        for m in [
            Smoothing::Bezier,
            Smoothing::BSpline,
            Smoothing::CatmullRom,
            Smoothing::NaturalSpline,
        ] {
            let mut out = [Vec2::default(); 9];
            Smoothed::open(m, &p).unwrap().sample(&mut out).unwrap();
            for (i, o) in out.iter().enumerate() {
                assert!(
                    (o.x - i as f64).abs() < 1e-12 && o.y == 0.0,
                    "{m:?} {i} {o:?}"
                );
            }
        }
    }
}
