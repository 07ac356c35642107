//! Time integrators: one type each, all behind the [`Integrator`] trait.
//!
//! A system names its integrator by type (`MassSpring<P, Shape, Topology, Verlet>`), so a
//! device image links that one method and nothing else. [`AnyIntegrator`] is the run-time
//! choice, for tools that compare methods or load them from a file; it links all eight.
//!
//! `ω` is the highest angular frequency of the spring network and `h` the substep.
//! [`MassSpring::step`](crate::MassSpring::step) bounds `ω` from the springs and masses
//! (Gershgorin: `ω² ≤ max_i w_i · Σ_{springs at i} k·(1 + [other end free])`, damping
//! added the same way) and splits each frame into enough substeps that `ω·h` stays at the
//! [`Accuracy`](crate::Accuracy)'s fraction of the method's limit.
//!
//! | integrator | `ω·h` limit | force evaluations per substep | energy | notes |
//! |---|---|---|---|---|
//! | [`ExplicitEuler`] | none: grows at any `h` without damping | 1 | gains | the textbook reference; substeps keep `ω·h ≤ 0.1` |
//! | [`SymplecticEuler`] | 2 | 1 | bounded | the default: cheapest stable method |
//! | [`Verlet`] | 2 | 2 | bounded | velocity Verlet, second order |
//! | [`Rk4`] | 2√2 ≈ 2.83 | 4 | slowly loses | fourth order, the accurate choice |
//! | [`ImplicitEuler`] | unconditionally stable | 1 + `iterations` Jacobian products | loses (damps high frequencies) | matrix-free conjugate gradient, no heap |
//! | [`Xpbd`] | unconditionally stable | 1 per XPBD substep + one projection per spring, and a pass over the springs to measure | loses a little | springs as compliant distance constraints (Macklin et al. 2016, 2019) |
//! | [`DirectChain`] | unconditionally stable, one substep a frame | 1 + `iterations` direct solves along the chain | loses where links stretch | a rope's links solved together, exactly: inextensible, or its springs at any stiffness |
//! | [`DirectSprings`] | unconditionally stable, one substep a frame | 1 + up to `iterations` banded back-substitutions and measures, one factorisation | loses (damps as backward Euler) | every spring of a rope or cloth solved together (projective dynamics): a sail at one solve a frame |
//!
//! The methods that iterate ([`ImplicitEuler`], [`Xpbd`], [`DirectChain`],
//! [`DirectSprings`]) say how far each step ended from their equations
//! ([`StepInfo::converged`](crate::system::StepInfo::converged) and
//! [`residual`](crate::system::StepInfo::residual), against [`TOLERANCE`]); a step is kept
//! either way.
//!
//! Per spring, a force evaluation costs one square root, one division and about 20
//! multiply-adds; per particle, about 6 operations.

mod banded;
mod chain;
mod conjugate;
mod direct;
mod euler;
mod implicit;
mod links;
mod model;
mod rk4;
mod rounds;
mod verlet;
mod xpbd;

use core::fmt::Debug;

pub use chain::DirectChain;
pub use direct::{DirectSprings, Factored};
pub use euler::{ExplicitEuler, SymplecticEuler};
pub use implicit::ImplicitEuler;
pub(crate) use implicit::solve_scale;
pub use model::{Model, State};
pub(crate) use model::{SubstepEnd, tiny_length};
pub use rk4::Rk4;
pub use verlet::Verlet;
pub use xpbd::Xpbd;

use crate::physics::force::ForceField;
use crate::physics::hash::StateHash;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// Where an iterating solve stops, as a fraction: a link within 0.1% of its length
/// ([`DirectChain`]), or a solve whose particles owe less than 0.1% of the shortest
/// spring's rest length to its equations ([`DirectSprings`], [`ImplicitEuler`], [`Xpbd`]:
/// [`StepInfo::residual`](crate::system::StepInfo::residual)).
pub const TOLERANCE: (u32, u32) = (1, 1000);

mod sealed {
    pub trait Sealed {}
}

/// A way to advance a mass-spring system by one substep. Implemented by the eight method
/// types of this module and by [`AnyIntegrator`]; sealed, so that every method's stability
/// limit is known to the substep planner.
///
/// ```
/// use dunas::{MassSpring, Settings, Vec2, integrator::Verlet, shape::Line, spring::{Material, Springs}};
/// let pos = [Vec2::new(0.0f32, 0.0), Vec2::new(1.0, 0.0)];
/// let springs = Springs::<f32, 1>::chain(&pos, Material { stiffness: 100.0, damping: 0.1 })?;
/// let settings = Settings { damping: 0.1, ..Settings::default() }.with_integrator(Verlet);
/// let mut s: MassSpring<_, Line<2>, _, Verlet> = MassSpring::new(pos, [0.0, 1.0], springs, settings)?;
/// s.step(1.0 / 60.0)?;
/// # Ok::<(), dunas::Error>(())
/// ```
pub trait Integrator: sealed::Sealed + Copy + Debug + Default + PartialEq {
    /// What the method keeps inside its system from one step to the next: `()` for every
    /// method but [`DirectSprings`] (and [`AnyIntegrator`]), which keeps its factor.
    type Memory<S: Scalar, Sh: Shape>: Copy;

    /// The memory of a system that has not stepped yet.
    fn memory<S: Scalar, Sh: Shape>() -> Self::Memory<S, Sh>;

    /// The largest stable `ω·h` for an undamped spring; `None` when the method is stable at
    /// any step. Explicit Euler, unstable at every step, reports `1/9` so that the substep
    /// planner keeps it at `ω·h ≤ 0.1` (it then gains at most 0.5% energy per substep).
    fn stability_limit<S: Scalar>(&self) -> Option<S>;

    /// Force evaluations per substep.
    fn force_evaluations(&self) -> u32;

    /// Advances `state` by `h` seconds under `model`'s forces and `forces`. Returns `false`
    /// when a `Q16` force saturated on the way (reported in the step's `StepInfo`).
    fn substep<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool;

    /// [`substep`](Self::substep) with the system's `memory`, then `touch(state, (h, lag))`
    /// (the contacts of a step that resolves them, `lag` seconds before the frame ends). A
    /// method that splits its substep into shorter solves resolves the contacts after each
    /// of them, with their own length and lag. Returns whether the forces fitted, whether
    /// an iterating solve reached its tolerance and the held links' stretch ([`Solved`]).
    #[allow(clippy::too_many_arguments)]
    fn substep_touching<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        memory: &mut Self::Memory<P::Scalar, Sh>,
        (h, lag): (P::Scalar, P::Scalar),
        forces: &mut F,
        touch: &mut impl FnMut(&mut State<P, Sh>, (P::Scalar, P::Scalar)),
    ) -> Solved<P::Scalar> {
        let _ = memory;
        let solved = self.substep_solved(model, state, h, forces);
        touch(state, (h, lag));
        solved
    }

    /// [`substep`](Self::substep), reporting how far an iterating solve ended from its
    /// equations ([`Solved`]); a method that does not iterate reports it converged.
    fn substep_solved<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> Solved<P::Scalar> {
        Solved::plain(self.substep(model, state, h, forces))
    }

    /// Adds to `hash` what of `memory` shapes the steps to come (for
    /// [`MassSpring::state_hash`](crate::MassSpring::state_hash)): nothing for the methods
    /// that keep nothing, or keep only what the state and the step make again (a factor).
    fn hash_memory<S: Scalar, Sh: Shape>(memory: &Self::Memory<S, Sh>, hash: &mut StateHash) {
        let _ = (memory, hash);
    }

    /// `true` when the method holds each link of a chain (the spring from particle `i` to
    /// `i + 1`) at its rest length as a constraint rather than a spring: an inextensible
    /// [`DirectChain`]. Such links store no energy
    /// ([`MassSpring::energy`](crate::MassSpring::energy)), and a step measures how far
    /// they ended from their length ([`StepInfo::stretch`](crate::system::StepInfo::stretch)).
    fn holds_links(&self) -> bool {
        false
    }
}

/// What a substep did, for its step's [`StepInfo`](crate::system::StepInfo).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solved<S> {
    /// `false` when a `Q16` force saturated on the way.
    pub fits: bool,
    /// `false` when an iterating solve ended beyond its tolerance after its last iteration
    /// and its last halving, or a held link ended beyond it (see [`DirectChain`]); `true`
    /// for methods that do not iterate.
    pub converged: bool,
    /// For a method that [holds its links](Integrator::holds_links): the largest
    /// `|length − rest| / rest` of a link at the substep's end, after its contacts; 0
    /// otherwise.
    pub stretch: S,
    /// How far an iterating solve ended from its equations, as a fraction of a length
    /// (see [`StepInfo::residual`](crate::system::StepInfo::residual)); 0 for methods
    /// that do not iterate.
    pub residual: S,
}

impl<S: Scalar> Solved<S> {
    /// A substep that did not iterate: `fits`, converged, no stretch.
    pub fn plain(fits: bool) -> Self {
        Solved {
            fits,
            converged: true,
            stretch: S::ZERO,
            residual: S::ZERO,
        }
    }

    /// This substep and then `later`: each flag holds only if it held in both; the stretch
    /// is `later`'s, the one at the end; the residual the larger.
    #[must_use]
    pub fn then(self, later: Solved<S>) -> Solved<S> {
        Solved {
            fits: self.fits & later.fits,
            converged: self.converged & later.converged,
            stretch: later.stretch,
            residual: self.residual.max(later.residual),
        }
    }
}

/// A fresh memory of `method`'s kind (`()` for all but [`DirectSprings`]).
fn memory_of<I: Integrator, S: Scalar, Sh: Shape>(_: &I) -> I::Memory<S, Sh> {
    I::memory()
}

/// Splits a step of `h` seconds into `substeps` equal solves (0 counts as 1), each
/// `solve(state, hs, forces)` followed by the contacts, `touch(state, (hs, lag))`. A held
/// particle is at its hand's place at the end of the frame, moving at the hand's velocity:
/// before each solve it is put where the hand was then (`lag` plus the solves left short of
/// the frame's end), so it moves through the solves and through the system's substeps; it is
/// back at the hand's place at the end.
fn split_solves<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
    substeps: u8,
    model: &Model<'_, P, Sh, T>,
    state: &mut State<P, Sh>,
    (h, lag): (P::Scalar, P::Scalar),
    forces: &mut F,
    touch: &mut impl FnMut(&mut State<P, Sh>, (P::Scalar, P::Scalar)),
    mut solve: impl FnMut(&mut State<P, Sh>, P::Scalar, &mut F) -> Solved<P::Scalar>,
) -> Solved<P::Scalar> {
    let n = substeps.max(1);
    if n == 1 && lag == P::Scalar::ZERO {
        // One solve at the frame's end: the held particles are where their hands put them
        // already, and the step puts them back there at its end (no copy of the positions).
        let ok = solve(state, h, forces);
        touch(state, (h, lag));
        return ok;
    }
    // One solve takes the whole step (a division spared: 200 instructions on a Cortex-M0).
    let hs = if n == 1 {
        h
    } else {
        h / P::Scalar::from_i16(i16::from(n))
    };
    let end = state.pos;
    let w = model.inv_mass();
    let mut ok = Solved::plain(true);
    for left in (0..n).rev() {
        let behind = lag + hs * P::Scalar::from_i16(i16::from(left));
        let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat(&state.vel));
        for (((x, &end), &v), &w) in x.iter_mut().zip(Sh::flat(&end)).zip(v).zip(w) {
            if w <= P::Scalar::ZERO {
                *x = end - v * behind;
            }
        }
        ok = ok.then(solve(state, hs, forces));
        touch(state, (hs, behind));
    }
    let x = Sh::flat_mut(&mut state.pos);
    for ((x, &end), &w) in x.iter_mut().zip(Sh::flat(&end)).zip(w) {
        if w <= P::Scalar::ZERO {
            *x = end;
        }
    }
    ok
}

/// Any of the eight methods, chosen at run time: for comparing them, or reading one from a
/// file. Links every method's code; a game that knows its method names the type instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum AnyIntegrator {
    /// [`ExplicitEuler`].
    ExplicitEuler,
    /// [`SymplecticEuler`].
    #[default]
    SymplecticEuler,
    /// [`Verlet`].
    Verlet,
    /// [`Rk4`].
    Rk4,
    /// [`ImplicitEuler`].
    ImplicitEuler(ImplicitEuler),
    /// [`Xpbd`].
    Xpbd(Xpbd),
    /// [`DirectChain`].
    DirectChain(DirectChain),
    /// [`DirectSprings`].
    DirectSprings(DirectSprings),
}

impl sealed::Sealed for AnyIntegrator {}

/// Runs `$body` with `$m` bound to the method `$any` names.
macro_rules! with_method {
    ($any:expr, $m:ident => $body:expr) => {
        match $any {
            AnyIntegrator::ExplicitEuler => {
                let $m = ExplicitEuler;
                $body
            }
            AnyIntegrator::SymplecticEuler => {
                let $m = SymplecticEuler;
                $body
            }
            AnyIntegrator::Verlet => {
                let $m = Verlet;
                $body
            }
            AnyIntegrator::Rk4 => {
                let $m = Rk4;
                $body
            }
            AnyIntegrator::ImplicitEuler($m) => $body,
            AnyIntegrator::Xpbd($m) => $body,
            AnyIntegrator::DirectChain($m) => $body,
            AnyIntegrator::DirectSprings($m) => $body,
        }
    };
}

impl Integrator for AnyIntegrator {
    /// [`DirectSprings`]'s, whichever method runs.
    type Memory<S: Scalar, Sh: Shape> = <DirectSprings as Integrator>::Memory<S, Sh>;

    fn memory<S: Scalar, Sh: Shape>() -> Self::Memory<S, Sh> {
        DirectSprings::memory()
    }

    fn stability_limit<S: Scalar>(&self) -> Option<S> {
        with_method!(*self, m => m.stability_limit())
    }

    fn force_evaluations(&self) -> u32 {
        with_method!(*self, m => m.force_evaluations())
    }

    fn substep<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool {
        with_method!(*self, m => m.substep(model, state, h, forces))
    }

    fn substep_touching<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        memory: &mut Self::Memory<P::Scalar, Sh>,
        times: (P::Scalar, P::Scalar),
        forces: &mut F,
        touch: &mut impl FnMut(&mut State<P, Sh>, (P::Scalar, P::Scalar)),
    ) -> Solved<P::Scalar> {
        if let AnyIntegrator::DirectSprings(m) = *self {
            return m.substep_touching(model, state, memory, times, forces, touch);
        }
        with_method!(*self, m => {
            let own = &mut memory_of::<_, P::Scalar, Sh>(&m);
            m.substep_touching(model, state, own, times, forces, touch)
        })
    }

    fn holds_links(&self) -> bool {
        with_method!(*self, m => m.holds_links())
    }

    fn hash_memory<S: Scalar, Sh: Shape>(memory: &Self::Memory<S, Sh>, hash: &mut StateHash) {
        DirectSprings::hash_memory(memory, hash);
    }
}
