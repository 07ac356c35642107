//! Springs along a chain solved all at once: one direct (tridiagonal) solve per iteration,
//! whatever the stiffness and the masses.

use super::{Integrator, Model, State, sealed, tiny_length};
use crate::physics::force::ForceField;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// A rope's links solved together, exactly, along the chain: a fixed cost a frame whatever
/// the stiffness, and a bob 100 times the rope's mass held at its length.
///
/// Each solve predicts the motion from gravity, damping and the force fields, then makes the
/// links (the springs joining particle `i` to `i + 1`) distance constraints and solves them
/// together: each of `iterations` Newton iterations builds the links' tridiagonal system
/// `(J W Jᵀ + α̃) Δλ = −C − α̃ λ` (`J` the links' directions, `W` the inverse masses, `C`
/// their stretch, `α̃ = 1 / (k h²)` their compliance), solves it directly (Thomas's
/// algorithm: one inverse a link) and takes the step, or half of it and so on while that
/// would not lower the links' squared stretch (a line search: far from the solution, as in
/// a whip, a full step overshoots). The last of two or more iterations starts near the
/// solution and is taken whole, unmeasured. With `inextensible` the compliance is 0 and
/// every link holds its rest length; otherwise the links keep their springs' stiffness `k`,
/// as backward Euler would, with no stability limit. Other springs (a hub, bending springs,
/// a cloth's shear) are projected once an iteration as [`Xpbd`](super::Xpbd) does. A held
/// particle moves with its hand through the solves. Velocities are each solve's displacement over
/// its length. Contacts are resolved after each solve, not inside it: a collider much
/// thinner than the particle spacing can be pulled through by the links (a peg of a tenth of
/// the spacing is; one of a third holds the rope, `direct_chain_rests_on_a_peg`); for thin
/// pegs, use [`SymplecticEuler`](super::SymplecticEuler).
///
/// Measured (`tests/suite/physics.rs`, `direct_chain_*`), with the defaults (4 solves of up to 4
/// iterations a 60 Hz frame), one substep a frame at any stiffness:
/// - the catapult's rope (1.6 m, 0.4 kg, 8 particles) whirled with its 3 kg penguin: links
///   within 0.01% of their length, the drawn curve within 0.5% (0.21% measured;
///   symplectic Euler on the same springs stretches 55%);
/// - a bob 100 times the rope's mass, swinging or whirled: within 0.5% (0.001% on the links,
///   0.11% on the drawn curve);
/// - 1 000 times: not held (the links stretch several times over); use a shorter step;
/// - an undamped released rope keeps 18% of its swing's energy over 10 s without a bob and
///   40% to 48% with one of 1 to 10 times its mass, against 96% to 97% for symplectic
///   Euler and Verlet: a solve removes the velocity that stretches a link, and a whipping
///   chain keeps feeding such velocity.
///   16 solves of 2 iterations keep 39% without a bob and 72% with one of 10 times the
///   rope's mass, but 25% with one of its own mass.
///   (Pulling each link along its direction at the solve's start, as SHAKE does, keeps 99%
///   without a bob, but the light links beside a heavy bob then whip out of control: their
///   sideways motion under its tension is stepped explicitly.)
///
/// Cost: per iteration, a square root, two inverses and about 15 multiplications a link
/// (in `Q16` no division: a link's inverse length comes with its root,
/// [`Point::length_and_inverse`], and a pivot's from [`Scalar::approx_recip`]); the same at
/// every stiffness (within 1.02× from 10² to 10⁸ N/m, `docs/summary.md`, section (j)), 1.24
/// times symplectic Euler's frame on the catapult rope's own soft springs. On a Cortex-M0 in
/// Q16.16, one solve of up to 2 iterations takes up to 18 326 instructions a step for 8
/// particles, and a frame with its 33-point curve up to 23 551 (`examples/mcu_catapult.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DirectChain {
    /// Newton iterations a solve at most (4 by default); an inextensible rope stops once
    /// its links are within 10⁻⁶ of its length. 0 counts as 1.
    pub iterations: u8,
    /// `true`: every link at its rest length (an inextensible rope). `false`: the links'
    /// springs with their stiffness.
    pub inextensible: bool,
    /// Solves a step, each of an equal share of it (4 by default); 0 counts as 1.
    pub substeps: u8,
}

impl Default for DirectChain {
    /// Four solves of four iterations a step, inextensible.
    fn default() -> Self {
        DirectChain {
            iterations: 4,
            inextensible: true,
            substeps: 4,
        }
    }
}

impl sealed::Sealed for DirectChain {}

impl Integrator for DirectChain {
    type Memory<S: Scalar, Sh: Shape> = ();

    fn memory<S: Scalar, Sh: Shape>() {}

    fn stability_limit<S: Scalar>(&self) -> Option<S> {
        None
    }

    fn force_evaluations(&self) -> u32 {
        u32::from(self.substeps.max(1))
    }

    fn substep<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool {
        self.substep_touching(
            model,
            state,
            &mut (),
            (h, P::Scalar::ZERO),
            forces,
            &mut |_, _| {},
        )
    }

    /// Each solve ends with the contacts, so that a link's solve never pulls the rope
    /// through a collider unseen for a whole substep.
    fn substep_touching<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        _: &mut (),
        (h, lag): (P::Scalar, P::Scalar),
        forces: &mut F,
        touch: &mut impl FnMut(&mut State<P, Sh>, (P::Scalar, P::Scalar)),
    ) -> bool {
        let solve = |state: &mut State<P, Sh>, hs, forces: &mut F| {
            self.solve_step(model, state, hs, forces)
        };
        super::split_solves(self.substeps, model, state, (h, lag), forces, touch, solve)
    }
}

impl DirectChain {
    fn solve_step<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool {
        let zero = P::Scalar::ZERO;
        let (a, ok) = model.accelerations_at(state, forces, false);
        let prev = state.pos;
        let w = model.inv_mass();
        {
            // A held particle stays where its hand put it (it is already at the end of the
            // hand's move); the others move on.
            let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat_mut(&mut state.vel));
            for (((x, v), a), &w) in x.iter_mut().zip(v.iter_mut()).zip(Sh::flat(&a)).zip(w) {
                if w > zero {
                    *v += *a * h;
                    *x += *v * h;
                }
            }
        }
        // Link `i` joins particle `i` to `i + 1`: its rest length, compliance, and whether
        // it is there to solve (a live spring with a free end).
        let mut links = Links::<P, Sh> {
            rest: Sh::filled(zero),
            compliance: Sh::filled(zero),
            linked: Sh::filled(false),
            lambda: Sh::filled(zero),
            dir: Sh::filled(P::default()),
            ratio: Sh::filled(zero),
            solved: Sh::filled(zero),
            before: Sh::filled(P::default()),
            length: Sh::filled(zero),
            inverse: Sh::filled(zero),
            measured: None,
        };
        let inv_h = P::Scalar::ONE / h;
        // `1 / (k h²)` as `(1/h) / (k h)`: in `Q16`, `h²` of a short solve is below the
        // format's resolution, and a stiffness past its range leaves 0 (held, inextensible).
        let compliance = |k: P::Scalar| inv_h / (k * h);
        model.topology.for_each_spring(|i, j, length, m| {
            if i.abs_diff(j) == 1 {
                let i = i.min(j);
                Sh::flat_mut(&mut links.rest)[i] = length;
                Sh::flat_mut(&mut links.linked)[i] = w[i] + w[i + 1] > zero;
                if !self.inextensible && m.stiffness > zero {
                    Sh::flat_mut(&mut links.compliance)[i] = compliance(m.stiffness);
                }
            }
        });
        // Held links have converged once their squared stretch is within that of 10⁻⁶ of the
        // rope's length (springs stretch by design: they take every iteration).
        let rest: P::Scalar = Sh::flat(&links.rest).iter().fold(zero, |sum, &l| sum + l);
        let tolerance = rest * P::Scalar::ratio(1, 1_000_000);
        let iterations = self.iterations.max(1);
        for iteration in 1..=iterations {
            // The last of several iterations starts near the solution, where a Newton step
            // lowers the stretch: it is taken whole, unmeasured.
            let whole = iteration > 1 && iteration == iterations;
            links.solve(Sh::flat_mut(&mut state.pos), w, whole);
            if super::xpbd::project(model, Sh::flat_mut(&mut state.pos), compliance, 1) {
                links.measured = None;
            } else if self.inextensible
                && links.measured.is_some_and(|r| r <= tolerance * tolerance)
            {
                break;
            }
        }
        let (x, v) = (Sh::flat(&state.pos), Sh::flat_mut(&mut state.vel));
        for (((v, &x), &p), &w) in v.iter_mut().zip(x).zip(Sh::flat(&prev)).zip(w) {
            if w > zero {
                *v = (x - p) * inv_h;
            }
        }
        ok
    }
}

/// The links of a row of particles (link `i` joins particle `i` to `i + 1`; the last slot is
/// unused) and the scratch of their solve, in the particles' own layout.
struct Links<P: Point, Sh: Shape> {
    rest: Sh::PerParticle<P::Scalar>,
    compliance: Sh::PerParticle<P::Scalar>,
    linked: Sh::PerParticle<bool>,
    /// Each link's multiplier, carried from one iteration to the next.
    lambda: Sh::PerParticle<P::Scalar>,
    dir: Sh::PerParticle<P>,
    /// Thomas's algorithm: each row's off-diagonal over its pivot, then its solution.
    ratio: Sh::PerParticle<P::Scalar>,
    solved: Sh::PerParticle<P::Scalar>,
    /// The positions before a Newton step, for its line search.
    before: Sh::PerParticle<P>,
    /// Each link's length and its inverse at the positions now, and their squared stretch,
    /// once measured (the line search measures them; the next iteration starts from them).
    length: Sh::PerParticle<P::Scalar>,
    inverse: Sh::PerParticle<P::Scalar>,
    measured: Option<P::Scalar>,
}

/// Most times a Newton step is halved before it is taken as it is.
const MAX_HALVINGS: u8 = 4;

/// Each link's length and its inverse into `length`, and `Σ (l − rest)²` over the links:
/// what a Newton step must lower.
fn measure<P: Point>(
    x: &[P],
    rest: &[P::Scalar],
    linked: &[bool],
    (length, inverse): (&mut [P::Scalar], &mut [P::Scalar]),
) -> P::Scalar {
    let mut sum = P::Scalar::ZERO;
    for i in 0..x.len().saturating_sub(1) {
        if linked[i] {
            (length[i], inverse[i]) = (x[i + 1] - x[i]).length_and_inverse();
            let c = length[i] - rest[i];
            sum += c * c;
        }
    }
    sum
}

impl<P: Point, Sh: Shape> Links<P, Sh> {
    /// One Newton iteration: the links' tridiagonal system `(J W Jᵀ + α̃) Δλ = −C − α̃ λ` at
    /// `x` solved by Thomas's algorithm (one inverse a link), and the particles moved by it:
    /// with `whole`, by the whole step, unmeasured; otherwise by the line search. A link too
    /// short to have a direction sits the iteration out.
    fn solve(&mut self, x: &mut [P], w: &[P::Scalar], whole: bool) {
        let zero = P::Scalar::ZERO;
        let (rest, compliance) = (Sh::flat(&self.rest), Sh::flat(&self.compliance));
        let (linked, lambda) = (Sh::flat(&self.linked), Sh::flat_mut(&mut self.lambda));
        let dir = Sh::flat_mut(&mut self.dir);
        let (ratio, solved) = (
            Sh::flat_mut(&mut self.ratio),
            Sh::flat_mut(&mut self.solved),
        );
        let links = x.len().saturating_sub(1);
        let length = Sh::flat_mut(&mut self.length);
        let inverse = Sh::flat_mut(&mut self.inverse);
        let residual = match self.measured {
            Some(residual) => residual,
            None => measure(x, rest, linked, (length, inverse)),
        };
        // Each link's direction and right-hand side `−C − α̃λ`; a zero direction marks one
        // too short to have a direction.
        for i in 0..links {
            (dir[i], solved[i]) = (P::default(), zero);
            if !linked[i] {
                continue;
            }
            let d = x[i + 1] - x[i];
            let l = length[i];
            let mut b = rest[i] - l;
            if compliance[i] > zero {
                b -= compliance[i] * lambda[i];
            }
            if l > tiny_length::<P::Scalar>() {
                (dir[i], solved[i]) = (d * inverse[i], b);
            } else {
                lambda[i] = zero;
            }
        }
        // Forward sweep; row i couples to link i + 1 through particle i + 1 by
        // `off_i = −w_{i+1} (n_i · n_{i+1})`.
        let (mut prev_ratio, mut prev_solved, mut prev_off) = (zero, zero, zero);
        for i in 0..links {
            ratio[i] = zero;
            if dir[i] == P::default() {
                (prev_ratio, prev_solved, prev_off) = (zero, zero, zero);
                continue;
            }
            let diag = w[i] + w[i + 1] + compliance[i] - prev_off * prev_ratio;
            if diag <= zero {
                (dir[i], solved[i]) = (P::default(), zero);
                (prev_ratio, prev_solved, prev_off) = (zero, zero, zero);
                continue;
            }
            let inv = diag.approx_recip();
            let off = if i + 1 < links && dir[i + 1] != P::default() {
                -(w[i + 1] * dir[i].dot(dir[i + 1]))
            } else {
                zero
            };
            ratio[i] = off * inv;
            solved[i] = (solved[i] - prev_off * prev_solved) * inv;
            (prev_ratio, prev_solved, prev_off) = (ratio[i], solved[i], off);
        }
        // Back substitution, then each particle moves by its links' pulls: the whole
        // Newton step, or half of it, and so on, until the links' squared stretch falls
        // (far from the solution, as in a whip, a full step can overshoot and feed on
        // itself).
        for i in (0..links.saturating_sub(1)).rev() {
            solved[i] -= ratio[i] * solved[i + 1];
        }
        let before = Sh::flat_mut(&mut self.before);
        if !whole {
            before.copy_from_slice(x);
        }
        for halving in 0..=MAX_HALVINGS {
            // Each particle moves by the difference of its two links' pulls.
            let mut pull = P::default();
            for i in 0..x.len() {
                let out = if i < links && dir[i] != P::default() {
                    dir[i] * solved[i]
                } else {
                    P::default()
                };
                if w[i] > zero {
                    x[i] += (pull - out) * w[i];
                }
                pull = out;
            }
            if whole {
                self.measured = None;
                return;
            }
            let after = measure(x, rest, linked, (length, inverse));
            self.measured = Some(after);
            if halving == MAX_HALVINGS || after <= residual {
                break;
            }
            x.copy_from_slice(before);
            for s in solved.iter_mut() {
                *s = *s * P::Scalar::ratio(1, 2);
            }
        }
        for i in 0..links {
            if dir[i] != P::default() {
                lambda[i] += solved[i];
            }
        }
    }
}
