//! The natural cubic spline through a row or ring of points: the B-spline control points
//! whose curve passes through them, by a tridiagonal (or cyclic) solve kept within the points'
//! differences so that fixed point stays in range.

use crate::{Point, Scalar};
use core::ops::{Add, Mul, Sub};

/// Turns a row (or, `closed`, a ring) of particles into the B-spline control points whose
/// curve passes through every particle: `c = p + e`, with `e[i-1] + 4·e[i] + e[i+1]` the
/// negated second difference of the particles (0 at open ends). Solving for the offset keeps
/// every intermediate within the particles' differences (fixed point stays in range).
pub(crate) fn natural_controls<P: Point, const K: usize>(points: &mut [P; K], closed: bool) {
    if !closed {
        return natural_open(points, K);
    }
    let mut offset = curvature(points, closed);
    for e in &mut offset {
        *e = -*e;
    }
    solve_tridiagonal(&mut offset, closed);
    for (p, e) in points.iter_mut().zip(offset) {
        *p += e;
    }
}

/// [`natural_controls`] of the first `n ≤ K` particles of an open row (the rest untouched).
pub(crate) fn natural_open<P: Point, const K: usize>(points: &mut [P; K], n: usize) {
    let n = n.min(K);
    let mut offset = [P::default(); K];
    for i in 1..n.saturating_sub(1) {
        offset[i] = (points[i] - points[i - 1]) - (points[i + 1] - points[i]);
    }
    solve_open(&mut offset, n);
    for (p, e) in points[..n].iter_mut().zip(offset) {
        *p += e;
    }
}

/// The particle weights of a natural spline from the B-spline weights `w` of its control
/// points (see [`natural_controls`]): the transpose of that map, `w - Δ²(A⁻¹·w)`, since the
/// tridiagonal `A` and the second difference `Δ²` are both symmetric. An open curve through
/// the first `n` particles has `w` zero past them, and so has the result.
pub(crate) fn natural_weights<S: Scalar, const K: usize>(w: &mut [S; K], closed: bool, n: usize) {
    let mut y = *w;
    if closed {
        solve_tridiagonal(&mut y, true);
    } else {
        (y[0], y[n - 1]) = (S::ZERO, S::ZERO);
        solve_open::<S, S, K>(&mut y, n);
    }
    for (w, d) in w.iter_mut().zip(curvature(&y, closed)) {
        *w -= d;
    }
}

/// The second differences `v[i-1] - 2·v[i] + v[i+1]`, wrapping when `closed`, else with
/// `v[-1] = v[K] = 0`.
fn curvature<T, const K: usize>(v: &[T; K], closed: bool) -> [T; K]
where
    T: Copy + Default + Add<Output = T> + Sub<Output = T>,
{
    core::array::from_fn(|i| {
        let (prev, next) = if closed {
            (v[(i + K - 1) % K], v[(i + 1) % K])
        } else {
            let prev = if i > 0 { v[i - 1] } else { T::default() };
            (prev, v.get(i + 1).copied().unwrap_or_default())
        };
        (prev - v[i]) + (next - v[i])
    })
}

/// Solves `x[i-1] + 4·x[i] + x[i+1] = r[i]` in place: over the inner entries with
/// `x[0] = x[K-1] = 0` for an open row (Thomas' algorithm, `O(K)`), or wrapping round a ring
/// (its inverse is the circulant `g(d) = (ρ^d + ρ^(K-d)) / (2√3·(1 - ρ^K))`, `ρ = √3 - 2`;
/// `O(K²)`). The system is diagonally dominant: `|x| ≤ |r| / 2`.
fn solve_tridiagonal<T, S: Scalar, const K: usize>(r: &mut [T; K], closed: bool)
where
    T: Copy + Default + Add<Output = T> + Sub<Output = T> + Mul<S, Output = T>,
{
    if closed {
        let rho = S::from_i16(3).sqrt() - S::from_i16(2);
        let mut power = [S::ONE; K]; // ρ^d
        for d in 1..K {
            power[d] = power[d - 1] * rho;
        }
        let wrap = power[K - 1] * rho; // ρ^K
        let scale = S::ONE / ((S::ONE - wrap) * S::from_i16(12).sqrt());
        let g = |d: usize| (power[d] + if d == 0 { wrap } else { power[K - d] }) * scale;
        let rhs = *r;
        for (i, x) in r.iter_mut().enumerate() {
            *x = rhs
                .iter()
                .enumerate()
                .fold(T::default(), |acc, (j, &rj)| acc + rj * g((i + K - j) % K));
        }
        return;
    }
    solve_open::<T, S, K>(r, K);
}

/// The open case of [`solve_tridiagonal`] over the first `n ≤ K` entries (Thomas'
/// algorithm, `x[0] = x[n-1] = 0`); later entries are left alone.
fn solve_open<T, S: Scalar, const K: usize>(r: &mut [T; K], n: usize)
where
    T: Copy + Default + Add<Output = T> + Sub<Output = T> + Mul<S, Output = T>,
{
    let n = n.min(K);
    if n < 3 {
        for x in &mut r[..n] {
            *x = T::default();
        }
        return;
    }
    // Forward: gamma[i] = 1 / (4 - gamma[i-1]), r[i] = (r[i] - r[i-1]) · gamma[i].
    let mut gamma = [S::ZERO; K];
    r[0] = T::default();
    for i in 1..n - 1 {
        gamma[i] = S::ONE / (S::from_i16(4) - gamma[i - 1]);
        r[i] = (r[i] - r[i - 1]) * gamma[i];
    }
    // Back: x[i] = r[i] - gamma[i] · x[i+1].
    r[n - 1] = T::default();
    for i in (1..n - 1).rev() {
        r[i] = r[i] - r[i + 1] * gamma[i];
    }
}
