//! Adaptive flattening: few straight segments for a 2D quadratic or cubic, placed where the
//! curve bends.
//!
//! [`lod::segments`](crate::curves::lod::segments) spaces points uniformly in `t` with Wang's count,
//! which is set by the sharpest bend and so wastes points where the curve is straight.
//! Here a cubic is first split into quadratics (each within a tenth of the tolerance of its
//! piece of the cubic), and each quadratic is flattened as the piece of the parabola
//! `y = x²` it is similar to: a chord of length `L` at curvature `κ` strays `κ L² / 8`, so
//! the points that keep every chord at the tolerance are evenly spaced in
//! `F(x) = ∫ (1 + 4x²)^(-1/4) dx`, which is approximated in closed form (within a few
//! percent, both ways). That count is asymptotic, so each quadratic's chords are then
//! measured exactly (a quadratic strays from a chord by a quarter of its second difference
//! across it) and segments added where one is over: the polyline is within the tolerance,
//! not about it. The spacing is the parabola method of R. Levien, "Flattening quadratic
//! Béziers" (2019).
//!
//! On random cubics (±200 px) at 0.25 px it draws 1.26× the segments of kurbo's flattener,
//! whose polylines stray up to 1.5× the tolerance, and 0.67× those of Wang's uniform count;
//! it costs about 1.5× kurbo's time (`docs/summary.md` (f)).
//!
//! For floats. In `Q16` prefer [`lod::segments`](crate::curves::lod::segments) with a uniform
//! sampler: exact dyadic steps, and no square roots on a device.
//!
//! ```
//! use dunas::{Bezier, Vec2, flatten};
//! let c = Bezier::new([Vec2::new(0.0f32, 0.0), Vec2::new(100.0, 200.0), Vec2::new(200.0, 0.0), Vec2::new(300.0, 0.0)])?;
//! let n = flatten::segments(&c, 0.25)?;
//! let mut out = [Vec2::default(); 128];
//! assert_eq!(flatten::flatten(&c, 0.25, &mut out)?, n + 1);
//! assert_eq!(out[0], c.start());
//! assert_eq!(out[n], c.end());
//! # Ok::<(), dunas::Error>(())
//! ```

use crate::curves::lod::MAX_SEGMENTS;
use crate::error::check_positive;
use crate::{Bezier, Error, Point, Scalar, Vec2};

/// The most quadratics a cubic is split into.
const MAX_QUADS: usize = 64;

/// `F(x) ≈ ∫₀ˣ (1 + 4u²)^(-1/4) du`: exact slope 1 at 0 and growth `√(2x)` far out.
fn parabola_integral<S: Scalar>(x: S) -> S {
    let d = S::ratio(67, 100);
    let d4 = d * d * d * d;
    x / (S::ONE - d + (d4 + x * x * S::ratio(1, 4)).sqrt().sqrt())
}

/// The inverse of [`parabola_integral`], approximated alike.
fn parabola_integral_inverse<S: Scalar>(y: S) -> S {
    let b = S::ratio(39, 100);
    y * (S::ONE - b + (b * b + y * y * S::ratio(1, 4)).sqrt())
}

/// How a quadratic `a, b, c` is flattened: `n` segments, evenly spaced in the parabola
/// integral (`map`: the integral at the start, its change, and the parabola coordinates the
/// inverse gives at both ends), or evenly in `t` (a straight or cusped quadratic, where the
/// parabola degenerates).
#[derive(Clone, Copy)]
struct Plan<S> {
    n: usize,
    map: Option<[S; 4]>,
}

impl<S: Scalar> Plan<S> {
    /// Wang's count for a quadratic of second difference `bend`: `sqrt(bend / (4 tol))`,
    /// evenly in `t`. Always within `tol`.
    fn uniform(bend: S, tol: S) -> Self {
        let n = (bend * S::ratio(1, 4) / tol).sqrt();
        Plan {
            n: n.ceil_usize(MAX_SEGMENTS).max(1),
            map: None,
        }
    }

    /// The estimate from the parabola integral (see the module docs).
    fn parabola(a: Vec2<S>, b: Vec2<S>, c: Vec2<S>, tol: S) -> Self {
        let dd = b + b - a - c;
        let bend = dd.length();
        let cross = (c - a).cross(dd);
        // |x2 - x0| = |dd|² / |cross|: past 4096 the parabola is too far out to resolve.
        if cross.abs() * S::from_i16(4096) <= bend * bend || bend <= S::ZERO {
            return Self::uniform(bend, tol);
        }
        let x0 = (b - a).dot(dd) / cross;
        let x2 = (c - b).dot(dd) / cross;
        let width = x2 - x0;
        // The quadratic is the unit parabola scaled by |dd| / (x2 - x0)².
        let scale = bend / (width * width);
        let (a0, a2) = (parabola_integral(x0), parabola_integral(x2));
        let estimate = (a2 - a0).abs() * (scale / tol).sqrt() * S::ratio(1, 2);
        let (u0, u2) = (parabola_integral_inverse(a0), parabola_integral_inverse(a2));
        if !estimate.is_finite() || u2 == u0 {
            return Self::uniform(bend, tol);
        }
        Plan {
            n: estimate.ceil_usize(MAX_SEGMENTS).max(1),
            map: Some([a0, a2 - a0, u0, u2 - u0]),
        }
    }

    /// The parameter of point `i` of `n` on the quadratic.
    fn parameter(&self, i: usize) -> S {
        let f = S::ratio(i as u32, self.n as u32);
        match self.map {
            _ if i >= self.n => S::ONE,
            // Through the inverse at both ends too, so that its own error cancels (far out on
            // the parabola the ends' coordinates are close and large).
            Some([a0, da, u0, du]) => (parabola_integral_inverse(a0 + da * f) - u0) / du,
            None => f,
        }
    }

    /// Writes the plan's points `1..=n` to `out[base + i]` (where `out` has room) and returns
    /// the largest distance
    /// between the quadratic and its chords. A piece of parameter length `h` is a quadratic
    /// with second difference `dd·h²`; it strays from the point of its chord at the same
    /// parameter by at most a quarter of that, and from the chord's line by a quarter of that
    /// difference's part across the chord, which bounds the distance to the chord itself when
    /// the piece runs forward along it (its control point projects inside the chord).
    fn write(&self, [a, b, c]: [Vec2<S>; 3], out: &mut [Vec2<S>], base: usize) -> S {
        let dd = b + b - a - c;
        let bend = dd.length();
        let velocity = |t: S| (b - a - dd * t) * S::from_i16(2);
        let (mut worst, mut t0, mut p0) = (S::ZERO, S::ZERO, a);
        for i in 1..=self.n {
            let t1 = self.parameter(i);
            let p1 = quadratic(a, b, c, t1);
            if let Some(slot) = out.get_mut(base + i) {
                *slot = p1;
            }
            let h = t1 - t0;
            let chord = p1 - p0;
            let len = chord.length();
            // The piece's control point, from its start: p0 + Q'(t0)·h/2.
            let reach = velocity(t0).dot(chord) * h * S::ratio(1, 2);
            let forward = len > S::ZERO && reach >= S::ZERO && reach <= len * len;
            let off = if forward {
                dd.cross(chord).abs() / len
            } else {
                bend
            };
            worst = worst.max(off * h * h * S::ratio(1, 4));
            (t0, p0) = (t1, p1);
        }
        worst
    }
}

/// Flattens a quadratic within `tol`, writing its points `1..=n` to `out[base + i]` (where
/// `out` has room), and returns `n`. The parabola's count is exact for many short chords; a
/// chord across a tight bend can stray more, so every chord's sag is measured and segments
/// added until none is over (Wang's uniform count after three tries).
fn settle<S: Scalar>(quad: [Vec2<S>; 3], tol: S, out: &mut [Vec2<S>], base: usize) -> usize {
    let mut plan = Plan::parabola(quad[0], quad[1], quad[2], tol);
    for _ in 0..3 {
        let worst = plan.write(quad, out, base);
        if worst <= tol || plan.n >= MAX_SEGMENTS {
            return plan.n;
        }
        let more = S::ratio(plan.n as u32, 1) * (worst / tol).sqrt();
        plan.n = (more.ceil_usize(MAX_SEGMENTS) + 1).min(MAX_SEGMENTS);
    }
    let plan = Plan::uniform((quad[1] + quad[1] - quad[0] - quad[2]).length(), tol);
    plan.write(quad, out, base);
    plan.n
}

/// The quadratics a cubic is split into: calls `visit(a, b, c)` for each, in order, each
/// within a tenth of `tol` of its piece of the cubic.
fn quadratics<S: Scalar>(curve: &Bezier<Vec2<S>, 4>, tol: S, mut visit: impl FnMut([Vec2<S>; 3])) {
    let [p0, p1, p2, p3] = *curve.points();
    // A piece of length 1/n strays from its quadratic by √3/36 · |Δ³P| / n³.
    let third = (p3 - p0 + (p1 - p2) * S::from_i16(3)).length();
    let budget = third * S::ratio(1732, 36_000) / (tol * S::ratio(1, 10));
    let mut n = 1;
    while n < MAX_QUADS && S::ratio((n * n * n) as u32, 1) < budget {
        n += 1;
    }
    let step = S::ratio(1, n as u32);
    let (mut c0, mut d0) = (p0, curve.tangent(S::ZERO));
    for i in 1..=n {
        let t1 = S::ratio(i as u32, n as u32);
        let (c3, d1) = (curve.eval(t1), curve.tangent(t1));
        // The quadratic through both ends whose control point averages the cubic's two.
        let mid = c0.midpoint(c3) + (d0 - d1) * (step * S::ratio(1, 4));
        visit([c0, mid, c3]);
        (c0, d0) = (c3, d1);
    }
}

/// Flattens `curve` within `tol`, writing its points `1..=segments` to `out` where it has
/// room (point 0 is the start), and returns the segment count.
fn walk<S: Scalar>(curve: &Bezier<Vec2<S>, 4>, tol: S, out: &mut [Vec2<S>]) -> usize {
    // A tenth of the tolerance for the split into quadratics, the rest for their chords.
    let flat = tol * S::ratio(9, 10);
    let mut done = 0usize;
    quadratics(curve, tol, |quad| {
        done = done.saturating_add(settle(quad, flat, out, done));
    });
    done
}

/// Segments [`flatten`] draws `curve` with at tolerance `tol` (as costly as flattening).
///
/// # Errors
/// [`Error::InvalidParameter`] for a tolerance that is not positive and finite.
pub fn segments<S: Scalar>(curve: &Bezier<Vec2<S>, 4>, tol: S) -> Result<usize, Error> {
    let tol = check_positive(tol, "tolerance")?;
    Ok(walk(curve, tol, &mut []))
}

/// Writes the flattened `curve` into `out` (its two ends exactly, and the points between)
/// and returns the count, [`segments`]` + 1`. Every point of the curve is within `tol` of
/// the polyline (checked at 2001 points of random cubics in `tests/suite/flatten.rs`). Cost: two
/// square roots a point, and a split into quadratics.
///
/// # Errors
/// [`Error::InvalidParameter`] for a tolerance that is not positive and finite;
/// [`Error::BufferTooSmall`] (naming the count needed) when `out` is too short, after
/// writing the points that fit.
pub fn flatten<S: Scalar>(
    curve: &Bezier<Vec2<S>, 4>,
    tol: S,
    out: &mut [Vec2<S>],
) -> Result<usize, Error> {
    let tol = check_positive(tol, "tolerance")?;
    let got = out.len();
    let Some(first) = out.first_mut() else {
        return Err(Error::BufferTooSmall {
            needed: segments(curve, tol)? + 1,
            got,
        });
    };
    *first = curve.start();
    let n = walk(curve, tol, out);
    if n >= got {
        return Err(Error::BufferTooSmall { needed: n + 1, got });
    }
    out[n] = curve.end();
    Ok(n + 1)
}

/// The quadratic's point at `t` (clamped to `[0, 1]`).
fn quadratic<S: Scalar>(a: Vec2<S>, b: Vec2<S>, c: Vec2<S>, t: S) -> Vec2<S> {
    let t = crate::curves::curve::clamp_unit(t);
    a.lerp(b, t).lerp(b.lerp(c, t), t)
}
