//! Drawing the spline rope and touching its drawn curve: its control points as the uniform
//! cubic B-spline's spans.

use super::*;

impl<P: Point, const K: usize, I: SplineStepper> SplineRope<P, K, I> {
    /// Draws the curve into `out` with the format's [`DefaultSampler`] (mul-free dyadic
    /// halving in `Q16`), span by span from their Bézier extraction: `(K-3)·s + 1` points,
    /// `s` points a span from `out`'s length (see [`Sampler::sample_joined`]); returns the
    /// count. The first and last points are the end control points.
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] when `out` holds fewer than `K - 2` points.
    pub fn sample(&self, out: &mut [P]) -> Result<usize, Error> {
        let spans = Spans::new(&self.ext, &self.pos);
        DefaultSampler.sample_joined(&spans.spans[..K - 3], out)
    }
}

/// A spline rope's curve as Bézier spans (its Bézier extraction), as contacts test it.
pub(super) struct Spans<'a, P: Point, const K: usize> {
    pub(super) ext: &'a [[[P::Scalar; 4]; 4]; K],
    /// Span `e` in `spans[e]` for `e < K - 3` (the rest unused).
    pub(super) spans: [Bezier<P, 4>; K],
}

impl<'a, P: Point, const K: usize> Spans<'a, P, K> {
    pub(super) fn new(ext: &'a [[[P::Scalar; 4]; 4]; K], pos: &[P; K]) -> Self {
        let mut spans = Spans {
            ext,
            spans: [Bezier::new_unchecked([P::default(); 4]); K],
        };
        spans.redraw(pos);
        spans
    }

    /// The spans' Bézier points. Span `e`'s inner two lie on the leg from `p_(e+1)` to
    /// `p_(e+2)` (at the extraction's weights: 4 products a span), and, the spans being of
    /// one length, a span ends halfway between its last inner point and the next span's
    /// first (the curve's ends are its end control points). A span starts where the last
    /// ends, exactly, in every format.
    fn redraw(&mut self, pos: &[P; K]) {
        let inner = |e: usize| {
            let leg = pos[e + 2] - pos[e + 1];
            let ext = &self.ext[e];
            (pos[e + 1] + leg * ext[1][2], pos[e + 1] + leg * ext[2][2])
        };
        let (mut start, mut here) = (pos[0], inner(0));
        for e in 0..K - 3 {
            let (next, end) = if e + 1 < K - 3 {
                let next = inner(e + 1);
                (next, here.1.midpoint(next.0))
            } else {
                (here, pos[K - 1])
            };
            self.spans[e] = Bezier::new_unchecked([start, here.0, here.1, end]);
            (start, here) = (end, next);
        }
    }
}

impl<P: Point, const K: usize> DrawnSpans<P, K> for Spans<'_, P, K> {
    fn span_count(&self) -> usize {
        K - 3
    }
    fn span_bounds(&self, span: usize) -> Aabb<P> {
        self.spans[span].bounding_box()
    }
    fn deepest(&self, span: usize, key: impl Fn(P) -> P::Scalar) -> P::Scalar {
        self.spans[span].deepest(key)
    }
    fn lowest(&self, span: usize, normal: P) -> P::Scalar {
        self.spans[span].lowest(normal)
    }
    fn nearest(&self, span: usize, c: P) -> P::Scalar {
        self.spans[span].nearest(c)
    }
    fn point(&self, span: usize, t: P::Scalar) -> P {
        self.spans[span].eval(t)
    }
    fn tangent(&self, span: usize, t: P::Scalar) -> P {
        self.spans[span].tangent(t)
    }
    fn cubic(&self, span: usize) -> Option<[P; 4]> {
        Some(*self.spans[span].points())
    }
    /// The Bernstein weights at `t` through the span's extraction.
    fn weights(&self, span: usize, t: P::Scalar, weights: &mut [P::Scalar; K]) {
        let mut bernstein = [P::Scalar::ZERO; 4];
        bernstein_weights(t, &mut bernstein);
        *weights = [P::Scalar::ZERO; K];
        for (r, &b) in bernstein.iter().enumerate() {
            for k in 0..4 {
                weights[span + k] += b * self.ext[span][r][k];
            }
        }
    }
    /// Draws every span again (each span's ends are its neighbours' midpoints).
    fn rebuild(&mut self, pos: &[P; K], _: (usize, usize)) -> Option<(usize, usize)> {
        self.redraw(pos);
        Some((0, K - 3))
    }
    /// Every span weighs in each control point: drawn again at once.
    fn outdated(&mut self, pos: &[P; K], _: (usize, usize)) -> Option<(usize, usize)> {
        self.redraw(pos);
        Some((0, 0))
    }
    fn redraw_spans(&mut self, pos: &[P; K], _: (usize, usize)) {
        self.redraw(pos);
    }
}
