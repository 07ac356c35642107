//! A mass-spring step that ends each substep with the contacts: the systems' side of
//! [`Contacts`], kept here so that the physics does not depend on the contacts.

use super::Contacts;
use super::timing::{Timing, Waited};
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

    /// The particles' box, and the fastest a free particle can go this frame: its speed now
    /// plus what gravity adds over `dt`. One pass over the particles and two roots.
    fn bounds_and_top_speed(&self, dt: P::Scalar) -> (Aabb<P>, P::Scalar) {
        let (x, v) = (self.positions(), self.velocities());
        let first = Aabb::point(x.first().copied().unwrap_or_default());
        // In `Q16`, whose squares saturate past 181 units a second, the length of the
        // longest velocity by exact 64-bit sums; in floats the root of the largest square.
        let (bounds, (longest, most)) = x.iter().zip(v).fold(
            (first, (P::default(), P::Scalar::ZERO)),
            |(b, (longest, most)), (x, v)| {
                let fastest = match P::Scalar::FIXED_POINT {
                    true => (if v.longer_than(longest) { *v } else { longest }, most),
                    false => (longest, most.max(v.dot(*v))),
                };
                (b.including(*x), fastest)
            },
        );
        let fastest = match P::Scalar::FIXED_POINT {
            true => longest.length(),
            false => most.sqrt(),
        };
        (bounds, fastest + self.settings().gravity.length() * dt)
    }

    /// A box that holds what `contacts` test, from the particles' box `b`, which holds their
    /// polyline and their Bézier and B-spline curves and surfaces (each inside its control
    /// points' convex hull), grown for a Catmull-Rom or natural spline
    /// ([`bulges`](Contacts::bulges)) by the largest coordinate step between particles next
    /// in memory (such a spline bulges past its particles by a fraction of its spacing along
    /// each axis). No root.
    fn drawn_bounds(&self, contacts: &Contacts<'_, P>, b: Aabb<P>) -> Aabb<P> {
        if !contacts.bulges() {
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
        let bounds = self.drawn_bounds(contacts, particles);
        let (speed, object) = ((top_speed, surface), (bounds, dt));
        if !contacts.can_touch(speed, object) {
            // Nothing within reach: the frame is a bare step's, and so is its key for sleep.
            return match self.sleeps_under(forces, Some(0)) {
                true => Reach::Asleep,
                false => Reach::Apart,
            };
        }
        let near = match self.sleep() {
            Some(_) => contacts.still_key(bounds, dt),
            None => None,
        };
        if self.sleeps_under(forces, near) {
            return Reach::Asleep;
        }
        let (rate, closing, depth) = contacts.rate(speed, object);
        let plan = Plan {
            rate,
            closing: (contacts.may_wait(false).then_some(closing), closing),
            speed: top_speed,
            allowance: contacts.allowance(depth, || self.model().shortest_rest()),
        };
        Reach::Within(plan, near)
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
        let near = match reach {
            Reach::Asleep => return check_non_negative(dt, "dt").map(|dt| self.doze(dt)),
            Reach::Apart => Some(0),
            Reach::Within(_, near) => near,
        };
        self.step_resolving(dt, forces, (None, near), |_, _, _, _| {})
    }

    /// The step of a frame within reach of `contacts` (`plan` and `near` as
    /// [`reach`](Self::reach) found them): its substeps end with `resolve` (the contacts)
    /// when they are [`due`](Contacts::due), at the step's end and before a point can close
    /// on a collider by more than the thickness, or at every substep when they may not wait
    /// ([`may_wait`](Contacts::may_wait)), and at the substep after one where `resolve`
    /// returned `true` (it holds parts apart); reporting impulses when `contacts` asks for
    /// them. When they may wait, costs at a substep's end a pass over the velocities when
    /// they are not due, and a copy of the positions when they are (what friction takes
    /// back after waited substeps is what the particles slid since).
    pub(crate) fn step_within<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
        contacts: &Contacts<'_, P>,
        (plan, near): (Plan<P::Scalar>, Option<u64>),
        mut resolve: impl FnMut(&mut State<P, Sh>, &Sh::PerParticle<P::Scalar>, Timing<'_, P>) -> bool,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        // Where the particles were when the contacts last ran, when that was within this
        // frame (at its start, the step's own copy serves).
        let mut since: Option<Sh::PerParticle<P>> = None;
        let mut waited = Waited::default();
        let mut holding = false;
        let resolve = |state: &mut State<P, Sh>,
                       w: &Sh::PerParticle<P::Scalar>,
                       (h, lag): (P::Scalar, P::Scalar),
                       start: &Sh::PerParticle<P>| {
            let slid: Sh::PerParticle<P>;
            let mut timing = Timing::substep((h, lag));
            match plan.closing.0 {
                None => contacts.advance_bodies(h),
                Some(closing) => {
                    // A call with no time passing is a round after a substep's contacts.
                    if h > P::Scalar::ZERO {
                        waited.time += h;
                        waited.count = waited.count.saturating_add(1);
                        let v = Sh::flat(&state.vel);
                        if !holding
                            && !contacts.due(
                                (h, lag),
                                &waited,
                                (closing, plan.speed, plan.allowance),
                                v,
                            )
                        {
                            return;
                        }
                    }
                    contacts.advance_bodies(waited.time);
                    if waited.count > 1 {
                        slid = moved::<P, Sh>(&state.pos, since.as_ref().unwrap_or(start));
                        timing = timing.waited(waited.count, Sh::flat(&slid));
                    }
                    waited = Waited::default();
                }
            }
            holding = resolve(state, w, timing);
            if plan.closing.0.is_some() && lag > P::Scalar::ZERO {
                since = Some(state.pos);
            }
        };
        let floor = (Some(plan.rate), near);
        contacts.finish_report(self.step_resolving(dt, forces, floor, resolve))
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
        mut resolve: impl FnMut(&mut State<P, Sh>, &Sh::PerParticle<P::Scalar>, Timing<'_, P>),
    ) -> Result<StepInfo<P::Scalar>, Error> {
        match self.reach(dt, &forces, contacts, surface) {
            Reach::Within(plan, near) => {
                let resolve = |state: &mut _, w: &_, timing: Timing<'_, P>| {
                    resolve(state, w, timing);
                    false
                };
                self.step_within(dt, forces, contacts, (plan, near), resolve)
            }
            apart => self.step_apart(dt, forces, apart),
        }
    }
}

/// How far each particle moved from `before` to `now`.
fn moved<P: Point, Sh: Shape>(
    now: &Sh::PerParticle<P>,
    before: &Sh::PerParticle<P>,
) -> Sh::PerParticle<P> {
    let mut moved = *now;
    for (m, x0) in Sh::flat_mut(&mut moved).iter_mut().zip(Sh::flat(before)) {
        *m -= *x0;
    }
    moved
}

/// What a frame's contacts ask of its step ([`MassSpring::reach`]).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Reach<S> {
    /// Asleep, with nothing near that moved: it stays so.
    Asleep,
    /// Nothing within reach: a plain step, keyed for sleep as one with no contacts.
    Apart,
    /// Something within reach: contacts as the plan asks (the key of what is near, for
    /// sleep).
    Within(Plan<S>, Option<u64>),
}

/// How often a frame within reach resolves its contacts ([`MassSpring::reach`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plan<S> {
    /// Substeps a second at least ([`Contacts::rate`]).
    rate: S,
    /// The fastest a point can close on a collider it can reach, or with self-contact on
    /// another part (m/s), when the contacts may wait ([`Contacts::may_wait`]; `None`: they
    /// run at every substep); and that rate whether they may or not.
    closing: (Option<S>, S),
    /// The particles' top speed the rate holds for (m/s), gravity's gain over the frame
    /// included.
    speed: S,
    /// How far a point may close on a collider between two runs of waiting contacts (m;
    /// [`Contacts::rate`]).
    allowance: S,
}

impl<S: Copy> Plan<S> {
    /// The plan of a step that keeps a [`PairMemory`](super::memory::PairMemory) for
    /// self-contact: its contacts may wait ([`Contacts::may_wait`] with `remembering`)
    /// while it holds no two parts apart.
    pub(crate) fn remembering<P: Point<Scalar = S>>(self, contacts: &Contacts<'_, P>) -> Self {
        let closing = contacts.may_wait(true).then_some(self.closing.1);
        Plan {
            closing: (closing, self.closing.1),
            ..self
        }
    }
}
