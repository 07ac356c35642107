//! Samplers: many points of a curve into a caller's buffer, each method a different trade
//! between speed and accuracy.
//!
//! Every sampler implements [`Sampler`]: it writes points at uniformly spaced parameters
//! `t = i / (n - 1)` into `out` and returns `n`, the count written. All of them write the end
//! points exactly. Pick one by what the scene needs:
//!
//! | sampler | cost per point (per coordinate) | error bound (`ε`: format epsilon, `R`: largest control coordinate) |
//! |---|---|---|
//! | [`BernsteinTable`] | `N` multiply-adds, weights from a table | `4·N·ε·R` — the per-frame default for floats |
//! | [`DeCasteljau`] | `N(N-1)/2` lerps + one division | `4·(N-1)·ε·R` in floats; in `Q16` plus the rounded `t`: `(N-1)·D·2⁻¹⁷` (`D`: longest control leg) |
//! | [`Horner`] | `N - 1` multiply-adds | `2^(N-1)·N·ε·R`: cancels at degree 7, saturates in `Q16` |
//! | [`ForwardDiff`] | `N - 1` additions | `n·2^(N-1)·ε·R`, growing with the count `n` |
//! | [`Subdivide`] | ≈ `N²/2` midpoints, no multiply | `(k+N)·ε·R` in floats; `k·(N-1)/2` units of 2⁻¹⁶ in `Q16` — the `Q16` default |
//!
//! Within 0.01 px (measured by `examples/sampler_errors.rs`): every method in `f64`;
//! [`BernsteinTable`], [`DeCasteljau`] and [`Subdivide`] in `f32` up to 10⁴ px at degree 7;
//! [`Horner`] in `f32` up to degree 3, in `Q16` up to degree 3 at 100 px; [`ForwardDiff`] in
//! `f32` up to degree 3 at 100 px and 1024 samples, in `Q16` nowhere. Only [`Subdivide`]
//! stays within 0.01 px in `Q16` at 10⁴ px.
//!
//! Errors are checked against an exact (integer) reference in the tests of `tests/suite/samplers.rs`.
//!
//! ```
//! use dunas::{Bezier, Vec2, sampler::{Sampler, DeCasteljau}};
//! let c = Bezier::new([Vec2::new(0.0f32, 0.0), Vec2::new(5.0, 10.0), Vec2::new(10.0, 0.0)])?;
//! let mut out = [Vec2::default(); 5];
//! let n = DeCasteljau.sample(&c, &mut out)?;
//! assert_eq!(n, 5);
//! assert_eq!(out[2], Vec2::new(5.0, 5.0));
//! # Ok::<(), dunas::Error>(())
//! ```

use crate::curves::curve::degree_scalar;
use crate::error::invalid;
use crate::{Bezier, Error, Point, Scalar};

/// Most points one call writes (`2^24`, where `f32` still counts exactly).
pub const MAX_SAMPLES: usize = 1 << 24;

/// Writes points of a curve at uniformly spaced parameters into a caller's buffer.
pub trait Sampler<P: Point, const N: usize> {
    /// Writes samples of `curve` into the front of `out`, from `t = 0` to `t = 1` inclusive,
    /// and returns how many it wrote (at most `out.len()`, see each sampler for the count).
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] when `out` cannot hold the smallest run the sampler makes
    /// (2 points for most). Nothing else can fail: the curve was checked when built.
    fn sample(&self, curve: &Bezier<P, N>, out: &mut [P]) -> Result<usize, Error>;

    /// Samples pieces joined end to end (the spans of a spline, a closed loop, a polyline)
    /// into `out`: each piece gets an equal share of the buffer and is sampled by
    /// [`sample`](Self::sample), and a joint shared by two pieces is written once. Returns the
    /// count, `pieces·(c - 1) + 1`, where `c` is what the sampler writes into a share of
    /// `⌊(out.len() - 1) / pieces⌋ + 1` points: the whole share for most samplers, `2^k + 1`
    /// for [`Subdivide`] (dyadic, so `Q16` needs no rounded `t`), `M` for a [`BernsteinTable`].
    /// Each piece's end should be the next one's start; the last piece's end is written last.
    ///
    /// ```
    /// use dunas::{Bezier, Vec2, sampler::{Sampler, BernsteinTable}};
    /// let a = Bezier::new([Vec2::new(0.0f32, 0.0), Vec2::new(1.0, 1.0), Vec2::new(2.0, 1.0), Vec2::new(3.0, 0.0)])?;
    /// let b = Bezier::new([Vec2::new(3.0f32, 0.0), Vec2::new(4.0, -1.0), Vec2::new(5.0, -1.0), Vec2::new(6.0, 0.0)])?;
    /// let mut out = [Vec2::default(); 40];
    /// let n = BernsteinTable::<f32, 4, 9>::new().sample_joined(&[a, b], &mut out)?;
    /// assert_eq!(n, 17); // 2 pieces of 8 segments
    /// assert_eq!((out[8], out[16]), (a.end(), b.end()));
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] when a share is smaller than the sampler's smallest run (it
    /// needs `pieces + 1` points for most samplers); [`Error::InvalidParameter`] for no pieces,
    /// or a sampler that writes fewer than 2 points or more than its share.
    fn sample_joined(&self, pieces: &[Bezier<P, N>], out: &mut [P]) -> Result<usize, Error> {
        let Some(last) = pieces.last() else {
            return Err(invalid("pieces", "at least one curve"));
        };
        let len = out.len();
        let total = |per_piece: usize| Error::BufferTooSmall {
            needed: pieces.len().saturating_mul(per_piece - 1).saturating_add(1),
            got: len,
        };
        let share = out.len().min(MAX_SAMPLES).saturating_sub(1) / pieces.len() + 1;
        if share < 2 {
            return Err(total(2));
        }
        let mut at = 0;
        for piece in pieces {
            let slot = out.get_mut(at..at + share).ok_or(total(2))?;
            match self.sample(piece, slot) {
                Ok(c) if (2..=share).contains(&c) => at += c - 1,
                // A sampler that breaks its contract (fewer than 2 points, more than asked).
                Ok(_) => {
                    return Err(invalid(
                        "sampler",
                        "writing 2 points or more, and no more than asked",
                    ));
                }
                Err(Error::BufferTooSmall { needed, .. }) => return Err(total(needed.max(2))),
                Err(e) => return Err(e),
            }
        }
        *out.get_mut(at).ok_or(total(2))? = last.end();
        Ok(at + 1)
    }
}

/// Uniform count for the samplers that fill the whole buffer.
#[inline]
fn uniform_count(len: usize) -> Result<usize, Error> {
    if len < 2 {
        Err(Error::BufferTooSmall {
            needed: 2,
            got: len,
        })
    } else {
        Ok(len.min(MAX_SAMPLES))
    }
}

/// The control points split into coordinate lanes (structure of arrays).
#[inline]
fn lanes<P: Point, const N: usize>(curve: &Bezier<P, N>) -> [[P::Scalar; N]; 3] {
    let mut l = [[P::Scalar::ZERO; N]; 3];
    for (i, p) in curve.points().iter().enumerate() {
        for (d, lane) in l.iter_mut().enumerate().take(P::DIM) {
            lane[i] = p.coord(d);
        }
    }
    l
}

#[inline]
fn de_casteljau_lane<S: Scalar, const N: usize>(lane: &[S; N], t: S) -> S {
    let mut b = *lane;
    for r in 1..N {
        for i in 0..N - r {
            b[i] = b[i] + (b[i + 1] - b[i]) * t;
        }
    }
    b[0]
}

/// De Casteljau's algorithm at each `t = i / (n-1)`: `n = out.len()` points.
///
/// Cost per point: one division for `t` and `N(N-1)/2` lerps per coordinate. Every step is
/// a convex combination, so the error stays near `N` rounding units of the largest
/// coordinate at any degree (`examples/sampler_errors.rs`: 5.4e-3 px in `f32` at 10⁴ px,
/// degree 7). In `Q16`, `t = i/(n-1)` is itself rounded to 2⁻¹⁶, which moves points by up
/// to `|P'|·2⁻¹⁷` (up to 1 px at 10⁴ px in the same example): use [`Subdivide`] there.
#[derive(Clone, Copy, Debug, Default)]
pub struct DeCasteljau;

impl<P: Point, const N: usize> Sampler<P, N> for DeCasteljau {
    fn sample(&self, curve: &Bezier<P, N>, out: &mut [P]) -> Result<usize, Error> {
        let n = uniform_count(out.len())?;
        let lanes = lanes(curve);
        let m = (n - 1) as u32;
        for (i, o) in out[..n].iter_mut().enumerate() {
            let t = P::Scalar::ratio(i as u32, m);
            for (d, lane) in lanes.iter().enumerate().take(P::DIM) {
                o.set_coord(d, de_casteljau_lane(lane, t));
            }
        }
        out[n - 1] = curve.end();
        Ok(n)
    }
}

/// Horner's rule on the power basis: `n = out.len()` points.
///
/// The control points are converted once to coefficients `a_j = C(d,j)·Δʲ P₀`
/// (`d = N - 1`), whose size grows like `2^d` times the coordinates; evaluation then costs
/// `d` multiply-adds per coordinate. Fast, but the large alternating coefficients cancel:
/// the error grows like `2^d · d` rounding units of the coordinate size, and in `Q16` the
/// coefficients saturate once `2^d · |P|` passes 32768 (degree 7 at about 250 px).
#[derive(Clone, Copy, Debug, Default)]
pub struct Horner;

/// Power-basis coefficients of one lane: `p(t) = Σ a[j] t^j`.
#[inline]
fn power_coefficients<S: Scalar, const N: usize>(lane: &[S; N]) -> [S; N] {
    // Forward differences Δʲ P₀, then scale by the binomials C(d, j).
    let mut diff = *lane;
    let mut a = [S::ZERO; N];
    a[0] = diff[0];
    let mut binom: usize = 1;
    for j in 1..N {
        for i in 0..N - j {
            diff[i] = diff[i + 1] - diff[i];
        }
        binom = binom.saturating_mul(N - j) / j;
        a[j] = diff[0] * degree_scalar::<S>(binom);
    }
    a
}

impl<P: Point, const N: usize> Sampler<P, N> for Horner {
    fn sample(&self, curve: &Bezier<P, N>, out: &mut [P]) -> Result<usize, Error> {
        let n = uniform_count(out.len())?;
        let mut coef = lanes(curve);
        for lane in coef.iter_mut().take(P::DIM) {
            *lane = power_coefficients(lane);
        }
        let m = (n - 1) as u32;
        for (i, o) in out[..n].iter_mut().enumerate() {
            let t = P::Scalar::ratio(i as u32, m);
            for (d, a) in coef.iter().enumerate().take(P::DIM) {
                let mut v = a[N - 1];
                for j in (0..N - 1).rev() {
                    v = v * t + a[j];
                }
                o.set_coord(d, v);
            }
        }
        out[0] = curve.start();
        out[n - 1] = curve.end();
        Ok(n)
    }
}

/// Forward differencing: `n = out.len()` points, `N - 1` additions each.
///
/// The power coefficients `a_j` (as in [`Horner`]) are scaled to the step, `b_j = a_j h^j`
/// with `h = 1/(n-1)`, and turned into the starting differences
/// `Δᵏ = Σ_j b_j · k!·S(j,k)` (Stirling numbers, exact small integers); each further point
/// is then a running sum. Every addition's rounding is carried into all later points, so
/// the error grows with the count and with the size of the power coefficients (about
/// `n · 2^(N-1)` rounding units of the coordinates): in `f32` a degree-7 curve at 10⁴ px
/// drifts by pixels, and in `Q16` the tiny high differences vanish below 2⁻¹⁶ even at 64
/// samples. Use it in `f64`, or in `f32` for low degree and short runs.
#[derive(Clone, Copy, Debug, Default)]
pub struct ForwardDiff;

/// Starting forward differences `Δᵏ p(0)`, `k = 0..N`, for step `h` of `p(t) = Σ a_j t^j`.
#[inline]
fn forward_differences<S: Scalar, const N: usize>(a: &[S; N], h: S) -> [S; N] {
    // surj[j][k] = k!·S(j,k), the number of maps from j onto k: surj[j][k] = k·(surj[j-1][k]
    // + surj[j-1][k-1]). Exact in floats for N <= 16; saturates harmlessly in Q16.
    let mut surj = [S::ZERO; N];
    let mut diff = [S::ZERO; N];
    let mut hj = S::ONE;
    surj[0] = S::ONE;
    diff[0] = a[0];
    for j in 1..N {
        hj = hj * h;
        for k in (1..=j).rev() {
            surj[k] = (surj[k] + surj[k - 1]) * degree_scalar::<S>(k);
        }
        surj[0] = S::ZERO;
        let b = a[j] * hj;
        for k in 1..=j {
            diff[k] += b * surj[k];
        }
    }
    diff
}

impl<P: Point, const N: usize> Sampler<P, N> for ForwardDiff {
    fn sample(&self, curve: &Bezier<P, N>, out: &mut [P]) -> Result<usize, Error> {
        let n = uniform_count(out.len())?;
        let mut diff = lanes(curve);
        let h = P::Scalar::ratio(1, (n - 1) as u32);
        for lane in diff.iter_mut().take(P::DIM) {
            *lane = forward_differences(&power_coefficients(lane), h);
        }
        // All coordinates advance together: independent add chains that overlap.
        for o in out[..n].iter_mut() {
            for (d, lane) in diff.iter_mut().enumerate().take(P::DIM) {
                o.set_coord(d, lane[0]);
                for k in 0..N - 1 {
                    let next = lane[k + 1];
                    lane[k] += next;
                }
            }
        }
        out[0] = curve.start();
        out[n - 1] = curve.end();
        Ok(n)
    }
}

/// Bernstein weights tabulated once for `M` uniform samples of an `N`-point curve.
///
/// Each point is then `Σ w[i][j]·P[j]`: `N` multiply-adds per coordinate, Horner's cost,
/// with weights that are all in `[0, 1]` and sum to 1, so the error stays at
/// de Casteljau's level. The table holds `M × N` scalars (`4·M·N` bytes in `f32`): build
/// it once per (curve size, sample count) and reuse it every frame.
///
/// ```
/// use dunas::{Bezier, Vec2, sampler::{Sampler, BernsteinTable}};
/// let table = BernsteinTable::<f32, 4, 33>::new();
/// let c = Bezier::new([Vec2::new(0.0f32, 0.0), Vec2::new(1.0, 2.0), Vec2::new(3.0, 2.0), Vec2::new(4.0, 0.0)])?;
/// let mut out = [Vec2::default(); 40];
/// assert_eq!(table.sample(&c, &mut out)?, 33); // always M points
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct BernsteinTable<S, const N: usize, const M: usize> {
    weights: [[S; N]; M],
}

impl<S: Scalar, const N: usize, const M: usize> BernsteinTable<S, N, M> {
    /// Tabulates the weights at `t = i / (M-1)` by the Bernstein recursion
    /// (`N²/2` multiply-adds per row, all convex). `M < 2` or `N < 2` does not compile.
    pub fn new() -> Self {
        const {
            assert!(
                M >= 2 && N >= 2,
                "a table needs N >= 2 points and M >= 2 samples"
            )
        };
        let mut weights = [[S::ZERO; N]; M];
        for (i, w) in weights.iter_mut().enumerate() {
            bernstein_weights(S::ratio(i as u32, (M - 1) as u32), w);
        }
        BernsteinTable { weights }
    }

    /// The weight row for sample `i` (`None` past the end).
    pub fn row(&self, i: usize) -> Option<&[S; N]> {
        self.weights.get(i)
    }
}

/// The Bernstein weights of degree `w.len() - 1` at `t`, by the convex recursion
/// (`n²/2` multiply-adds, every weight in `[0, 1]`).
pub(crate) fn bernstein_weights<S: Scalar>(t: S, w: &mut [S]) {
    let s = S::ONE - t;
    if let Some(first) = w.first_mut() {
        *first = S::ONE;
    }
    for r in 1..w.len() {
        w[r] = w[r - 1] * t;
        for j in (1..r).rev() {
            w[j] = w[j] * s + w[j - 1] * t;
        }
        w[0] = w[0] * s;
    }
}

impl<S: Scalar, const N: usize, const M: usize> Default for BernsteinTable<S, N, M> {
    fn default() -> Self {
        Self::new()
    }
}

impl<P: Point, const N: usize, const M: usize> Sampler<P, N> for BernsteinTable<P::Scalar, N, M> {
    /// Writes exactly `M` points.
    fn sample(&self, curve: &Bezier<P, N>, out: &mut [P]) -> Result<usize, Error> {
        if out.len() < M {
            return Err(Error::BufferTooSmall {
                needed: M,
                got: out.len(),
            });
        }
        let lanes = lanes(curve);
        for (o, w) in out[..M].iter_mut().zip(self.weights.iter()) {
            for (d, lane) in lanes.iter().enumerate().take(P::DIM) {
                let mut v = P::Scalar::ZERO;
                for j in 0..N {
                    v += lane[j] * w[j];
                }
                o.set_coord(d, v);
            }
        }
        out[0] = curve.start();
        out[M - 1] = curve.end();
        Ok(M)
    }
}

/// Recursive midpoint subdivision: `2^k + 1` points at the dyadic parameters `t = i / 2^k`,
/// for the largest `k <= max_level` that fits in `out`.
///
/// Only additions and halvings (shifts in `Q16`): no multiplications and no rounded `t`,
/// which makes it the method for chips without an FPU. Cost per point ≈ `N²/2` midpoints
/// plus copying an `N`-point polygon; scratch space on the stack: `max_level + 1`
/// polygons. Error: exact in floats (halving is exact); in `Q16` each level rounds by at most
/// half a unit (2⁻¹⁷): at `k = 10`, 1e-4 px for a cubic and 2.5e-4 px at degree 7, whatever
/// the coordinate size (`examples/sampler_errors.rs`).
#[derive(Clone, Copy, Debug)]
pub struct Subdivide {
    /// Largest `k` to use (`2^k + 1` points); clamped to 16.
    pub max_level: u32,
}

impl Subdivide {
    /// Deepest subdivision: `2^16 + 1` points.
    pub const MAX_LEVEL: u32 = 16;

    /// The number of points written into a buffer of `len`, with the level: the largest
    /// `2^k + 1 <= len`, `k <= max_level`. `None` when `len < 2`.
    pub fn count_for(&self, len: usize) -> Option<(usize, u32)> {
        if len < 2 {
            return None;
        }
        let top = self.max_level.min(Self::MAX_LEVEL);
        let mut k = 0;
        while k < top && (1usize << (k + 1)) < len {
            k += 1;
        }
        Some(((1usize << k) + 1, k))
    }
}

impl Default for Subdivide {
    /// Up to `2^16 + 1` points: the buffer length decides.
    fn default() -> Self {
        Subdivide {
            max_level: Self::MAX_LEVEL,
        }
    }
}

impl<P: Point, const N: usize> Sampler<P, N> for Subdivide {
    fn sample(&self, curve: &Bezier<P, N>, out: &mut [P]) -> Result<usize, Error> {
        let (n, k) = self.count_for(out.len()).ok_or(Error::BufferTooSmall {
            needed: 2,
            got: out.len(),
        })?;
        let mut at = 0;
        subdivide_into(curve, k, out, &mut at);
        out[n - 1] = curve.end();
        Ok(n)
    }
}

/// Writes the start points of the `2^level` pieces of `curve` (halved `level` times) into
/// `out` from index `*at`, advancing it; the caller writes the end point. Depth-first
/// recursion, at most 16 deep: only midpoints (shifts in `Q16`), nothing else on the stack.
pub(crate) fn subdivide_into<P: Point, const N: usize>(
    curve: &Bezier<P, N>,
    level: u32,
    out: &mut [P],
    at: &mut usize,
) {
    if level == 0 {
        if let Some(o) = out.get_mut(*at) {
            *o = curve.start();
        }
        *at += 1;
    } else {
        let (l, r) = curve.split_half();
        subdivide_into(&l, level - 1, out, at);
        subdivide_into(&r, level - 1, out, at);
    }
}

/// The sampler [`Bezier::sample`] and the smoothed curves use: [`DeCasteljau`] in floats
/// (exact endpoints, format-rounding error at any degree and count) and [`Subdivide`] in
/// `Q16` (no multiplications, dyadic `t`).
#[derive(Clone, Copy, Debug, Default)]
pub struct DefaultSampler;

impl<P: Point, const N: usize> Sampler<P, N> for DefaultSampler {
    fn sample(&self, curve: &Bezier<P, N>, out: &mut [P]) -> Result<usize, Error> {
        if P::Scalar::FIXED_POINT {
            Subdivide::default().sample(curve, out)
        } else {
            DeCasteljau.sample(curve, out)
        }
    }
}

impl<P: Point, const N: usize> Bezier<P, N> {
    /// Samples the curve into `out` with the format's default sampler ([`DefaultSampler`]) and
    /// returns the count written: `out.len()` in floats, the largest `2^k + 1 <= out.len()`
    /// in `Q16`.
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] when `out` holds fewer than 2 points.
    pub fn sample(&self, out: &mut [P]) -> Result<usize, Error> {
        DefaultSampler.sample(self, out)
    }
}
