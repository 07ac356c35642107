//! First-order Euler methods: explicit (the reference) and symplectic (the default).

use super::{Integrator, Model, State, sealed};
use crate::physics::force::ForceField;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// `x += v·h; v += a·h`. Gains energy at any step without damping: a reference, not a
/// choice. One force evaluation per substep.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ExplicitEuler;

/// `v += a·h; x += v·h` (semi-implicit Euler): stable while `ω·h < 2`, energy bounded. One
/// force evaluation per substep: the cheapest stable method, and the default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SymplecticEuler;

/// One Euler substep, velocity first (`symplectic`) or position first.
#[inline]
fn euler<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
    model: &Model<'_, P, Sh, T>,
    state: &mut State<P, Sh>,
    h: P::Scalar,
    forces: &mut F,
    symplectic: bool,
) -> bool {
    let (a, ok) = model.accelerations_at(state, forces, true);
    let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat_mut(&mut state.vel));
    for (((x, v), a), &w) in x
        .iter_mut()
        .zip(v.iter_mut())
        .zip(Sh::flat(&a))
        .zip(model.inv_mass())
    {
        // Pinned particles neither accelerate nor move: skip their multiplications where
        // they are costly (fixed point); floats keep a branch-free, vectorisable loop.
        if P::Scalar::FIXED_POINT && w <= P::Scalar::ZERO {
            continue;
        }
        if symplectic {
            *v += *a * h;
            *x += *v * h;
        } else {
            *x += *v * h;
            *v += *a * h;
        }
    }
    ok
}

impl sealed::Sealed for ExplicitEuler {}

impl Integrator for ExplicitEuler {
    type Memory<S: Scalar, Sh: Shape> = ();

    fn memory<S: Scalar, Sh: Shape>() {}

    fn stability_limit<S: Scalar>(&self) -> Option<S> {
        Some(S::ratio(1, 9))
    }
    fn force_evaluations(&self) -> u32 {
        1
    }
    #[inline]
    fn substep<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool {
        euler(model, state, h, forces, false)
    }
}

impl sealed::Sealed for SymplecticEuler {}

impl Integrator for SymplecticEuler {
    type Memory<S: Scalar, Sh: Shape> = ();

    fn memory<S: Scalar, Sh: Shape>() {}

    fn stability_limit<S: Scalar>(&self) -> Option<S> {
        Some(S::from_i16(2))
    }
    fn force_evaluations(&self) -> u32 {
        1
    }
    #[inline]
    fn substep<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool {
        euler(model, state, h, forces, true)
    }
}
