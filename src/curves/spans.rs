//! How a smoothing builds each cubic span (or straight segment) of a
//! [`Smoothed`](crate::curves::smooth::Smoothed) curve from the particles it weighs: one
//! function a span, shared by drawing a curve whole and by redrawing the spans a push moved.

use crate::curves::curve::Bezier;
use crate::curves::smooth::Smoothing;
use crate::{Point, Scalar};

/// The B-spline knot point `(p + 4q + r) / 6`, written as `q` plus scaled differences so that
/// no intermediate sum leaves the range.
#[inline]
pub(super) fn knot<P: Point>(p: P, q: P, r: P) -> P {
    let sixth = P::Scalar::ratio(1, 6);
    q + (p - q) * sixth + (r - q) * sixth
}

/// The `n - 1` B-spline spans of the first `n` of an open row (later entries unused);
/// phantom ends reflected through the end particles clamp the curve to them.
pub(super) fn bspline_spans<P: Point, const K: usize>(d: &[P; K], n: usize) -> [Bezier<P, 4>; K] {
    let f = Fractions::new();
    core::array::from_fn(|i| bspline_span(d, n, i, f))
}

/// Thirds and a sixth, taken once for a curve's spans (in `Q16` each is a division).
#[derive(Clone, Copy)]
pub(super) struct Fractions<S> {
    third: S,
    two_thirds: S,
    sixth: S,
}

impl<S: Scalar> Fractions<S> {
    pub(super) fn new() -> Self {
        Fractions {
            third: S::ratio(1, 3),
            two_thirds: S::ratio(2, 3),
            sixth: S::ratio(1, 6),
        }
    }
}

/// Span `i` of [`bspline_spans`].
#[inline]
pub(super) fn bspline_span<P: Point, const K: usize>(
    d: &[P; K],
    n: usize,
    i: usize,
    f: Fractions<P::Scalar>,
) -> Bezier<P, 4> {
    let (third, two_thirds) = (f.third, f.two_thirds);
    let knot_at = |i: usize| -> P {
        if i == 0 || i + 1 >= n {
            d[i]
        } else {
            knot(d[i - 1], d[i], d[i + 1])
        }
    };
    if i + 1 >= n {
        return Bezier::new_unchecked([d[n - 1]; 4]);
    }
    let step = d[i + 1] - d[i];
    Bezier::new_unchecked([
        knot_at(i),
        d[i] + step * third,
        d[i] + step * two_thirds,
        knot_at(i + 1),
    ])
}

/// The `n - 1` Catmull-Rom spans of the first `n` of an open row (later entries unused).
pub(super) fn catmull_rom_spans<P: Point, const K: usize>(
    p: &[P; K],
    n: usize,
) -> [Bezier<P, 4>; K] {
    let f = Fractions::new();
    core::array::from_fn(|i| catmull_rom_span(p, n, i, f))
}

/// Span `i` of [`catmull_rom_spans`].
#[inline]
pub(super) fn catmull_rom_span<P: Point, const K: usize>(
    p: &[P; K],
    n: usize,
    i: usize,
    f: Fractions<P::Scalar>,
) -> Bezier<P, 4> {
    let (sixth, third) = (f.sixth, f.third);
    if i + 1 >= n {
        return Bezier::new_unchecked([p[n - 1]; 4]);
    }
    // Tangent at a particle: (next - previous) / 2; a phantom end reflected through
    // the last particle makes it (next - this) at the ends.
    let out_handle = if i == 0 {
        (p[1] - p[0]) * third
    } else {
        (p[i + 1] - p[i - 1]) * sixth
    };
    let in_handle = if i + 2 >= n {
        (p[i + 1] - p[i]) * third
    } else {
        (p[i + 2] - p[i]) * sixth
    };
    Bezier::new_unchecked([p[i], p[i] + out_handle, p[i + 1] - in_handle, p[i + 1]])
}

/// Span `i` of the closed curve `method` draws through the ring `controls` (the natural
/// spline's control points, the particles for the others): Catmull-Rom's, or the
/// B-spline's.
#[inline]
pub(super) fn ring_span<P: Point, const K: usize>(
    method: Smoothing,
    controls: &[P; K],
    i: usize,
    f: Fractions<P::Scalar>,
) -> Bezier<P, 4> {
    let at = |i: usize| controls[i % K];
    let (prev, a, b, next) = (at(i + K - 1), at(i), at(i + 1), at(i + 2));
    if method == Smoothing::CatmullRom {
        return Bezier::new_unchecked([a, a + (b - prev) * f.sixth, b - (next - a) * f.sixth, b]);
    }
    let (third, step) = (f.third, b - a);
    Bezier::new_unchecked([
        knot(prev, a, b),
        a + step * third,
        b - step * third,
        knot(a, b, next),
    ])
}

/// The `n - 1` straight segments of the first `n` of an open row (later entries unused).
pub(super) fn segments<P: Point, const K: usize>(p: &[P; K], n: usize) -> [Bezier<P, 2>; K] {
    core::array::from_fn(|i| segment(p, n, i))
}

/// Segment `i` of [`segments`].
#[inline]
pub(super) fn segment<P: Point, const K: usize>(p: &[P; K], n: usize, i: usize) -> Bezier<P, 2> {
    Bezier::new_unchecked([p[i], p[(i + 1).min(n - 1)]])
}

/// Segment `i` of the closed polyline through the ring `p`.
#[inline]
pub(super) fn ring_segment<P: Point, const K: usize>(p: &[P; K], i: usize) -> Bezier<P, 2> {
    Bezier::new_unchecked([p[i % K], p[(i + 1) % K]])
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;
    use crate::curves::smooth::Smoothed;

    /// Redrawing the spans a run of moved particles weighs in gives the curve drawn whole
    /// from the moved particles, for every method, open, closed and a piece of a row, and
    /// names every span that changed.
    #[test]
    fn a_redraw_is_the_curve_drawn_again() {
        let methods = [
            Smoothing::Bezier,
            Smoothing::BSpline,
            Smoothing::CatmullRom,
            Smoothing::NaturalSpline,
            Smoothing::Polyline,
        ];
        let row: [Vec2<f64>; 9] = core::array::from_fn(|i| {
            let x = i as f64;
            Vec2::new(x, (x * 1.3).sin())
        });
        for method in methods {
            for (lo, hi) in [
                (0, 0),
                (0, 1),
                (3, 4),
                (4, 4),
                (7, 8),
                (8, 8),
                (2, 6),
                (0, 8),
            ] {
                let mut moved = row;
                for p in &mut moved[lo..=hi] {
                    *p += Vec2::new(0.25, -0.5);
                }
                for shape in ["open", "closed", "piece"] {
                    let build = |p: &[Vec2<f64>; 9]| match shape {
                        "open" => Smoothed::open(method, p),
                        "closed" => Smoothed::ring(method, p),
                        _ => Smoothed::open_first(method, p, 6),
                    };
                    let (Ok(mut curve), Ok(whole)) = (build(&row), build(&moved)) else {
                        continue;
                    };
                    let len = match shape {
                        "closed" => 9,
                        _ => curve.span_count() + 1,
                    };
                    let (lo, hi) = (lo.min(len - 1), hi.min(len - 1));
                    let mut piece = row;
                    piece[lo..=hi].copy_from_slice(&moved[lo..=hi]);
                    let Ok(whole) = (if len < 9 { build(&piece) } else { Ok(whole) }) else {
                        continue;
                    };
                    let (first, count) = curve.redraw(&piece, (lo, hi)).unwrap();
                    let before = build(&row).unwrap();
                    let spans = curve.span_count();
                    assert_eq!(spans, whole.span_count());
                    for span in 0..spans {
                        assert_eq!(
                            curve.span_points(span),
                            whole.span_points(span),
                            "{method:?} {shape} moved {lo}..={hi}: span {span}"
                        );
                        let redrawn = (0..count).any(|j| (first + j) % spans == span);
                        let changed = before.span_points(span) != curve.span_points(span);
                        assert!(
                            redrawn || !changed,
                            "{method:?} {shape}: span {span} changed"
                        );
                    }
                }
            }
        }
    }
}
