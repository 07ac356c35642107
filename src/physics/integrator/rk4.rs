//! Classic fourth-order Runge-Kutta.

use super::{Integrator, Model, State, sealed};
use crate::physics::force::ForceField;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::{Point, Scalar};

/// Classic fourth-order Runge-Kutta: stable while `ω·h < 2√2`, slowly loses energy. Four
/// force evaluations per substep: the accurate choice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rk4;

impl sealed::Sealed for Rk4 {}

impl Integrator for Rk4 {
    type Memory<S: Scalar, Sh: Shape> = ();

    fn memory<S: Scalar, Sh: Shape>() {}

    fn stability_limit<S: Scalar>(&self) -> Option<S> {
        // 2·sqrt(2), the extent of RK4's stability region along the imaginary axis.
        Some(S::ratio(2_828_427, 1_000_000))
    }
    fn force_evaluations(&self) -> u32 {
        4
    }
    fn substep<P: Point, Sh: Shape, T: Topology<P::Scalar>, F: ForceField<P>>(
        &self,
        model: &Model<'_, P, Sh, T>,
        state: &mut State<P, Sh>,
        h: P::Scalar,
        forces: &mut F,
    ) -> bool {
        let half = h * P::Scalar::ratio(1, 2);
        let sixth = h * P::Scalar::ratio(1, 6);
        let two = P::Scalar::from_i16(2);
        let start = *state;
        let mut stage_state = start;
        let mut a = Sh::filled(P::default());
        let (mut sum_x, mut sum_v) = (Sh::filled(P::default()), Sh::filled(P::default()));
        let mut ok = true;
        for stage in 0..4 {
            ok &= model.accelerations(
                Sh::flat(&stage_state.pos),
                Sh::flat(&stage_state.vel),
                forces,
                Sh::flat_mut(&mut a),
                true,
            );
            let weight = if stage == 0 || stage == 3 {
                P::Scalar::ONE
            } else {
                two
            };
            let reach = if stage < 2 { half } else { h };
            let rows = Sh::flat_mut(&mut stage_state.pos)
                .iter_mut()
                .zip(Sh::flat_mut(&mut stage_state.vel))
                .zip(Sh::flat(&a))
                .zip(Sh::flat(&start.pos).iter().zip(Sh::flat(&start.vel)))
                .zip(
                    Sh::flat_mut(&mut sum_x)
                        .iter_mut()
                        .zip(Sh::flat_mut(&mut sum_v)),
                );
            for ((((x, v), &a), (&x0, &v0)), (sx, sv)) in rows {
                // This stage's slopes are (v, a); the next stage starts from x0 + slope·reach.
                *sx += *v * weight;
                *sv += a * weight;
                if stage < 3 {
                    *x = x0 + *v * reach;
                    *v = v0 + a * reach;
                }
            }
        }
        let rows = Sh::flat_mut(&mut state.pos)
            .iter_mut()
            .zip(Sh::flat_mut(&mut state.vel))
            .zip(Sh::flat(&sum_x).iter().zip(Sh::flat(&sum_v)));
        for ((x, v), (&sx, &sv)) in rows {
            *x += sx * sixth;
            *v += sv * sixth;
        }
        ok
    }
}
