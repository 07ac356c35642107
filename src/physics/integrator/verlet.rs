//! Velocity Verlet.

use super::{Integrator, Model, State, sealed};
use crate::physics::force::ForceField;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// Velocity Verlet (kick, drift, kick): second order, stable while `ω·h < 2`, energy
/// bounded. Two force evaluations per substep.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Verlet;

impl sealed::Sealed for Verlet {}

impl Integrator for Verlet {
    type Memory<S: Scalar, Sh: Shape> = ();

    fn memory<S: Scalar, Sh: Shape>() {}

    fn stability_limit<S: Scalar>(&self) -> Option<S> {
        Some(S::from_i16(2))
    }
    fn force_evaluations(&self) -> u32 {
        2
    }
    fn substep<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool {
        let half = h * P::Scalar::ratio(1, 2);
        let mut ok = true;
        for kick in 0..2 {
            let (a, fine) = model.accelerations_at(state, forces, true);
            ok &= fine;
            let (x, v) = (Sh::flat_mut(&mut state.pos), Sh::flat_mut(&mut state.vel));
            for ((x, v), a) in x.iter_mut().zip(v.iter_mut()).zip(Sh::flat(&a)) {
                *v += *a * half;
                if kick == 0 {
                    *x += *v * h;
                }
            }
        }
        ok
    }
}
