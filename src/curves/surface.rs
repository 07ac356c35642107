//! Smooth surfaces through a grid of particles, drawn separably: the smoothing of a row of
//! particles ([`Smoothing`]) along both grid directions.
//!
//! The surface over a `U × V` grid is `S(u, v) = Σ_ij wu_i(u) wv_j(v) p_ij`, with `wu` and
//! `wv` the particle weights the smoothing gives a curve of `U` (or `V`) particles, so the
//! same names mean the same thing on curves and surfaces: [`Smoothing::CatmullRom`] passes
//! through every particle (C¹), [`Smoothing::NaturalSpline`] passes through every particle
//! and is C², [`Smoothing::BSpline`] is C² and stays inside them,
//! [`Smoothing::Bezier`] is the single patch of [`Patch`](crate::Patch), and
//! [`Smoothing::Polyline`] is the raw bilinear grid. Parameters run over the whole grid: a
//! sample at `u = i / (U - 1)` lies on the column of particles `i` (for the splines).
//!
//! A [`SurfaceTable`] holds one direction's weights and their slopes for a sample count,
//! built once (the way [`BernsteinTable`](crate::curves::sampler::BernsteinTable) does for curves).
//! [`sample`] then evaluates rows first and columns second, and takes the normals from the two
//! slope tables: for a `U × V` grid drawn `nu × nv` with 4-wide bases, about
//! `4·(2·V·nu + 3·nu·nv)` multiply-adds a coordinate and one square root a normal.
//!
//! ```
//! use dunas::{Smoothing, Vec3, surface::{SurfaceTable, sample}};
//! let grid: [[Vec3<f32>; 4]; 4] = core::array::from_fn(|j| {
//!     core::array::from_fn(|i| Vec3::new(i as f32, 0.0, j as f32))
//! });
//! let table = SurfaceTable::<f32, 4, 16>::new(Smoothing::CatmullRom, 7)?;
//! let (mut pos, mut nor) = ([Vec3::default(); 49], [Vec3::default(); 49]);
//! assert_eq!(sample(&grid, &table, &table, &mut pos, &mut nor)?, 49);
//! assert_eq!(pos[2 * 7 + 4], grid[1][2]); // sample (4, 2) lies on particle (2, 1)
//! assert!(nor[0].x == 0.0 && nor[0].z == 0.0); // a flat sheet: normals along y
//! assert!((nor[0].y.abs() - 1.0).abs() < 0.035); // unit length (within 3.5% with `micromath`)
//! # Ok::<(), dunas::Error>(())
//! ```

use crate::curves::natural::natural_controls;
use crate::error::invalid;
use crate::{Error, Point, Scalar, Smoothing, Vec3};

/// One direction's particle weights and slopes at `count ≤ N` evenly spaced parameters over
/// a row of `K` particles (for [`Smoothing::NaturalSpline`], the weights of the B-spline
/// control net that [`sample`] solves for). Size: `2·N·K` numbers.
#[derive(Clone, Debug)]
pub struct SurfaceTable<S, const K: usize, const N: usize> {
    smoothing: Smoothing,
    /// Round a ring of particles ([`closed`](Self::closed)).
    closed: bool,
    count: usize,
    weights: [[S; K]; N],
    /// `d/du` of the weights, `u` over the whole row (`0..=1`).
    slopes: [[S; K]; N],
    /// The non-zero weights of each sample: `first..end`.
    support: [(u8, u8); N],
}

impl<S: Scalar, const K: usize, const N: usize> SurfaceTable<S, K, N> {
    /// The table for `count` samples, `2 ≤ count ≤ N`, of a row of `K` particles smoothed by
    /// `smoothing`, at evenly spaced parameters.
    ///
    /// In fixed point ([`Scalar::FIXED_POINT`], `Q16`) the parameters are dyadic, so that
    /// every one is exact: the count is rounded down to `spans·2^m + 1` (`spans` is `K - 1`,
    /// or 1 for [`Smoothing::Bezier`]), or, below `spans + 1`, to `d + 1` for the largest
    /// divisor `d` of `spans` (samples on particle columns); [`count`](Self::count) gives it.
    /// Each sample's weights are then corrected to sum to exactly one and its slopes to
    /// exactly zero, so a grid moved by any offset draws moved by exactly that offset.
    ///
    /// ```
    /// use dunas::{Q16, Smoothing, surface::SurfaceTable};
    /// // 8 particles: 7 spans of 2 segments, not 16 points at rounded parameters.
    /// let table = SurfaceTable::<Q16, 8, 16>::new(Smoothing::NaturalSpline, 16)?;
    /// assert_eq!(table.count(), 15);
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `count` outside `2..=N`.
    pub fn new(smoothing: Smoothing, count: usize) -> Result<Self, Error> {
        Self::build(smoothing, count, false)
    }

    /// The table for `count` samples, `2 ≤ count ≤ N`, around a ring of `K` particles (a
    /// direction that closes on itself: round a [`Torus`](crate::Torus), or a cloth rolled
    /// into a tube): `K` spans, the last from particle `K - 1` back to particle 0, sampled at
    /// `u = k / (count - 1)`, so that the last sample lies on the first (a mesh's seam). A
    /// natural spline solves the periodic system. In fixed point the count is rounded down
    /// as [`new`](Self::new) does, with `K` spans.
    ///
    /// ```
    /// use dunas::{Smoothing, surface::SurfaceTable};
    /// let table = SurfaceTable::<f32, 8, 33>::closed(Smoothing::CatmullRom, 33)?;
    /// assert!(table.is_closed() && table.count() == 33); // 8 spans of 4 segments
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for `count` outside `2..=N`, fewer than 3 particles, or
    /// [`Smoothing::Bezier`] (one Bézier does not close on itself).
    pub fn closed(smoothing: Smoothing, count: usize) -> Result<Self, Error> {
        if smoothing == Smoothing::Bezier {
            return Err(invalid("smoothing", "a spline or Polyline to close a ring"));
        }
        if K < 3 {
            return Err(invalid("particle count", "at least 3 to close a ring"));
        }
        Self::build(smoothing, count, true)
    }

    fn build(smoothing: Smoothing, count: usize, closed: bool) -> Result<Self, Error> {
        const { assert!(K >= 2 && K <= 255, "a surface row has 2 to 255 particles") };
        if !(2..=N).contains(&count) {
            return Err(invalid(
                "count",
                "from 2 to the table's sample capacity (its second size, N)",
            ));
        }
        let spans = match smoothing {
            _ if closed => K,
            Smoothing::Bezier => 1,
            _ => K - 1,
        };
        let count = if S::FIXED_POINT {
            dyadic_count(spans, count)
        } else {
            count
        };
        let zero = S::ZERO;
        let mut table = SurfaceTable {
            smoothing,
            closed,
            count,
            weights: [[zero; K]; N],
            slopes: [[zero; K]; N],
            support: [(0, 0); N],
        };
        // A natural spline is the B-spline of a control net that `sample` solves for.
        let basis = match smoothing {
            Smoothing::NaturalSpline => Smoothing::BSpline,
            other => other,
        };
        let per_span = S::ratio(spans as u32, 1);
        for k in 0..count {
            // Sample k at u = k / (count - 1): span ⌊u·spans⌋ at the fraction left over.
            let scaled = k * spans;
            let last = count - 1;
            let (span, t) = if k == last {
                (spans - 1, S::ONE)
            } else {
                (scaled / last, S::ratio((scaled % last) as u32, last as u32))
            };
            basis.weights(closed, span, t, &mut table.weights[k]);
            basis.slopes(closed, span, t, &mut table.slopes[k]);
            for s in &mut table.slopes[k] {
                *s = *s * per_span;
            }
            if S::FIXED_POINT {
                settle(&mut table.weights[k], S::ONE);
                settle(&mut table.slopes[k], S::ZERO);
            }
            let nonzero = |i: &usize| table.weights[k][*i] != zero || table.slopes[k][*i] != zero;
            let mut first = (0..K).find(nonzero).unwrap_or(0);
            let mut end = (0..K).rev().find(nonzero).map_or(first, |i| i + 1);
            // Four weights where they fit, zeros included: the unrolled path of `sample`.
            if K >= 4 && end - first <= 4 {
                first = first.min(K - 4);
                end = first + 4;
            }
            table.support[k] = (first as u8, end as u8);
        }
        Ok(table)
    }

    /// Samples in this direction.
    #[inline]
    pub fn count(&self) -> usize {
        self.count
    }

    /// The smoothing the table was built for.
    #[inline]
    pub fn smoothing(&self) -> Smoothing {
        self.smoothing
    }

    /// Whether the table goes round a ring of particles ([`closed`](Self::closed)).
    #[inline]
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Sample `k`'s first particle and its four weights and slopes, when it has four (the
    /// splines): what [`sample`] hoists out of a line of samples.
    #[inline(always)]
    fn quad(&self, k: usize) -> Option<(usize, [S; 4], [S; 4])> {
        let (first, end) = self.support[k];
        let span = usize::from(first)..usize::from(end);
        let weights = <[S; 4]>::try_from(self.weights[k].get(span.clone())?).ok()?;
        let slopes = <[S; 4]>::try_from(self.slopes[k].get(span)?).ok()?;
        Some((usize::from(first), weights, slopes))
    }

    /// `(Σ w_i p_i, Σ w'_i p_i, Σ w_i q_i)` of sample `k` over `points` and `others` (the
    /// last `P::default()` without `others`), on the sample's non-zero weights only: the
    /// path of a sample without four weights (one Bézier, up to `K`).
    fn apply<P: Point<Scalar = S>>(
        &self,
        k: usize,
        points: &[P; K],
        others: Option<&[P; K]>,
    ) -> (P, P, P) {
        let (first, end) = self.support[k];
        let span = usize::from(first)..usize::from(end);
        let (weights, slopes) = (
            &self.weights[k][span.clone()],
            &self.slopes[k][span.clone()],
        );
        let (mut at, mut slope, mut other) = (P::default(), P::default(), P::default());
        for (i, (&w, &s)) in span.zip(weights.iter().zip(slopes)) {
            at += points[i] * w;
            slope += points[i] * s;
            if let Some(q) = others {
                other += q[i] * w;
            }
        }
        (at, slope, other)
    }
}

/// The largest count up to `count` whose parameters over `spans` spans are dyadic:
/// `spans·2^m + 1`, or `d + 1` for the largest divisor `d` of `spans` below `count`.
fn dyadic_count(spans: usize, count: usize) -> usize {
    let segments = count - 1;
    let per_span = segments / spans;
    if per_span >= 1 {
        spans * (1 << per_span.ilog2()) + 1
    } else {
        (1..=segments)
            .rev()
            .find(|d| spans.is_multiple_of(*d))
            .unwrap_or(1)
            + 1
    }
}

/// Adds to the largest entry of `values` what makes them sum to exactly `total` (the
/// rounding of fixed-point weights, a few units of the last place).
fn settle<S: Scalar>(values: &mut [S], total: S) {
    let mut sum = S::ZERO;
    let mut largest = 0;
    for (i, &v) in values.iter().enumerate() {
        sum += v;
        if v.abs() > values[largest].abs() {
            largest = i;
        }
    }
    if let Some(v) = values.get_mut(largest) {
        *v += total - sum;
    }
}

/// Samples the surface of `grid` (row `j` is `grid[j]`, along `u`) at `tu.count() ×
/// tv.count()` points, writing positions and unit normals (`∂u × ∂v`, the zero vector where
/// the surface is degenerate; with the `micromath` feature, `f32` normals are within 3.5% of
/// unit length) row by row, `u` fastest; returns the count. Rows first, then
/// columns: for each of the `V` particle rows, its `nu` curve points and slopes; then each
/// sample combines the rows with `tv`'s weights. A natural spline first solves its control
/// net (a tridiagonal system along every row and column, `O(U·V)`). Needs stack for
/// `U·V + 2·V·NU` points.
///
/// # Errors
/// [`Error::InvalidParameter`] when the tables were built for different smoothings;
/// [`Error::BufferTooSmall`] when either buffer holds fewer than `nu·nv` points.
pub fn sample<S: Scalar, const U: usize, const V: usize, const NU: usize, const NV: usize>(
    grid: &[[Vec3<S>; U]; V],
    tu: &SurfaceTable<S, U, NU>,
    tv: &SurfaceTable<S, V, NV>,
    positions: &mut [Vec3<S>],
    normals: &mut [Vec3<S>],
) -> Result<usize, Error> {
    if tu.smoothing != tv.smoothing {
        return Err(invalid("tables", "of one smoothing in both directions"));
    }
    let (nu, nv) = (tu.count, tv.count);
    let needed = nu * nv;
    let got = positions.len().min(normals.len());
    if got < needed {
        return Err(Error::BufferTooSmall { needed, got });
    }
    let mut net = *grid;
    if tu.smoothing == Smoothing::NaturalSpline {
        natural_net(&mut net, tu.closed, tv.closed);
    }
    // Rows first: every particle row's points and u-slopes at the nu samples, stored by
    // sample (column `a` holds row j's point at sample a), so that columns read in a line.
    let zero = Vec3::default();
    let mut columns = [[zero; V]; NU];
    let mut column_slopes = [[zero; V]; NU];
    let samples = columns.iter_mut().zip(&mut column_slopes).enumerate();
    for (a, (column, slopes)) in samples.take(nu) {
        let points = column.iter_mut().zip(slopes).zip(&net);
        if let Some((i, w, s)) = tu.quad(a).filter(|&(i, _, _)| i + 4 <= U) {
            for ((p, du), row) in points {
                let q = &row[i..i + 4];
                (*p, *du) = (weigh(q, w), weigh(q, s));
            }
        } else {
            for ((p, du), row) in points {
                (*p, *du, _) = tu.apply(a, row, None);
            }
        }
    }
    // Then columns: position, ∂v from the rows' points, ∂u from their slopes.
    let lines = positions
        .chunks_exact_mut(nu)
        .zip(normals.chunks_exact_mut(nu));
    for (b, (line, line_normals)) in lines.take(nv).enumerate() {
        let samples = columns.iter().zip(&column_slopes);
        let points = line.iter_mut().zip(line_normals).zip(samples);
        // Four weights a line (the splines): read once, not once a sample.
        if let Some((j, w, s)) = tv.quad(b).filter(|&(j, _, _)| j + 4 <= V) {
            for ((p, n), (column, slopes)) in points {
                let (q, r) = (&column[j..j + 4], &slopes[j..j + 4]);
                *p = weigh(q, w);
                *n = unit_normal(weigh(r, w), weigh(q, s)).unwrap_or_default();
            }
        } else {
            for ((p, n), (column, slopes)) in points {
                let (at, dv, du) = tv.apply(b, column, Some(slopes));
                *p = at;
                *n = unit_normal(du, dv).unwrap_or_default();
            }
        }
    }
    Ok(needed)
}

/// `Σ w_i p_i` over four points (the first four of `points`).
#[inline(always)]
fn weigh<S: Scalar>(points: &[Vec3<S>], w: [S; 4]) -> Vec3<S> {
    points[0] * w[0] + points[1] * w[1] + points[2] * w[2] + points[3] * w[3]
}

/// Turns a grid of particles into the B-spline control net whose surface passes through
/// every particle: the natural spline's solve along every row, then every column.
pub(crate) fn natural_grid<P: Point, const U: usize, const V: usize>(grid: &mut [[P; U]; V]) {
    natural_net(grid, false, false);
}

/// [`natural_grid`] with rows (`closed_u`) or columns (`closed_v`) that close on themselves.
#[inline(never)]
pub(crate) fn natural_net<P: Point, const U: usize, const V: usize>(
    grid: &mut [[P; U]; V],
    closed_u: bool,
    closed_v: bool,
) {
    for row in grid.iter_mut() {
        natural_controls(row, closed_u);
    }
    for i in 0..U {
        // Gathered by a loop: `array::from_fn` built it aside and copied it in.
        let mut column = [P::default(); V];
        for (c, row) in column.iter_mut().zip(grid.iter()) {
            *c = row[i];
        }
        natural_controls(&mut column, closed_v);
        for (row, c) in grid.iter_mut().zip(column) {
            row[i] = c;
        }
    }
}

/// `∂u × ∂v`, normalised: in floats by [`Scalar::approx_inv_sqrt`] of its squared length
/// (exact, or micromath's within 3.5% with the `micromath` feature: the direction stays
/// exact, the length is within `1 ± 0.035`); in fixed point the partials are first scaled
/// by powers of two to a largest coordinate in `[½, 2)`, so that their product stays in
/// range (one normalisation, not three).
fn unit_normal<S: Scalar>(du: Vec3<S>, dv: Vec3<S>) -> Option<Vec3<S>> {
    if S::FIXED_POINT {
        du.balanced()?.cross(dv.balanced()?).normalize()
    } else {
        let n = du.cross(dv);
        let squared = n.dot(n);
        // Positive and finite (`∞ · 0` is NaN): two float comparisons.
        (squared > S::ZERO && squared * S::ZERO == S::ZERO).then(|| n * squared.approx_inv_sqrt())
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Patch;
    use crate::curves::smooth::Smoothed;

    /// A bumpy 5×4 grid.
    fn grid() -> [[Vec3<f64>; 5]; 4] {
        core::array::from_fn(|j| {
            core::array::from_fn(|i| {
                let (x, z) = (i as f64, j as f64 * 1.3);
                Vec3::new(x + 0.1 * z, (x * 1.7).sin() * (z * 0.9).cos(), z)
            })
        })
    }

    fn close(a: Vec3<f64>, b: Vec3<f64>) -> bool {
        (a - b).length() < 1e-9
    }

    #[test]
    fn catmull_rom_passes_through_every_particle() {
        let g = grid();
        // 4 spans × 3 samples each along u, 3 spans × 2 along v: particles on samples.
        let tu = SurfaceTable::<f64, 5, 16>::new(Smoothing::CatmullRom, 13).unwrap();
        let tv = SurfaceTable::<f64, 4, 16>::new(Smoothing::CatmullRom, 7).unwrap();
        let (mut pos, mut nor) = ([Vec3::default(); 91], [Vec3::default(); 91]);
        assert_eq!(sample(&g, &tu, &tv, &mut pos, &mut nor), Ok(91));
        for j in 0..4 {
            for i in 0..5 {
                assert!(close(pos[2 * j * 13 + 3 * i], g[j][i]), "({i}, {j})");
            }
        }
    }

    /// The natural spline surface passes through every particle, and along a particle row it
    /// is that row's natural spline curve (the column solve leaves particle rows alone).
    #[test]
    fn natural_spline_passes_through_every_particle() {
        let g = grid();
        let tu = SurfaceTable::<f64, 5, 16>::new(Smoothing::NaturalSpline, 13).unwrap();
        let tv = SurfaceTable::<f64, 4, 16>::new(Smoothing::NaturalSpline, 7).unwrap();
        let (mut pos, mut nor) = ([Vec3::default(); 91], [Vec3::default(); 91]);
        assert_eq!(sample(&g, &tu, &tv, &mut pos, &mut nor), Ok(91));
        for j in 0..4 {
            for i in 0..5 {
                assert!(close(pos[2 * j * 13 + 3 * i], g[j][i]), "({i}, {j})");
            }
        }
        let mut curve = [Vec3::default(); 13];
        Smoothed::open(Smoothing::NaturalSpline, &g[2])
            .unwrap()
            .sample(&mut curve)
            .unwrap();
        for (a, c) in curve.iter().enumerate() {
            assert!(close(pos[4 * 13 + a], *c), "{a}");
        }
    }

    #[test]
    fn bezier_is_the_patch_and_its_normals() {
        let g = grid();
        let patch = Patch::new(g).unwrap();
        let tu = SurfaceTable::<f64, 5, 16>::new(Smoothing::Bezier, 9).unwrap();
        let tv = SurfaceTable::<f64, 4, 16>::new(Smoothing::Bezier, 6).unwrap();
        let (mut pos, mut nor) = ([Vec3::default(); 54], [Vec3::default(); 54]);
        sample(&g, &tu, &tv, &mut pos, &mut nor).unwrap();
        for b in 0..6 {
            for a in 0..9 {
                let (u, v) = (a as f64 / 8.0, b as f64 / 5.0);
                let k = b * 9 + a;
                assert!(close(pos[k], patch.eval(u, v)), "({a}, {b})");
                assert!(close(nor[k], patch.normal(u, v).unwrap()), "({a}, {b})");
            }
        }
    }

    /// Each row of the B-spline surface at a particle row is that row's B-spline curve, and
    /// the normals agree with central differences of the positions.
    #[test]
    fn rows_are_the_curves_and_normals_the_differences() {
        let g = grid();
        let n = 17;
        let tu = SurfaceTable::<f64, 5, 32>::new(Smoothing::BSpline, n).unwrap();
        let tv = SurfaceTable::<f64, 4, 32>::new(Smoothing::BSpline, 7).unwrap();
        let (mut pos, mut nor) = ([Vec3::default(); 17 * 7], [Vec3::default(); 17 * 7]);
        sample(&g, &tu, &tv, &mut pos, &mut nor).unwrap();
        // Row v = 0 is the clamped B-spline of particle row 0.
        let mut curve = [Vec3::default(); 17];
        Smoothed::open(Smoothing::BSpline, &g[0])
            .unwrap()
            .sample(&mut curve)
            .unwrap();
        for a in 0..n {
            assert!(close(pos[a], curve[a]), "{a}");
        }
        // Normals against the cross product of central differences (second order).
        for b in 1..6 {
            for a in 1..n - 1 {
                let k = b * n + a;
                let du = pos[k + 1] - pos[k - 1];
                let dv = pos[k + n] - pos[k - n];
                let reference = du.cross(dv).normalize().unwrap();
                assert!((nor[k] - reference).length() < 0.05, "({a}, {b})");
            }
        }
    }

    #[test]
    fn bad_tables_and_buffers_are_errors() {
        assert!(SurfaceTable::<f32, 4, 8>::new(Smoothing::BSpline, 1).is_err());
        assert!(SurfaceTable::<f32, 4, 8>::new(Smoothing::BSpline, 9).is_err());
        let g = [[Vec3::<f32>::default(); 4]; 4];
        let a = SurfaceTable::<f32, 4, 8>::new(Smoothing::BSpline, 4).unwrap();
        let b = SurfaceTable::<f32, 4, 8>::new(Smoothing::CatmullRom, 4).unwrap();
        let (mut pos, mut nor) = ([Vec3::default(); 16], [Vec3::default(); 15]);
        assert!(matches!(
            sample(&g, &a, &b, &mut pos, &mut nor),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            sample(&g, &a, &a, &mut pos, &mut nor),
            Err(Error::BufferTooSmall {
                needed: 16,
                got: 15
            })
        ));
    }

    /// In Q16 the counts are dyadic, the particles are drawn exactly where they are, a grid
    /// moved by whole units draws moved by exactly that, and every point is within a few
    /// units of the format's last place of the f64 surface at the same parameters.
    #[cfg(feature = "fixed")]
    #[test]
    fn q16_tables_take_dyadic_parameters() {
        use crate::Q16;
        for (smoothing, asked, count) in [
            (Smoothing::CatmullRom, 16, 9),
            (Smoothing::NaturalSpline, 9, 9),
            (Smoothing::BSpline, 4, 3),
            (Smoothing::Bezier, 12, 9),
        ] {
            let tu = SurfaceTable::<Q16, 5, 16>::new(smoothing, asked).unwrap();
            assert_eq!(tu.count(), count, "{smoothing:?}");
        }
        let g = grid();
        let q =
            |p: Vec3<f64>| Vec3::new(Q16::from_f64(p.x), Q16::from_f64(p.y), Q16::from_f64(p.z));
        let gq: [[Vec3<Q16>; 5]; 4] =
            core::array::from_fn(|j| core::array::from_fn(|i| q(g[j][i])));
        let g64: [[Vec3<f64>; 5]; 4] = core::array::from_fn(|j| {
            core::array::from_fn(|i| {
                let p = gq[j][i];
                Vec3::new(p.x.to_f64(), p.y.to_f64(), p.z.to_f64())
            })
        });
        let offset = Vec3::new(Q16::from_i16(3), Q16::from_i16(-2), Q16::from_i16(5));
        let moved: [[Vec3<Q16>; 5]; 4] =
            core::array::from_fn(|j| core::array::from_fn(|i| gq[j][i] + offset));
        for smoothing in [
            Smoothing::CatmullRom,
            Smoothing::NaturalSpline,
            Smoothing::BSpline,
        ] {
            let tu = SurfaceTable::<Q16, 5, 16>::new(smoothing, 16).unwrap();
            let tv = SurfaceTable::<Q16, 4, 16>::new(smoothing, 16).unwrap();
            let (nu, nv) = (tu.count(), tv.count());
            assert_eq!((nu, nv), (9, 13)); // 4 spans of 2 segments, 3 of 4
            let fu = SurfaceTable::<f64, 5, 16>::new(smoothing, nu).unwrap();
            let fv = SurfaceTable::<f64, 4, 16>::new(smoothing, nv).unwrap();
            let zq = Vec3::new(Q16::ZERO, Q16::ZERO, Q16::ZERO);
            let (mut pq, mut nq, mut mq, mut mn) = ([zq; 117], [zq; 117], [zq; 117], [zq; 117]);
            let (mut pf, mut nf) = ([Vec3::default(); 117], [Vec3::default(); 117]);
            sample(&gq, &tu, &tv, &mut pq, &mut nq).unwrap();
            sample(&moved, &tu, &tv, &mut mq, &mut mn).unwrap();
            sample(&g64, &fu, &fv, &mut pf, &mut nf).unwrap();
            for k in 0..117 {
                assert_eq!(mq[k], pq[k] + offset, "{smoothing:?} sample {k}");
                let d = Vec3::new(pq[k].x.to_f64(), pq[k].y.to_f64(), pq[k].z.to_f64()) - pf[k];
                assert!(
                    d.length() < 2e-4,
                    "{smoothing:?} sample {k}: {}",
                    d.length()
                );
            }
            if smoothing == Smoothing::CatmullRom {
                for j in 0..4 {
                    for i in 0..5 {
                        assert_eq!(pq[4 * j * 9 + 2 * i], gq[j][i], "particle ({i}, {j})");
                    }
                }
            }
        }
    }

    /// The test grid's natural-spline normals in `f64` and in `S` (widened to `f64`), 9×7.
    fn normals_against_f64<S: Scalar>() -> [(Vec3<f64>, Vec3<f64>); 63] {
        let g = grid();
        let gs: [[Vec3<S>; 5]; 4] = core::array::from_fn(|j| {
            core::array::from_fn(|i| {
                let p = g[j][i];
                Vec3::new(S::from_f64(p.x), S::from_f64(p.y), S::from_f64(p.z))
            })
        });
        let t = SurfaceTable::<f64, 5, 16>::new(Smoothing::NaturalSpline, 9).unwrap();
        let tv = SurfaceTable::<f64, 4, 16>::new(Smoothing::NaturalSpline, 7).unwrap();
        let ts = SurfaceTable::<S, 5, 16>::new(Smoothing::NaturalSpline, 9).unwrap();
        let tvs = SurfaceTable::<S, 4, 16>::new(Smoothing::NaturalSpline, 7).unwrap();
        let (mut p, mut n) = ([Vec3::default(); 63], [Vec3::default(); 63]);
        let (mut ps, mut ns) = ([Vec3::default(); 63], [Vec3::default(); 63]);
        sample(&g, &t, &tv, &mut p, &mut n).unwrap();
        sample(&gs, &ts, &tvs, &mut ps, &mut ns).unwrap();
        core::array::from_fn(|k| {
            let b = ns[k];
            (n[k], Vec3::new(b.x.to_f64(), b.y.to_f64(), b.z.to_f64()))
        })
    }

    /// `Q16` normals (the partials scaled by powers of two, then one normalisation) point
    /// where the f64 ones do and are of unit length, both within 2⁻¹² (a few units of the
    /// format's last place).
    #[test]
    fn q16_normals_keep_their_direction() {
        for (a, b) in normals_against_f64::<crate::Q16>() {
            let length = b.length();
            assert!((length - 1.0).abs() <= 1.0 / 4096.0, "length {length}");
            assert!(a.cross(b).length() < 1.0 / 4096.0, "direction {a:?} {b:?}");
        }
    }

    /// `f32` normals point where the f64 ones do, and are of unit length within the 3.5%
    /// the docs allow (micromath's inverse square root with the `micromath` feature, exact
    /// without it).
    #[test]
    fn f32_normals_keep_their_direction() {
        for (a, b) in normals_against_f64::<f32>() {
            assert!((b.length() - 1.0).abs() <= 0.035, "length {}", b.length());
            assert!(
                a.cross(b).length() / b.length() < 1e-5,
                "direction {a:?} {b:?}"
            );
        }
    }
}
