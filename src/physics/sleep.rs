//! Sleep: an object at rest stops costing its step until something can move it.

use crate::error::{check_non_negative, invalid};
use crate::physics::force::ForceField;
use crate::physics::hash::StateHash;
use crate::physics::integrator::Integrator;
use crate::physics::shape::Shape;
use crate::physics::spring::Topology;
use crate::physics::system::StepInfo;
use crate::{Aabb, Error, MassSpring, Point, Scalar};

/// When a [`MassSpring`] (a rope, a cloth, a torus) may fall asleep: after `frames` steps in
/// a row with every particle slower than `speed`, under force fields and colliders that did
/// not change. Asleep, a step costs a comparison of those keys (no pass over the particles;
/// with contacts, one pass for the object's box and one test a collider) and moves nothing;
/// its positions stay put, so what was drawn last can be drawn again.
///
/// It wakes, and resumes exactly from the state it fell asleep in, when something can move
/// it:
/// - the game changes it: a position, velocity, impulse, inverse mass, hung weight, weld,
///   spring (a cut, a reel, a snap limit) or its gravity, damping, bounds or accuracy
///   (a call that leaves every value as it was does not wake it);
/// - the force fields of its step are not the ones it fell asleep under
///   ([`ForceField::steady`]: a field that changes with time, such as a gusty
///   [`Wind`](crate::force::Wind), keeps it awake);
/// - with contacts: a collider within its reach moves, has a velocity or a mass (it may
///   push back), or comes within reach.
///
/// While asleep, [`step`](MassSpring::step) reports [`StepInfo::asleep`], no substeps and
/// the `dt` simulated; the clock runs on. An awake run would have moved it by about what
/// its last speeds cover while damping takes them (up to `2 · speed / damping rate` for a
/// damped swing): choose `speed` from what may go unseen. In `Q16`, rounding keeps a rope
/// at rest moving a little: a 7-unit [`DirectChain`](crate::integrator::DirectChain) rope
/// held at both ends under a drag of 0.1/s moves up to 0.12 units/s with its default 4
/// substeps and 0.007 with one (`tests/suite/physics.rs`); under a drag of 2/s, under the
/// default `speed`: it falls asleep at its defaults (`tests/suite/sleep.rs`).
///
/// Cost (`cargo run --release -p dunas-evaluate -- --only sleep`, section (k) of
/// `docs/summary.md`): a frame of 100 objects asleep takes under 1% of their frame awake, and
/// a woken object's first frame costs what an awake frame does.
///
/// ```
/// use dunas::prelude::*;
/// let settings = Settings { gravity: Vec2::new(0.0f32, -9.8), damping: 2.0, ..Settings::default() };
/// let m = Material { stiffness: 400.0, damping: 1.0 };
/// let mut rope: Rope<Vec2<f32>, 8> = Rope::new(Vec2::new(0.0, 0.0), Vec2::new(0.0, -7.0), 1.0, m, settings)?;
/// rope.set_sleep(Some(Sleep::default()))?;
/// let mut asleep = false;
/// for _ in 0..600 {
///     asleep = rope.step(1.0 / 60.0)?.asleep;
/// }
/// assert!(asleep && rope.is_asleep());
/// rope.set_position(0, Vec2::new(0.5, 0.0))?; // the hand moves: it wakes
/// assert!(!rope.is_asleep() && !rope.step(1.0 / 60.0)?.asleep);
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Sleep<S> {
    /// Speed (units per second, finite, `>= 0`) that every particle stays below: by its
    /// velocity, or by how far it moved over the step (along each axis no more than half
    /// what `speed` covers in the step), whichever holds (a particle that a contact holds
    /// where it was is still, whatever velocity the contact's last push left it).
    pub speed: S,
    /// Steps in a row (`>= 1`) that it does so before the object falls asleep.
    pub frames: u16,
}

impl<S: Scalar> Default for Sleep<S> {
    /// 1 cm/s in metres (a hundredth of a unit a second) for 30 steps: half a second at
    /// 60 Hz.
    fn default() -> Self {
        Sleep {
            speed: S::ratio(1, 100),
            frames: 30,
        }
    }
}

impl<S: Scalar> Sleep<S> {
    /// Checks the fields.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite `speed` or `frames` of 0.
    pub fn check(&self) -> Result<(), Error> {
        check_non_negative(self.speed, "sleep speed")?;
        if self.frames == 0 {
            return Err(invalid("sleep frames", "at least 1"));
        }
        Ok(())
    }
}

/// What an object knows of its rest, in 20 bytes (`f32`): its sleep setting (off when
/// `frames` is 0), how many still steps it has had, whether it is asleep and, asleep, the
/// key of the forces and colliders it fell asleep under.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rest<S> {
    sleep: Sleep<S>,
    still: u16,
    asleep: bool,
    key: [u32; 2],
}

impl<S: Scalar> Default for Rest<S> {
    fn default() -> Self {
        Rest::new(None)
    }
}

impl<S: Scalar> Rest<S> {
    /// Awake, with `sleep` in force.
    fn new(sleep: Option<Sleep<S>>) -> Self {
        Rest {
            sleep: sleep.unwrap_or(Sleep {
                speed: S::ZERO,
                frames: 0,
            }),
            still: 0,
            asleep: false,
            key: [0; 2],
        }
    }

    /// The sleep setting.
    #[inline]
    fn setting(&self) -> Option<Sleep<S>> {
        (self.sleep.frames > 0).then_some(self.sleep)
    }

    /// Whether sleep is on.
    #[inline]
    pub(crate) fn is_on(&self) -> bool {
        self.sleep.frames > 0
    }

    /// The key it sleeps under, if asleep.
    #[inline]
    fn asleep(&self) -> Option<u64> {
        self.asleep
            .then(|| u64::from(self.key[0]) | u64::from(self.key[1]) << 32)
    }

    /// Back to awake, with no still steps counted.
    #[inline]
    pub(crate) fn wake(&mut self) {
        (self.still, self.asleep) = (0, false);
    }

    /// Wakes when `changed`.
    #[inline]
    pub(crate) fn wake_if(&mut self, changed: bool) {
        if changed {
            self.wake();
        }
    }

    /// The key of a step under `forces` with `near` (the colliders in reach, or `None` when
    /// one of them moves): `None` when sleep is off or something in it is not steady.
    #[inline]
    pub(crate) fn key<P: Point<Scalar = S>, F: ForceField<P>>(
        &self,
        forces: &F,
        near: Option<u64>,
    ) -> Option<u64> {
        if !self.is_on() {
            return None;
        }
        let near = near?;
        let mut key = StateHash::new();
        forces.steady(&mut key).then(|| key.unmixed() ^ near)
    }

    /// Whether the step keyed `key` finds the object asleep under the same key (then it
    /// stays asleep); otherwise it is awake from here on, and one that was asleep counts its
    /// still steps afresh (so that it takes `frames` steps to answer what woke it).
    #[inline]
    pub(crate) fn sleeps_through(&mut self, key: Option<u64>) -> bool {
        if self.asleep && self.asleep() == key {
            return true;
        }
        if self.asleep {
            self.wake();
        }
        false
    }

    /// After a kept step keyed `key` (`None`: it cannot count as still), whose particles
    /// were `still` or not ([`count_rest`](MassSpring::count_rest)): counts it still or
    /// not, and falls asleep after enough still steps.
    pub(crate) fn count(&mut self, key: Option<u64>, still: impl FnOnce(S) -> bool) {
        let Some(sleep) = self.setting() else { return };
        let still = key.is_some() && still(sleep.speed);
        self.still = if still {
            self.still.saturating_add(1)
        } else {
            0
        };
        if let (true, Some(key)) = (self.still >= sleep.frames, key) {
            (self.asleep, self.key) = (true, [key as u32, (key >> 32) as u32]);
        }
    }

    /// Adds what shapes the steps to come to a state checksum: nothing while sleep is off.
    pub(crate) fn hash(&self, hash: &mut StateHash) {
        if self.is_on() {
            hash.add_scalar(self.sleep.speed);
            hash.add_u32(u32::from(self.sleep.frames) | u32::from(self.still) << 16);
            hash.add_u64(self.asleep().unwrap_or(0));
            hash.add_u32(u32::from(self.asleep));
        }
    }
}

impl<P: Point, Sh: Shape, T: Topology<P::Scalar>, I: Integrator> MassSpring<P, Sh, T, I> {
    /// Lets the object fall asleep at rest (see [`Sleep`]), or never (`None`, the default).
    /// Wakes it.
    ///
    /// # Errors
    /// As [`Sleep::check`]; the setting stays as it was.
    pub fn set_sleep(&mut self, sleep: Option<Sleep<P::Scalar>>) -> Result<(), Error> {
        if let Some(sleep) = sleep {
            sleep.check()?;
        }
        self.rest = Rest::new(sleep);
        Ok(())
    }

    /// The sleep setting in force.
    #[inline]
    pub fn sleep(&self) -> Option<Sleep<P::Scalar>> {
        self.rest.setting()
    }

    /// Whether it is asleep: its next step under the same forces and colliders moves
    /// nothing.
    #[inline]
    pub fn is_asleep(&self) -> bool {
        self.rest.asleep
    }

    /// Wakes it (the next step steps), with no still steps counted.
    #[inline]
    pub fn wake(&mut self) {
        self.rest.wake();
    }

    /// Whether it is asleep under the key of `forces` and `near` (see
    /// [`step_resolving`](Self::step_resolving)): its step would move nothing.
    #[inline]
    pub(crate) fn sleeps_under<F: ForceField<P>>(&self, forces: &F, near: Option<u64>) -> bool {
        self.rest.asleep && self.rest.asleep() == self.rest.key(forces, near)
    }

    /// The step that a sleeping object takes: the clock runs on, nothing moves.
    #[inline]
    pub(crate) fn doze(&mut self, dt: P::Scalar) -> StepInfo<P::Scalar> {
        self.time += dt;
        StepInfo {
            substeps: 0,
            simulated: dt,
            slow_motion: false,
            saturated: false,
            snapped: 0,
            converged: true,
            stretch: P::Scalar::ZERO,
            residual: P::Scalar::ZERO,
            asleep: true,
        }
    }

    /// Where the particles are before a step, when sleep is on (to judge them still after
    /// it: [`count_rest`](Self::count_rest)).
    pub(crate) fn rest_start(&self) -> Option<Sh::PerParticle<P>> {
        if self.rest.is_on() {
            Some(self.state.pos)
        } else {
            None
        }
    }

    /// After a kept step of `dt` from positions `start` ([`rest_start`](Self::rest_start)),
    /// keyed `key` (`None`: it cannot count as still), counts it still or not: still when
    /// every particle is slower than the sleep's speed, or moved along each axis no more
    /// than half what that speed covers in the step (so less than it along any direction;
    /// pinned ones are still). A particle that a contact holds where it was is still,
    /// whatever velocity the contact's last push left it. No root, no division.
    pub(crate) fn count_rest(
        &mut self,
        start: Option<Sh::PerParticle<P>>,
        key: Option<u64>,
        dt: P::Scalar,
    ) {
        let Some(start) = start else { return };
        let (v, x, x0) = (
            Sh::flat(&self.state.vel),
            Sh::flat(&self.state.pos),
            Sh::flat(&start),
        );
        let still = |speed: P::Scalar| {
            let (fast, near) = (speed * speed, speed * dt * P::Scalar::ratio(1, 2));
            let mut particles = v.iter().zip(x.iter().zip(x0));
            particles
                .all(|(v, (x, x0))| v.dot(*v) <= fast || Aabb::point(*x0).grown(near).contains(*x))
        };
        self.rest.count(key, still);
    }
}
