//! What each particle weighs in a point of the curve a [`Smoothing`] draws, and in its
//! slope: the weights a contact pushes a drawn point through, and that rebuild it from the
//! particles. They depend on the basis only, not on the particles.

use super::natural::natural_weights;
#[cfg(doc)]
use super::smooth::Smoothed;
use super::smooth::Smoothing;
use crate::Scalar;

impl Smoothing {
    /// The particle weights of span `span` at `t` of the open (or `closed`) curve of `K`
    /// particles: see [`Smoothed::weights`]. Depends on the basis only, not on the particles.
    pub(crate) fn weights<S: Scalar, const K: usize>(
        self,
        closed: bool,
        span: usize,
        t: S,
        weights: &mut [S; K],
    ) {
        self.row_weights(closed, K, span, t, weights);
    }

    /// [`weights`](Self::weights) of the curve through the first `n` of the `K` particles
    /// (`2 ≤ n ≤ K`; a piece of a broken rope): the later particles weigh 0. One Bézier
    /// repeats the `n`-th particle up to degree `K - 1`, as [`Smoothed`] builds it.
    pub(crate) fn row_weights<S: Scalar, const K: usize>(
        self,
        closed: bool,
        n: usize,
        span: usize,
        t: S,
        weights: &mut [S; K],
    ) {
        let len = if closed { K } else { n.clamp(2.min(K), K) };
        let t = crate::curves::curve::clamp_unit(t);
        let Some(local) = self.local(t) else {
            if self == Smoothing::NaturalSpline {
                Smoothing::BSpline.row_weights(closed, len, span, t, weights);
                return natural_weights(weights, closed, len);
            }
            crate::curves::sampler::bernstein_weights(t, weights);
            let repeated: S = weights[len..].iter().fold(S::ZERO, |sum, &w| sum + w);
            weights[len - 1] += repeated;
            weights[len..].fill(S::ZERO);
            return;
        };
        *weights = [S::ZERO; K];
        fold(local, (closed, K), span, len, |i, w| weights[i] += w);
    }

    /// [`row_weights`](Self::row_weights) of an open curve through `n ≥ 4` particles, the
    /// same numbers, for the 4 particles from the first returned on (every other weighs 0):
    /// no pass over all `K`. `None` for one Bézier and the natural spline (every particle
    /// weighs in) and for fewer than 4 particles.
    pub(crate) fn window<S: Scalar>(self, n: usize, span: usize, t: S) -> Option<(usize, [S; 4])> {
        let local = self
            .local(crate::curves::curve::clamp_unit(t))
            .filter(|_| n >= 4)?;
        let first = span.min(n - 2).saturating_sub(1).min(n - 4);
        let mut weights = [S::ZERO; 4];
        fold(local, (false, n), span, n, |i, w| weights[i - first] += w);
        Some((first, weights))
    }

    /// The weights of the 4 particles from the one before a span of a cubic spline or
    /// the polyline at `t` in `[0, 1]`; `None` for one Bézier and the natural spline.
    fn local<S: Scalar>(self, t: S) -> Option<[S; 4]> {
        let zero = S::ZERO;
        let (t2, sixth, half) = (t * t, S::ratio(1, 6), S::ratio(1, 2));
        let t3 = t2 * t;
        let n = |k: i16| S::from_i16(k);
        match self {
            Smoothing::Bezier | Smoothing::NaturalSpline => None,
            Smoothing::Polyline => Some([zero, S::ONE - t, t, zero]),
            Smoothing::BSpline => {
                let s = S::ONE - t;
                Some([
                    s * s * s * sixth,
                    (n(3) * t3 - n(6) * t2 + n(4)) * sixth,
                    (n(-3) * t3 + n(3) * t2 + n(3) * t + S::ONE) * sixth,
                    t3 * sixth,
                ])
            }
            Smoothing::CatmullRom => Some([
                (-t3 + n(2) * t2 - t) * half,
                (n(3) * t3 - n(5) * t2 + n(2)) * half,
                (n(-3) * t3 + n(4) * t2 + t) * half,
                (t3 - t2) * half,
            ]),
        }
    }

    /// The derivatives `d/dt` of [`weights`](Self::weights) at the same point: the particle
    /// weights of the curve's velocity along span `span` (per unit of the span's `t`).
    pub(crate) fn slopes<S: Scalar, const K: usize>(
        self,
        closed: bool,
        span: usize,
        t: S,
        slopes: &mut [S; K],
    ) {
        let t = crate::curves::curve::clamp_unit(t);
        let zero = S::ZERO;
        let (t2, half) = (t * t, S::ratio(1, 2));
        let n = |k: i16| S::from_i16(k);
        let local = match self {
            Smoothing::Bezier => {
                // B'_i = (K-1)·(B_{i-1} - B_i) over the Bernstein basis of degree K-2.
                let mut lower = [zero; K];
                crate::curves::sampler::bernstein_weights(t, &mut lower[..K - 1]);
                let degree = S::ratio((K - 1) as u32, 1);
                for i in 0..K {
                    let before = if i > 0 { lower[i - 1] } else { zero };
                    let here = if i < K - 1 { lower[i] } else { zero };
                    slopes[i] = (before - here) * degree;
                }
                return;
            }
            Smoothing::Polyline => [zero, -S::ONE, S::ONE, zero],
            Smoothing::NaturalSpline => {
                Smoothing::BSpline.slopes(closed, span, t, slopes);
                return natural_weights(slopes, closed, K);
            }
            Smoothing::BSpline => {
                let s = S::ONE - t;
                [
                    -s * s * half,
                    (n(3) * t2 - n(4) * t) * half,
                    (n(-3) * t2 + n(2) * t + S::ONE) * half,
                    t2 * half,
                ]
            }
            Smoothing::CatmullRom => [
                (n(-3) * t2 + n(4) * t - S::ONE) * half,
                (n(9) * t2 - n(10) * t) * half,
                (n(-9) * t2 + n(8) * t + S::ONE) * half,
                (n(3) * t2 - n(2) * t) * half,
            ],
        };
        *slopes = [S::ZERO; K];
        fold(local, (closed, K), span, K, |i, w| slopes[i] += w);
    }
}

/// Hands `add` the local weights of particles `span-1 ..= span+2` of a spline over the
/// first `n` particles (`2 ≤ n`; all `ring` when `closed`), each with its particle,
/// `span` clamped to the last: open ends reflect a phantom particle through the end one
/// (`2·p0 - p1`), as the spans were built; a closed curve wraps.
fn fold<S: Scalar>(
    local: [S; 4],
    (closed, ring): (bool, usize),
    span: usize,
    n: usize,
    mut add: impl FnMut(usize, S),
) {
    let spans = if closed { ring } else { n.saturating_sub(1) };
    let span = span.min(spans.saturating_sub(1));
    for (k, w) in local.into_iter().enumerate() {
        let i = span as isize + k as isize - 1;
        let last = n as isize - 1;
        if closed {
            add(i.rem_euclid(ring as isize) as usize, w);
        } else if i < 0 {
            add(0, w + w);
            add(1, -w);
        } else if i > last {
            add(n - 1, w + w);
            add(n - 2, -w);
        } else {
            add(i as usize, w);
        }
    }
}
