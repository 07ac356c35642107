//! Level of detail: how few segments keep a curve or patch within a pixel tolerance.
//!
//! Wang's formula bounds the distance between a degree-`d` Bézier curve and the polyline of
//! its `n` uniform samples: with `M = max |P[i+2] - 2 P[i+1] + P[i]|`,
//!
//! ```text
//! n = ceil( sqrt( d(d-1)/8 · M / tol ) )   ⇒   every point of the curve is within tol
//! ```
//!
//! It costs `N` vector subtractions and norms plus two square roots: cheap enough to run
//! every frame, so a rope far away is drawn with 4 segments and the same rope close up with 40.
//!
//! ```
//! use dunas::{Bezier, Vec2, lod};
//! let c = Bezier::new([Vec2::new(0.0f32, 0.0), Vec2::new(100.0, 200.0), Vec2::new(200.0, 0.0)])?;
//! let n = lod::segments(&c, 0.5)?; // 0.5 px tolerance
//! assert_eq!(n, 15); // sqrt(2/8 · 400 / 0.5) = 14.1
//! let mut pts = [Vec2::default(); 64];
//! let written = c.sample(&mut pts[..n + 1])?;
//! assert_eq!(written, 16);
//! # Ok::<(), dunas::Error>(())
//! ```

use crate::curves::smooth::{Smoothed, Smoothing};
use crate::error::check_positive;
use crate::{Bezier, Error, Patch, Point, Scalar};

/// The most segments [`segments`] returns (`2^16`); a request that needs more is clamped.
pub const MAX_SEGMENTS: usize = 1 << 16;

/// Half the largest second difference of a control polygon, `max |Δ²P| / 2`, computed with
/// midpoints so it cannot overflow `Q16`.
fn half_second_difference<P: Point>(points: impl Iterator<Item = P> + Clone) -> P::Scalar {
    let mut m = P::Scalar::ZERO;
    let mut it = points;
    let (Some(mut a), Some(mut b)) = (it.next(), it.next()) else {
        return m;
    };
    for c in it {
        // (c - b) - (b - a), halved inside a 64-bit midpoint in Q16.
        let h = (c - b).midpoint(-(b - a));
        m = m.max(h.length());
        (a, b) = (b, c);
    }
    m
}

/// `ceil( sqrt(d(d-1)/4) · sqrt(half_m) / sqrt(tol) )`, which is Wang's count with
/// `M = 2 · half_m`. Products of square roots keep `Q16` in range.
fn wang_count<S: Scalar>(degree: usize, half_m: S, tol: S) -> usize {
    if degree < 2 || half_m <= S::ZERO {
        return 1;
    }
    let k = S::ratio((degree * (degree - 1)) as u32, 4).sqrt();
    let x = k * half_m.sqrt() / tol.sqrt();
    if !x.is_finite() {
        return MAX_SEGMENTS;
    }
    x.ceil_usize(MAX_SEGMENTS).max(1)
}

/// The number of uniform segments (samples minus one) that keeps the polyline of `curve`
/// within `tolerance` of the curve everywhere, by Wang's formula. Always at least 1, at most
/// [`MAX_SEGMENTS`].
///
/// # Errors
/// [`Error::InvalidParameter`] when `tolerance` is not a positive finite number.
pub fn segments<P: Point, const N: usize>(
    curve: &Bezier<P, N>,
    tolerance: P::Scalar,
) -> Result<usize, Error> {
    check_positive(tolerance, "tolerance")?;
    let m = half_second_difference(curve.points().iter().copied());
    Ok(wang_count(N - 1, m, tolerance))
}

/// Segment counts `(nu, nv)` along `u` and `v` that keep the bilinear quads of a sampled
/// `(nu + 1) × (nv + 1)` grid within `tolerance` of `patch`.
///
/// Each direction gets half the tolerance and Wang's formula over every row (for `u`) or
/// column (for `v`): the bilinear interpolation error is at most the sum of the two linear
/// interpolation errors. Splitting each quad into two triangles can add the twist term
/// `h_u·h_v·max|∂²P/∂u∂v| / 4`, which vanishes on a flat sail.
///
/// # Errors
/// [`Error::InvalidParameter`] when `tolerance` is not a positive finite number.
pub fn patch_segments<P: Point, const U: usize, const V: usize>(
    patch: &Patch<P, U, V>,
    tolerance: P::Scalar,
) -> Result<(usize, usize), Error> {
    check_positive(tolerance, "tolerance")?;
    let half_tol = Scalar::midpoint(tolerance, P::Scalar::ZERO);
    let rows = patch.points();
    let mut mu = P::Scalar::ZERO;
    for row in rows {
        mu = mu.max(half_second_difference(row.iter().copied()));
    }
    let mut mv = P::Scalar::ZERO;
    for i in 0..U {
        mv = mv.max(half_second_difference(rows.iter().map(|row| row[i])));
    }
    Ok((
        wang_count(U - 1, mu, half_tol),
        wang_count(V - 1, mv, half_tol),
    ))
}

/// Segment counts `(nu, nv)` along `u` and `v` that keep the bilinear quads of a
/// `(nu + 1) × (nv + 1)` grid drawn by [`surface::sample`](crate::curves::surface::sample) within
/// `tolerance` of the surface `smoothing` makes of `grid` (row `j` is `grid[j]`, along `u`).
/// For a distant sail pass the pixel tolerance divided by the camera's pixels per world unit:
/// the counts fall with the distance.
///
/// Each direction gets half the tolerance. For the splines, every row (and column) curve's
/// cubic spans give Wang's bound per span (on the natural spline's control net), times the
/// most the other direction's weights add up to in absolute value (4/3 for the B-splines'
/// clamped ends, 5/4 for Catmull-Rom); the count is that per span times the spans, so that
/// samples fall on span joints. One Bézier is [`patch_segments`]; the raw grid is one segment
/// a cell. Cost: `O(U·V)`, two square roots a direction.
///
/// # Errors
/// [`Error::InvalidParameter`] when `tolerance` is not a positive finite number;
/// [`Error::NonFinite`] / [`Error::OutOfRange`] for a particle outside the format's range.
pub fn surface_segments<P: Point, const U: usize, const V: usize>(
    grid: &[[P; U]; V],
    smoothing: Smoothing,
    tolerance: P::Scalar,
) -> Result<(usize, usize), Error> {
    check_positive(tolerance, "tolerance")?;
    const { assert!(U >= 2 && V >= 2, "a surface needs at least 2×2 particles") };
    crate::error::check_points(grid.as_flattened(), "grid point")?;
    let (basis, blend) = match smoothing {
        Smoothing::Bezier => return patch_segments(&Patch::new(*grid)?, tolerance),
        Smoothing::Polyline => return Ok((U - 1, V - 1)),
        Smoothing::CatmullRom => (Smoothing::CatmullRom, P::Scalar::ratio(5, 4)),
        Smoothing::BSpline | Smoothing::NaturalSpline => {
            (Smoothing::BSpline, P::Scalar::ratio(4, 3))
        }
    };
    let mut net = *grid;
    if smoothing == Smoothing::NaturalSpline {
        crate::curves::surface::natural_grid(&mut net);
    }
    let half_tol = Scalar::midpoint(tolerance, P::Scalar::ZERO);
    let (mut mu, mut mv) = (P::Scalar::ZERO, P::Scalar::ZERO);
    for row in &net {
        mu = mu.max(span_bend(basis, row)?);
    }
    for i in 0..U {
        let column: [P; V] = core::array::from_fn(|j| net[j][i]);
        mv = mv.max(span_bend(basis, &column)?);
    }
    let per_span = |m: P::Scalar| wang_count(3, m * blend, half_tol);
    Ok((
        per_span(mu).saturating_mul(U - 1).min(MAX_SEGMENTS),
        per_span(mv).saturating_mul(V - 1).min(MAX_SEGMENTS),
    ))
}

/// The largest half second difference of the cubic spans `smoothing` makes of `row`.
fn span_bend<P: Point, const K: usize>(
    smoothing: Smoothing,
    row: &[P; K],
) -> Result<P::Scalar, Error> {
    let curve = Smoothed::open(smoothing, row)?;
    Ok(curve
        .cubic_spans()
        .iter()
        .map(|span| half_second_difference(span.points().iter().copied()))
        .fold(P::Scalar::ZERO, P::Scalar::max))
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;

    #[test]
    fn straight_curves_need_one_segment() {
        let line = Bezier::new([
            Vec2::new(0.0f32, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(2.0, 2.0),
        ])
        .unwrap();
        assert_eq!(segments(&line, 0.1), Ok(1));
        let two = Bezier::new([Vec2::new(0.0f32, 0.0), Vec2::new(9.0, 1.0)]).unwrap();
        assert_eq!(segments(&two, 0.1), Ok(1));
    }

    #[test]
    fn matches_the_formula_directly() {
        let c = Bezier::new([
            Vec2::new(0.0f64, 0.0),
            Vec2::new(10.0, 30.0),
            Vec2::new(40.0, -20.0),
            Vec2::new(50.0, 0.0),
        ])
        .unwrap();
        let p = c.points();
        let m = (0..2)
            .map(|i| (p[i + 2] - p[i + 1] * 2.0 + p[i]).length())
            .fold(0.0, f64::max);
        for tol in [0.05, 0.25, 1.0, 4.0] {
            let n = (6.0 / 8.0 * m / tol).sqrt().ceil() as usize;
            assert_eq!(segments(&c, tol), Ok(n));
        }
    }

    #[test]
    fn bad_tolerance_is_an_error_and_tiny_ones_clamp() {
        let c = Bezier::new([
            Vec2::new(0.0f32, 0.0),
            Vec2::new(5.0, 9.0),
            Vec2::new(9.0, 0.0),
        ])
        .unwrap();
        for tol in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(matches!(
                segments(&c, tol),
                Err(Error::InvalidParameter { .. })
            ));
        }
        assert_eq!(segments(&c, 1e-30), Ok(MAX_SEGMENTS));
    }

    /// The drawn grid at the counts `surface_segments` picks is within the tolerance of the
    /// surface everywhere: bilinear interpolation of the coarse samples against 4× finer ones
    /// at the same parameters, for every smoothing.
    #[test]
    fn surface_counts_keep_the_grid_within_tolerance() {
        use crate::Vec3;
        use crate::curves::surface::{SurfaceTable, sample};
        use std::vec;
        let grid: [[Vec3<f64>; 6]; 5] = core::array::from_fn(|j| {
            core::array::from_fn(|i| {
                let (x, z) = (i as f64, j as f64);
                Vec3::new(x + 0.2 * z, 0.8 * (x * 1.3).sin() * (z * 1.1).cos(), z)
            })
        });
        for smoothing in [
            Smoothing::Bezier,
            Smoothing::BSpline,
            Smoothing::CatmullRom,
            Smoothing::NaturalSpline,
        ] {
            let mut previous = (usize::MAX, usize::MAX);
            for tol in [0.02, 0.05, 0.2] {
                let (su, sv) = surface_segments(&grid, smoothing, tol).unwrap();
                assert!(su <= previous.0 && sv <= previous.1, "{smoothing:?} {tol}");
                previous = (su, sv);
                let coarse =
                    |n: usize, k: usize| SurfaceTable::<f64, 6, 400>::new(smoothing, n * k + 1);
                let (cu, cv) = (
                    coarse(su, 1).unwrap(),
                    SurfaceTable::<f64, 5, 400>::new(smoothing, sv + 1).unwrap(),
                );
                let (fu, fv) = (
                    coarse(su, 4).unwrap(),
                    SurfaceTable::<f64, 5, 400>::new(smoothing, 4 * sv + 1).unwrap(),
                );
                let (nu, nv) = (su + 1, sv + 1);
                let mut c = (
                    vec![Vec3::default(); nu * nv],
                    vec![Vec3::default(); nu * nv],
                );
                sample(&grid, &cu, &cv, &mut c.0, &mut c.1).unwrap();
                let (mu, mv) = (4 * su + 1, 4 * sv + 1);
                let mut f = (
                    vec![Vec3::default(); mu * mv],
                    vec![Vec3::default(); mu * mv],
                );
                sample(&grid, &fu, &fv, &mut f.0, &mut f.1).unwrap();
                let mut worst: f64 = 0.0;
                for b in 0..mv {
                    for a in 0..mu {
                        let (i, j) = ((a / 4).min(su - 1), (b / 4).min(sv - 1));
                        let (s, t) = ((a - 4 * i) as f64 / 4.0, (b - 4 * j) as f64 / 4.0);
                        let q = |i: usize, j: usize| c.0[j * nu + i];
                        let bilinear = q(i, j)
                            .lerp(q(i + 1, j), s)
                            .lerp(q(i, j + 1).lerp(q(i + 1, j + 1), s), t);
                        worst = worst.max((bilinear - f.0[b * mu + a]).length());
                    }
                }
                assert!(
                    worst <= tol,
                    "{smoothing:?} tol {tol}: {worst} at {su}×{sv}"
                );
            }
        }
    }
}
