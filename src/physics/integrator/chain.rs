//! Springs along a chain solved all at once: one direct (tridiagonal) solve per iteration,
//! whatever the stiffness and the masses.

use super::{Integrator, Model, Solved, State, sealed, tiny_length};
use crate::physics::force::ForceField;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};
use core::cell::Cell;

/// A rope's links solved together, exactly, along the chain: a fixed cost a frame whatever
/// the stiffness, and a bob 100 times the rope's mass held at its length.
///
/// Each solve predicts the motion from gravity, damping and the force fields, then makes the
/// links (the springs joining particle `i` to `i + 1`) distance constraints and solves them
/// together: each of up to `iterations` Newton iterations builds the links' tridiagonal
/// system `(J W Jᵀ + α̃) Δλ = −C − α̃ λ` (`J` the links' directions, `W` the inverse masses,
/// `C` their stretch, `α̃ = 1 / (k h²)` their compliance), solves it directly (Thomas's
/// algorithm: one inverse a link) and takes the step, or half of it and so on while that
/// would not lower the links' squared stretch (a line search: far from the solution, as in
/// a whip, a full step overshoots). With `inextensible` the compliance is 0 and every link
/// holds its rest length; otherwise the links keep their springs' stiffness `k`, as
/// backward Euler would, with no stability limit. Other springs (a hub, bending springs, a
/// cloth's shear) are projected once an iteration as [`Xpbd`](super::Xpbd) does. A held
/// particle moves with its hand through the solves. Velocities are each solve's
/// displacement over its length.
///
/// **Converge or say so.** A solve that ends with a link more than
/// [`TOLERANCE`](Self::TOLERANCE) (0.1%) from its goal is undone and done again as two
/// solves of half its length, up to [`halvings`](Self::halvings) times. Links that start a
/// solve beyond the tolerance (put there by the game, or left by a solve that did not
/// converge) are first brought back as positions only, so that the correction does not
/// become speed. Every step measures its links after the contacts and reports the largest
/// stretch ([`StepInfo::stretch`](crate::system::StepInfo::stretch)) and whether it kept
/// the tolerance ([`StepInfo::converged`](crate::system::StepInfo::converged)); a step that
/// would leave a link more than [`MAX_STRETCH`](crate::system::MAX_STRETCH) (10%) off is
/// refused with [`Error::Diverged`](crate::Error::Diverged) and the state as it was.
/// In `f32` and `f64` a solve with no hand moving never ends with more energy (motion,
/// gravity, springs but the links) than it started with plus the work of the force fields
/// and the drag: where the links' solve would add some (light links folding under a heavy
/// bob fed one 1 000 times the rope's mass 90% of its fall's energy), the free particles'
/// velocities are scaled down (`tests/suite/converge.rs`). Two passes over the particles
/// and the other springs a solve.
/// Contacts are resolved after each solve, not inside it; where they moved particles and
/// stretched a link, the links are brought back with those particles 4 times as heavy. A
/// collider much thinner than the particle spacing can still be pulled through by the links
/// (a peg of a tenth of the spacing is; one of a third holds the rope,
/// `direct_chain_rests_on_a_peg`); for thin pegs, use
/// [`SymplecticEuler`](super::SymplecticEuler). A load far heavier than the rope pulls it
/// straight across what it wraps, and the links then take back what the contacts did: a
/// 70 kg player on a 2 kg rope pulls its drawn curve up to 0.7 m into the corner of a box
/// it wraps (`examples/mcu_wrap.rs`: `inside_permille` of its 5 cm thickness), and such a
/// step reports it: `converged` false, and in the residual how far the links took a
/// particle back along its push, over the shortest link
/// (`promises::a_chain_whose_links_pull_the_rope_into_what_it_touches_says_so`: every
/// frame with the curve in the box says so).
///
/// Measured (`tests/suite/physics.rs`, `direct_chain_*`; `tests/suite/promises.rs`), with
/// the defaults (4 solves of up to 4 iterations a 60 Hz frame), one substep a frame at any
/// stiffness:
/// - the catapult's rope (1.6 m, 0.4 kg, 8 particles) whirled with its 3 kg penguin: links
///   within 0.01% of their length, the drawn curve within 0.5% (0.21% measured;
///   symplectic Euler on the same springs stretches 55%);
/// - a bob 100 times the rope's mass, swinging or whirled: within 0.5% (0.001% on the links,
///   0.11% on the drawn curve);
/// - a bob 1 000 times the rope's mass, released level: links within 0.1%, the step
///   flagged unconverged in 7 frames of 240. Its light links can fold under it: it passes
///   under its pin 7.5% late (0.637 s where the closed form's pendulum takes 0.592), 0.3%
///   with 16 iterations a solve (`converge::direct_chain_swings_a_heavy_bob_as_a_pendulum`
///   holds 8% and 0.5%); a 70 kg player on a 2 kg, 12-particle rope
///   at one solve of two iterations a frame: within 0.1%, no frame flagged;
/// - one step of 1 s under that player: within 0.1%; one of 10 s: refused;
/// - an undamped released rope keeps 17% of its swing's energy over 10 s without a bob and
///   40% to 48% with one of 1 to 10 times its mass, against 96% to 97% for symplectic
///   Euler and Verlet: a solve removes the velocity that stretches a link, and a whipping
///   chain keeps feeding such velocity.
///   16 solves of 2 iterations keep 39% without a bob and 72% with one of 10 times the
///   rope's mass, but 25% with one of its own mass.
///   (Pulling each link along its direction at the solve's start, as SHAKE does, keeps 99%
///   without a bob, but the light links beside a heavy bob then whip out of control: their
///   sideways motion under its tension is stepped explicitly.)
///
/// Cost: per iteration, a square root, two inverses and about 15 multiplications a link;
/// per solve, about five multiplications a link and a square root to check where the links
/// end (and as much to check where they start, when no converged solve left them there)
/// (in `Q16` no division: a link's inverse length comes with its root,
/// [`Point::length_and_inverse`], and a pivot's from [`Scalar::approx_recip`]); the same at
/// every stiffness (within 1.01× from 10² to 10⁸ N/m, `docs/summary.md`, section (j)), 1.99
/// times symplectic Euler's frame on the catapult rope's own soft springs. On a Cortex-M0 in
/// Q16.16, one solve of up to 2 iterations takes up to 22 100 instructions a step for 8
/// particles, and a frame with its 33-point curve up to 27 328 (`examples/mcu_catapult.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DirectChain {
    /// Newton iterations a solve at most (4 by default); a solve stops as soon as its links
    /// are within 10⁻⁶ of the rope's length. 0 counts as 1.
    pub iterations: u8,
    /// `true`: every link at its rest length (an inextensible rope). `false`: the links'
    /// springs with their stiffness.
    pub inextensible: bool,
    /// Solves a step, each of an equal share of it (4 by default); 0 counts as 1.
    pub substeps: u8,
    /// How many times a solve that ends with a link beyond [`DirectChain::TOLERANCE`] of
    /// its goal is undone and done again as two of half its length (6 by default: down to
    /// 1/64 of its share; at most 12); 0 never. A share then costs up to `2^(halvings + 1)`
    /// solves. What is still beyond the tolerance after the last halving is reported
    /// ([`StepInfo::converged`](crate::system::StepInfo::converged), and the links' stretch
    /// in [`StepInfo::stretch`](crate::system::StepInfo::stretch)).
    pub halvings: u8,
}

impl DirectChain {
    /// How far a solve may leave a link from its goal, relative to its rest length (0.1%):
    /// the rest length when inextensible, the balance of the spring and the constraint
    /// otherwise. Beyond it the solve is halved (see [`halvings`](Self::halvings)).
    pub const TOLERANCE: (u32, u32) = super::TOLERANCE;
}

impl Default for DirectChain {
    /// Four solves of up to four iterations a step, inextensible, each solve halved up to six
    /// times.
    fn default() -> Self {
        DirectChain {
            iterations: 4,
            inextensible: true,
            substeps: 4,
            halvings: 6,
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

    fn holds_links(&self) -> bool {
        self.inextensible
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
        .fits
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
    ) -> Solved<P::Scalar> {
        // Whether the links are where a solve that kept the tolerance left them: the
        // step's start as the system knows it, then each solve's and contacts' end.
        let settled = Cell::new(model.settled);
        let solve = |state: &mut State<P, Sh>, hs, forces: &mut F| {
            let solved = self.solve_halving(model, state, hs, forces, settled.get());
            settled.set(solved.converged);
            solved
        };
        // The stretch the last solve's contacts left, and how far the links took back what
        // they did, when they moved a particle.
        let mut after_contacts = None;
        let mut touch = |state: &mut State<P, Sh>, times| {
            if !self.inextensible {
                return touch(state, times);
            }
            let before = state.pos;
            touch(state, times);
            after_contacts = self.hold_after_contacts(model, state, &before);
            if let Some((stretch, _)) = after_contacts {
                settled.set(settled.get() && stretch <= tolerance_of(DirectChain::TOLERANCE));
            }
        };
        let mut solved = super::split_solves(
            self.substeps,
            model,
            state,
            (h, lag),
            forces,
            &mut touch,
            solve,
        );
        if let Some((stretch, undone)) = after_contacts {
            let off = stretch.max(undone);
            solved.converged &= off <= tolerance_of(DirectChain::TOLERANCE);
            solved.stretch = stretch;
            solved.residual = solved.residual.max(off);
        }
        solved
    }
}

impl DirectChain {
    /// After the contacts of a solve: where they moved particles (from `before`) and left
    /// a link beyond the tolerance, the links are brought back, positions only, with each
    /// particle a contact moved 4 times as heavy, so that the links and the contacts mostly
    /// agree at the end of the solve (made much heavier, a rope pulled over a box's corner
    /// by a heavy load would fight the box's faces, stretching further each frame). Returns
    /// the links' stretch then and how much of the contacts' work they undid: the farthest
    /// a particle was taken back along its push, over the shortest link's rest length (about
    /// how deep the curve went back in); `None` when no contact moved a particle (at no
    /// cost). A square root a link and a particle when one did. Out of line: most solves
    /// touch nothing.
    #[inline(never)]
    fn hold_after_contacts<P: Point, Sh: Shape, T: Topology<P::Scalar>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        before: &Sh::PerParticle<P>,
    ) -> Option<(P::Scalar, P::Scalar)> {
        let (x, before) = (Sh::flat(&state.pos), Sh::flat(before));
        if x == before {
            return None;
        }
        let mut w = *model.inv_mass;
        for ((w, &x), &b) in Sh::flat_mut(&mut w).iter_mut().zip(x).zip(before) {
            if x != b {
                *w = *w * P::Scalar::ratio(1, 4);
            }
        }
        let mut links = Links::<P, Sh>::new(model, None);
        let iterations = self.iterations.max(1);
        let pushed = state.pos;
        let stretch = links.bring_back(Sh::flat_mut(&mut state.pos), Sh::flat(&w), iterations);
        let zero = P::Scalar::ZERO;
        let mut undone = zero;
        let (x, pushed) = (Sh::flat(&state.pos), Sh::flat(&pushed));
        for ((&x, &p), &b) in x.iter().zip(pushed).zip(before) {
            let (push, inverse) = (p - b).length_and_inverse();
            if push > zero {
                undone = undone.max((p - x).dot(p - b) * inverse);
            }
        }
        let shortest = (Sh::flat(&links.rest).iter().zip(Sh::flat(&links.linked)))
            .filter(|&(_, &linked)| linked)
            .fold(None, |least: Option<P::Scalar>, (&rest, _)| {
                Some(least.map_or(rest, |least| least.min(rest)))
            });
        let undone = match shortest {
            Some(rest) if rest > zero && undone > zero => undone / rest,
            _ => zero,
        };
        Some((stretch, undone))
    }

    /// A share `h` of a step in solves of `h / 2^k`: a solve whose links end beyond the
    /// tolerance is undone and done again as two of half its length, up to
    /// [`halvings`](Self::halvings) times (while half a solve is longer than the format's
    /// resolution, and unless its links start off and cannot be brought back). A held
    /// particle is where its hand is at the end of each solve: its place at the end of the
    /// share less its velocity times the time left.
    fn solve_halving<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
        settled: bool,
    ) -> Solved<P::Scalar> {
        let zero = P::Scalar::ZERO;
        let w = model.inv_mass();
        let end = state.pos;
        let mut report = Solved::plain(true);
        // `pieces` solves of `piece` make the share; `done` of them are solved. Unless the
        // links are known to start within the tolerance (`settled`), they are brought back
        // first, as positions only (the game put the particles there, or a solve that did
        // not converge): a solve turns that correction into velocity, and a shorter one
        // into more of it. Where that fails (a straight rope pushed shorter than its length
        // cannot tell which way to bend), shorter solves could only do worse: the solve is
        // not halved.
        let (mut piece, mut pieces, mut done, mut halved) = (h, 1u16, 0u16, 0u8);
        let (mut settled, mut halvable) = (settled || !self.inextensible, true);
        while done < pieces {
            if pieces > 1 {
                let behind = piece * P::Scalar::from_i16((pieces - done - 1) as i16);
                let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat(&state.vel));
                for (((x, &end), &v), &w) in x.iter_mut().zip(Sh::flat(&end)).zip(v).zip(w) {
                    if w <= zero {
                        *x = end - v * behind;
                    }
                }
            }
            if !settled {
                halvable = self.bring_back_start(model, state, piece);
                settled = true;
            }
            let start = *state;
            let solved = self.solve_step(model, state, piece, forces);
            let half = piece * P::Scalar::ratio(1, 2);
            let may_halve = halvable && halved < self.halvings.min(MOST_HALVINGS);
            if !solved.converged && may_halve && half > tiny_length::<P::Scalar>() {
                *state = start;
                (piece, pieces, done, halved) = (half, pieces * 2, done * 2, halved + 1);
                continue;
            }
            report = report.then(solved);
            settled = solved.converged;
            done += 1;
        }
        report
    }

    /// Brings the links of `state` back within the tolerance as positions only, with each
    /// held particle where its hand was `h` seconds before (its place less its velocity
    /// times `h`), and puts the held particles back; whether the links got there.
    #[cold]
    #[inline(never)]
    fn bring_back_start<P: Point, Sh: Shape, T: Topology<P::Scalar>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
    ) -> bool {
        let (zero, w) = (P::Scalar::ZERO, model.inv_mass());
        let hands = state.pos;
        let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat(&state.vel));
        for ((x, &v), &w) in x.iter_mut().zip(v).zip(w) {
            if w <= zero {
                *x -= v * h;
            }
        }
        let mut links = Links::<P, Sh>::new(model, None);
        let iterations = self.iterations.max(1);
        let off = links.bring_back(Sh::flat_mut(&mut state.pos), w, iterations);
        let x = Sh::flat_mut(&mut state.pos);
        for ((x, &hand), &w) in x.iter_mut().zip(Sh::flat(&hands)).zip(w) {
            if w <= zero {
                *x = hand;
            }
        }
        off <= tolerance_of(DirectChain::TOLERANCE)
    }

    fn solve_step<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> Solved<P::Scalar> {
        let zero = P::Scalar::ZERO;
        let (a, ok) = model.accelerations_at(state, forces, false);
        let w = model.inv_mass();
        let inv_h = P::Scalar::ONE / h;
        let mut links = Links::<P, Sh>::new(model, (!self.inextensible).then_some((inv_h, h)));
        let compliance = |k: P::Scalar| compliance(inv_h, h, k);
        let iterations = self.iterations.max(1);
        let prev = state.pos;
        // The energy at the start, in floating point when no hand moves (a moving hand does
        // work on the rope; `Q16` cannot hold a scene's energy in pixels).
        let (xs, vs) = (Sh::flat(&state.pos), Sh::flat(&state.vel));
        let still = !P::Scalar::FIXED_POINT
            && vs
                .iter()
                .zip(w)
                .all(|(v, &w)| w > zero || *v == P::default());
        let start_energy = still.then(|| model.energy(xs, vs, self.inextensible));
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
        for iteration in 1..=iterations {
            // The last of several iterations, after one that took its whole step, starts near
            // the solution, where a Newton step lowers the stretch: it is taken whole,
            // unmeasured (the check below measures). Far from it (the one before was cut
            // short, as in a whip), it takes the line search too.
            let whole = iteration > 1 && iteration == iterations && links.took_whole;
            links.solve(Sh::flat_mut(&mut state.pos), w, whole);
            if super::xpbd::project(model, Sh::flat_mut(&mut state.pos), compliance, 1) {
                links.measured = None;
            } else if self.inextensible && links.exact() {
                break;
            }
        }
        let off = links.off(Sh::flat(&state.pos));
        let converged = off <= tolerance_of(DirectChain::TOLERANCE);
        let (x, v) = (Sh::flat(&state.pos), Sh::flat_mut(&mut state.vel));
        for (((v, &x), &p), &w) in v.iter_mut().zip(x).zip(Sh::flat(&prev)).zip(w) {
            if w > zero {
                *v = (x - p) * inv_h;
            }
        }
        if let Some(e0) = start_energy {
            never_gain(
                model,
                state,
                (Sh::flat(&prev), e0),
                Sh::flat(&a),
                self.inextensible,
            );
        }
        Solved {
            fits: ok,
            converged,
            stretch: if self.inextensible { off } else { zero },
            residual: off,
        }
    }
}

/// Scales the free particles' velocities down so that the energy at the end of a solve
/// (`model.energy`) is at most `e0`, the start's, plus the work of the forces other than
/// gravity in the accelerations `a` from the start `x0` (a field, the drag), and the
/// velocities to 0 when the positions alone already hold more.
fn never_gain<P: Point, Sh: Shape, T: Topology<P::Scalar>>(
    model: &Model<'_, P, Sh, T>,
    state: &mut State<P, Sh>,
    (x0, e0): (&[P], P::Scalar),
    a: &[P],
    held_links: bool,
) {
    let (zero, one, half) = (P::Scalar::ZERO, P::Scalar::ONE, P::Scalar::ratio(1, 2));
    let w = model.inv_mass();
    let (mut work, mut kinetic) = (zero, zero);
    let (x, v) = (Sh::flat(&state.pos), Sh::flat(&state.vel));
    for ((&x, &x0), ((&v, &a), &w)) in x.iter().zip(x0).zip(v.iter().zip(a).zip(w)) {
        if w > zero {
            let m = one / w;
            work += ((a - model.gravity) * m).dot(x - x0);
            kinetic += half * m * v.dot(v);
        }
    }
    let gained = model.energy(x, v, held_links) - e0 - work;
    if !(gained > zero && kinetic > zero && gained.is_finite()) {
        return;
    }
    let scale = if gained >= kinetic {
        zero
    } else {
        (one - gained / kinetic).sqrt()
    };
    for (v, &w) in Sh::flat_mut(&mut state.vel).iter_mut().zip(w) {
        if w > zero {
            *v = *v * scale;
        }
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
    /// Whether the last iteration's line search took the whole Newton step.
    took_whole: bool,
    /// The squared stretch within which held links are exact: that of 10⁻⁶ of the rope's
    /// length (springs stretch by design: they take every iteration).
    exact: P::Scalar,
}

/// A spring's compliance `1 / (k h²)` in a solve of `h`, as `(1/h) / (k h)` from `1/h`: in
/// `Q16`, `h²` of a short solve is below the format's resolution, and a stiffness past its
/// range leaves 0 (held, inextensible).
fn compliance<S: Scalar>(inv_h: S, h: S, k: S) -> S {
    inv_h / (k * h)
}

/// A tolerance given as `(numerator, denominator)`, in the format.
fn tolerance_of<S: Scalar>((n, d): (u32, u32)) -> S {
    S::ratio(n, d)
}

/// Most times a solve is halved, whatever [`DirectChain::halvings`] says: 4 096 solves a
/// share.
const MOST_HALVINGS: u8 = 12;

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
    /// The links of `model`'s springs from particle `i` to `i + 1` that have a free end,
    /// each with its spring's compliance `1 / (k h²)` for a solve of `h` when given as
    /// `(1 / h, h)` (inextensible without).
    fn new<T: Topology<P::Scalar>>(
        model: &Model<'_, P, Sh, T>,
        h: Option<(P::Scalar, P::Scalar)>,
    ) -> Self {
        let zero = P::Scalar::ZERO;
        let w = model.inv_mass();
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
            took_whole: false,
            exact: zero,
        };
        model.topology.for_each_spring(|i, j, length, m| {
            if i.abs_diff(j) == 1 {
                let i = i.min(j);
                Sh::flat_mut(&mut links.rest)[i] = length;
                Sh::flat_mut(&mut links.linked)[i] = w[i] + w[i + 1] > zero;
                if let (Some((inv_h, h)), true) = (h, m.stiffness > zero) {
                    Sh::flat_mut(&mut links.compliance)[i] = compliance(inv_h, h, m.stiffness);
                }
            }
        });
        let rest: P::Scalar = Sh::flat(&links.rest).iter().fold(zero, |sum, &l| sum + l);
        let exact = rest * P::Scalar::ratio(1, 1_000_000);
        links.exact = exact * exact;
        links
    }

    /// Whether the last iteration measured the links within 10⁻⁶ of the rope's length.
    fn exact(&self) -> bool {
        self.measured.is_some_and(|r| r <= self.exact)
    }

    /// The largest distance of a link at `x` from its goal, relative to its rest length:
    /// `|l − g| / rest`, `g = rest − α̃ λ` its goal (its rest length when inextensible; a
    /// spring's multiplier is known to the format's resolution only, so 16 units of it are
    /// allowed for: in `Q16`, 0.02% of a 1 m link under a compliance of 1). First from the
    /// squared lengths, `|l² − g²| / g²` (about twice the ratio): where every link is within
    /// twice the tolerance that way, only the largest is measured (one square root), and
    /// the ratio is the largest to within its own square; otherwise every link is measured
    /// ([`off_measured`](Self::off_measured)). About five multiplications a link.
    fn off(&mut self, x: &[P]) -> P::Scalar {
        let zero = P::Scalar::ZERO;
        let (n, d) = DirectChain::TOLERANCE;
        let twice = P::Scalar::ratio(2 * n, d);
        let (rest, linked) = (Sh::flat(&self.rest), Sh::flat(&self.linked));
        let (compliance, lambda) = (Sh::flat(&self.compliance), Sh::flat(&self.lambda));
        // The largest ratio as its numerator and denominator, compared by products; a
        // link of the same goal as the one before (a rope's) reuses its square and limit.
        let (mut most, mut of, mut at) = (zero, P::Scalar::ONE, None);
        let (mut last, mut g2, mut limit) = (zero, zero, zero);
        for i in (0..x.len().saturating_sub(1)).filter(|&i| linked[i]) {
            let c = compliance[i];
            let g = if c > zero {
                rest[i] - c * lambda[i]
            } else {
                rest[i]
            };
            if g != last {
                (last, g2) = (g, g * g);
                limit = g2 * twice;
            }
            let d = x[i + 1] - x[i];
            let off = (d.dot(d) - g2).abs();
            if !(off.is_finite() && g2 > zero && off <= limit) {
                return self.off_measured(x);
            }
            let larger = if g2 == of {
                off >= most
            } else {
                off * of >= most * g2
            };
            if larger {
                (most, of, at) = (off, g2, Some(i));
            }
        }
        let Some(i) = at else {
            return zero;
        };
        let off = ((x[i + 1] - x[i]).length() - rest[i] + compliance[i] * lambda[i]).abs();
        (off - compliance[i] * tiny_length::<P::Scalar>()).max(zero) / rest[i]
    }

    /// [`off`](Self::off) from every link's length: measures the links unless the last
    /// iteration did. A multiplication a link and one division.
    #[cold]
    #[inline(never)]
    fn off_measured(&mut self, x: &[P]) -> P::Scalar {
        let zero = P::Scalar::ZERO;
        let (rest, linked) = (Sh::flat(&self.rest), Sh::flat(&self.linked));
        let (length, inverse) = (
            Sh::flat_mut(&mut self.length),
            Sh::flat_mut(&mut self.inverse),
        );
        if self.measured.is_none() {
            self.measured = Some(measure(x, rest, linked, (length, inverse)));
        }
        let (compliance, lambda) = (Sh::flat(&self.compliance), Sh::flat(&self.lambda));
        let rounding = tiny_length::<P::Scalar>();
        let (mut most, mut of) = (zero, P::Scalar::ONE);
        for i in (0..x.len().saturating_sub(1)).filter(|&i| linked[i]) {
            let off = (length[i] - rest[i] + compliance[i] * lambda[i]).abs();
            let off = (off - compliance[i] * rounding).max(zero);
            if off * of > most * rest[i] {
                (most, of) = (off, rest[i]);
            }
        }
        most / of
    }

    /// Moves the particles (positions only, by inverse masses `w`) towards every link
    /// within [`DirectChain::TOLERANCE`], in up to `4 · iterations` Newton iterations; how
    /// far off they end ([`off`](Self::off)). Does nothing when they are within already
    /// (about five multiplications a link to find out).
    #[inline(never)]
    fn bring_back(&mut self, x: &mut [P], w: &[P::Scalar], iterations: u8) -> P::Scalar {
        let off = self.off(x);
        if off <= tolerance_of(DirectChain::TOLERANCE) {
            return off;
        }
        for _ in 0..iterations.saturating_mul(4) {
            self.solve(x, w, false);
            if self.exact() {
                break;
            }
        }
        Sh::flat_mut(&mut self.lambda).fill(P::Scalar::ZERO);
        self.off(x)
    }

    /// One Newton iteration: the links' tridiagonal system `(J W Jᵀ + α̃) Δλ = −C − α̃ λ` at
    /// `x` solved by Thomas's algorithm (one inverse a link), and the particles moved by it:
    /// with `whole`, by the whole step, unmeasured; otherwise the whole step or, while that
    /// would not lower the links' squared stretch, half of it and so on (a line search,
    /// [`took_whole`](Self::took_whole) unless it cut the step). A link too short to have a
    /// direction sits the iteration out.
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
        self.took_whole = true;
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
            self.took_whole = false;
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
