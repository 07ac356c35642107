//! The spline rope's matrices: the B-spline basis at any arc length, the consistent mass
//! matrix and its banded factor, the curvature band, and the fits between control points and
//! samples.

use super::*;

/// The Greville abscissa of control point `i` in span units times the span (`0..=K-3`):
/// where a straight line puts its control point.
pub(super) fn greville(i: usize, k: usize) -> f64 {
    let knot = |j: usize| (j.saturating_sub(3) as f64).min((k - 3) as f64);
    (knot(i + 1) + knot(i + 2) + knot(i + 3)) / 3.0
}

/// The clamped uniform cubic basis at `u ∈ [0, K-3]` (in spans): the four non-zero values
/// (control points `span..span+4`) and their derivatives by `u`.
pub(super) fn basis(u: f64, k: usize) -> ([f64; 4], [f64; 4]) {
    let u = u.clamp(0.0, (k - 3) as f64);
    let (n, dn, _) = basis_in((u as usize).min(k - 4), u, k);
    (n, dn)
}

/// [`basis`] on span `span` (`u` may be its right end), with the clamped quadratic basis on
/// the same breaks (`K - 1` functions; the span's are `span..span+3`).
pub(super) fn basis_in(span: usize, u: f64, k: usize) -> ([f64; 4], [f64; 4], [f64; 3]) {
    let spans = k - 3;
    // Knot j of the clamped vector 0,0,0,0,1,..,spans-1,spans,spans,spans,spans.
    let t = |j: isize| (j - 3).clamp(0, spans as isize) as f64;
    let i = span as isize + 3;
    let mut n = [0.0f64; 4];
    n[0] = 1.0;
    let (mut left, mut right) = ([0.0f64; 4], [0.0f64; 4]);
    let mut n2 = [0.0f64; 3];
    for j in 1..=3usize {
        left[j] = u - t(i + 1 - j as isize);
        right[j] = t(i + j as isize) - u;
        let mut saved = 0.0;
        for r in 0..j {
            let den = right[r + 1] + left[j - r];
            let temp = if den != 0.0 { n[r] / den } else { 0.0 };
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
        if j == 2 {
            n2 = [n[0], n[1], n[2]];
        }
    }
    // N'_(i-3+a),3 = 3·(N_(i-3+a),2 / (t_(i+a) - t_(i-3+a)) - N_(i-2+a),2 / (t_(i+1+a) - t_(i-2+a))).
    let deg2 = |a: isize| -> f64 {
        // N_(i-2+a'),2 is n2[a'] for a' in 0..3, zero outside.
        if (0..3).contains(&a) {
            n2[a as usize]
        } else {
            0.0
        }
    };
    let mut dn = [0.0; 4];
    for (a, d) in dn.iter_mut().enumerate() {
        let a = a as isize;
        let first = i - 3 + a;
        let den1 = t(first + 3) - t(first);
        let den2 = t(first + 4) - t(first + 1);
        let x1 = if den1 > 0.0 { deg2(a - 1) / den1 } else { 0.0 };
        let x2 = if den2 > 0.0 { deg2(a) / den2 } else { 0.0 };
        *d = 3.0 * (x1 - x2);
    }
    (n, dn, n2)
}

/// An `f64` that multiplies by a format's numbers read in `f64`: the substep bound's
/// arithmetic on the tables the steps use, without an `f64` copy of them.
#[derive(Clone, Copy, Default, PartialEq)]
pub(super) struct Wide(pub(super) f64);

impl<S: Scalar> Mul<S> for Wide {
    type Output = Wide;
    fn mul(self, s: S) -> Wide {
        Wide(self.0 * s.to_f64())
    }
}

impl Sub for Wide {
    type Output = Wide;
    fn sub(self, other: Wide) -> Wide {
        Wide(self.0 - other.0)
    }
}

impl core::ops::AddAssign for Wide {
    fn add_assign(&mut self, other: Wide) {
        self.0 += other.0;
    }
}

/// The control points' differences `x_(i+1) − x_i` (the last entry 0): the cubic's slope
/// is a quadratic spline on them (see [`slope_at`]).
pub(super) fn differences<T, const K: usize>(x: &[T; K]) -> [T; K]
where
    T: Copy + Default + Sub<Output = T>,
{
    core::array::from_fn(|i| {
        if i + 1 < K {
            x[i + 1] - x[i]
        } else {
            T::default()
        }
    })
}

/// The slope `x'` at a stretch point of span `e` with slope weights `d`, from the
/// [`differences`] `dx`: `Σ_a d_a·dx_(e+a)` (3 products where the 4 basis slopes would
/// take 4).
#[inline]
pub(super) fn slope_at<T, S: Copy, const K: usize>(d: &[S; 3], dx: &[T; K], e: usize) -> T
where
    T: Copy + Default + core::ops::AddAssign + Mul<S, Output = T>,
{
    let mut out = T::default();
    for (a, &da) in d.iter().enumerate() {
        out += dx[e + a] * da;
    }
    out
}

/// Adds to `pull` what `g` at a stretch point of span `e` does to the [`differences`]
/// through the weights `d` (the transpose of [`slope_at`]; a tension's pull takes the
/// point's pull weights); [`spread`] takes them to the control points.
#[inline]
pub(super) fn add_pull<T, S: Copy, const K: usize>(pull: &mut [T; K], d: &[S; 3], e: usize, g: T)
where
    T: Copy + core::ops::AddAssign + Mul<S, Output = T>,
{
    for (a, &da) in d.iter().enumerate() {
        pull[e + a] += g * da;
    }
}

/// Adds to `out` the generalized forces of `pull`, forces on the [`differences`]:
/// `out_i += pull_(i−1) − pull_i` (the transpose of [`differences`]).
pub(super) fn spread<T, const K: usize>(out: &mut [T; K], pull: &[T; K])
where
    T: Copy + core::ops::AddAssign + core::ops::SubAssign,
{
    for i in 0..K - 1 {
        out[i] -= pull[i];
        out[i + 1] += pull[i];
    }
}

/// The least-squares fit of `field` (values at the stretch points) among the quadratic
/// splines on the rope's breaks (tables from [`SplineRope::new`]): their `K − 1`
/// coefficients (entry `K − 1` is 0). With `sparse`, the field's zeros are skipped: worth a
/// test per value where most are 0.
pub(super) fn fit<T, S: Copy, const K: usize>(
    proj: &[[[S; 3]; POINTS]; K],
    weights: &[S; POINTS],
    gram: &[[S; 3]; K],
    field: &[[T; POINTS]; K],
    sparse: bool,
) -> [T; K]
where
    T: Copy + Default + PartialEq + core::ops::AddAssign + Sub<Output = T> + Mul<S, Output = T>,
{
    let mut c = [T::default(); K];
    for e in 0..K - 3 {
        for q in 0..POINTS {
            if sparse && field[e][q] == T::default() {
                continue;
            }
            let weighted = field[e][q] * weights[q];
            for a in 0..3 {
                c[e + a] += weighted * proj[e][q][a];
            }
        }
    }
    solve(gram, &mut c);
    c
}

/// The values at the stretch points of the quadratic spline of coefficients `c`.
pub(super) fn evaluate<T, S: Copy, const K: usize>(
    proj: &[[[S; 3]; POINTS]; K],
    c: &[T; K],
) -> [[T; POINTS]; K]
where
    T: Copy + Default + core::ops::AddAssign + Mul<S, Output = T>,
{
    let mut field = [[T::default(); POINTS]; K];
    for e in 0..K - 3 {
        for q in 0..POINTS {
            for a in 0..3 {
                field[e][q] += c[e + a] * proj[e][q][a];
            }
        }
    }
    field
}

/// Replaces `field` (values at the stretch points) by its least-squares fit among the
/// quadratic splines ([`fit`], then [`evaluate`]).
pub(super) fn project<T, S: Copy, const K: usize>(
    proj: &[[[S; 3]; POINTS]; K],
    weights: &[S; POINTS],
    gram: &[[S; 3]; K],
    field: &mut [[T; POINTS]; K],
) where
    T: Copy + Default + PartialEq + core::ops::AddAssign + Sub<Output = T> + Mul<S, Output = T>,
{
    *field = evaluate(proj, &fit(proj, weights, gram, field, false));
}

/// The consistent mass matrix of a rope of density `rho` on spans of `ds`, `∫ ρ N_i N_j ds`
/// in band form (`band[i][d] = M[i][i+d]`), and its row sums `∫ ρ N_i ds` (4-point Gauss per
/// span: exact).
pub(super) fn mass_matrix<const K: usize>(rho: f64, ds: f64) -> ([[f64; 4]; K], [f64; K]) {
    let (mut band, mut load) = ([[0.0; 4]; K], [0.0; K]);
    for e in 0..K - 3 {
        for &(xi, w) in &GAUSS {
            let (n, _, _) = basis_in(e, e as f64 + (xi + 1.0) / 2.0, K);
            let wds = w * ds / 2.0;
            for a in 0..4 {
                load[e + a] += rho * n[a] * wds;
                for b in a..4 {
                    band[e + a][b - a] += rho * n[a] * n[b] * wds;
                }
            }
        }
    }
    (band, load)
}

/// The Bézier extraction of span `e`: row `r` holds the weights of control points
/// `e..e+4` in the span's Bézier point `r` (from the basis at 4 points of the span and the
/// inverse Bernstein matrix at `t = 0, 1/3, 2/3, 1`).
pub(super) fn extraction(e: usize, k: usize) -> [[f64; 4]; 4] {
    // Inverse of B[m][r] = C(3,r) t_m^r (1-t_m)^(3-r) at t = 0, 1/3, 2/3, 1.
    const INV: [[f64; 4]; 4] = [
        [1.0, 0.0, 0.0, 0.0],
        [-5.0 / 6.0, 3.0, -3.0 / 2.0, 1.0 / 3.0],
        [1.0 / 3.0, -3.0 / 2.0, 3.0, -5.0 / 6.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let values: [[f64; 4]; 4] =
        core::array::from_fn(|m| basis_in(e, e as f64 + m as f64 / 3.0, k).0);
    core::array::from_fn(|r| {
        core::array::from_fn(|c| (0..4).map(|m| INV[r][m] * values[m][c]).sum())
    })
}

/// `A·u` for a symmetric `band` (`band[i][d] = A[i][i+d]`).
pub(super) fn band_times<T, S: Copy, const K: usize, const W: usize>(
    band: &[[S; W]; K],
    u: &[T; K],
) -> [T; K]
where
    T: Copy + Default + core::ops::AddAssign + Mul<S, Output = T>,
{
    let mut out = [T::default(); K];
    for i in 0..K {
        for d in 0..W {
            let j = i + d;
            if j < K {
                let a = band[i][d];
                out[i] += u[j] * a;
                if d > 0 {
                    out[j] += u[i] * a;
                }
            }
        }
    }
    out
}

/// The bending band per unit `EI`: `∫ N_i'' N_j'' ds` (`band[i][d]` for `j = i + d`), from
/// each span's Bézier extraction (`x'' = 6·((1−t)·Δ²b_0 + t·Δ²b_1) / ds²`), by 4-point
/// Gauss (exact: the integrand is quadratic).
pub(super) fn curvature_band<const K: usize>(ds: f64) -> [[f64; 4]; K] {
    let mut band = [[0.0; 4]; K];
    for e in 0..K - 3 {
        let ext = extraction(e, K);
        let second = |r: usize, k: usize| ext[r][k] - 2.0 * ext[r + 1][k] + ext[r + 2][k];
        for &(xi, w) in &GAUSS {
            let t = (xi + 1.0) / 2.0;
            let n: [f64; 4] = core::array::from_fn(|k| {
                6.0 * ((1.0 - t) * second(0, k) + t * second(1, k)) / (ds * ds)
            });
            for a in 0..4 {
                for b in a..4 {
                    band[e + a][b - a] += n[a] * n[b] * w * ds / 2.0;
                }
            }
        }
    }
    band
}

/// Banded `L D Lᵀ` (square-root-free Cholesky) of a symmetric positive-definite `band` of
/// `W` diagonals (`band[i][d] = A[i][i+d]`): the unit lower factor's `L[i][i-d]` in
/// `out[i][d]`, and `1 / D[i]` from `inverse` in `out[i][0]`; `None` when it is not
/// positive definite (or rounding makes it seem not) or `inverse` finds no `1 / D[i]` in
/// the format.
pub(super) fn ldl<S, const K: usize, const W: usize>(
    band: &[[S; W]; K],
    inverse: impl Fn(S) -> Option<S>,
) -> Option<[[S; W]; K]>
where
    S: Copy + Default + PartialOrd + Sub<Output = S> + Mul<Output = S>,
{
    let zero = S::default();
    let mut l = [[zero; W]; K];
    // `L[i][j]·D[j]` for the row being factored, by `d = i − j`.
    let mut scaled = [zero; W];
    for i in 0..K {
        for d in (1..W).rev() {
            if d > i {
                continue;
            }
            let j = i - d;
            // `A[i][j] − Σ over m < j of L[i][m]·D[m]·L[j][m]`, within the band.
            let mut sum = band[j][d];
            for k in 1..W - d {
                if k <= j {
                    sum = sum - scaled[d + k] * l[j][k];
                }
            }
            scaled[d] = sum;
            l[i][d] = sum * l[j][0];
        }
        let mut pivot = band[i][0];
        for d in 1..W {
            if d <= i {
                pivot = pivot - scaled[d] * l[i][d];
            }
        }
        if pivot.partial_cmp(&zero) != Some(core::cmp::Ordering::Greater) {
            return None;
        }
        l[i][0] = inverse(pivot)?;
    }
    Some(l)
}

/// Cholesky of a dense symmetric matrix in place: `L` in the lower triangle, its diagonal
/// inverted; `false` when a pivot is not positive (not positive definite, or rounding).
pub(super) fn dense_cholesky<S: Scalar, const K: usize>(a: &mut [[S; K]; K]) -> bool {
    for j in 0..K {
        let mut d = a[j][j];
        for k in 0..j {
            d -= a[j][k] * a[j][k];
        }
        if d.partial_cmp(&S::ZERO) != Some(core::cmp::Ordering::Greater) || !d.is_finite() {
            return false;
        }
        let inv = S::ONE / d.sqrt();
        a[j][j] = inv;
        for i in j + 1..K {
            let mut v = a[i][j];
            for k in 0..j {
                v -= a[i][k] * a[j][k];
            }
            a[i][j] = v * inv;
        }
    }
    true
}

/// Solves `L Lᵀ x = b` in place, `L` from [`dense_cholesky`].
pub(super) fn dense_solve<S: Scalar, const K: usize>(l: &[[S; K]; K], b: &mut [S; K]) {
    for i in 0..K {
        let mut v = b[i];
        for k in 0..i {
            v -= l[i][k] * b[k];
        }
        b[i] = v * l[i][i];
    }
    for i in (0..K).rev() {
        let mut v = b[i];
        for k in i + 1..K {
            v -= l[k][i] * b[k];
        }
        b[i] = v * l[i][i];
    }
}

/// `1 / x` where it is finite (the construction's `f64`, which need not be a [`Scalar`]:
/// a `Q16`-only build has no float math).
pub(super) fn finite_inverse(x: f64) -> Option<f64> {
    Some(1.0 / x).filter(|i| i.is_finite())
}

/// Solves `L D Lᵀ x = b` in place, the factor from [`ldl`] in the format: `(2W − 1)·K`
/// multiplies.
pub(super) fn solve<T, S, const K: usize, const W: usize>(l: &[[S; W]; K], b: &mut [T; K])
where
    T: Copy + Sub<Output = T> + Mul<S, Output = T>,
    S: Copy,
{
    for i in 0..K {
        let mut s = b[i];
        for d in 1..W {
            if d <= i {
                s = s - b[i - d] * l[i][d];
            }
        }
        b[i] = s;
    }
    for i in (0..K).rev() {
        let mut s = b[i] * l[i][0];
        for d in 1..W {
            if i + d < K {
                s = s - b[i + d] * l[i + d][d];
            }
        }
        b[i] = s;
    }
}

/// The largest eigenvalue of `M⁻¹ K` on the free control points (`K` by its action
/// `stiffness`, `M` by its band `mass` and factor `chol`, pinned rows the identity's): the
/// largest Ritz value of at most `K` Lanczos steps in the `M` inner product, found by
/// bisection on the tridiagonal's Sturm counts. Exact in `K` steps but for rounding, and
/// never above the true value; `O(K)` memory, `K` stiffness products.
pub(super) fn largest_eigenvalue<const K: usize>(
    stiffness: impl Fn(&[f64; K]) -> [f64; K],
    mass: &[[f64; 4]; K],
    chol: &[[f64; 4]; K],
    pinned: &[bool; K],
) -> f64 {
    let free = |mut x: [f64; K]| {
        for (xi, &p) in x.iter_mut().zip(pinned) {
            if p {
                *xi = 0.0;
            }
        }
        x
    };
    let dot = |a: &[f64; K], b: &[f64; K]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let m_norm = |x: &[f64; K]| crate::geometry::catenary::sqrt(dot(x, &band_times(mass, x)));
    // Alternating signs lean on the highest mode; the ramp breaks the rope's symmetries.
    let mut q = free(core::array::from_fn(|i| {
        let ramp = 1.0 + i as f64 / K as f64;
        if i % 2 == 0 { ramp } else { -ramp }
    }));
    let norm = m_norm(&q);
    if norm.is_nan() || norm <= 0.0 {
        return 0.0;
    }
    q = q.map(|v| v / norm);
    let (mut alpha, mut beta) = ([0.0; K], [0.0; K]);
    let mut previous = [0.0; K];
    let mut steps = 0;
    for j in 0..K {
        let r = free(stiffness(&q));
        alpha[j] = dot(&q, &r);
        steps = j + 1;
        let mut w = r;
        solve(chol, &mut w);
        let w = free(core::array::from_fn(|i| {
            w[i] - alpha[j] * q[i]
                - if j > 0 {
                    beta[j - 1] * previous[i]
                } else {
                    0.0
                }
        }));
        let b = m_norm(&w);
        // A Krylov space closed (or rounding's floor): the Ritz values are exact.
        if b.is_nan() || b <= 1e-12 * alpha[j].abs() {
            break;
        }
        beta[j] = b;
        previous = q;
        q = w.map(|v| v / b);
    }
    // Past `f64` (an `EA` near its range): no bound, which the caller reports as too stiff.
    if alpha[..steps]
        .iter()
        .chain(&beta[..steps])
        .any(|v| !v.is_finite())
    {
        return f64::INFINITY;
    }
    // Bisection between the largest diagonal and Gershgorin's bound of the tridiagonal.
    let (mut low, mut high) = (f64::MIN, 0.0f64);
    for j in 0..steps {
        let side =
            if j > 0 { beta[j - 1] } else { 0.0 } + if j + 1 < steps { beta[j] } else { 0.0 };
        low = low.max(alpha[j]);
        high = high.max(alpha[j] + side);
    }
    // How many eigenvalues of the tridiagonal lie above `x` (its `LDLᵀ - x` pivots).
    let above = |x: f64| {
        let (mut d, mut count) = (1.0f64, 0);
        for j in 0..steps {
            let coupling = if j > 0 {
                beta[j - 1] * beta[j - 1] / d
            } else {
                0.0
            };
            d = alpha[j] - x - coupling;
            if d == 0.0 {
                d = f64::EPSILON * (x.abs() + 1.0);
            }
            if d > 0.0 {
                count += 1;
            }
        }
        count
    };
    for _ in 0..64 {
        let mid = 0.5 * (low + high);
        if mid <= low || mid >= high || mid.is_nan() {
            break;
        }
        if above(mid) > 0 {
            low = mid;
        } else {
            high = mid;
        }
    }
    high.max(0.0)
}
