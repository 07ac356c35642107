//! Springs along a chain solved all at once: one direct (tridiagonal) solve per iteration,
//! whatever the stiffness and the masses.

use super::links::{Held, Links, compliance};
use super::rounds::{CONTACT_ROUNDS, contact_rounds};
use super::{Integrator, Model, Solved, State, sealed, split_solves, tiny_length};
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
/// **Contacts and links agree.** An inextensible chain's contacts come after each solve,
/// and take turns with the links: each round of contacts is followed by a hold of the
/// links (positions only, the motion it takes becoming velocity) in which every particle a
/// contact pushed is held along its push (it slides across it, and is let go where its
/// links pull it outward), until a round moves nothing, up to 8 rounds; where the links
/// cannot get within the tolerance so, they have the last word. A step whose rounds did
/// not agree, or left a link beyond the tolerance, says so (`converged` false, and in the
/// residual how far the links took a particle back along its push, over the shortest
/// link). A 70 kg player on a 2 kg rope wrapping a box 3 spacings wide
/// (`examples/mcu_wrap.rs`) keeps its drawn curve out of the box and its links within
/// 0.1% in every frame that says it converged (`promises::a_heavy_load_round_a_box_*`;
/// it used to pull the curve 0.7 m into the box), and a rope rests on a peg of a tenth
/// of its spacing (`direct_chain_rests_on_a_peg`). Each round costs a pass of the
/// contacts and up to `8 · iterations` Newton iterations of the links (twice that where
/// they fall back; a hold stops once an iteration takes less than a sixteenth off the
/// links' squared stretch, and falls back then): in the player's scene on a Cortex-M0,
/// 248 824 instructions a frame on average and 2.0 million at worst (`docs/devices.md`),
/// 4.0 times the frame without the box in f32 on the host (`docs/summary.md`, targets).
/// With springs instead of links (`inextensible: false`), the contacts take rounds after
/// each solve as [`DirectSprings`](super::DirectSprings)' do (until a round moves no
/// particle by more than 0.1% of the shortest spring, `converged` false where they do not
/// agree): a load of 20
/// to 70 kg on 2 000 N/m springs wrapping the same box went a quarter of the rope's
/// thickness to 5 times it into the box with one round, and stays out now
/// (`promises::a_load_round_a_box_keeps_a_springy_rope_out_of_it`).
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
/// - in `Q16`, a 7-unit, 8-particle rope held at both ends under a drag of 0.1/s moves up
///   to 0.12 units/s in its 60th second (0.007 with one substep a step): the format's
///   rounding, left over. A solve keeps the share of each velocity that `v h` rounds away,
///   and solves its links' multipliers in units of the largest inverse mass (a power of two,
///   up to 1 024), so that a light particle moves in steps of the format's resolution
///   (0.46 and 0.023 units/s without either;
///   `physics::direct_chain_in_q16_keeps_a_rope_at_rest_nearly_still`).
///
/// Cost: per iteration, a square root, two inverses and about 15 multiplications a link;
/// per solve, about five multiplications a link and a square root to check where the links
/// end (and as much to check where they start, when no converged solve left them there)
/// (in `Q16` no division: a link's inverse length comes with its root,
/// [`Point::length_and_inverse`], and a pivot's from [`Scalar::approx_recip`]); the same at
/// every stiffness (within 1.01× from 10² to 10⁸ N/m, `docs/summary.md`, section (j)), 1.99
/// times symplectic Euler's frame on the catapult rope's own soft springs. On a Cortex-M0 in
/// Q16.16, one solve of up to 2 iterations takes up to 23 331 instructions a step for 8
/// particles, and a frame with its 33-point curve up to 28 597 (`examples/mcu_catapult.rs`).
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
        // The stretch the last solve's contacts left, how far the links took back what they
        // did, and whether the two agreed (a round of contacts or of links moved nothing),
        // when the contacts moved a particle.
        let mut after_contacts = None;
        // Springs instead of links: the contacts take rounds as `DirectSprings`' do.
        let mut rounds_agreed = true;
        let mut touch = |state: &mut State<P, Sh>, times: (P::Scalar, P::Scalar)| {
            if !self.inextensible {
                rounds_agreed &= contact_rounds(model, state, times, touch);
                return;
            }
            after_contacts = self.contact_rounds(model, state, times, touch);
            if let Some((stretch, _, _)) = after_contacts {
                settled.set(settled.get() && stretch <= tolerance_of(DirectChain::TOLERANCE));
            }
        };
        let (times, n) = ((h, lag), self.substeps);
        let mut solved = split_solves(n, model, state, times, forces, &mut touch, solve);
        solved.converged &= rounds_agreed;
        if let Some((stretch, undone, agreed)) = after_contacts {
            let off = stretch.max(undone);
            solved.converged &= agreed && off <= tolerance_of(DirectChain::TOLERANCE);
            solved.stretch = stretch;
            solved.residual = solved.residual.max(off);
        }
        solved
    }
}

impl DirectChain {
    /// The contacts of a solve (`touch`, at `times`: its length and the time left in the
    /// frame) and the links in turns: each round of contacts is followed by a hold of the
    /// links ([`hold_after_contacts`](Self::hold_after_contacts)), and the rounds go on,
    /// with no time passing (`h` 0: no collider moves, no friction takes back sliding),
    /// while a hold moves a particle, up to [`CONTACT_ROUNDS`]. Returns the last hold's
    /// stretch and undoing, and whether the contacts and the links agreed (the last round's
    /// contacts or hold moved nothing); `None` when the contacts moved nothing.
    fn contact_rounds<P: Point, Sh: Shape, T: Topology<P::Scalar>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        (h, lag): (P::Scalar, P::Scalar),
        touch: &mut impl FnMut(&mut State<P, Sh>, (P::Scalar, P::Scalar)),
    ) -> Option<(P::Scalar, P::Scalar, bool)> {
        if !model.touching {
            touch(state, (h, lag));
            return None;
        }
        let mut before = state.pos;
        touch(state, (h, lag));
        if Sh::flat(&state.pos) == Sh::flat(&before) {
            return None;
        }
        let mut normal = Sh::filled(P::default());
        for round in 1..=CONTACT_ROUNDS {
            let pushed = state.pos;
            let (stretch, undone) =
                self.hold_after_contacts(model, state, (&before, &mut normal), h);
            let agreed = Sh::flat(&state.pos) == Sh::flat(&pushed);
            if agreed || round == CONTACT_ROUNDS {
                return Some((stretch, undone, agreed));
            }
            before = state.pos;
            touch(state, (P::Scalar::ZERO, lag));
            if Sh::flat(&state.pos) == Sh::flat(&before) {
                return Some((stretch, undone, true));
            }
        }
        None
    }

    /// After a round of contacts in a solve of `h`: where they moved particles (from
    /// `before`) and left a link beyond the tolerance, the links are brought back, positions
    /// only, with each particle a contact pushed held along its push ([`Held`]: it slides
    /// across it but not back along it, and is let go where its links pull it outward), and
    /// the motion that takes becomes velocity (none when `h` is 0). Where the links cannot
    /// get within the tolerance so, they are brought back with every particle free: the
    /// links have the last word. `normal` keeps each held particle's push from one round to
    /// the next. Returns the links' stretch then and how much of the contacts' work they
    /// undid: the farthest a held particle was taken back along its push, over the shortest
    /// link's rest length (about how deep the curve went back in). Up to
    /// `8 · HOLD_ITERATIONS · iterations` Newton iterations (two holds), and a square root
    /// a particle the contacts moved. Out of line: most solves touch nothing.
    #[inline(never)]
    fn hold_after_contacts<P: Point, Sh: Shape, T: Topology<P::Scalar>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        (before, normal): (&Sh::PerParticle<P>, &mut Sh::PerParticle<P>),
        h: P::Scalar,
    ) -> (P::Scalar, P::Scalar) {
        let (zero, w) = (P::Scalar::ZERO, model.inv_mass());
        let (x, before) = (Sh::flat(&state.pos), Sh::flat(before));
        // Each particle a contact moved is held along its push from now on in this solve,
        // unless it moved against a neighbour that moved further: a drawn spline's
        // counterweight (a Catmull-Rom span's outer particles move back when its inner
        // ones are pushed out).
        let moved = |i: usize| x[i] - before[i];
        // This round's pushes as unit vectors (zero where not held): `normal` lets go of a
        // held particle during the hold, these do not.
        let mut pushes = Sh::filled(P::default());
        let held = Sh::flat_mut(normal)
            .iter_mut()
            .zip(Sh::flat_mut(&mut pushes));
        for (i, (n, out)) in held.enumerate() {
            let push = moved(i);
            let counter = |j: usize| {
                let other = moved(j);
                other.dot(push) < zero && other.longer_than(push)
            };
            if (i > 0 && counter(i - 1)) || (i + 1 < x.len() && counter(i + 1)) {
                continue;
            }
            let (length, inverse) = push.length_and_inverse();
            if length > zero {
                (*n, *out) = (push * inverse, push * inverse);
            }
        }
        let mut links = Links::<P, Sh>::new(model, None).measured_finely();
        let iterations = self.iterations.max(1).saturating_mul(HOLD_ITERATIONS);
        let pushed = state.pos;
        let x = Sh::flat_mut(&mut state.pos);
        let mut held = Held {
            w,
            normal: Sh::flat_mut(normal),
        };
        let mut stretch = links.bring_back(x, &mut held, (iterations, links.close));
        if stretch > tolerance_of(DirectChain::TOLERANCE) {
            stretch = links.bring_back(x, &mut { w }, (iterations, links.close));
        }
        let (x, pushed) = (Sh::flat(&state.pos), Sh::flat(&pushed));
        if h > zero {
            let inv_h = P::Scalar::ONE / h;
            let v = Sh::flat_mut(&mut state.vel);
            for (((v, &x), &p), &w) in v.iter_mut().zip(x).zip(pushed).zip(w) {
                if w > zero {
                    *v += (x - p) * inv_h;
                }
            }
        }
        let mut undone = zero;
        for ((&x, &p), &out) in x.iter().zip(pushed).zip(Sh::flat(&pushes)) {
            undone = undone.max((p - x).dot(out));
        }
        let shortest = links.shortest();
        match shortest > zero && undone > zero {
            true => (stretch, undone / shortest),
            false => (stretch, zero),
        }
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
        let off = links.bring_back(
            Sh::flat_mut(&mut state.pos),
            &mut { w },
            (iterations, links.exact),
        );
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
        // In `Q16`, where the velocities alone carried the particles: a velocity is kept as
        // that velocity plus the solve's correction over `h`, so that what `v h` rounded
        // away (a drag's or gravity's share under a unit of the format) stays in it.
        let predicted = P::Scalar::FIXED_POINT.then_some(state.pos);
        for iteration in 1..=iterations {
            // The last of several iterations, after one that took its whole step, starts near
            // the solution, where a Newton step lowers the stretch: it is taken whole,
            // unmeasured (the check below measures). Far from it (the one before was cut
            // short, as in a whip), it takes the line search too.
            let whole = iteration > 1 && iteration == iterations && links.took_whole;
            links.solve(Sh::flat_mut(&mut state.pos), &mut { w }, whole);
            if super::xpbd::project(model, Sh::flat_mut(&mut state.pos), compliance, 1) {
                links.measured = None;
            } else if self.inextensible && links.exact() {
                break;
            }
        }
        let off = links.off(Sh::flat(&state.pos));
        let converged = off <= tolerance_of(DirectChain::TOLERANCE);
        let (x, v) = (Sh::flat(&state.pos), Sh::flat_mut(&mut state.vel));
        let from = Sh::flat(predicted.as_ref().unwrap_or(&prev));
        for (((v, &x), &p), &w) in v.iter_mut().zip(x).zip(from).zip(w) {
            if w > zero {
                match predicted {
                    Some(_) => *v += (x - p) * inv_h,
                    None => *v = (x - p) * inv_h,
                }
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

/// A tolerance given as `(numerator, denominator)`, in the format.
pub(super) fn tolerance_of<S: Scalar>((n, d): (u32, u32)) -> S {
    S::ratio(n, d)
}

/// Most times a solve is halved, whatever [`DirectChain::halvings`] says: 4 096 solves a
/// share.
const MOST_HALVINGS: u8 = 12;

/// Newton iterations (times 4) a hold after contacts takes at most, for each of a solve's
/// ([`DirectChain::hold_after_contacts`]).
const HOLD_ITERATIONS: u8 = 2;
