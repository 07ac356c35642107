//! The mass-spring system: particles and springs, stepped by an integrator in substeps, and
//! a step that cannot explode.

use crate::error::invalid;
use crate::error::{
    check_index, check_inside, check_inv_mass, check_non_negative, check_points, check_positive,
};
use crate::physics::body::Body;
use crate::physics::force::ForceField;
use crate::physics::integrator::{Integrator, Model, Solved, State, SubstepEnd, SymplecticEuler};
use crate::physics::shape::Shape;
use crate::physics::sleep::Rest;
use crate::physics::spring::{Spread, Topology, check_rest};
use crate::physics::substeps::{plan, spring_bound, substeps_per_rate};
use crate::{Error, Point, Scalar, Settings};

pub use crate::physics::substeps::MAX_SUBSTEPS;

/// What a step did. Look at it: `slow_motion` says the frame simulated less time than asked
/// (the scene looks frozen), `saturated` that a `Q16` force was clamped.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[must_use = "`slow_motion` says the step simulated less than `dt` (springs too stiff for the substep cap); `saturated` that a Q16 force was clamped"]
pub struct StepInfo<S> {
    /// Substeps taken.
    pub substeps: u16,
    /// Simulated time (seconds): the `dt` asked for, or less when the substep cap was hit.
    pub simulated: S,
    /// `true` when the substep cap was hit, so the step simulated less than asked (the
    /// springs are too stiff for this `dt`; see [`MAX_SUBSTEPS`]).
    pub slow_motion: bool,
    /// `true` when a `Q16` force or acceleration reached the format's limit during the step
    /// and was clamped there: the motion is bounded but no longer what `f64` would compute
    /// (a hand yanked far faster than the rope can follow). Each such substep then halves
    /// the velocities (clamped forces would feed the motion energy; halved, they only slow
    /// it), so the system comes back once the load is gone. Always `false` in floats,
    /// whose overflow is caught as [`Error::Diverged`] instead.
    pub saturated: bool,
    /// Springs that snapped at the end of the step (their [`Snap`](crate::physics::spring::Snap)
    /// limits, checked once a step); they stay broken.
    pub snapped: u16,
    /// `false` when the step did not keep what its method promises: an iterating solve
    /// ended beyond [`TOLERANCE`](crate::integrator::TOLERANCE) (0.1%) after its last
    /// iteration (and, for a `DirectChain`, its last halving), or a link that the method
    /// holds ended more than that from its length after the contacts, or, holding its
    /// links, it took back more than that of what the contacts did (see
    /// [`residual`](Self::residual) and [`stretch`](Self::stretch)). The step is kept.
    /// `true` for the methods that do not iterate (the explicit ones).
    pub converged: bool,
    /// For a method that holds its links at their rest length
    /// ([`Integrator::holds_links`]: an inextensible `DirectChain`), the largest
    /// `|length − rest| / rest` of a link at the end of the step, after the contacts (0.001
    /// is 0.1%); a step that would leave it above [`MAX_STRETCH`] is refused. 0 for the
    /// methods whose links are springs (they stretch by design: measure them with
    /// [`MassSpring::positions`]).
    pub stretch: S,
    /// How far the step's iterating solves ended from their equations, the largest over its
    /// substeps, as a fraction (`converged` is `residual ≤ 0.001`):
    /// - [`DirectSprings`](crate::integrator::DirectSprings),
    ///   [`ImplicitEuler`](crate::integrator::ImplicitEuler) and
    ///   [`Xpbd`](crate::integrator::Xpbd): the largest distance a particle still owes to
    ///   backward Euler's equations (its force imbalance times `h²` over its mass), over
    ///   the shortest rest length of a spring with a free end;
    /// - [`DirectChain`](crate::integrator::DirectChain): the largest
    ///   `|length − goal| / rest` of a link (its stretch when inextensible) and, when
    ///   inextensible, how far its links took a particle back along the push the last
    ///   contacts gave it, over the shortest link's rest length (about how deep the drawn
    ///   curve went back into what it touches: a heavy load pulling a rope round a box's
    ///   corner);
    /// - the explicit methods: 0.
    pub residual: S,
    /// `true` when the object slept through the step ([`Sleep`](crate::Sleep)):
    /// nothing moved, no substep was taken, the clock ran on by `dt`.
    pub asleep: bool,
}

/// The largest stretch of a held link a step keeps (10%, as a fraction): a step of an
/// inextensible [`DirectChain`](crate::integrator::DirectChain) that would leave a link
/// further from its length is refused with [`Error::Diverged`] and the state as it was.
pub const MAX_STRETCH: (u32, u32) = (1, 10);

/// Particles joined by springs, advanced by an [`Integrator`].
///
/// `Sh` is the particle layout ([`Line`](crate::physics::shape::Line) for a rope,
/// [`Grid`](crate::physics::shape::Grid) for a cloth), `T` the [`Topology`] and `I` the integrator
/// type. Everything is stored inline: `size_of` is the whole state.
///
/// A particle with inverse mass 0 is pinned: the integrators never move it, and the game moves
/// it with [`set_position`](Self::set_position) (a rope held by a hand).
#[derive(Clone)]
pub struct MassSpring<P: Point, Sh: Shape, T, I: Integrator = SymplecticEuler> {
    pub(in crate::physics) state: State<P, Sh>,
    pub(in crate::physics) inv_mass: Sh::PerParticle<P::Scalar>,
    pub(in crate::physics) topology: T,
    pub(in crate::physics) time: P::Scalar,
    /// Whether it may sleep, and whether it does.
    pub(in crate::physics) rest: Rest<P::Scalar>,
    /// `ω + γ` of the springs alone (see [`stiffness_bound`](Self::stiffness_bound)), kept
    /// current by every method that changes masses or springs; after springs break it may
    /// be higher than the springs left need, which is safe.
    spring_rate: P::Scalar,
    /// Substeps per unit of `rate · dt`, from the integrator and the accuracy.
    per_rate: P::Scalar,
    pub(in crate::physics) settings: Settings<P, I>,
    /// What the integrator keeps between steps (`DirectSprings`: its factor).
    pub(in crate::physics) memory: I::Memory<P::Scalar, Sh>,
    /// A key of the free particles' positions at the end of the last step, if that step
    /// kept its method's tolerance ([`Model::settled`] when they are still there).
    pub(in crate::physics) settled: Option<u32>,
}

impl<P: Point, Sh: Shape, T: core::fmt::Debug, I: Integrator> core::fmt::Debug
    for MassSpring<P, Sh, T, I>
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MassSpring")
            .field("pos", &Sh::flat(&self.state.pos))
            .field("vel", &Sh::flat(&self.state.vel))
            .field("inv_mass", &Sh::flat(&self.inv_mass))
            .field("topology", &self.topology)
            .field("time", &self.time)
            .field("settings", &self.settings)
            .finish()
    }
}

/// Coordinates below this are flushed to 0 after every step so that damped motion never
/// decays into subnormal floats: a rope hanging still has its sideways offsets and speeds
/// shrinking geometrically, and arithmetic on subnormals is several times slower on x86.
/// `ε²` (1.4e-14 in `f32`) is far below anything visible at any game scale; `Q16` has no
/// subnormals and skips the flush.
#[inline]
fn flush_tiny<P: Point>(v: &mut P, limit: P::Scalar) -> bool {
    let tiny = P::Scalar::EPSILON * P::Scalar::EPSILON;
    let mut ok = true;
    for d in 0..P::DIM {
        let c = v.coord(d);
        if !P::Scalar::FIXED_POINT {
            v.set_coord(d, c.flush_tiny(tiny));
        }
        ok &= c.within(limit);
    }
    ok
}

impl<P: Point, Sh: Shape, T: Topology<P::Scalar>, I: Integrator> MassSpring<P, Sh, T, I> {
    /// A system at rest at `positions`, with per-particle inverse masses (0 pins).
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a bad position, [`Error::InvalidParameter`]
    /// for an inverse mass that is negative or not finite, or a positive one whose mass
    /// `1 / w` is beyond [`Scalar::SAFE_RANGE`] (in `Q16`, below `5 / 65 536`), so that a
    /// momentum fits the format, [`Error::IndexOutOfRange`] for a spring that
    /// names a particle past the count, [`Error::OutOfRange`] for a position beyond
    /// [`Settings::bounds`], [`Error::ZeroRestLength`] for a spring whose rest
    /// length is not positive, finite and within the safe range, the errors of
    /// [`Material::check`](crate::Material::check) for its material, and those of
    /// [`Settings::check`].
    pub fn new(
        positions: Sh::PerParticle<P>,
        inv_mass: Sh::PerParticle<P::Scalar>,
        topology: T,
        settings: Settings<P, I>,
    ) -> Result<Self, Error> {
        check_points(Sh::flat(&positions), "positions")?;
        for &w in Sh::flat(&inv_mass) {
            check_inv_mass(w)?;
        }
        let mut bad = None;
        topology.for_each_spring(|a, b, rest, material| {
            if bad.is_none() {
                bad = check_index(a.max(b), Sh::LEN)
                    .and_then(|_| check_rest(a, b, rest))
                    .and_then(|_| material.check())
                    .err();
            }
        });
        if let Some(error) = bad {
            return Err(error);
        }
        settings.check()?;
        check_inside(Sh::flat(&positions), settings.bounds, "positions")?;
        let mut system = MassSpring {
            state: State {
                pos: positions,
                vel: Sh::filled(P::default()),
            },
            inv_mass,
            topology,
            time: P::Scalar::ZERO,
            spring_rate: P::Scalar::ZERO,
            per_rate: substeps_per_rate(&settings.integrator, settings.accuracy),
            settings,
            memory: I::memory(),
            settled: None,
            rest: Rest::default(),
        };
        system.update_spring_rate();
        Ok(system)
    }

    /// Positions, in flat order.
    #[inline]
    pub fn positions(&self) -> &[P] {
        Sh::flat(&self.state.pos)
    }

    /// Positions in the layout's own array (`[P; N]` or `[[P; U]; V]`).
    #[inline]
    pub fn position_array(&self) -> &Sh::PerParticle<P> {
        &self.state.pos
    }

    /// Velocities, in flat order.
    #[inline]
    pub fn velocities(&self) -> &[P] {
        Sh::flat(&self.state.vel)
    }

    /// Inverse masses, in flat order (0 = pinned).
    #[inline]
    pub fn inv_masses(&self) -> &[P::Scalar] {
        Sh::flat(&self.inv_mass)
    }

    /// The springs.
    #[inline]
    pub fn topology(&self) -> &T {
        &self.topology
    }

    /// The springs, to change in place; the stiffness bound is brought up to date when the
    /// closure returns.
    pub(crate) fn with_topology<R>(&mut self, f: impl FnOnce(&mut T) -> R) -> R {
        let r = f(&mut self.topology);
        self.update_spring_rate();
        // A new rest length leaves the links off where a converged step left them.
        self.settled = None;
        r
    }

    /// The springs, to break some in place. Breaking only lowers the stiffness bound, so the
    /// bound kept is still safe (a step may take more substeps than the springs left need,
    /// until masses or springs next change).
    pub(crate) fn break_springs<R>(&mut self, f: impl FnOnce(&mut T) -> R) -> R {
        self.rest.wake();
        f(&mut self.topology)
    }

    /// Simulated time since creation (seconds).
    #[inline]
    pub fn time(&self) -> P::Scalar {
        self.time
    }

    /// The settings in force.
    #[inline]
    pub fn settings(&self) -> &Settings<P, I> {
        &self.settings
    }

    /// Replaces the settings (gravity, damping, bounds, integrator, accuracy) between steps.
    ///
    /// # Errors
    /// As [`Settings::check`], and [`Error::OutOfRange`] for bounds that a particle is
    /// already beyond; the old settings stay.
    pub fn set_settings(&mut self, settings: Settings<P, I>) -> Result<(), Error> {
        settings.check()?;
        check_inside(self.positions(), settings.bounds, "positions")?;
        self.per_rate = substeps_per_rate(&settings.integrator, settings.accuracy);
        let old = &self.settings;
        self.rest.wake_if(
            (old.gravity, old.damping, old.bounds, old.accuracy)
                != (
                    settings.gravity,
                    settings.damping,
                    settings.bounds,
                    settings.accuracy,
                ),
        );
        self.settings = settings;
        Ok(())
    }

    /// Moves particle `i` to `p` (teleports; velocity unchanged). The way to drive a pinned
    /// particle from the game.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`], or [`Error::NonFinite`] / [`Error::OutOfRange`] for `p`
    /// (beyond the safe range or [`Settings::bounds`]).
    pub fn set_position(&mut self, i: usize, p: P) -> Result<(), Error> {
        check_index(i, Sh::LEN)?;
        check_points(&[p], "position")?;
        check_inside(&[p], self.settings.bounds, "position")?;
        let x = &mut Sh::flat_mut(&mut self.state.pos)[i];
        self.rest.wake_if(*x != p);
        *x = p;
        Ok(())
    }

    /// Moves particle `i` to `p` as a hand would over the last `dt` seconds: its velocity
    /// becomes `(p - where it was) / dt`, so the springs' damping and the rope's momentum see
    /// the hand move (`set_position` teleports at rest). A held (pinned) particle keeps that
    /// velocity for the next step and stays at `p` through it; call this every frame the
    /// hand moves. On a free particle it is a teleport with that velocity.
    ///
    /// ```
    /// use dunas::prelude::*;
    /// let settings = Settings { gravity: Vec2::new(0.0, -9.8), ..Settings::default() };
    /// let m = Material { stiffness: 400.0, damping: 2.0 };
    /// let mut rope: Rope<Vec2<f32>, 8> = Rope::new(Vec2::new(0.0, 0.0), Vec2::new(0.0, -7.0), 1.0, m, settings)?;
    /// rope.move_pinned(0, Vec2::new(0.1, 0.0), 1.0 / 60.0)?; // the hand moves 6 m/s right
    /// assert!((rope.velocities()[0].x - 6.0).abs() < 1e-5);
    /// rope.step(1.0 / 60.0)?;
    /// assert_eq!(rope.positions()[0], Vec2::new(0.1, 0.0)); // held where the hand is
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::InvalidParameter`] for a `dt` that is not positive
    /// and finite; [`Error::NonFinite`] / [`Error::OutOfRange`] for `p` or for the velocity.
    /// Nothing changes on an error.
    pub fn move_pinned(&mut self, i: usize, p: P, dt: P::Scalar) -> Result<(), Error> {
        check_index(i, Sh::LEN)?;
        check_positive(dt, "dt")?;
        check_points(&[p], "position")?;
        check_inside(&[p], self.settings.bounds, "p")?;
        let v = (p - Sh::flat(&self.state.pos)[i]) * (P::Scalar::ONE / dt);
        check_points(&[v], "velocity")?;
        self.rest
            .wake_if(v != P::default() || Sh::flat(&self.state.vel)[i] != v);
        Sh::flat_mut(&mut self.state.pos)[i] = p;
        Sh::flat_mut(&mut self.state.vel)[i] = v;
        Ok(())
    }

    /// Lets go of held particle `i`, giving it inverse mass `inv_mass` (`> 0`) and keeping
    /// the velocity its hand gave it this frame ([`move_pinned`](Self::move_pinned)), so it
    /// leaves with the hand's momentum.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::InvalidParameter`] for an `inv_mass` that is not
    /// positive and finite, or whose mass `1 / inv_mass` is beyond [`Scalar::SAFE_RANGE`].
    pub fn let_go(&mut self, i: usize, inv_mass: P::Scalar) -> Result<(), Error> {
        check_index(i, Sh::LEN)?;
        check_positive(check_inv_mass(inv_mass)?, "inverse mass")?;
        Sh::flat_mut(&mut self.inv_mass)[i] = inv_mass;
        self.update_spring_rate();
        Ok(())
    }

    /// Hangs a weight of `mass` on free particle `i` (a bob, a penguin, a lantern): the
    /// particle's mass grows by `mass`, and the substeps follow. Undo it with
    /// [`release`](Self::release).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::InvalidParameter`] for a `mass` that is not
    /// positive and finite, or one that makes the particle heavier than
    /// [`Scalar::SAFE_RANGE`] (in `Q16`, an inverse mass below `5 / 65 536`: about 14 500
    /// mass units in all);
    /// [`Error::Pinned`] for a pinned particle (a hand holds it: the weight would not show).
    pub fn hang(&mut self, i: usize, mass: P::Scalar) -> Result<(), Error> {
        check_index(i, Sh::LEN)?;
        check_positive(mass, "mass")?;
        let w = Sh::flat(&self.inv_mass)[i];
        if w <= P::Scalar::ZERO {
            return Err(Error::Pinned { index: i });
        }
        let heavier = P::Scalar::ONE / (P::Scalar::ONE / w + mass);
        if !(heavier > P::Scalar::ZERO && check_inv_mass(heavier).is_ok()) {
            return Err(invalid(
                "hung mass",
                "one the format can add to the particle (Q16: a total of at most 13 107)",
            ));
        }
        Sh::flat_mut(&mut self.inv_mass)[i] = heavier;
        self.update_spring_rate();
        Ok(())
    }

    /// Takes `mass` off free particle `i` and returns it as a [`Body`] with the particle's
    /// position and velocity: a hung weight let go (the catapult's penguin). The particle
    /// keeps the rest of its mass and its velocity, so linear momentum is conserved (to
    /// rounding); the body then flies on its own ([`Body::fly`]).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::Pinned`] for a pinned particle;
    /// [`Error::InvalidParameter`] for a `mass` that is not positive, or not less than the
    /// particle's own. Nothing changes on an error.
    pub fn release(&mut self, i: usize, mass: P::Scalar) -> Result<Body<P>, Error> {
        check_index(i, Sh::LEN)?;
        check_positive(mass, "mass")?;
        let w = Sh::flat(&self.inv_mass)[i];
        if w <= P::Scalar::ZERO {
            return Err(Error::Pinned { index: i });
        }
        let left = P::Scalar::ONE / w - mass;
        let lighter = P::Scalar::ONE / left;
        if !(left > P::Scalar::ZERO && lighter.is_finite() && lighter > P::Scalar::ZERO) {
            return Err(invalid("let-go mass", "less than the particle's mass"));
        }
        Sh::flat_mut(&mut self.inv_mass)[i] = lighter;
        self.update_spring_rate();
        Ok(Body {
            position: Sh::flat(&self.state.pos)[i],
            velocity: Sh::flat(&self.state.vel)[i],
            mass,
        })
    }

    /// Ties particle `i` to particle `j` of `other` (a rope's end to a point on another rope
    /// or on a cloth): both move to their mass-weighted mean position and velocity, so the
    /// pair's momentum is kept (to rounding); a pinned side holds the other where it is.
    /// Call it every frame after stepping both systems. Both pinned: nothing moves.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] for a missing particle on either side. Nothing changes then.
    pub fn weld<Sh2: Shape, T2, I2: Integrator>(
        &mut self,
        i: usize,
        other: &mut MassSpring<P, Sh2, T2, I2>,
        j: usize,
    ) -> Result<(), Error> {
        check_index(i, Sh::LEN)?;
        check_index(j, Sh2::LEN)?;
        let (wa, wb) = (Sh::flat(&self.inv_mass)[i], Sh2::flat(&other.inv_mass)[j]);
        let (pa, pb) = (Sh::flat(&self.state.pos)[i], Sh2::flat(&other.state.pos)[j]);
        let (va, vb) = (Sh::flat(&self.state.vel)[i], Sh2::flat(&other.state.vel)[j]);
        let zero = P::Scalar::ZERO;
        let (p, v) = match (wa > zero, wb > zero) {
            (false, false) => return Ok(()),
            (false, true) => (pa, va),
            (true, false) => (pb, vb),
            (true, true) => {
                let (sa, sb) = (wb / (wa + wb), wa / (wa + wb));
                (pa * sa + pb * sb, va * sa + vb * sb)
            }
        };
        self.rest.wake_if((pa, va) != (p, v));
        other.rest.wake_if((pb, vb) != (p, v));
        Sh::flat_mut(&mut self.state.pos)[i] = p;
        Sh::flat_mut(&mut self.state.vel)[i] = v;
        Sh2::flat_mut(&mut other.state.pos)[j] = p;
        Sh2::flat_mut(&mut other.state.vel)[j] = v;
        Ok(())
    }

    /// Sets the velocity of free particle `i`.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`], [`Error::NonFinite`] / [`Error::OutOfRange`] for `v`, and
    /// [`Error::Pinned`] for a pinned particle (its velocity stays 0).
    pub fn set_velocity(&mut self, i: usize, v: P) -> Result<(), Error> {
        check_index(i, Sh::LEN)?;
        check_points(&[v], "velocity")?;
        if self.inv_masses()[i] <= P::Scalar::ZERO {
            return Err(Error::Pinned { index: i });
        }
        let old = &mut Sh::flat_mut(&mut self.state.vel)[i];
        self.rest.wake_if(*old != v);
        *old = v;
        Ok(())
    }

    /// An instant change of momentum `j` (mass × velocity) on particle `i`: a hit, a jump. A
    /// pinned particle is infinitely heavy: the impulse changes nothing and is `Ok`.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`], [`Error::NonFinite`] / [`Error::OutOfRange`] for `j` or
    /// for the velocity it would give.
    pub fn apply_impulse(&mut self, i: usize, j: P) -> Result<(), Error> {
        check_index(i, Sh::LEN)?;
        check_points(&[j], "impulse")?;
        let w = self.inv_masses()[i];
        if w <= P::Scalar::ZERO {
            return Ok(());
        }
        let v = Sh::flat(&self.state.vel)[i] + j * w;
        self.set_velocity(i, v)
    }

    /// Sets particle `i`'s inverse mass (0 pins it and stops it).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::InvalidParameter`] for a negative or non-finite
    /// value, or a positive one whose mass `1 / inv_mass` is beyond [`Scalar::SAFE_RANGE`]
    /// (in `Q16`, below `5 / 65 536`).
    pub fn set_inv_mass(&mut self, i: usize, inv_mass: P::Scalar) -> Result<(), Error> {
        check_index(i, Sh::LEN)?;
        check_inv_mass(inv_mass)?;
        Sh::flat_mut(&mut self.inv_mass)[i] = inv_mass;
        if inv_mass == P::Scalar::ZERO {
            Sh::flat_mut(&mut self.state.vel)[i] = P::default();
        }
        self.update_spring_rate();
        Ok(())
    }

    /// Total energy: kinetic + spring + gravitational (relative to the origin), for tests and
    /// diagnostics. Pinned particles count as infinitely heavy and still. Costs a division per
    /// particle and a square root per spring; may saturate in `Q16`, and overflow to ±∞ in
    /// floats past the format's range.
    pub fn energy(&self) -> P::Scalar {
        let held = self.settings.integrator.holds_links();
        self.model()
            .energy(self.positions(), self.velocities(), held)
    }

    /// The system as the integrators see it, outside a step.
    pub(crate) fn model(&self) -> Model<'_, P, Sh, T> {
        Model {
            inv_mass: &self.inv_mass,
            topology: &self.topology,
            gravity: self.settings.gravity,
            damping: self.settings.damping,
            time: self.time,
            settled: false,
            touching: false,
        }
    }

    /// The highest angular frequency `ω` (rad/s) of the springs, by Gershgorin's bound, and
    /// the damping rate `γ` (1/s) that the substep count guards against: the springs'
    /// damping plus [`Settings::damping`]. One pass over the springs.
    pub fn stiffness_bound(&self) -> (P::Scalar, P::Scalar) {
        let (omega, gamma) = spring_bound::<_, Sh>(&self.inv_mass, &self.topology);
        (omega, gamma + self.settings.damping)
    }

    /// After a change of masses or springs: the stiffness bound brought up to date, and
    /// awake.
    fn update_spring_rate(&mut self) {
        let (omega, gamma) = spring_bound::<_, Sh>(&self.inv_mass, &self.topology);
        self.spring_rate = omega + gamma;
        self.rest.wake();
    }

    /// The substeps for a frame of `dt` seconds and their length: enough that `(ω + γ)·h`
    /// stays at the [`Accuracy`](crate::Accuracy)'s fraction of the integrator's limit, at
    /// most [`MAX_SUBSTEPS`]; `(0, 0)` for `dt = 0`. Depends only on the current masses,
    /// springs and settings.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite `dt`; [`Error::TooStiff`]
    /// when the substep would round to zero in the format.
    pub fn substeps_for(&self, dt: P::Scalar) -> Result<(u16, P::Scalar), Error> {
        self.plan(dt).map(|(n, h, _)| (n, h))
    }

    fn plan(&self, dt: P::Scalar) -> Result<(u16, P::Scalar, bool), Error> {
        self.plan_at_least(dt, P::Scalar::ZERO)
    }

    /// As [`plan`](Self::plan), with at least `floor` substeps a second.
    fn plan_at_least(
        &self,
        dt: P::Scalar,
        floor: P::Scalar,
    ) -> Result<(u16, P::Scalar, bool), Error> {
        check_non_negative(dt, "dt")?;
        plan(
            dt,
            self.spring_rate + self.settings.damping,
            self.per_rate,
            floor,
        )
    }

    /// Advances by `dt` seconds with gravity, damping and springs only.
    ///
    /// # Errors
    /// See [`step_with`](Self::step_with).
    #[inline]
    pub fn step(&mut self, dt: P::Scalar) -> Result<StepInfo<P::Scalar>, Error> {
        self.step_with(dt, ())
    }

    /// Advances by `dt` seconds, adding the forces of `forces` (a
    /// [`ForceField`], a tuple of them, or `()`).
    ///
    /// `dt = 0` does nothing. A large `dt` is split into substeps that keep the integrator
    /// stable; past [`MAX_SUBSTEPS`] the step simulates less time than asked (reported in
    /// [`StepInfo`]) rather than explode.
    ///
    /// # Errors
    /// Every error leaves the state as it was before the call:
    /// - [`Error::InvalidParameter`] for a negative, NaN or infinite `dt`;
    /// - [`Error::TooStiff`] when even [`MAX_SUBSTEPS`] substeps would advance no time;
    /// - [`Error::Diverged`] when a position or velocity came out non-finite or beyond
    ///   [`Settings::bounds`].
    ///
    /// A `Q16` force that saturates is not an error (refusing it would freeze a rope whose
    /// hand keeps pulling): it is clamped, and [`StepInfo::saturated`] says so.
    #[inline]
    pub fn step_with<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        if self.sleeps_under(&forces, Some(0)) && dt >= P::Scalar::ZERO && dt.is_finite() {
            return Ok(self.doze(dt));
        }
        self.step_resolving(dt, forces, (None, Some(0)), |_, _, _, _| {})
    }

    /// A step whose substeps each end with `resolve(state, inverse masses, (substep length,
    /// time left in the frame))`, with at least `floor` substeps a second (`None`: no
    /// contacts, `resolve` does nothing); `near` is the key of the colliders within reach
    /// (`Some(0)` for none, `None` when one moves), for [`Sleep`](crate::Sleep).
    // Out of line on a host, so that a sleeping object's step (the top of `step_with`) is
    // inlined without this prologue; inlined on a microcontroller (half a KB of flash).
    #[cfg_attr(not(target_os = "none"), inline(never))]
    pub(crate) fn step_resolving<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        mut forces: F,
        (floor, near): (Option<P::Scalar>, Option<u64>),
        mut resolve: impl SubstepEnd<P, Sh>,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        let key = self.rest.key(&forces, near);
        if self.rest.sleeps_through(key) {
            check_non_negative(dt, "dt")?;
            return Ok(self.doze(dt));
        }
        let (n, h, slow_motion) = self.plan_at_least(dt, floor.unwrap_or(P::Scalar::ZERO))?;
        let start = self.rest_start();
        let solved = self.substeps_or_undo(n, h, &mut forces, floor.is_some(), &mut resolve)?;
        self.count_rest(start, key.filter(|_| !slow_motion && solved.fits), dt);
        Ok(StepInfo {
            substeps: n,
            simulated: if slow_motion {
                h * P::Scalar::from_i16(n as i16)
            } else {
                dt
            },
            slow_motion,
            saturated: !solved.fits,
            snapped: self.snap(),
            converged: solved.converged,
            stretch: solved.stretch,
            residual: solved.residual,
            asleep: false,
        })
    }

    /// One integrator step of exactly `h`, without the substeps that keep it stable: for
    /// measuring an integrator at its limits. Respecting [`Integrator::stability_limit`] is
    /// up to the caller; divergence is still caught and undone.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite `h`, and the errors of a
    /// step ([`step_with`](Self::step_with)).
    pub fn step_once<F: ForceField<P>>(
        &mut self,
        h: P::Scalar,
        mut forces: F,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        let n = u16::from(check_non_negative(h, "h")? > P::Scalar::ZERO);
        self.rest.wake();
        let solved = self.substeps_or_undo(n, h, &mut forces, false, &mut |_, _, _, _| {})?;
        Ok(StepInfo {
            substeps: n,
            simulated: h,
            slow_motion: false,
            saturated: !solved.fits,
            snapped: self.snap(),
            converged: solved.converged,
            stretch: solved.stretch,
            residual: solved.residual,
            asleep: false,
        })
    }

    /// Breaks the springs past their snap lengths (the stiffness bound kept is still safe:
    /// see [`break_springs`](Self::break_springs)).
    fn snap(&mut self) -> u16 {
        let snapped = self.topology.snap(Sh::flat(&self.state.pos));
        u16::try_from(snapped).unwrap_or(u16::MAX)
    }

    /// `n` substeps of `h` (`touching`: `resolve` does something), undone if the result is
    /// not sane (a held link's stretch past [`MAX_STRETCH`] included); what they reported.
    fn substeps_or_undo<F: ForceField<P>>(
        &mut self,
        n: u16,
        h: P::Scalar,
        forces: &mut F,
        touching: bool,
        resolve: &mut impl SubstepEnd<P, Sh>,
    ) -> Result<Solved<P::Scalar>, Error> {
        let saved = (self.state, self.time);
        let mut solved = Solved::plain(true);
        let holds = self.settings.integrator.holds_links();
        let mut settled = holds && self.settled.is_some() && self.settled == Some(self.key());
        for k in 1..=n {
            let model = Model {
                inv_mass: &self.inv_mass,
                topology: &self.topology,
                gravity: self.settings.gravity,
                damping: self.settings.damping,
                time: self.time,
                settled,
                touching,
            };
            let lag = h * P::Scalar::from_i16((n - k) as i16);
            let inv_mass = &self.inv_mass;
            solved = solved.then(self.settings.integrator.substep_touching(
                &model,
                &mut self.state,
                &mut self.memory,
                (h, lag),
                forces,
                &mut |state, times| resolve(state, inv_mass, times, &saved.0.pos),
            ));
            settled = solved.converged;
            self.time += h;
        }
        if !solved.fits {
            self.calm();
        }
        let (most, of) = MAX_STRETCH;
        if self.settle(Sh::flat(&saved.0.pos)) && solved.stretch <= P::Scalar::ratio(most, of) {
            self.settled = (holds && solved.converged).then(|| self.key());
            Ok(solved)
        } else {
            (self.state, self.time) = saved;
            Err(Error::Diverged)
        }
    }

    /// A key of the free particles' positions (their bits, in order): a pass over them.
    fn key(&self) -> u32 {
        let mut key = Spread::default();
        let free = self.positions().iter().zip(self.inv_masses());
        for (p, _) in free.filter(|(_, w)| **w > P::Scalar::ZERO) {
            for d in 0..P::DIM {
                key.add(p.coord(d).bits());
            }
        }
        let sum = key.sum();
        (sum >> 32) as u32 ^ sum as u32
    }

    /// After a `Q16` step whose forces saturated (a hand yanked far past what the rope can
    /// follow): every velocity is halved. Clamped forces are no longer conservative and
    /// would feed the motion energy; halved, they can only slow it, so once the load is gone
    /// the system is back where its forces are exact and its damping brings it to rest.
    /// Cost: one multiplication a coordinate, in saturated steps only.
    #[cold]
    fn calm(&mut self) {
        let half = P::Scalar::ratio(1, 2);
        for v in Sh::flat_mut(&mut self.state.vel) {
            *v = *v * half;
        }
    }

    /// Ends a step, in one pass with no early exit: a held particle where its hand put it
    /// (`held`, the positions at the step's start) and at rest (the hand's velocity,
    /// [`move_pinned`](Self::move_pinned), lasted this step, for the springs' damping); a free
    /// one's coordinates flushed (see [`flush_tiny`]) and checked: its position finite and
    /// inside `±bounds`, its velocity inside the safe range. `false` when a check failed.
    fn settle(&mut self, held: &[P]) -> bool {
        let (bounds, zero) = (self.settings.bounds, P::Scalar::ZERO);
        let particles = Sh::flat_mut(&mut self.state.pos)
            .iter_mut()
            .zip(Sh::flat_mut(&mut self.state.vel))
            .zip(Sh::flat(&self.inv_mass).iter().zip(held));
        let mut ok = true;
        for ((x, v), (&w, &before)) in particles {
            if w > zero {
                ok &= flush_tiny(x, bounds) & flush_tiny(v, P::Scalar::SAFE_RANGE);
            } else {
                (*x, *v) = (before, P::default());
            }
        }
        ok
    }
}
