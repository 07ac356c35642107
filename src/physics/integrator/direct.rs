//! Every spring of a rope or a cloth solved together: one banded factorisation a solve and a
//! back-substitution an iteration, whatever the stiffness (projective dynamics).

use super::banded::{Factor, Springs};
use super::conjugate::Conjugate;
use super::{Integrator, Model, Solved, State, sealed, split_solves, tiny_length};
use crate::physics::force::ForceField;
use crate::physics::hash::StateHash;
use crate::physics::shape::Shape;
use crate::physics::spring::{Spread, Topology};
use crate::{Point, Scalar};
use core::cell::Cell;

/// The springs of a rope or a cloth solved together by a direct, banded solve: stable at
/// any stiffness with one solve a frame. Made for cloth held along its edges (a sail, a
/// flag, an awning): the boat scene's sail takes one solve a frame where symplectic Euler
/// takes 8 substeps.
///
/// Each solve predicts the motion from gravity, damping and the force fields (`y`), then
/// finds the positions `x` that minimise `½ |x − y|²_M + ½ h² Σ k |xa − xb − p|²`, `p` each
/// spring's direction at its rest length (projective dynamics, Bouaziz et al. 2014; the
/// mass-spring form of Liu et al. 2013). The matrix `M + h² Σ k (ea − eb)(ea − eb)ᵀ` does not
/// depend on the positions; for the springs whose ends are at most
/// [`Shape::BAND`](crate::physics::shape::Shape::BAND) apart in flat order (every spring of a rope or
/// a cloth) it is banded. The system keeps its factor (`LDLᵀ`, no pivoting: the matrix is
/// positive definite) in its [`Factored`] memory and factors again only when the step's
/// length, a mass, a pin or a spring changed (a `hang`, a `release`, a snap, a cut, another
/// `dt`: use [`FixedTimestep`](crate::FixedTimestep) to keep it). The matrix's rows are
/// the free particles only, in the order of a breadth-first walk over the springs,
/// reversed, which keeps their envelopes short (the particles' own order where the walk
/// would put a spring beyond the band). Each iteration (up to `iterations`)
/// points every spring at its rest length from the positions so far (the first from where
/// the velocities alone would carry the particles, so a loaded cloth at rest stays in its
/// balance) and solves for the change of the positions (a forward and a back substitution).
/// A spring wider than the band (a hub, a weld) puts its stiffness on its free ends'
/// diagonals only (a block-Jacobi split: converged iterations reach the same positions). A
/// held particle moves with its hand through the solves and enters them as a fixed end.
/// Velocities are each solve's displacement over its length. Contacts are resolved after
/// each solve, in rounds: after the first, rounds with no time passing follow (no collider
/// moves, friction takes back no sliding) while the last one moved a particle by more than
/// 0.1% of the shortest spring's rest length along an axis ([`TOLERANCE`](super::TOLERANCE)),
/// up to 8 (fewer when two rounds in a row move no less than the one before: contacts
/// pushing against each other); a solve whose rounds still moved a particle that far reports
/// [`converged`](crate::system::StepInfo::converged) `false`. A long solve's pushes are large,
/// and a push on one span moves particles that a span pushed out before is drawn through:
/// with one round, a `DirectSprings` rope pulled round a box by a load went up to 14 times its
/// thickness into the box; with the rounds it stays out (`tests/suite/promises.rs`,
/// `a_load_round_a_box_keeps_a_springy_rope_out_of_it`; a 20 kg load's rope in f32, 600
/// frames: never in the box, 8.1 times the frame without the box, `docs/summary.md`,
/// targets). A frame that touches pays a round more at least, each a pass of the contacts;
/// a rope pressed onto many pegs pays up to 8 (16 pegs 0.1 times its spacing under an
/// 8-particle rope: 16.8 times its bare frame, 3.0 times in the last run before the
/// rounds; section (l)).
///
/// A spring's `damping` `c` acts along it from the velocities at the solve's start, as an
/// explicit force clamped to what stops its ends' closing speed in one solve
/// (`c ≤ 1 / (h (wa + wb))`).
///
/// In floats with more than one iteration, the iterations after the first go along
/// conjugate directions: nonlinear conjugate gradients, preconditioned by the factor, each
/// direction taken as far as the solve's objective curves along it (each spring's
/// stiffness along it, its tension across it). The factor's own step, which is all `Q16`
/// and one iteration take, turns a stiff spring only by about `m / (h² k)` an iteration
/// (projective dynamics' locking), and slows whatever turns stiff springs. Such a solve
/// also never ends with more energy than it started with (motion, gravity and springs,
/// plus the force fields' work, less the drag and the springs' damping): what it would
/// gain is taken from the free particles' velocities.
///
/// Measured (`tests/suite/physics.rs` and `tests/suite/converge.rs`, `direct_springs_*`;
/// `docs/summary.md`, section (j) and its targets):
/// - the boat scene's sail in a steady wind rests within 0.001 mm of the balance
///   symplectic Euler reaches in `f64`, and within 0.008 mm 100 times stiffer (3.1 mm in
///   `Q16`); a hanging rope sags as statics says at every stiffness from 10² to 10⁸ N/m,
///   one substep a frame;
/// - a 1 m, 1 kg cloth held level by two corners under a drag of 2/s, 8×8 and 20×20,
///   at the defaults hangs within 1% of the statics' 1.00 m after 10 s at axial stiffness
///   `EA = 10³` and `10⁴ N` (it hung 0.93 and 0.90 m, 8×8, with the factor's own steps),
///   and comes to rest: no particle moves more than 0.4 mm in its 10th second, where the
///   converged motion (symplectic Euler at 480 Hz) moves 0.18 to 0.34 mm (solves that
///   stopped once within the tolerance, at most 4 iterations, left it creeping 1 to 12 mm);
///   stiffer still, it falls slower. A 1 kg, 8×8 cloth of 900 N/m let go of all but one
///   pin swings down as far as symplectic Euler's in its first half second (102%; 46% with
///   one iteration). A measured solve that stops short says so ([`measure`](Self::measure));
/// - a stiff cloth moves in time: the boat scene's sail 100 times stiffer, in its gusts,
///   stays within 9.5 mm of the fully iterated solve over 10 s, of a 150 mm swing (36 mm
///   behind with solves stopped once within the tolerance, at most 4 iterations);
/// - it damps, as backward Euler does: an undamped released rope keeps 3.7% of its swing's
///   energy over 10 s (7.6% and 9.4% with a bob of 1 and 10 times its mass), where the
///   converged solve keeps 3.7%, 7.7% and 9.8%, against 96% for symplectic Euler; with
///   [`keep_energy`](Self::keep_energy) it keeps it whole. For a rope under a heavy bob,
///   use [`DirectChain`](super::DirectChain) (a 10 kg bob on a 1 kg rope of 10⁵ N/m
///   stretches it 2.0% here).
///
/// Cost per solve, `n` particles of which `f` free, and band `b` (2 for a rope, `2U` for a
/// cloth): a factor, when something changed, of two passes over the springs, a walk of
/// about `n·2b` steps and about `f·b²/2` multiply-adds; per iteration a square root and a
/// division a spring and `2·e` vector multiply-adds, `e ≤ f·b` the entries of the rows'
/// envelopes (each row from its first spring), and the measure, a pass over the springs
/// after each; along conjugate directions, another pass over the springs (a division
/// each) and three passes over the particles an iteration, and two passes over the
/// springs a solve for the energy. Unmeasured, the same at every stiffness; measured, from
/// 1 iteration where they converge at once to `iterations` where they do not: the boat
/// sail 100 times stiffer in its gusts, its solves taking up to all 16 iterations to keep
/// pace, costs 3.56 times its frame at its own stiffness (1.93 times with at most 4, in
/// slow motion), and a 30-particle rope of axial stiffness 1 000 N swinging costs 3.72
/// times symplectic Euler's frame (1.28 times with at most 4; `docs/summary.md`, section
/// (j) and its targets). A topology that lists its
/// springs in runs ([`Topology::for_each_run`]: a cloth's rows) has each run's numbers
/// taken once. On a Cortex-M4F the 8×8 sail (band 16, 42 particles free, 378 entries),
/// with one iteration unmeasured, takes about 58 000 instructions a step, 43 000 of them
/// the iteration, and 124 000 more for a new factor (`examples/mcu_sail.rs`); its frame
/// takes 98 800 on average, 132 900 measured and 274 700 at the defaults (along conjugate
/// directions; 264 700 with at most 4 iterations). Memory: the factor, the masses, the envelopes and the rows' particles,
/// `n·(b + 2)` scalars, `n` 16-bit counts and `n` 32-bit indices in the system (5.0 KB for
/// the 8×8 sail in `f32`), and about `n·10` scalars of stack in 3D.
///
/// ```
/// use dunas::integrator::DirectSprings;
/// use dunas::prelude::*;
/// // A stiff rope (10⁵ N/m) let go level from its pin, one solve a frame, its swing kept.
/// let solver = DirectSprings { keep_energy: true, ..DirectSprings::default() };
/// let settings = Settings { gravity: Vec2::new(0.0, -9.81), ..Settings::default() }
///     .with_integrator(solver);
/// let material = Material { stiffness: 1e5, damping: 0.0 };
/// let mut rope: Rope<Vec2<f64>, 8, 8, DirectSprings> =
///     Rope::new(Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), 1.0, material, settings)?;
/// // Level and still, its energy is 0; hanging at rest it would be about −4.9 J.
/// for _ in 0..120 {
///     let info = rope.step(1.0 / 60.0)?;
///     assert_eq!(info.substeps, 1);
/// }
/// // Two seconds on, the rope swings through with the energy it had.
/// assert!(rope.energy().abs() < 0.01 * 4.9, "{}", rope.energy());
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DirectSprings {
    /// Most iterations a solve (16 by default; 0 counts as 1), each a spring direction
    /// update and a back-substitution; in floats, from 2 on, along conjugate directions
    /// (see the type's docs). With [`measure`](Self::measure), a solve stops as soon as it
    /// is done (see there): a soft or resting cloth stops after a few, a stiff one in
    /// motion may take all of them (the default was 4 before: a stiff cloth then moved in
    /// slow motion).
    pub iterations: u8,
    /// Whether each solve measures how far it ended from its equations (`true` by
    /// default): what each free particle still owes to them (its force imbalance times
    /// `h²` over its mass), over the shortest rest length of a spring with a free end. A
    /// solve stops once that is within [`TOLERANCE`](super::TOLERANCE) (0.1%) and either at
    /// most half of the farthest it moved a particle along an axis this step (it keeps pace
    /// with the motion: what it leaves would otherwise slow the motion, and keep a cloth
    /// creeping towards its balance long after it should rest) or more than half of what
    /// the iteration before left (it stalled, as at rest in the format's rounding); and once
    /// it is within a 64th of the tolerance. One that reaches `iterations` beyond the
    /// tolerance reports it in [`StepInfo::converged`](crate::system::StepInfo::converged)
    /// and [`StepInfo::residual`](crate::system::StepInfo::residual). The measure is a pass
    /// over the springs (a square root and a division each) and one over the particles
    /// after each iteration: the boat scene's sail on a Cortex-M4F, one iteration a solve,
    /// takes 132 900 instructions a frame measured and 98 800 unmeasured
    /// (`examples/mcu_sail.rs`). Unmeasured, a solve takes all its `iterations` and reports
    /// `converged` with a residual of 0.
    pub measure: bool,
    /// Solves a step, each of an equal share of it (1 by default); 0 counts as 1.
    pub substeps: u8,
    /// Gives back, after each solve, the energy its own damping took from the motion
    /// (`false` by default): the free particles' velocities are scaled, by a factor from 0
    /// to 2, so that the motion's energy (their motion, gravity and the springs, as
    /// [`MassSpring::energy`](crate::MassSpring::energy) counts it) is what it was at the
    /// solve's start plus the work of the force fields and the drag of
    /// [`Settings::damping`](crate::Settings::damping), less what the springs' damping
    /// takes; what a solve cannot give back (its particles nearly still) is owed to the
    /// next. Measured (`tests/suite/physics.rs`, `direct_springs_keep_energy_*`): an undamped
    /// released rope keeps its swing's energy within 1% over 10 s, with a bob of up to 10
    /// times its mass too (3.7% without); a bob on a spring loses its energy to drag as
    /// `e^(−γ t)` says within 15% over 4 s; the boat scene's sail rests within 0.002 mm of
    /// its balance; with a drag of 0.1/s the released rope keeps 39% of its swing over 10 s
    /// (symplectic Euler 35%, Verlet 41%: `docs/summary.md`, section (j)). The motion it
    /// keeps is livelier where stiff springs turn: a heavy bob stretches its rope as
    /// symplectic Euler's does. Costs two passes over the springs more a solve, a square
    /// root a spring each, where the iterations are the factor's own; along conjugate
    /// directions (floats, the defaults) those passes are taken anyway, but the livelier
    /// swing it keeps takes more iterations a solve to keep pace with (the undamped
    /// 8-particle rope's frame 1.7 times as dear: `docs/summary.md`, section (j)).
    pub keep_energy: bool,
}

impl Default for DirectSprings {
    /// One measured solve a step of at most 16 iterations, its damping kept.
    fn default() -> Self {
        DirectSprings {
            iterations: 16,
            substeps: 1,
            measure: true,
            keep_energy: false,
        }
    }
}

impl sealed::Sealed for DirectSprings {}

impl Integrator for DirectSprings {
    type Memory<S: Scalar, Sh: Shape> = Factored<S, Sh>;

    fn memory<S: Scalar, Sh: Shape>() -> Factored<S, Sh> {
        Factored {
            key: None,
            mass: Sh::filled(S::ZERO),
            factor: Factor::default(),
            owed: S::ZERO,
        }
    }

    fn stability_limit<S: Scalar>(&self) -> Option<S> {
        None
    }

    fn force_evaluations(&self) -> u32 {
        u32::from(self.substeps.max(1))
    }

    /// The energy a solve with [`keep_energy`](Self::keep_energy) owes to the next (the
    /// factor is made again from the state and the step).
    fn hash_memory<S: Scalar, Sh: Shape>(memory: &Factored<S, Sh>, hash: &mut StateHash) {
        hash.add_scalar(memory.owed);
    }

    fn substep<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool {
        let memory = &mut Self::memory();
        let times = (h, P::Scalar::ZERO);
        self.substep_touching(model, state, memory, times, forces, &mut |_, _| {})
            .fits
    }

    /// Each solve ends with the contacts.
    fn substep_touching<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        memory: &mut Factored<P::Scalar, Sh>,
        (h, lag): (P::Scalar, P::Scalar),
        forces: &mut F,
        touch: &mut impl FnMut(&mut State<P, Sh>, (P::Scalar, P::Scalar)),
    ) -> Solved<P::Scalar> {
        let solve = |state: &mut State<P, Sh>, hs, forces: &mut F| {
            if self.keep_energy || self.conjugate::<P::Scalar>() {
                self.solve_keeping(model, state, memory, hs, forces)
            } else {
                self.solve(model, state, memory, hs, forces, (None, None))
            }
        };
        let mut agreed = true;
        let mut touch = |state: &mut State<P, Sh>, times: (P::Scalar, P::Scalar)| {
            agreed &= super::rounds::contact_rounds(model, state, times, touch);
        };
        let (times, n) = ((h, lag), self.substeps);
        let mut solved = split_solves(n, model, state, times, forces, &mut touch, solve);
        solved.converged &= agreed;
        solved
    }
}

/// What [`DirectSprings`] keeps inside its system between steps: the factor of its last
/// matrix, the masses it was built with, and a 64-bit key of what made it (the step's
/// length, every inverse mass, the springs' [`fingerprint`](Topology::fingerprint)). A step
/// whose key is the same solves with the factor kept; any change (a pin, a hang, a snap or
/// a cut, another `dt`) factors again.
pub struct Factored<S: Scalar, Sh: Shape> {
    key: Option<u64>,
    /// Each free particle's mass (0 for a held one).
    mass: Sh::PerParticle<S>,
    factor: Factor<S, Sh>,
    /// The energy a solve with [`DirectSprings::keep_energy`] could not give back (its
    /// particles nearly still), owed to the next.
    owed: S,
}

impl<S: Scalar, Sh: Shape> Clone for Factored<S, Sh> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S: Scalar, Sh: Shape> Copy for Factored<S, Sh> {}

impl<S: Scalar, Sh: Shape> core::fmt::Debug for Factored<S, Sh> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Factored").field("key", &self.key).finish()
    }
}

/// `key` with `x` mixed in (two 32-bit multiply-rotate lanes: cheap on a Cortex-M0).
#[inline]
fn mix(key: u64, x: u64) -> u64 {
    let a = ((key as u32) ^ (x as u32))
        .wrapping_mul(0x9E37_79B1)
        .rotate_left(15);
    let b = ((key >> 32) as u32 ^ (x >> 32) as u32 ^ a)
        .wrapping_mul(0x85EB_CA77)
        .rotate_left(13);
    (u64::from(b) << 32) | u64::from(a)
}

impl<S: Scalar, Sh: Shape> Factored<S, Sh> {
    /// Builds the matrix `M + h² Σ k (ea − eb)(ea − eb)ᵀ` of `model`'s springs and factors
    /// it ([`Factor::build`]), `weight(k)` a spring's `h² k`.
    fn factor_springs<P: Point<Scalar = S>, T: Topology<S>>(
        &mut self,
        model: &Model<'_, P, Sh, T>,
        weight: impl Fn(S) -> S,
    ) {
        let zero = S::ZERO;
        let w = model.inv_mass();
        let mass = Sh::flat_mut(&mut self.mass);
        for (m, &w) in mass.iter_mut().zip(w) {
            *m = if w > zero { S::ONE / w } else { zero };
        }
        let springs = Weighted {
            topology: model.topology,
            weight,
        };
        self.factor
            .build(|i| w[i] > zero, Sh::flat(&self.mass), &springs);
    }
}

/// A topology's springs of some stiffness, each weighed by `weight` (its `h² k`).
struct Weighted<'a, T, W> {
    topology: &'a T,
    weight: W,
}

impl<S: Scalar, T: Topology<S>, W: Fn(S) -> S> Springs<S> for Weighted<'_, T, W> {
    fn each(&self, mut f: impl FnMut(usize, usize, S)) {
        self.topology.for_each_run(|a, b, count, _, m| {
            if a != b && m.stiffness > S::ZERO {
                let k = (self.weight)(m.stiffness);
                for i in 0..count {
                    f(a + i, b + i, k);
                }
            }
        });
    }
}

impl DirectSprings {
    /// [`solve`](Self::solve), along conjugate directions where
    /// [`conjugate`](Self::conjugate), then the energy its damping took given back (see
    /// [`keep_energy`](Self::keep_energy)), or without it what the solve gained taken
    /// away; its own function, so that a plain solve keeps no room on the stack for the
    /// start's positions, the forces and the directions.
    #[inline(never)]
    fn solve_keeping<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        memory: &mut Factored<P::Scalar, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> Solved<P::Scalar> {
        // The motion's energy at the start, less what the springs' damping takes over the
        // solve, plus what earlier solves owe; where the particles started.
        let (x, v) = (Sh::flat(&state.pos), Sh::flat(&state.vel));
        let e0 = model.energy_less_damping(x, v, h, false) + memory.owed;
        let x0 = state.pos;
        let mut pushes = Sh::filled(P::default());
        let mut conjugate = self.conjugate::<P::Scalar>().then(Conjugate::new);
        let outputs = (Some(&mut pushes), conjugate.as_mut());
        let ok = self.solve(model, state, memory, h, forces, outputs);
        let (start, mass) = ((Sh::flat(&x0), e0), Sh::flat(&memory.mass));
        let most = if self.keep_energy { 2 } else { 1 };
        let left = give_back(model, state, start, Sh::flat(&pushes), (mass, most));
        memory.owed = if self.keep_energy {
            left
        } else {
            P::Scalar::ZERO
        };
        ok
    }

    /// Whether a solve's iterations go along conjugate directions (floats, more than one
    /// iteration: see [`iterations`](Self::iterations)).
    fn conjugate<S: Scalar>(&self) -> bool {
        !S::FIXED_POINT && self.iterations > 1
    }

    /// One solve; the accelerations of its forces copied into `pushes` when asked, its
    /// iterations along `conjugate`'s directions when given.
    fn solve<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        memory: &mut Factored<P::Scalar, Sh>,
        h: P::Scalar,
        forces: &mut F,
        (pushes, mut conjugate): Extras<'_, P, Sh>,
    ) -> Solved<P::Scalar> {
        let zero = P::Scalar::ZERO;
        let w = model.inv_mass();
        // `h² k` as `(k h) h`: in `Q16`, `h²` of a frame is below the format's resolution.
        let weight = |k: P::Scalar| k * h * h;
        // The key of the matrix: the step's length, every inverse mass and the springs.
        let mut masses = Spread::default();
        for &w in w {
            masses.add(w.bits());
        }
        let key = mix(mix(0, h.bits()), masses.sum());
        let key = model.topology.fingerprint(key, mix);
        if memory.key != Some(key) {
            memory.factor_springs(model, weight);
            memory.key = Some(key);
        }
        // The prediction `y = x + (v + a h) h`, kept as its gap to the positions so far
        // times the masses (`M a h²` at first), in the right-hand side's own array. The
        // positions start where the velocities alone would carry the particles: at rest
        // under a steady load those are the directions of the balance, so that even one
        // iteration keeps it (from `y`, every spring would lean by `h² a`). A held particle
        // stays where its hand put it (its acceleration and its mass here are 0).
        let mut rhs = Sh::filled(P::default());
        let mut ok = model.accelerations(
            Sh::flat(&state.pos),
            Sh::flat(&state.vel),
            forces,
            Sh::flat_mut(&mut rhs),
            false,
        );
        if let Some(pushes) = pushes {
            *pushes = rhs;
        }
        let h2 = h * h;
        let mass = Sh::flat(&memory.mass);
        {
            let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat(&state.vel));
            let particles = x
                .iter_mut()
                .zip(Sh::flat_mut(&mut rhs))
                .zip(v.iter().zip(mass));
            for ((x, r), (&v, &m)) in particles {
                if m > zero {
                    *x += v * h;
                    *r = *r * h2 * m;
                }
            }
        }
        let inv_h = P::Scalar::ONE / h;
        let fixed = P::Scalar::FIXED_POINT;
        let cap = self.iterations.max(1);
        // Each iteration after the first starts from the gap again: a copy, only then.
        let mut gap = if cap > 1 || self.measure {
            Some(rhs)
        } else {
            None
        };
        let mut solved = Sh::filled(P::default());
        // What the residual is measured against, and how far the particles ended from the
        // solve's equations.
        let shortest = self.measure.then(|| model.shortest_rest());
        let mut solved_as = None;
        let mut before = None;
        // Unmeasured, `cap` passes over the springs, each followed by a solve; measured, one
        // more that measures the last solve's result.
        let passes = u16::from(cap) + u16::from(self.measure);
        for iteration in 0..passes {
            // The right-hand side at the positions so far: `M (y − x)` and each spring's
            // pull at `x`, the solve's equations' imbalance. A held particle is no row of the
            // solve, so pulls are added to both ends unchecked.
            if let (Some(gap), true) = (&gap, iteration > 0) {
                rhs = *gap;
            }
            let r = Sh::flat_mut(&mut rhs);
            let (x, v) = (Sh::flat(&state.pos), Sh::flat(&state.vel));
            // The sums as cells: a run's two ends may step through the same particles.
            let sums = Cell::from_mut(&mut *r).as_slice_of_cells();
            let n = x.len().min(v.len()).min(w.len()).min(sums.len());
            model.topology.for_each_run(|a, b, count, rest, m| {
                // Its own constant: one captured by reference is loaded again each spring.
                let zero = P::Scalar::ZERO;
                if !(m.stiffness > zero && a.max(b).saturating_add(count) <= n) {
                    return;
                }
                let (from_a, from_b) = (a..a + count, b..b + count);
                let (xa, xb) = (&x[from_a.clone()], &x[from_b.clone()]);
                let (va, vb) = (&v[from_a.clone()], &v[from_b.clone()]);
                let (wa, wb) = (&w[from_a.clone()], &w[from_b.clone()]);
                let (ra, rb) = (&sums[from_a], &sums[from_b]);
                let (k, ch) = (weight(m.stiffness), m.damping * h);
                // The damping's clamp (below) bites for `wa + wb > 1 / (h c)`: that bound
                // once a run, not a product a spring.
                let (chh, clamp) = (ch * h, (ch > zero).then(|| P::Scalar::ONE / ch));
                let ends = xa.iter().zip(xb).zip(va.iter().zip(vb));
                let weights = wa.iter().zip(wb).zip(ra.iter().zip(rb));
                for (((&xa, &xb), (&va, &vb)), ((&wa, &wb), (ra, rb))) in ends.zip(weights) {
                    // A spring between held ends pulls nothing; one from a particle to
                    // itself has no length (below).
                    let wsum = wa + wb;
                    if wsum <= zero {
                        continue;
                    }
                    // The spring's pull from the positions so far: stiffness towards its
                    // rest length, and its damping as an explicit force along it, at most
                    // what stops its ends' closing speed in one solve (`h² c` up to
                    // `h / (wa + wb)`).
                    let d = xa - xb;
                    let l = d.length();
                    if l <= tiny_length::<P::Scalar>() {
                        continue;
                    }
                    let c = match clamp {
                        Some(most) if wsum > most => h / wsum,
                        _ => chh,
                    };
                    let inv = P::Scalar::ONE / l;
                    let closing = (va - vb).dot(d) * inv;
                    let pull = d * ((k * (rest - l) - c * closing) * inv);
                    ra.set(ra.get() + pull);
                    rb.set(rb.get() - pull);
                }
            });
            if fixed {
                ok &= r.iter().zip(w).all(|(r, &w)| w <= zero || r.is_finite());
            }
            if let (Some(shortest), true) = (shortest, iteration > 0) {
                // What a free particle still owes: its imbalance over its mass.
                let measured = model.solved(ok, r, P::Scalar::ONE, shortest);
                solved_as = Some(measured);
                let moved = shortest.map_or(zero, |s| largest_move(state, w, h) / s);
                if iteration == u16::from(cap) || enough(measured, moved, before) {
                    break;
                }
                before = Some(measured.residual);
            }
            // The change of each free particle (a held one's is 0), in the rows' order: the
            // solve's, or a length along the conjugate direction made from it.
            let factor = &memory.factor;
            let rows = factor.particles();
            let mut change = factor.solve(r, Sh::flat_mut(&mut solved));
            let mut length = P::Scalar::ONE;
            if let Some(conjugate) = conjugate.as_deref_mut() {
                let x = Sh::flat(&state.pos);
                length = conjugate.turn(model, (x, r), (change, rows), mass, h);
                change = Sh::flat(&conjugate.direction);
            }
            let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat_mut(&mut state.vel));
            for (&p, &dx) in rows.iter().zip(change) {
                let (p, dx) = (p as usize, dx * length);
                if let (Some(x), Some(v)) = (x.get_mut(p), v.get_mut(p)) {
                    *x += dx;
                    *v += dx * inv_h;
                }
            }
            if iteration + 1 == passes {
                break;
            }
            if let Some(gap) = &mut gap {
                let g = Sh::flat_mut(gap);
                for (&p, &dx) in rows.iter().zip(change) {
                    let p = p as usize;
                    if let (Some(g), Some(&m)) = (g.get_mut(p), mass.get(p)) {
                        *g -= dx * (length * m);
                    }
                }
            }
        }
        solved_as.unwrap_or(Solved::plain(ok))
    }
}

/// Whether a measured solve is done ([`DirectSprings::measure`]), having `measured` its
/// equations, moved a particle by `moved` along an axis (over the shortest rest length, as
/// the residual) and left `before` at the iteration before: within a 64th of
/// [`TOLERANCE`](super::TOLERANCE), or within it and either keeping pace with the motion
/// (leaving at most half of `moved`) or stalled (leaving more than half of `before`).
fn enough<S: Scalar>(measured: Solved<S>, moved: S, before: Option<S>) -> bool {
    let (n, d) = super::TOLERANCE;
    let r = measured.residual;
    let still = r <= S::ratio(n, d * 64);
    let paced = r + r <= moved;
    let stalled = before.is_some_and(|b| r + r > b);
    still || (measured.converged && (paced || stalled))
}

/// The farthest a free particle (`w` its inverse mass, 0 for a held one) moved along an axis
/// over a solve of `h` so far: its velocity's largest coordinate times `h` (`x − x₀ = v h`).
fn largest_move<P: Point, Sh: Shape>(
    state: &State<P, Sh>,
    w: &[P::Scalar],
    h: P::Scalar,
) -> P::Scalar {
    let mut fastest = P::Scalar::ZERO;
    for (v, &w) in Sh::flat(&state.vel).iter().zip(w) {
        if w > P::Scalar::ZERO {
            for axis in 0..P::DIM {
                fastest = fastest.max(v.coord(axis).abs());
            }
        }
    }
    fastest * h
}

/// Where a solve keeps what it is asked for beyond the state: its forces' accelerations
/// ([`DirectSprings::keep_energy`]) and its conjugate directions.
type Extras<'a, P, Sh> = (
    Option<&'a mut <Sh as Shape>::PerParticle<P>>,
    Option<&'a mut Conjugate<P, Sh>>,
);

/// Scales the free particles' velocities so that the motion's energy is back to `e0` (the
/// start's, less the springs' damping, plus what is owed), plus the work of the forces in
/// the accelerations `a` (gravity's part is in the energy) from the start `x0` (`mass` each
/// particle's, 0 for a held one), by a factor from 0 to `most`; returns what that could not
/// give back (0 when a figure is not finite).
fn give_back<P: Point, Sh: Shape, T: Topology<P::Scalar>>(
    model: &Model<'_, P, Sh, T>,
    state: &mut State<P, Sh>,
    (x0, e0): (&[P], P::Scalar),
    a: &[P],
    (mass, most): (&[P::Scalar], i16),
) -> P::Scalar {
    let (zero, one, half) = (P::Scalar::ZERO, P::Scalar::ONE, P::Scalar::ratio(1, 2));
    let (mut work, mut kinetic) = (zero, zero);
    let (x, v) = (Sh::flat(&state.pos), Sh::flat(&state.vel));
    let particles = x.iter().zip(x0).zip(v.iter().zip(a).zip(mass));
    for ((&x, &x0), ((&v, &a), &m)) in particles {
        if m > zero {
            work += ((a - model.gravity) * m).dot(x - x0);
            kinetic += half * m * v.dot(v);
        }
    }
    let missing = e0 + work - model.energy(x, v, false);
    if !(missing.is_finite() && kinetic > zero) {
        return if missing.is_finite() { missing } else { zero };
    }
    let scale = (one + missing / kinetic)
        .max(zero)
        .sqrt()
        .min(P::Scalar::from_i16(most));
    if !scale.is_finite() {
        return zero;
    }
    for (v, &m) in Sh::flat_mut(&mut state.vel).iter_mut().zip(mass) {
        if m > zero {
            *v = *v * scale;
        }
    }
    let left = missing - kinetic * (scale * scale - one);
    if left.is_finite() { left } else { zero }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Material;
    use crate::physics::grid_springs::GridSprings;
    use crate::physics::shape::Grid;

    /// The boat scene's sail (8×8, its luff, head and foot held, every spring in the band):
    /// its 42 free particles' rows hold at most 378 entries in the walk's order, where the
    /// particles' own order (every row but the held ones', from its first spring) holds 458.
    #[test]
    fn the_walk_shortens_the_sails_envelopes() {
        type Sh = Grid<8, 8>;
        let m = Material {
            stiffness: 900.0,
            damping: 0.6,
        };
        let springs = GridSprings::<f64, 8, 8>::new(0.4, 0.5, [0.6, 0.6], [m; 3]);
        let held = |i: usize| i.is_multiple_of(8) || !(8..56).contains(&i);
        let mass: [f64; 64] = core::array::from_fn(|i| if held(i) { 0.0 } else { 0.03 });
        let weighted = Weighted {
            topology: &springs,
            weight: |k: f64| k / 3600.0,
        };
        let mut factor = Factor::<f64, Sh>::default();
        factor.build(|i| !held(i), &mass, &weighted);
        assert_eq!(factor.particles().len(), 42);
        let mut own = 0;
        let mut first = [usize::MAX; 64];
        weighted.each(|a, b, _| {
            if !held(a) && !held(b) {
                let (i, j) = (a.max(b), a.min(b));
                first[i] = first[i].min(j);
            }
        });
        // The particles' own order, the held ones left out: a row's first column is its
        // first joined particle's place among the free ones.
        let place = |p: usize| (0..p).filter(|&q| !held(q)).count();
        for i in (0..64).filter(|&i| !held(i) && first[i] != usize::MAX) {
            own += place(i) - place(first[i]);
        }
        assert_eq!(own, 458);
        let walked = factor.entry_count();
        assert!(walked <= 378, "{walked} entries");
    }
}
