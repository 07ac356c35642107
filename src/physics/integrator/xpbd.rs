//! Extended position-based dynamics.

use super::{Integrator, Model, Solved, State, sealed, tiny_length};
use crate::physics::force::ForceField;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// Extended position-based dynamics: springs become distance constraints with compliance
/// `1/k`, projected once per XPBD substep ("small steps", Macklin et al. 2016, 2019). Stable
/// at any step; loses a little energy.
///
/// One projection per spring per substep does not converge a long chain, so the chain acts
/// softer than its springs and stretches more under gravity than the force-based methods on
/// the same springs. The excess falls as `1/substeps²`; to match them, raise `substeps`.
/// A 1 m, 1 kg rope of 30 particles with axial stiffness 1000 N, hanging at rest, stretches
/// by (`tests/suite/physics.rs`, `xpbd_stretch_converges_to_the_springs_as_substeps_grow`):
///
/// | substeps | 4 | 16 | 64 | force-based methods | continuum `m·g/(2·EA)` |
/// |---|---|---|---|---|---|
/// | stretch | 7.2% | 0.92% | 0.52% | 0.49% | 0.49% |
///
/// A step says how far its last XPBD substep ended from backward Euler's equations, which
/// XPBD converges to ([`StepInfo::residual`](crate::system::StepInfo::residual): the
/// largest distance a particle still owes them, over the shortest rest length; converged
/// within 0.1%), at the cost of a pass over the springs: a 1 m, 1 kg rope of 30 particles
/// of `10⁴ N/m` released level converges in every frame with 64 substeps, in at most 3 of
/// 300 with the default 4 (`tests/suite/converge.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Xpbd {
    /// XPBD substeps per step (4 to 20 is typical); 0 counts as 1.
    pub substeps: u8,
}

impl Default for Xpbd {
    /// 4 substeps.
    fn default() -> Self {
        Xpbd { substeps: 4 }
    }
}

impl sealed::Sealed for Xpbd {}

impl Integrator for Xpbd {
    type Memory<S: Scalar, Sh: Shape> = ();

    fn memory<S: Scalar, Sh: Shape>() {}

    fn stability_limit<S: Scalar>(&self) -> Option<S> {
        None
    }
    fn force_evaluations(&self) -> u32 {
        self.substeps.max(1) as u32
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

    /// `substeps` XPBD substeps of `h`; the last one's residual: what each free particle
    /// still owes to backward Euler's equations, `x − y − hs² F(x, v) / m` (`y` where its
    /// velocity and the forces other than the springs carry it), as a distance. A pass over
    /// the springs more (a square root each).
    fn substep_solved<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> Solved<P::Scalar> {
        let n = self.substeps.max(1);
        let hs = h / P::Scalar::from_i16(n as i16);
        let inv_hs = P::Scalar::ONE / hs;
        let w = model.inv_mass();
        let mut ok = true;
        let mut predicted = state.pos;
        for _ in 0..n {
            let (a, fine) = model.accelerations_at(state, forces, false);
            ok &= fine;
            let prev = state.pos;
            {
                let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat_mut(&mut state.vel));
                for ((x, v), a) in x.iter_mut().zip(v.iter_mut()).zip(Sh::flat(&a)) {
                    *v += *a * hs;
                    *x += *v * hs;
                }
            }
            predicted = state.pos;
            let x = Sh::flat_mut(&mut state.pos);
            let px = Sh::flat(&prev);
            model.topology.for_each_spring(|ia, ib, rest, m| {
                let d = x[ib] - x[ia];
                let l = d.length();
                let wsum = w[ia] + w[ib];
                if l <= tiny_length::<P::Scalar>() || wsum <= P::Scalar::ZERO {
                    return;
                }
                let nrm = d * (P::Scalar::ONE / l);
                // Compliance α̃ = 1/(k h²); damping γ = c/(k h) (Macklin et al. 2016, eq. 26).
                let kh = m.stiffness * hs;
                let alpha = P::Scalar::ONE / (kh * hs);
                let gamma = m.damping / kh;
                let closing = ((x[ib] - px[ib]) - (x[ia] - px[ia])).dot(nrm);
                let c = l - rest;
                let dl = -(c + gamma * closing) / ((P::Scalar::ONE + gamma) * wsum + alpha);
                x[ia] -= nrm * (dl * w[ia]);
                x[ib] += nrm * (dl * w[ib]);
            });
            let (x, v) = (Sh::flat(&state.pos), Sh::flat_mut(&mut state.vel));
            for ((v, &x), &p) in v.iter_mut().zip(x).zip(Sh::flat(&prev)) {
                *v = (x - p) * inv_hs;
            }
        }
        // The last substep's imbalance `M (x − y) − hs² F`, its springs' forces at the end.
        let (x, v) = (Sh::flat(&state.pos), Sh::flat(&state.vel));
        let mut owed = Sh::filled(P::default());
        let r = Sh::flat_mut(&mut owed);
        for ((r, (&x, &y)), &w) in r.iter_mut().zip(x.iter().zip(Sh::flat(&predicted))).zip(w) {
            if w > P::Scalar::ZERO {
                *r = (x - y) * (P::Scalar::ONE / w);
            }
        }
        let h2 = hs * hs;
        model.topology.for_each_spring(|a, b, rest, m| {
            let d = x[b] - x[a];
            let l = d.length();
            if l <= tiny_length::<P::Scalar>() {
                return;
            }
            let nrm = d * (P::Scalar::ONE / l);
            let closing = (v[b] - v[a]).dot(nrm);
            let pull = nrm * ((m.stiffness * (l - rest) + m.damping * closing) * h2);
            r[a] -= pull;
            r[b] += pull;
        });
        model.solved(ok, r, P::Scalar::ONE, model.shortest_rest())
    }
}

/// Every spring wider than `band` (its ends more than `band` apart in flat order: what a
/// direct solve leaves out) projected once, as [`Xpbd`] does with no damping, with compliance
/// `compliance(k)` (`1 / (k h²)`); `true` when there was one.
pub(super) fn project<P: Point, Sh: Shape, T: Topology<P::Scalar>>(
    model: &Model<'_, P, Sh, T>,
    x: &mut [P],
    compliance: impl Fn(P::Scalar) -> P::Scalar,
    band: usize,
) -> bool {
    let w = model.inv_mass();
    let mut moved = false;
    model.topology.for_each_spring(|a, b, rest, m| {
        let wsum = w[a] + w[b];
        if a.abs_diff(b) <= band || wsum <= P::Scalar::ZERO || m.stiffness <= P::Scalar::ZERO {
            return;
        }
        let d = x[b] - x[a];
        let l = d.length();
        if l <= tiny_length::<P::Scalar>() {
            return;
        }
        let nrm = d * (P::Scalar::ONE / l);
        let dl = -(l - rest) / (wsum + compliance(m.stiffness));
        x[a] -= nrm * (dl * w[a]);
        x[b] += nrm * (dl * w[b]);
        moved = true;
    });
    moved
}
