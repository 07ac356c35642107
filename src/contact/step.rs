//! A mass-spring step that ends each substep with the contacts: the systems' side of
//! [`Contacts`], kept here so that the physics does not depend on the contacts.

use super::{Contacts, Touch};
use crate::error::check_non_negative;
use crate::physics::force::ForceField;
use crate::physics::integrator::{Integrator, State};
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::physics::system::StepInfo;
use crate::{Aabb, Error, MassSpring, Point, Scalar};

impl<P: Point, Sh: Shape, T: Topology<P::Scalar>, I: Integrator> MassSpring<P, Sh, T, I> {
    /// As [`step_with`](Self::step_with), resolving `contacts` at the particles after every
    /// substep, whatever their [`Touch`](crate::contact::Touch), with enough substeps that
    /// nothing tunnels (see [`contact`](crate::contact)). A system that knows what it draws
    /// has `step_touching`, which tests that: [`Rope::step_touching`](crate::Rope::step_touching)
    /// the drawn curve, [`Cloth::step_touching`](crate::Cloth::step_touching) the drawn
    /// surface.
    ///
    /// ```
    /// use dunas::prelude::*;
    /// use dunas::collider::Collider;
    /// use dunas::contact::{Contacts, Touch};
    ///
    /// let settings = Settings { gravity: Vec2::new(0.0, -9.8), ..Settings::default() };
    /// let material = Material { stiffness: 400.0, damping: 0.5 };
    /// let mut rope: Rope<Vec2<f32>, 8> = Rope::new(Vec2::new(0.0, 0.0), Vec2::new(7.0, 0.0), 1.0, material, settings)?;
    /// let floor = [Collider::half_space(Vec2::new(0.0, -3.0), Vec2::new(0.0, 1.0))?];
    /// let contacts = Contacts::new(&floor, 0.05, Touch::Particles)?;
    /// for _ in 0..120 {
    ///     let _ = rope.step_touching_particles(1.0 / 60.0, (), &contacts)?;
    /// }
    /// assert!(rope.positions().iter().all(|p| p.y >= -3.0));
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`step_with`](Self::step_with).
    pub fn step_touching_particles<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
        contacts: &Contacts<'_, P>,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        self.step_contacts(dt, forces, contacts, false, |state, inv_mass, times| {
            contacts.resolve_particles(
                Sh::flat_mut(&mut state.pos),
                Sh::flat_mut(&mut state.vel),
                Sh::flat(inv_mass),
                times,
            )
        })
    }

    /// A box that holds what `touch` tests: the particles' box, grown for a drawn curve or
    /// surface by the largest coordinate step between particles next in memory (a spline
    /// bulges past its particles by a fraction of its spacing along each axis). No root.
    fn drawn_bounds(&self, touch: Touch) -> Aabb<P> {
        let x = self.positions();
        let b = Aabb::from_points(x).unwrap_or(Aabb::point(P::default()));
        if touch == Touch::Particles {
            return b;
        }
        let step = x.windows(2).fold(P::Scalar::ZERO, |most, w| {
            (0..P::DIM).fold(most, |most, d| {
                most.max((w[1].coord(d) - w[0].coord(d)).abs())
            })
        });
        b.grown(step)
    }

    /// A step that ends each substep with `resolve` (the contacts of `contacts`), with the
    /// substeps the contacts ask for (`surface`: the drawn points are a surface's), reporting
    /// impulses when `contacts` asks for them.
    pub(crate) fn step_contacts<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
        contacts: &Contacts<'_, P>,
        surface: bool,
        resolve: impl FnMut(&mut State<P, Sh>, &Sh::PerParticle<P::Scalar>, (P::Scalar, P::Scalar)),
    ) -> Result<StepInfo<P::Scalar>, Error> {
        contacts.clear_pushes();
        let bounds = self.drawn_bounds(contacts.touch());
        let near = match self.sleep() {
            Some(_) => contacts.still_key(bounds, dt),
            None => None,
        };
        // Asleep with nothing near moved: it stays so, with no contacts to test.
        if self.sleeps_under(&forces, near) {
            return check_non_negative(dt, "dt").map(|dt| self.doze(dt));
        }
        let (speed, object) = ((self.top_speed(dt), surface), (bounds, dt));
        // Nothing within reach this frame: a plain step, with no contacts to test.
        if !contacts.can_touch(speed, object) {
            return contacts.finish_report(self.step_resolving(
                dt,
                forces,
                (P::Scalar::ZERO, near),
                |_, _, _| {},
            ));
        }
        let floor = contacts.rate(speed, object);
        let mut resolve = resolve;
        let resolve = |state: &mut State<P, Sh>,
                       w: &Sh::PerParticle<P::Scalar>,
                       times: (P::Scalar, P::Scalar)| {
            contacts.advance_bodies(times.0);
            resolve(state, w, times)
        };
        contacts.finish_report(self.step_resolving(dt, forces, (floor, near), resolve))
    }
}
