//! The conjugate directions of a [`DirectSprings`](super::DirectSprings) solve's iterations
//! after the first (floats, more than one iteration), and how far to go along each.

use super::{Model, tiny_length};
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// The directions of a solve's iterations after the first (floats, more than one
/// iteration): nonlinear conjugate gradients preconditioned by the factor (Polak-Ribière,
/// started again where a direction would not lower the solve's objective), each taken as
/// far as the objective's second-order model along it says. The factor's own step turns a
/// stiff spring only by about `m / (h² k)` an iteration; a length along a conjugate
/// direction takes the slow motion it leaves whole.
pub(super) struct Conjugate<P: Point, Sh: Shape> {
    /// This iteration's direction, in the rows' order.
    pub(super) direction: Sh::PerParticle<P>,
    /// The last iteration's solve, in the rows' order.
    last: Sh::PerParticle<P>,
    /// This iteration's direction by particle (0 for a held one).
    spread: Sh::PerParticle<P>,
    /// The last iteration's residual times its solve (0 before the first).
    last_dot: P::Scalar,
}

impl<P: Point, Sh: Shape> Conjugate<P, Sh> {
    pub(super) fn new() -> Self {
        Conjugate {
            direction: Sh::filled(P::default()),
            last: Sh::filled(P::default()),
            spread: Sh::filled(P::default()),
            last_dot: P::Scalar::ZERO,
        }
    }

    /// Makes the next direction from the residual `r` at `x` (by particle) and its
    /// `solve` by the factor (in the order of `rows`), and returns how far to go along it:
    /// the residual along it over the objective's curvature along it (`M` and each
    /// spring's `h² k` along it, its tension's `h² k (1 − rest / l)` across it and its
    /// damping's `h c` along it), up to 64; 1 where that is not a positive number.
    pub(super) fn turn<T: Topology<P::Scalar>>(
        &mut self,
        model: &Model<'_, P, Sh, T>,
        (x, r): (&[P], &[P]),
        (solve, rows): (&[P], &[u32]),
        mass: &[P::Scalar],
        h: P::Scalar,
    ) -> P::Scalar {
        let zero = P::Scalar::ZERO;
        let (direction, last) = (
            Sh::flat_mut(&mut self.direction),
            Sh::flat_mut(&mut self.last),
        );
        let residual = |p: u32| r.get(p as usize).copied().unwrap_or_default();
        let (mut dot, mut across) = (zero, zero);
        for ((&p, &z), &last) in rows.iter().zip(solve).zip(last.iter()) {
            dot += residual(p).dot(z);
            across += residual(p).dot(last);
        }
        let beta = if self.last_dot > zero {
            ((dot - across) / self.last_dot).max(zero)
        } else {
            zero
        };
        self.last_dot = dot;
        let mut descent = zero;
        for (((&p, &z), d), last) in rows.iter().zip(solve).zip(direction.iter_mut()).zip(last) {
            *d = z + *d * beta;
            *last = z;
            descent += residual(p).dot(*d);
        }
        // Not downhill (or not finite): the solve's own direction.
        if descent.partial_cmp(&zero) != Some(core::cmp::Ordering::Greater) {
            for (d, &z) in direction.iter_mut().zip(solve) {
                *d = z;
            }
            descent = dot;
        }
        let spread = Sh::flat_mut(&mut self.spread);
        spread.fill(P::default());
        let mut curvature = zero;
        for (&p, &d) in rows.iter().zip(direction.iter()) {
            if let (Some(s), Some(&m)) = (spread.get_mut(p as usize), mass.get(p as usize)) {
                *s = d;
                curvature += m * d.dot(d);
            }
        }
        curvature += springs_curvature(model, x, spread, h);
        let length = (descent / curvature).min(P::Scalar::from_i16(64));
        if curvature > zero && length > zero && length.is_finite() {
            length
        } else {
            P::Scalar::ONE
        }
    }
}

/// `Σ h² k (u·Δ)² + h² k max(0, 1 − rest / l) (|Δ|² − (u·Δ)²) + h c (u·Δ)²` over the springs
/// with a free end, `u` a spring's direction at `x`, `l` its length and `Δ` the difference of
/// its ends' `d`: the springs' curvature of a solve's objective along `d`. A division a
/// spring and no square root: the tension's share is taken as `(l² − rest²) / (2 l²)`,
/// `1 − rest / l` to within half the spring's strain.
fn springs_curvature<P: Point, Sh: Shape, T: Topology<P::Scalar>>(
    model: &Model<'_, P, Sh, T>,
    x: &[P],
    d: &[P],
    h: P::Scalar,
) -> P::Scalar {
    let zero = P::Scalar::ZERO;
    let w = model.inv_mass();
    let n = x.len().min(d.len()).min(w.len());
    let tiny = tiny_length::<P::Scalar>();
    let mut sum = zero;
    model.topology.for_each_run(|a, b, count, rest, m| {
        if !(m.stiffness > zero && a.max(b).saturating_add(count) <= n) {
            return;
        }
        let k = m.stiffness * h * h;
        let c = m.damping * h;
        let (rest2, half) = (rest * rest, P::Scalar::ratio(1, 2));
        for i in 0..count {
            let wsum = w[a + i] + w[b + i];
            let span = x[a + i] - x[b + i];
            let l2 = span.dot(span);
            if wsum <= zero || l2 <= tiny * tiny {
                continue;
            }
            let inv = P::Scalar::ONE / l2;
            let change = d[a + i] - d[b + i];
            let projected = span.dot(change);
            let along = projected * projected * inv;
            let across = (change.dot(change) - along).max(zero);
            // The damping's clamp as in the solve: `h² c` at most `h / (wa + wb)` (a
            // division only where it bites).
            let damping = if c * wsum > P::Scalar::ONE {
                P::Scalar::ONE / wsum
            } else {
                c
            };
            let tension = ((l2 - rest2) * inv * half).max(zero);
            sum += (k + damping) * along + k * tension * across;
        }
    });
    sum
}
