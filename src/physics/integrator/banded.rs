//! The banded factor of [`DirectSprings`](super::DirectSprings): the free particles' matrix
//! `M + h² Σ k (ea − eb)(ea − eb)ᵀ`, its rows in an order that keeps their envelopes short,
//! factored once (`LDLᵀ`) and solved by a forward and a back substitution.

use crate::physics::shape::Shape;
use crate::{Point, Scalar};

/// The factor `LDLᵀ` of the free particles' banded matrix, band `b` ([`Shape::BAND`]).
///
/// Its rows are the free particles only, in the order of a breadth-first walk over the
/// springs, reversed (Cuthill–McKee's reverse), where that keeps every spring within the
/// band, or in their own order otherwise: on the boat scene's 8×8 sail, 42 rows of 378
/// entries, where the particles' own order holds 458 (and the earlier solver's 64 rows,
/// the held particles' included, held 521). Row `k` of `L` holds
/// `L[k][j]` at `j + b − k` for the columns `j` from `k − b` to `k − 1`; `entries[k]` counts
/// the columns of row `k`'s envelope, from its first spring to `k − 1` (the factor fills no
/// slot before it).
pub(super) struct Factor<S: Scalar, Sh: Shape> {
    low: Sh::PerParticle<Sh::Band<S>>,
    /// The diagonal's inverses.
    inv_d: Sh::PerParticle<S>,
    entries: Sh::PerParticle<u16>,
    /// The particle of each row.
    order: Sh::PerParticle<u32>,
    rows: usize,
}

impl<S: Scalar, Sh: Shape> Clone for Factor<S, Sh> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S: Scalar, Sh: Shape> Copy for Factor<S, Sh> {}

impl<S: Scalar, Sh: Shape> Default for Factor<S, Sh> {
    /// No rows.
    fn default() -> Self {
        Factor {
            low: Sh::filled(Sh::band(S::ZERO)),
            inv_d: Sh::filled(S::ZERO),
            entries: Sh::filled(0),
            order: Sh::filled(0),
            rows: 0,
        }
    }
}

/// The springs a [`Factor`] is built from, each as `(a, b, h² k)`.
pub(super) trait Springs<S> {
    /// Calls `f` for every spring, in a fixed order.
    fn each(&self, f: impl FnMut(usize, usize, S));
}

/// How far apart two rows of a spring may be: the band, within a row's 16-bit count.
fn reach<Sh: Shape>() -> usize {
    Sh::BAND.min(usize::from(u16::MAX))
}

impl<S: Scalar, Sh: Shape> Factor<S, Sh> {
    /// Builds and factors the matrix of the particles `free` says are free: `mass` on the
    /// diagonal (particle by particle), and each spring that `springs` lists as `(a, b, h² k)`
    /// (`a ≠ b`, `h² k > 0`, both below the particle count, as a
    /// [`Topology`](crate::physics::spring::Topology)'s are). A spring puts its weight on its
    /// free ends' diagonals; it joins them in the band when both are free and at most
    /// [`Shape::BAND`] (and 65 535) apart in the particles' order: any other spring is on the
    /// diagonals only (a block-Jacobi split: converged iterations reach the same positions).
    /// Cost: two passes over the springs (three when the walk's order does not fit), a walk
    /// of `n·2b` steps and the factor, about `rows·e²/2` multiply-adds for `e` entries a row.
    pub(super) fn build(
        &mut self,
        free: impl Fn(usize) -> bool,
        mass: &[S],
        springs: &impl Springs<S>,
    ) {
        let (zero, band) = (S::ZERO, Sh::BAND);
        let reach = reach::<Sh>();
        let low = Sh::flat_mut(&mut self.low);
        let n = mass.len();
        let joined = |a: usize, b: usize| a.abs_diff(b) <= reach && free(a) && free(b);
        // The matrix in the particles' order first: its band says who is joined to whom.
        let mut diag = Sh::filled(zero);
        let d = Sh::flat_mut(&mut diag);
        d.iter_mut().zip(mass).for_each(|(d, &m)| *d = m);
        low.fill(Sh::band(zero));
        springs.each(|a, b, k| {
            for end in [a, b] {
                if free(end) {
                    d[end] += k;
                }
            }
            if joined(a, b) {
                let (i, j) = (a.max(b), a.min(b));
                Sh::band_mut(&mut low[i])[j + band - i] -= k;
            }
        });
        // The walk: from the first free particle of each group of joined ones, every
        // particle joined to the one taken, in the particles' order; then reversed.
        let order = Sh::flat_mut(&mut self.order);
        let mut place = Sh::filled(u32::MAX);
        let place = Sh::flat_mut(&mut place);
        let mut rows = 0;
        for start in 0..n {
            if !free(start) || place[start] != u32::MAX {
                continue;
            }
            (place[start], order[rows]) = (rows as u32, start as u32);
            rows += 1;
            let mut next = rows - 1;
            while next < rows {
                let p = order[next] as usize;
                next += 1;
                let below = p.saturating_sub(band)..p;
                let below = below.filter(|&q| Sh::band_flat(&low[p])[q + band - p] != zero);
                let above = p + 1..n.min(p + band + 1);
                let above = above.filter(|&q| Sh::band_flat(&low[q])[p + band - q] != zero);
                for q in below.chain(above) {
                    if place[q] == u32::MAX {
                        (place[q], order[rows]) = (rows as u32, q as u32);
                        rows += 1;
                    }
                }
            }
        }
        order[..rows].reverse();
        for (k, &p) in order[..rows].iter().enumerate() {
            place[p as usize] = k as u32;
        }
        // The matrix again, in the rows' order; in the particles' own if the walk put a
        // spring farther apart than the band.
        let entries = Sh::flat_mut(&mut self.entries);
        for walked in [true, false] {
            if !walked {
                rows = 0;
                for p in (0..n).filter(|&p| free(p)) {
                    (place[p], order[rows]) = (rows as u32, p as u32);
                    rows += 1;
                }
            }
            low.fill(Sh::band(zero));
            entries.fill(0);
            let mut fits = true;
            springs.each(|a, b, k| {
                if fits && joined(a, b) {
                    let (pa, pb) = (place[a] as usize, place[b] as usize);
                    let (i, j) = (pa.max(pb), pa.min(pb));
                    fits = i - j <= reach;
                    if fits {
                        Sh::band_mut(&mut low[i])[j + band - i] -= k;
                        entries[i] = entries[i].max((i - j) as u16);
                    }
                }
            });
            if fits {
                break;
            }
        }
        let mut ordered = Sh::filled(zero);
        let ordered_diag = Sh::flat_mut(&mut ordered);
        for (o, &p) in ordered_diag.iter_mut().zip(&order[..rows]) {
            *o = d[p as usize];
        }
        self.rows = rows;
        self.factor(ordered_diag);
    }

    /// Factors in place the rows' matrix whose diagonal is `diag` and whose band is
    /// already in `low`, within the envelopes in `entries`. A pivot that rounding left at
    /// or below zero (`Q16` with tiny masses) is replaced by its row's diagonal.
    fn factor(&mut self, diag: &[S]) {
        let zero = S::ZERO;
        let band = Sh::BAND;
        let low = Sh::flat_mut(&mut self.low);
        let inv_d = Sh::flat_mut(&mut self.inv_d);
        let entries = Sh::flat(&self.entries);
        // Row `j`'s first column.
        let first = |j: usize| j - usize::from(entries[j]).min(band).min(j);
        for i in 0..self.rows.min(diag.len()) {
            let start = first(i);
            // `L_ij · D_j` (the sum before the division), in row i's layout.
            let mut scaled = Sh::band(zero);
            let mut row = low[i];
            let mut pivot = diag[i];
            {
                let (row, scaled) = (Sh::band_mut(&mut row), Sh::band_mut(&mut scaled));
                for j in start..i {
                    let at = j + band - i;
                    // `Σ L_im D_m L_jm` over the columns `m` both rows reach, up to `j − 1`.
                    let from = start.max(first(j));
                    let earlier = &Sh::band_flat(&low[j])[from + band - j..];
                    let dot = dot(&scaled[from + band - i..at], earlier);
                    let s = row[at] - dot;
                    let l = s * inv_d[j];
                    scaled[at] = s;
                    row[at] = l;
                    pivot -= l * s;
                }
            }
            low[i] = row;
            if pivot <= zero {
                pivot = diag[i];
            }
            inv_d[i] = if pivot > zero { S::ONE / pivot } else { zero };
        }
    }

    /// The particle of each row, in the rows' order.
    pub(super) fn particles(&self) -> &[u32] {
        &Sh::flat(&self.order)[..self.rows]
    }

    /// The entries of every row's envelope.
    #[cfg(test)]
    pub(super) fn entry_count(&self) -> usize {
        let entries = Sh::flat(&self.entries).iter().take(self.rows);
        entries.map(|&e| usize::from(e)).sum()
    }

    /// Solves `LDLᵀ y = r`, `r` the particles' right-hand sides taken in the rows' order,
    /// each row over its envelope only; returns `y`, a row a free particle (the
    /// [`particles`](Self::particles)' order), in the front of `out`.
    #[inline(never)]
    pub(super) fn solve<'a, P: Point<Scalar = S>>(&self, r: &[P], out: &'a mut [P]) -> &'a [P] {
        let band = Sh::BAND;
        let rows = self.rows.min(out.len());
        let y = &mut out[..rows];
        let low = Sh::flat(&self.low);
        let inv_d = Sh::flat(&self.inv_d);
        let (entries, order) = (Sh::flat(&self.entries), Sh::flat(&self.order));
        // Forward, from the right-hand side of each row's particle. Row `i`'s `count`
        // entries four at a time after the first `count % 4`: the rows' lengths vary, and a
        // loop of one product at a time is mostly its own overhead.
        for i in 0..rows {
            let (before, rest) = y.split_at_mut(i);
            let (Some(row), Some(&count), Some(&p), Some(yi)) =
                (low.get(i), entries.get(i), order.get(i), rest.first_mut())
            else {
                continue;
            };
            let count = usize::from(count);
            let mut sum = r.get(p as usize).copied().unwrap_or_default();
            if let (Some(ls), Some(ys)) = (
                Sh::band_flat(row).get(band.wrapping_sub(count)..),
                before.get(i.wrapping_sub(count)..),
            ) {
                let ((y1, ys), (l1, ls)) = (ys.as_rchunks::<4>(), ls.as_rchunks::<4>());
                for (&y, &l) in y1.iter().zip(l1) {
                    sum -= y * l;
                }
                for (y, l) in ys.iter().zip(ls) {
                    sum = sum - y[0] * l[0] - y[1] * l[1] - y[2] * l[2] - y[3] * l[3];
                }
            }
            *yi = sum;
        }
        for (y, &inv) in y.iter_mut().zip(inv_d) {
            *y = *y * inv;
        }
        for i in (0..rows).rev() {
            let (Some(row), Some(&count)) = (low.get(i), entries.get(i)) else {
                continue;
            };
            let count = usize::from(count);
            let (before, rest) = y.split_at_mut(i);
            let (Some(ls), Some(ys), Some(&yi)) = (
                Sh::band_flat(row).get(band.wrapping_sub(count)..),
                before.get_mut(i.wrapping_sub(count)..),
                rest.first(),
            ) else {
                continue;
            };
            let ((y1, ys), (l1, ls)) = (ys.as_rchunks_mut::<4>(), ls.as_rchunks::<4>());
            for (y, &l) in y1.iter_mut().zip(l1) {
                *y -= yi * l;
            }
            for (y, l) in ys.iter_mut().zip(ls) {
                for (y, &l) in y.iter_mut().zip(l) {
                    *y -= yi * l;
                }
            }
        }
        y
    }
}

/// `Σ a_i b_i` over the shorter of the two, four products at a time (the factor's inner
/// loop: about half its cost is loop overhead when summed one at a time).
#[inline]
fn dot<S: Scalar>(a: &[S], b: &[S]) -> S {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let (mut sums, mut chunks_b) = ([S::ZERO; 4], b.chunks_exact(4));
    let mut chunks_a = a.chunks_exact(4);
    for (a, b) in (&mut chunks_a).zip(&mut chunks_b) {
        for k in 0..4 {
            sums[k] += a[k] * b[k];
        }
    }
    let tail = chunks_a
        .remainder()
        .iter()
        .zip(chunks_b.remainder())
        .fold(S::ZERO, |sum, (&a, &b)| sum + a * b);
    (sums[0] + sums[1]) + (sums[2] + sums[3]) + tail
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;
    use crate::physics::shape::Grid;

    /// Springs listed as `(a, b, h² k)`, one from a particle to itself left out.
    struct List<'a>(&'a [(usize, usize, f64)]);

    impl Springs<f64> for List<'_> {
        fn each(&self, mut f: impl FnMut(usize, usize, f64)) {
            for &(a, b, k) in self.0.iter().filter(|s| s.0 != s.1) {
                f(a, b, k);
            }
        }
    }

    /// A 5×4 grid's springs at random, within the band (10) and beyond it, a third of the
    /// particles held: the rows' factor solves the free particles' system exactly (the
    /// springs beyond the band on the diagonals only), every free particle once.
    #[test]
    fn the_rows_solve_the_free_particles() {
        type Sh = Grid<5, 4>;
        const N: usize = 20;
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut walked = 0;
        for _ in 0..200 {
            let free: [bool; N] = core::array::from_fn(|_| next() > 0.33);
            let mass: [f64; N] = core::array::from_fn(|_| 0.5 + next());
            let springs: [(usize, usize, f64); 30] = core::array::from_fn(|_| {
                let i = (next() * N as f64) as usize;
                let j = i.saturating_sub(1 + (next() * 1.5 * Sh::BAND as f64) as usize);
                (i, j, 10.0 * next())
            });
            let list = List(&springs);
            let mut dense = [[0.0f64; N]; N];
            for i in 0..N {
                dense[i][i] = mass[i];
            }
            list.each(|a, b, k| {
                for (p, q) in [(a, b), (b, a)] {
                    if free[p] {
                        dense[p][p] += k;
                        if free[q] && a.abs_diff(b) <= Sh::BAND {
                            dense[p][q] -= k;
                        }
                    }
                }
            });
            let mut factor = Factor::<f64, Sh>::default();
            factor.build(|i| free[i], &mass, &list);
            let particles = factor.particles();
            let mut seen = [false; N];
            for &p in particles {
                assert!(free[p as usize] && !seen[p as usize], "particle {p}");
                seen[p as usize] = true;
            }
            assert_eq!(seen, free);
            walked += usize::from(!particles.is_sorted());
            let rhs: [Vec2<f64>; N] = core::array::from_fn(|_| Vec2::new(next() - 0.5, next()));
            let mut out = [Vec2::default(); N];
            let y = factor.solve(&rhs, &mut out);
            let mut x = [Vec2::default(); N];
            for (&p, &y) in particles.iter().zip(y) {
                x[p as usize] = y;
            }
            for i in (0..N).filter(|&i| free[i]) {
                let mut sum = Vec2::default();
                for j in (0..N).filter(|&j| free[j]) {
                    sum += x[j] * dense[i][j];
                }
                let miss = (sum - rhs[i]).length();
                assert!(miss < 1e-12, "row {i}: off by {miss:e}");
            }
        }
        // The walk's order, not the particles' own, in most builds.
        assert!(walked > 100, "{walked} of 200");
    }
}
