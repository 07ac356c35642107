//! A mass-spring step that ends each substep with the contacts: the systems' side of
//! [`Contacts`], kept here so that the physics does not depend on the contacts.

use super::{Contacts, Touch};
use crate::curves::smooth::Smoothing;
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

    /// A box that holds what `touch` tests, from the particles' box `b`, which holds their
    /// polyline and their Bézier and B-spline curves and surfaces (each inside its control
    /// points' convex hull), grown for a Catmull-Rom or natural spline by the largest
    /// coordinate step between particles next in memory (such a spline bulges past its
    /// particles by a fraction of its spacing along each axis). No root.
    fn drawn_bounds(&self, touch: Touch, b: Aabb<P>) -> Aabb<P> {
        use Smoothing::{CatmullRom, NaturalSpline};
        let bulging = matches!(
            touch,
            Touch::Drawn(CatmullRom | NaturalSpline) | Touch::DrawnLoop(CatmullRom | NaturalSpline)
        );
        if !bulging {
            return b;
        }
        let x = self.positions();
        let step = x.windows(2).fold(P::Scalar::ZERO, |most, w| {
            (0..P::DIM).fold(most, |most, d| {
                most.max((w[1].coord(d) - w[0].coord(d)).abs())
            })
        });
        b.grown(step)
    }

    /// What `contacts` ask of this frame's step (`surface`: the drawn points are a
    /// surface's), its pushes cleared: sleep on, step with no contacts, or step with them
    /// at the substeps they ask for. Costs a pass over the particles (their box and top
    /// speed) and, per collider, a box test of its path ([`can_touch`](Contacts::can_touch)).
    #[inline]
    pub(crate) fn reach<F: ForceField<P>>(
        &self,
        dt: P::Scalar,
        forces: &F,
        contacts: &Contacts<'_, P>,
        surface: bool,
    ) -> Reach<P::Scalar> {
        contacts.clear_pushes();
        let (particles, top_speed) = self.bounds_and_top_speed(dt);
        let bounds = self.drawn_bounds(contacts.touch(), particles);
        let near = match self.sleep() {
            Some(_) => contacts.still_key(bounds, dt),
            None => None,
        };
        let (speed, object) = ((top_speed, surface), (bounds, dt));
        if self.sleeps_under(forces, near) {
            Reach::Asleep
        } else if contacts.can_touch(speed, object) {
            Reach::Within(contacts.rate(speed, object), near)
        } else {
            Reach::Apart(near)
        }
    }

    /// The step of a frame that `reach` found asleep or with nothing within reach: a doze,
    /// or a plain step with no contacts to test and no pushes to report (the contacts of a
    /// [`Within`](Reach::Within) frame left out).
    pub(crate) fn step_apart<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
        reach: Reach<P::Scalar>,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        match reach {
            Reach::Asleep => check_non_negative(dt, "dt").map(|dt| self.doze(dt)),
            Reach::Apart(near) | Reach::Within(_, near) => {
                self.step_resolving(dt, forces, (None, near), |_, _, _| {})
            }
        }
    }

    /// The step of a frame within reach of `contacts` (`rate` substeps a second at least,
    /// `near` as [`reach`](Self::reach) found them): each substep ends with `resolve` (the
    /// contacts), reporting impulses when `contacts` asks for them.
    pub(crate) fn step_within<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
        contacts: &Contacts<'_, P>,
        (rate, near): (P::Scalar, Option<u64>),
        mut resolve: impl FnMut(&mut State<P, Sh>, &Sh::PerParticle<P::Scalar>, (P::Scalar, P::Scalar)),
    ) -> Result<StepInfo<P::Scalar>, Error> {
        let resolve = |state: &mut State<P, Sh>,
                       w: &Sh::PerParticle<P::Scalar>,
                       times: (P::Scalar, P::Scalar)| {
            contacts.advance_bodies(times.0);
            resolve(state, w, times)
        };
        contacts.finish_report(self.step_resolving(dt, forces, (Some(rate), near), resolve))
    }

    /// A step that ends each substep with `resolve` (the contacts of `contacts`), with the
    /// substeps the contacts ask for (`surface`: the drawn points are a surface's), reporting
    /// impulses when `contacts` asks for them; a plain step when nothing is within reach.
    pub(crate) fn step_contacts<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
        contacts: &Contacts<'_, P>,
        surface: bool,
        resolve: impl FnMut(&mut State<P, Sh>, &Sh::PerParticle<P::Scalar>, (P::Scalar, P::Scalar)),
    ) -> Result<StepInfo<P::Scalar>, Error> {
        match self.reach(dt, &forces, contacts, surface) {
            Reach::Within(rate, near) => {
                self.step_within(dt, forces, contacts, (rate, near), resolve)
            }
            apart => self.step_apart(dt, forces, apart),
        }
    }
}

/// What a frame's contacts ask of its step ([`MassSpring::reach`]).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Reach<S> {
    /// Asleep, with nothing near that moved: it stays so.
    Asleep,
    /// Nothing within reach: a plain step (the key of what is near, for sleep).
    Apart(Option<u64>),
    /// Something within reach: contacts after every substep, at least this many substeps a
    /// second (the key of what is near, for sleep).
    Within(S, Option<u64>),
}
