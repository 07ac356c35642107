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
//! - [`Smoothing::Polyline`]: straight segments between the particles, the unsmoothed
//!   reference. 1 lerp a point.
//!
//! All of them write into the caller's buffer and spread the samples uniformly over the
//! particle index (`u = i·(K-1)/(n-1)`), so each span gets the same number of points.
//!
//! ```
//! use dunas::{Vec2, smooth::{self, Smoothing}};
//! let rope = [Vec2::new(0.0f32, 0.0), Vec2::new(1.0, -1.0), Vec2::new(2.0, -1.0), Vec2::new(3.0, 0.0)];
//! let mut out = [Vec2::default(); 31];
//! let n = smooth::sample(Smoothing::CatmullRom, &rope, &mut out)?;
//! assert_eq!(n, 31);
//! assert_eq!(out[10], rope[1]); // Catmull-Rom passes through every particle
//! # Ok::<(), dunas::Error>(())
//! ```

use crate::error::check_points;
use crate::{Bezier, Error, Point, Scalar};

/// How a row of particles becomes a curve. See the [module docs](self).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Smoothing {
    /// One Bézier curve of degree `K - 1` over all the particles.
    #[default]
    Bezier,
    /// Uniform cubic B-spline, C² (ends clamped by reflected phantom points).
    BSpline,
    /// Catmull-Rom spline through every particle, C¹.
    CatmullRom,
    /// Straight lines between the particles.
    Polyline,
}

/// Samples the curve that `method` makes of `particles` into `out`; returns the count.
///
/// The count is `out.len()` in floats. In `Q16` every method samples at dyadic parameters with
/// shifts and additions only (no rounded `t`, no multiplication): [`Smoothing::Bezier`] writes
/// the largest `2^k + 1 <= out.len()` points, the others the largest `(K-1)·2^k + 1` (each span
/// halved `k` times).
///
/// # Errors
/// [`Error::NonFinite`] / [`Error::OutOfRange`] when a particle is NaN, infinite, saturated
/// or beyond [`Scalar::SAFE_RANGE`]; [`Error::BufferTooSmall`] when `out` holds fewer than 2.
// Inlined so that a constant `method` folds away the other methods' code (flash on a device).
#[inline]
pub fn sample<P: Point, const K: usize>(
    method: Smoothing,
    particles: &[P; K],
    out: &mut [P],
) -> Result<usize, Error> {
    const { assert!(K >= 2, "smoothing needs at least 2 particles") };
    check_points(particles)?;
    if out.len() < 2 {
        return Err(Error::BufferTooSmall {
            needed: 2,
            got: out.len(),
        });
    }
    match method {
        Smoothing::Bezier => Bezier::new(*particles)?.sample(out),
        Smoothing::BSpline => Ok(sample_spans(&bspline_spans(particles), out)),
        Smoothing::CatmullRom => Ok(sample_spans(&catmull_rom_spans(particles), out)),
        Smoothing::Polyline => Ok(sample_polyline(particles, out)),
    }
}

/// Samples the *closed* curve through a ring of particles (a loop topology): the spans wrap
/// from the last particle back to the first with no seam, `K` spans in all. The first sample
/// is repeated as the last, so a polyline through `out[..n]` closes.
///
/// [`Smoothing::BSpline`] is C² all round, [`Smoothing::CatmullRom`] passes through every
/// particle, [`Smoothing::Polyline`] joins them straight. A single Bézier curve cannot close
/// smoothly, so [`Smoothing::Bezier`] is an error here.
///
/// ```
/// use dunas::{Vec2, smooth::{self, Smoothing}};
/// let square = [Vec2::new(0.0f32, 0.0), Vec2::new(1.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0)];
/// let mut out = [Vec2::default(); 17];
/// assert_eq!(smooth::sample_closed(Smoothing::CatmullRom, &square, &mut out), Ok(17));
/// assert_eq!(out[0], out[16]);
/// assert_eq!(out[4], square[1]); // 4 samples per span: particle k at sample 4k
/// # Ok::<(), dunas::Error>(())
/// ```
///
/// # Errors
/// As [`sample`]; [`Error::InvalidParameter`] for [`Smoothing::Bezier`].
pub fn sample_closed<P: Point, const K: usize>(
    method: Smoothing,
    particles: &[P; K],
    out: &mut [P],
) -> Result<usize, Error> {
    const { assert!(K >= 3, "a closed loop needs at least 3 particles") };
    check_points(particles)?;
    if out.len() < 2 {
        return Err(Error::BufferTooSmall {
            needed: 2,
            got: out.len(),
        });
    }
    let at = |i: usize| particles[i % K];
    let sixth = P::Scalar::ratio(1, 6);
    let mut spans = [[particles[0]; 4]; K];
    for (i, span) in spans.iter_mut().enumerate() {
        let (prev, a, b, next) = (at(i + K - 1), at(i), at(i + 1), at(i + 2));
        *span = match method {
            Smoothing::Bezier => return Err(Error::InvalidParameter),
            Smoothing::Polyline => [a, a, b, b],
            Smoothing::CatmullRom => [a, a + (b - prev) * sixth, b - (next - a) * sixth, b],
            Smoothing::BSpline => {
                let third = P::Scalar::ratio(1, 3);
                let knot = |p: P, q: P, r: P| q + (p - q) * sixth + (r - q) * sixth;
                let step = b - a;
                [
                    knot(prev, a, b),
                    a + step * third,
                    b - step * third,
                    knot(a, b, next),
                ]
            }
        };
    }
    let n = out.len().min(crate::sampler::MAX_SAMPLES);
    for_each_param::<P::Scalar>(K, n, |i, s, t| out[i] = eval_cubic(&spans[s], t));
    out[n - 1] = out[0];
    Ok(n)
}

/// Length of the curve that `method` makes of `particles`, within `accuracy` (see
/// [`Bezier::arclen`]); the polyline's length is exact.
///
/// # Errors
/// As [`sample`], for bad particles.
pub fn length<P: Point, const K: usize>(
    method: Smoothing,
    particles: &[P; K],
    accuracy: P::Scalar,
) -> Result<P::Scalar, Error> {
    const { assert!(K >= 2, "smoothing needs at least 2 particles") };
    check_points(particles)?;
    let spans = match method {
        Smoothing::Bezier => return Ok(Bezier::new(*particles)?.arclen(accuracy)),
        Smoothing::Polyline => {
            let mut len = P::Scalar::ZERO;
            for w in particles.windows(2) {
                len += w[0].distance(w[1]);
            }
            return Ok(len);
        }
        Smoothing::BSpline => bspline_spans(particles),
        Smoothing::CatmullRom => catmull_rom_spans(particles),
    };
    let share = accuracy / P::Scalar::from_i16((K - 1).min(i16::MAX as usize) as i16);
    let mut len = P::Scalar::ZERO;
    for span in &spans[..K - 1] {
        len += Bezier::new(*span)?.arclen(share);
    }
    Ok(len)
}

/// Cubic Bézier control points of the `K - 1` B-spline spans (the last entry is unused).
pub fn bspline_spans<P: Point, const K: usize>(d: &[P; K]) -> [[P; 4]; K] {
    let sixth = P::Scalar::ratio(1, 6);
    let third = P::Scalar::ratio(1, 3);
    let two_thirds = P::Scalar::ratio(2, 3);
    // Knot points (d[i-1] + 4 d[i] + d[i+1]) / 6, written as d[i] plus scaled differences
    // so that no intermediate sum leaves the range; phantom ends make them d[0], d[K-1].
    let knot = |i: usize| -> P {
        if i == 0 || i == K - 1 {
            d[i]
        } else {
            d[i] + (d[i - 1] - d[i]) * sixth + (d[i + 1] - d[i]) * sixth
        }
    };
    let mut spans = [[d[0]; 4]; K];
    for i in 0..K - 1 {
        let step = d[i + 1] - d[i];
        spans[i] = [
            knot(i),
            d[i] + step * third,
            d[i] + step * two_thirds,
            knot(i + 1),
        ];
    }
    spans
}

/// Cubic Bézier control points of the `K - 1` Catmull-Rom spans (the last entry is unused).
pub fn catmull_rom_spans<P: Point, const K: usize>(p: &[P; K]) -> [[P; 4]; K] {
    let sixth = P::Scalar::ratio(1, 6);
    let third = P::Scalar::ratio(1, 3);
    let mut spans = [[p[0]; 4]; K];
    for i in 0..K - 1 {
        // Tangent at a particle: (next - previous) / 2; a phantom end reflected through
        // the last particle makes it (next - this) at the ends.
        let out_handle = if i == 0 {
            (p[1] - p[0]) * third
        } else {
            (p[i + 1] - p[i - 1]) * sixth
        };
        let in_handle = if i + 2 >= K {
            (p[i + 1] - p[i]) * third
        } else {
            (p[i + 2] - p[i]) * sixth
        };
        spans[i] = [p[i], p[i] + out_handle, p[i + 1] - in_handle, p[i + 1]];
    }
    spans
}

/// Walks `n` samples over `spans` uniform spans: yields (sample, span, t) with `t` in
/// `[0, 1]`. No division per sample for the span index (an incremental remainder); in floats
/// `t` is the remainder times a precomputed reciprocal (within 1 ulp), in `Q16` the exactly
/// rounded ratio (a reciprocal rounded to 2⁻¹⁶ would move points by tenths of a pixel).
#[inline]
fn for_each_param<S: Scalar>(spans: usize, n: usize, mut f: impl FnMut(usize, usize, S)) {
    let m = n - 1;
    let inv = S::ratio(1, m as u32);
    let (mut span, mut rem) = (0usize, 0usize);
    for i in 0..n {
        // Parameter u = i·spans/m = span + rem/m; the last sample lands on the end of the
        // last span rather than the start of a span that does not exist.
        let (s, t) = if span >= spans {
            (spans - 1, S::ONE)
        } else if S::FIXED_POINT {
            (span, S::ratio(rem as u32, m as u32))
        } else {
            (span, S::ratio(rem as u32, 1) * inv)
        };
        f(i, s, t);
        rem += spans;
        while rem >= m {
            rem -= m;
            span += 1;
        }
    }
}

/// A cubic span at `t` by de Casteljau (6 lerps).
#[inline]
fn eval_cubic<P: Point>(b: &[P; 4], t: P::Scalar) -> P {
    let q0 = b[0].lerp(b[1], t);
    let q1 = b[1].lerp(b[2], t);
    let q2 = b[2].lerp(b[3], t);
    q0.lerp(q1, t).lerp(q1.lerp(q2, t), t)
}

/// The dyadic level `k` for `spans` pieces in `len` slots: the largest `spans·2^k + 1 <= len`
/// (`k <= 12`), or `None` when even one point per span does not fit.
fn dyadic_level(spans: usize, len: usize) -> Option<u32> {
    let mut k = None;
    for level in 0..=12u32 {
        match spans.checked_mul(1 << level) {
            Some(m) if m < len => k = Some(level),
            _ => break,
        }
    }
    k
}

/// `Q16` path: each span halved `k` times (shifts only), `spans·2^k + 1` points.
fn sample_spans_dyadic<P: Point, const M: usize>(spans: &[[P; M]], k: u32, out: &mut [P]) -> usize {
    let mut at = 0;
    for span in spans {
        crate::sampler::subdivide_into(&Bezier::new_unchecked(*span), k, out, &mut at);
    }
    if let (Some(o), Some(last)) = (out.get_mut(at), spans.last()) {
        *o = last[M - 1];
    }
    at + 1
}

fn sample_spans<P: Point, const K: usize>(spans: &[[P; 4]; K], out: &mut [P]) -> usize {
    if P::Scalar::FIXED_POINT
        && let Some(k) = dyadic_level(K - 1, out.len())
    {
        return sample_spans_dyadic(&spans[..K - 1], k, out);
    }
    let n = out.len().min(crate::sampler::MAX_SAMPLES);
    for_each_param::<P::Scalar>(K - 1, n, |i, s, t| out[i] = eval_cubic(&spans[s], t));
    out[0] = spans[0][0];
    out[n - 1] = spans[K - 2][3];
    n
}

fn sample_polyline<P: Point, const K: usize>(p: &[P; K], out: &mut [P]) -> usize {
    if P::Scalar::FIXED_POINT
        && let Some(k) = dyadic_level(K - 1, out.len())
    {
        let segments: [[P; 2]; K] = core::array::from_fn(|i| [p[i], p[(i + 1).min(K - 1)]]);
        return sample_spans_dyadic(&segments[..K - 1], k, out);
    }
    let n = out.len().min(crate::sampler::MAX_SAMPLES);
    for_each_param::<P::Scalar>(K - 1, n, |i, s, t| out[i] = p[s].lerp(p[s + 1], t));
    out[n - 1] = p[K - 1];
    n
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
        ] {
            let mut out = [Vec2::default(); 17];
            let n = sample(m, &p, &mut out).unwrap();
            assert_eq!(n, 17);
            assert_eq!(out[0], p[0], "{m:?}");
            assert_eq!(out[16], p[5], "{m:?}");
        }
    }

    #[test]
    fn catmull_rom_and_polyline_pass_through_particles() {
        let p = zigzag();
        let mut out = [Vec2::default(); 26]; // 5 spans × 5 + 1: particle k at sample 5k
        for m in [Smoothing::CatmullRom, Smoothing::Polyline] {
            sample(m, &p, &mut out).unwrap();
            for (k, &pk) in p.iter().enumerate() {
                assert!((out[5 * k] - pk).length() < 1e-12, "{m:?} particle {k}");
            }
        }
    }

    #[test]
    fn bspline_joins_are_c2() {
        let p = zigzag();
        let s = bspline_spans(&p);
        for i in 0..p.len() - 2 {
            let (a, b) = (s[i], s[i + 1]);
            assert_eq!(a[3], b[0]);
            // C1: equal first derivatives; C2: equal second derivatives at the join.
            assert!(((a[3] - a[2]) - (b[1] - b[0])).length() < 1e-12);
            let a2 = a[3] - a[2] * 2.0 + a[1];
            let b2 = b[2] - b[1] * 2.0 + b[0];
            assert!((a2 - b2).length() < 1e-12);
        }
    }

    #[test]
    fn catmull_rom_joins_are_c1() {
        let p = zigzag();
        let s = catmull_rom_spans(&p);
        for i in 0..p.len() - 2 {
            let (a, b) = (s[i], s[i + 1]);
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
        for m in [Smoothing::BSpline, Smoothing::CatmullRom] {
            sample_closed(m, &ring, &mut out).unwrap();
            // The same distance from the centre all round, and rotating the ring only
            // rotates the curve: the seam at particle 0 is like every other joint.
            let r0 = out[0].length();
            for o in &out {
                assert!((o.length() - r0).abs() < 0.05, "{m:?}");
            }
            let rotated: [Vec2<f64>; 6] = core::array::from_fn(|i| ring[(i + 1) % 6]);
            let mut out2 = [Vec2::default(); 6 * 8 + 1];
            sample_closed(m, &rotated, &mut out2).unwrap();
            for k in 0..out.len() - 8 {
                assert!((out[k + 8] - out2[k]).length() < 1e-12, "{m:?} {k}");
            }
        }
        assert_eq!(
            sample_closed(Smoothing::Bezier, &ring, &mut out),
            Err(Error::InvalidParameter)
        );
    }

    #[test]
    fn bad_input_is_an_error() {
        let mut p = zigzag();
        let mut out = [Vec2::default(); 8];
        assert_eq!(
            sample(Smoothing::BSpline, &p, &mut out[..1]),
            Err(Error::BufferTooSmall { needed: 2, got: 1 })
        );
        p[3].y = f64::NAN;
        assert_eq!(
            sample(Smoothing::Polyline, &p, &mut out),
            Err(Error::NonFinite)
        );
    }

    #[test]
    fn straight_particles_give_a_straight_curve() {
        let p: [Vec2<f64>; 5] = core::array::from_fn(|i| Vec2::new(2.0 * i as f64, 0.0));
        for m in [Smoothing::Bezier, Smoothing::BSpline, Smoothing::CatmullRom] {
            let mut out = [Vec2::default(); 9];
            sample(m, &p, &mut out).unwrap();
            for (i, o) in out.iter().enumerate() {
                assert!(
                    (o.x - i as f64).abs() < 1e-12 && o.y == 0.0,
                    "{m:?} {i} {o:?}"
                );
            }
        }
    }
}
