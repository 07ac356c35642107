//! Backward Euler, linearised once per substep and solved by conjugate gradient.

use super::{Integrator, Model, Solved, State, sealed, tiny_length};
use crate::physics::force::ForceField;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// Backward Euler linearised once per substep (Baraff–Witkin) and solved by conjugate
/// gradient with at most `iterations` steps. Stable at any step; damps what it cannot
/// resolve. Cost per CG iteration: one spring Jacobian product (a square root per spring).
///
/// Each solve reports how far its conjugate gradient ended from the linearised equations
/// ([`StepInfo::residual`](crate::system::StepInfo::residual): a velocity's error is at most
/// its residual over its mass, times `h` a distance; converged within 0.1% of the shortest
/// spring): a 1 m, 1 kg rope of 30 particles released level converges every frame at
/// 100 N/m with 16 iterations; at `10⁴ N/m` in no frame with one iteration and in 1 of 300
/// with 16 (`tests/suite/converge.rs`). The measure is a pass over the particles.
///
/// Its one linearization does not follow a very stiff spring as it turns: a 1 m, 1 kg rope
/// of 8 particles released level at 60 Hz never rises above its starting energy up to
/// `k = 10⁶ N/m`, but at `10⁷` its energy rises for a while to 3 times what the fall
/// releases (at `10⁸`, 14 times) before the step's damping settles it (`tests/suite/physics.rs`).
/// A [`SplineRope`](crate::objects::spline_rope::SplineRope) solves its step fully instead (Newton's
/// method, `iterations` per Newton step) and, in `f32` and `f64`, never gains energy: for
/// stiff cables, see [`SplineStepper`](crate::objects::spline_rope::SplineStepper).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ImplicitEuler {
    /// Conjugate-gradient iteration budget (8 to 32 is typical).
    pub iterations: u8,
}

impl Default for ImplicitEuler {
    /// 16 iterations.
    fn default() -> Self {
        ImplicitEuler { iterations: 16 }
    }
}

/// The scale `s` a conjugate gradient solves `A·x = b` at (for `x / s`, from `b / s`): in
/// `Q16` the power of two that brings `b`'s largest coordinate into `[4, 8)` (from `2⁻¹²`
/// to `2¹⁴`), since its inner products (squares of momenta over masses) would saturate
/// the format when large and lose its resolution when small; 1 in floating point. A power
/// of two, so `s` and `1 / s` are exact.
pub(crate) fn solve_scale<P: Point>(b: &[P]) -> P::Scalar {
    let mut scale = P::Scalar::ONE;
    if !P::Scalar::FIXED_POINT {
        return scale;
    }
    let mut largest = P::Scalar::ZERO;
    for bi in b {
        for axis in 0..P::DIM {
            largest = largest.max(bi.coord(axis).abs());
        }
    }
    if largest == P::Scalar::ZERO {
        return scale;
    }
    let (two, half) = (P::Scalar::from_i16(2), P::Scalar::ratio(1, 2));
    let (top, bottom) = (P::Scalar::from_i16(8), P::Scalar::from_i16(4));
    for _ in 0..14 {
        if largest < top {
            break;
        }
        largest = largest * half;
        scale = scale * two;
    }
    for _ in 0..12 {
        if largest >= bottom {
            break;
        }
        largest = largest * two;
        scale = scale * half;
    }
    scale
}

fn dot_all<P: Point>(a: &[P], b: &[P]) -> P::Scalar {
    let mut s = P::Scalar::ZERO;
    for (x, y) in a.iter().zip(b) {
        s += x.dot(*y);
    }
    s
}

/// `out = J·p` for the springs' force Jacobian at positions `x`, scaled for backward Euler:
/// `J·p = h·c·(n·δ)n + h²·k·[(n·δ)n + s·(δ - (n·δ)n)]` with `δ = p_b - p_a` and
/// `s = max(0, 1 - rest/l)` (the compressive transverse term is dropped so the system stays
/// positive definite). Subtracted at `a`, added at `b`.
fn spring_jacobian_product<S: Scalar, P: Point<Scalar = S>>(
    topology: &impl Topology<S>,
    x: &[P],
    h: S,
    p: &[P],
    out: &mut [P],
    damping_too: bool,
) {
    let h2 = h * h;
    topology.for_each_spring(|a, b, rest, m| {
        let d = x[b] - x[a];
        let l = d.length();
        if l <= tiny_length::<S>() {
            return;
        }
        let n = d * (S::ONE / l);
        let s = (S::ONE - rest / l).max(S::ZERO);
        let delta = p[b] - p[a];
        let along = n * delta.dot(n);
        let mut j = (along + (delta - along) * s) * (h2 * m.stiffness);
        if damping_too {
            j += along * (h * m.damping);
        }
        out[a] -= j;
        out[b] += j;
    });
}

impl sealed::Sealed for ImplicitEuler {}

impl Integrator for ImplicitEuler {
    type Memory<S: Scalar, Sh: Shape> = ();

    fn memory<S: Scalar, Sh: Shape>() {}

    fn stability_limit<S: Scalar>(&self) -> Option<S> {
        None
    }
    fn force_evaluations(&self) -> u32 {
        1
    }
    fn substep<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool {
        self.substep_solved(model, state, h, forces).fits
    }

    /// One linearised backward Euler solve of `h` (`iterations` conjugate gradient steps),
    /// and how far it ended from its equations.
    fn substep_solved<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> Solved<P::Scalar> {
        let zero = P::default();
        let w = model.inv_mass();
        let x0 = Sh::flat(&state.pos);
        let mut mass = Sh::filled(P::Scalar::ZERO);
        for (m, &wi) in Sh::flat_mut(&mut mass).iter_mut().zip(w) {
            *m = if wi > P::Scalar::ZERO {
                P::Scalar::ONE / wi
            } else {
                P::Scalar::ZERO
            };
        }
        let mass = Sh::flat(&mass);
        let free = |i: usize| w[i] > P::Scalar::ZERO;
        let diag = P::Scalar::ONE + h * model.damping;

        // Right side b = h·M·a0 + h²·K·v0 (the spring part of K only; damping is in a0).
        let (mut r, ok) = model.accelerations_at(state, forces, true);
        for (i, ri) in Sh::flat_mut(&mut r).iter_mut().enumerate() {
            *ri = *ri * (h * mass[i]);
        }
        // K·v0 enters with the opposite sign of the system matrix's -h²K term.
        let mut kv = Sh::filled(zero);
        let topology = model.topology;
        spring_jacobian_product(
            topology,
            x0,
            h,
            Sh::flat(&state.vel),
            Sh::flat_mut(&mut kv),
            false,
        );
        for (i, (ri, kvi)) in Sh::flat_mut(&mut r)
            .iter_mut()
            .zip(Sh::flat(&kv))
            .enumerate()
        {
            *ri = if free(i) { *ri - *kvi } else { zero };
        }

        // Conjugate gradient on (M(1 + hγ) - hC - h²K) Δv = b, pinned rows filtered out, for
        // Δv / s (see `solve_scale`).
        let scale = solve_scale(Sh::flat(&r));
        let shrink = P::Scalar::ONE / scale;
        for ri in Sh::flat_mut(&mut r) {
            *ri = *ri * shrink;
        }
        let mut dv = Sh::filled(zero);
        let mut p = r;
        let mut ap = Sh::filled(zero);
        let mut rs = dot_all(Sh::flat(&r), Sh::flat(&r));
        for _ in 0..self.iterations {
            if rs <= P::Scalar::ZERO || !rs.is_finite() {
                break;
            }
            {
                let (pf, apf) = (Sh::flat(&p), Sh::flat_mut(&mut ap));
                for (i, q) in apf.iter_mut().enumerate() {
                    *q = pf[i] * (mass[i] * diag);
                }
                spring_jacobian_product(topology, x0, h, pf, apf, true);
                for (i, q) in apf.iter_mut().enumerate() {
                    if !free(i) {
                        *q = zero;
                    }
                }
            }
            let pap = dot_all(Sh::flat(&p), Sh::flat(&ap));
            if pap <= P::Scalar::ZERO || !pap.is_finite() {
                break;
            }
            let alpha = rs / pap;
            for ((d, r), (&pi, &api)) in Sh::flat_mut(&mut dv)
                .iter_mut()
                .zip(Sh::flat_mut(&mut r))
                .zip(Sh::flat(&p).iter().zip(Sh::flat(&ap)))
            {
                *d += pi * alpha;
                *r -= api * alpha;
            }
            let rs_new = dot_all(Sh::flat(&r), Sh::flat(&r));
            let beta = rs_new / rs;
            for (pi, &ri) in Sh::flat_mut(&mut p).iter_mut().zip(Sh::flat(&r)) {
                *pi = ri + *pi * beta;
            }
            rs = rs_new;
        }
        // A velocity's error is at most the residual over the mass (the matrix is at least
        // the masses'); times `h`, a distance.
        let solved = model.solved(ok, Sh::flat(&r), h * scale, model.shortest_rest());
        let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat_mut(&mut state.vel));
        for ((x, v), &d) in x.iter_mut().zip(v.iter_mut()).zip(Sh::flat(&dv)) {
            *v += d * scale;
            *x += *v * h;
        }
        solved
    }
}

#[cfg(test)]
mod tests {
    use super::solve_scale;
    use crate::{Q16, Scalar, Vec2};

    /// In `Q16` the scale is a power of two that brings the largest coordinate into
    /// `[4, 8)` within its limits; in floating point it is 1.
    #[test]
    fn the_solve_scale_brings_the_largest_coordinate_to_a_few_units() {
        for raw in [
            1,
            3,
            100,
            65_535,
            65_536,
            262_143,
            524_288,
            9_999_999,
            i32::MAX,
        ] {
            for sign in [1, -1] {
                let big = Q16::from_bits(raw.saturating_mul(sign));
                let b = [
                    Vec2::new(Q16::ZERO, big / Q16::from_i16(2)),
                    Vec2::new(big, Q16::ZERO),
                ];
                let largest = big.abs();
                let scale = solve_scale(&b);
                assert_eq!(scale.to_bits().count_ones(), 1, "{raw}: {scale:?}");
                let scaled = (largest / scale).to_f64();
                let limited = scale == Q16::from_i16(1 << 14) || scale.to_bits() == 16;
                assert!((4.0..8.0).contains(&scaled) || limited, "{raw}: {scaled}");
            }
        }
        assert_eq!(solve_scale(&[Vec2::new(Q16::ZERO, Q16::ZERO)]), Q16::ONE);
        assert_eq!(solve_scale(&[Vec2::new(1.0e6f32, 3.0)]), 1.0);
    }
}
