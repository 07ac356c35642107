//! Time integrators: one type each, all behind the [`Integrator`] trait.
//!
//! A system names its integrator by type (`MassSpring<P, Shape, Topology, Verlet>`), so a
//! device image links that one method and nothing else. [`AnyIntegrator`] is the run-time
//! choice, for tools that compare methods or load them from a file; it links all seven.
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
//! | [`Xpbd`] | unconditionally stable | 1 per XPBD substep + one projection per spring | loses a little | springs as compliant distance constraints (Macklin et al. 2016, 2019) |
//! | [`DirectChain`] | unconditionally stable, one substep a frame | 1 + `iterations` direct solves along the chain | loses where links stretch | a rope's links solved together, exactly: inextensible, or its springs at any stiffness |
//!
//! Per spring, a force evaluation costs one square root, one division and about 20
//! multiply-adds; per particle, about 6 operations.

mod chain;
mod euler;
mod implicit;
mod model;
mod rk4;
mod verlet;
mod xpbd;

use core::fmt::Debug;

pub use chain::DirectChain;
pub use euler::{ExplicitEuler, SymplecticEuler};
pub use implicit::ImplicitEuler;
pub(crate) use implicit::solve_scale;
pub(crate) use model::tiny_length;
pub use model::{Model, State};
pub use rk4::Rk4;
pub use verlet::Verlet;
pub use xpbd::Xpbd;

use crate::force::ForceField;
use crate::shape::Shape;
use crate::spring::Topology;
use crate::{Point, Scalar};

mod sealed {
    pub trait Sealed {}
}

/// A way to advance a mass-spring system by one substep. Implemented by the seven method
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

    /// [`substep`](Self::substep), then `touch(state, (h, lag))` (the contacts of a step
    /// that resolves them, `lag` seconds before the frame ends). A method that splits its
    /// substep into shorter solves resolves the contacts after each of them, with their own
    /// length and lag.
    fn substep_touching<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        (h, lag): (P::Scalar, P::Scalar),
        forces: &mut F,
        touch: &mut impl FnMut(&mut State<P, Sh>, (P::Scalar, P::Scalar)),
    ) -> bool {
        let fits = self.substep(model, state, h, forces);
        touch(state, (h, lag));
        fits
    }
}

/// Any of the seven methods, chosen at run time: for comparing them, or reading one from a
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
        }
    };
}

impl Integrator for AnyIntegrator {
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
        times: (P::Scalar, P::Scalar),
        forces: &mut F,
        touch: &mut impl FnMut(&mut State<P, Sh>, (P::Scalar, P::Scalar)),
    ) -> bool {
        with_method!(*self, m => m.substep_touching(model, state, times, forces, touch))
    }
}
