//! A rope: a row of particles on springs, drawn as a smooth curve.

use crate::error::{invalid, out_of_range};
use core::ops::{Deref, DerefMut};

use crate::contact::{Contacts, PairMemory, Plan, Reach, Touch};
use crate::curves::smooth::{self, Smoothing};
use crate::error::{check_points, check_positive};
use crate::geometry::catenary::Catenary;
use crate::physics::force::ForceField;
use crate::physics::integrator::{Integrator, SymplecticEuler};
use crate::physics::shape::Line;
use crate::physics::spring::{Material, Springs};
use crate::physics::system::{MassSpring, StepInfo};
use crate::{Error, Point, Scalar, Settings};

/// A rope of `N` particles with room for `CAP` springs of one material (by default `N`: the
/// chain's `N - 1` and one spare, for a loop).
///
/// It derefs to its [`MassSpring`], so `rope.step(dt)`, `rope.set_position(0, hand)` and
/// `rope.positions()` work directly. Drawing goes through [`sample`](Rope::sample), which
/// smooths the particles into a curve with as many points as the buffer holds.
///
/// Masses are lumped the usual way: a rope of mass `m` gives each inner particle
/// `m / (N - 1)` and each end half that, so the masses add up to `m`; a pinned end's share
/// is carried by whatever holds it.
///
/// A rope at rest looks at rest: in `f32`, a settled 1 m rope of 30 particles moves its
/// particles by at most 2 µm over 2 s (measured 0.5 µm); the speeds left, up to 1e-3 m/s
/// (measured 5e-4), are rounding noise in the stiffest spring mode, too fast and too small
/// to see (`tests/suite/rope.rs`, `a_resting_f32_rope_stays_still`).
///
/// State size in `f32` 2D: `20·N + 16·CAP + 80` bytes; 368 for 8 particles.
///
/// # Where things are
/// - Stepping, holding and weights are its [`MassSpring`]'s, reached through `Deref`:
///   [`step`](MassSpring::step), [`step_with`](MassSpring::step_with),
///   [`set_position`](MassSpring::set_position), [`move_pinned`](MassSpring::move_pinned),
///   [`set_inv_mass`](MassSpring::set_inv_mass), [`hang`](MassSpring::hang),
///   [`release`](MassSpring::release).
/// - Touching: [`step_touching`](Rope::step_touching) tests what [`Touch`](crate::contact::Touch)
///   names, the drawn curve included.
/// - Breaking: [`set_snap`](MassSpring::set_snap) and
///   [`set_spring_snap`](MassSpring::set_spring_snap) (snap limits), [`cut`](Rope::cut) (a
///   swipe), [`pieces`](Rope::pieces).
/// - Drawing: [`draw`](Rope::draw) (one curve a piece, whole or cut),
///   [`sample`](Rope::sample) (one curve through the whole rope; refused once it is cut).
///
/// ```
/// use dunas::prelude::*;
///
/// let settings = Settings { gravity: Vec2::new(0.0, -9.8), damping: 0.2, ..Settings::default() };
/// let material = Material { stiffness: 400.0, damping: 0.5 };
/// let mut rope: Rope<Vec2<f32>, 8> = Rope::new(Vec2::new(0.0, 0.0), Vec2::new(7.0, 0.0), 1.0, material, settings)?;
/// for _ in 0..60 {
///     rope.step(1.0 / 60.0)?;
/// }
/// let mut screen = [Vec2::default(); 32];
/// let n = rope.sample(Smoothing::BSpline, &mut screen)?;
/// assert_eq!(screen[0], Vec2::new(0.0, 0.0)); // still pinned
/// assert!(screen[n - 1].y < -1.0); // the free end swung down
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Rope<P: Point, const N: usize, const CAP: usize = N, I: Integrator = SymplecticEuler> {
    system: MassSpring<P, Line<N>, Springs<P::Scalar, CAP>, I>,
}

impl<P: Point, const N: usize, const CAP: usize, I: Integrator> Rope<P, N, CAP, I> {
    /// A straight rope from `start` (pinned) to `end` of total `mass`, its springs relaxed
    /// at the initial spacing.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive or non-finite mass or when
    /// `start == end`, and the errors of [`MassSpring::new`].
    pub fn new(
        start: P,
        end: P,
        mass: P::Scalar,
        material: Material<P::Scalar>,
        settings: Settings<P, I>,
    ) -> Result<Self, Error> {
        check_points(&[start, end], "start or end")?;
        if start == end {
            return Err(invalid("end", "a different point from start"));
        }
        let last = (N - 1) as u32;
        let positions: [P; N] =
            core::array::from_fn(|i| start.lerp(end, P::Scalar::ratio(i as u32, last)));
        let springs = Springs::chain(&positions, material)?;
        Self::pinned_chain(positions, mass, springs, settings)
    }

    /// A rope of length `length` hanging under gravity from `start` (pinned) to `end`
    /// (pinned): a rope bridge, a power line, a washing line. The particles start on the
    /// catenary through both ends, at equal arc lengths, with each spring's rest length
    /// `length / (N - 1)`, so the rope hangs in its catenary from the first frame; its
    /// springs then stretch under the rope's weight by `m·g / k` at most.
    ///
    /// The catenary is solved once, in `f64` arithmetic (no `std` or `libm` needed).
    ///
    /// ```
    /// use dunas::prelude::*;
    ///
    /// let settings = Settings { gravity: Vec2::new(0.0, -9.8), ..Settings::default() };
    /// let line: Rope<Vec2<f32>, 12> = Rope::hanging(
    ///     Vec2::new(0.0, 0.0), Vec2::new(10.0, 0.0), 12.0, 1.0, Material { stiffness: 2000.0, damping: 1.0 }, settings,
    /// )?;
    /// let lowest = line.positions().iter().map(|p| p.y).fold(0.0, f32::min);
    /// assert!((lowest + 3.0).abs() < 0.2); // a 12 m line over 10 m sags about 3 m
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive mass, a zero gravity, ends on one
    /// vertical (gravity's direction), or a `length` not longer than the distance between
    /// the ends; the errors of [`MassSpring::new`].
    pub fn hanging(
        start: P,
        end: P,
        length: P::Scalar,
        mass: P::Scalar,
        material: Material<P::Scalar>,
        settings: Settings<P, I>,
    ) -> Result<Self, Error> {
        check_points(&[start, end], "start or end")?;
        check_positive(length, "length")?;
        settings.check()?;
        let coords = |p: P| -> [f64; 3] {
            core::array::from_fn(|d| if d < P::DIM { p.coord(d).to_f64() } else { 0.0 })
        };
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let (chord, gravity) = (coords(end - start), coords(settings.gravity));
        let g = dot(gravity, gravity);
        if g <= 0.0 {
            return Err(invalid("gravity", "non-zero (a rope hangs along it)"));
        }
        // Up is against gravity; across is the chord's part square to it.
        let up: [f64; 3] =
            core::array::from_fn(|d| -gravity[d] / crate::geometry::catenary::sqrt(g));
        let rise = dot(chord, up);
        let across: [f64; 3] = core::array::from_fn(|d| chord[d] - rise * up[d]);
        let span = crate::geometry::catenary::sqrt(dot(across, across));
        let length_f = length.to_f64();
        if span <= 1e-9 * length_f || length_f * length_f <= dot(chord, chord) {
            return Err(invalid(
                "length",
                "longer than the distance between the ends, which are not on one vertical",
            ));
        }
        let curve = Catenary::through(span, rise, length_f);
        let mut positions = [start; N];
        for (i, p) in positions.iter_mut().enumerate() {
            let (x, y) = curve.at(length_f * i as f64 / (N - 1) as f64);
            for d in 0..P::DIM {
                let offset = across[d] / span * x + up[d] * y;
                p.set_coord(d, start.coord(d) + P::Scalar::from_f64(offset));
            }
        }
        (positions[0], positions[N - 1]) = (start, end);
        check_points(&positions, "positions")?;
        let rest = length / P::Scalar::from_i16((N - 1).min(i16::MAX as usize) as i16);
        let mut springs = Springs::new(material);
        for i in 0..N - 1 {
            springs.connect_with_rest(N, i, i + 1, rest)?;
        }
        let mut rope = Self::pinned_chain(positions, mass, springs, settings)?;
        rope.system.set_inv_mass(N - 1, P::Scalar::ZERO)?;
        Ok(rope)
    }

    /// The particles with lumped masses and the first pinned.
    fn pinned_chain(
        positions: [P; N],
        mass: P::Scalar,
        springs: Springs<P::Scalar, CAP>,
        settings: Settings<P, I>,
    ) -> Result<Self, Error> {
        const {
            assert!(N >= 2, "a rope needs at least 2 particles");
            assert!(
                CAP + 1 >= N,
                "a rope of N particles needs room for N - 1 springs"
            );
        };
        check_positive(mass, "mass")?;
        // Inner particles carry m/(N-1), the ends half that.
        let inner = P::Scalar::ratio((N - 1) as u32, 1) / mass;
        let end = inner * P::Scalar::from_i16(2);
        let mut inv_mass = [inner; N];
        inv_mass[0] = P::Scalar::ZERO;
        inv_mass[N - 1] = end;
        check_positive(end, "end particle mass (N - 1) / mass")?;
        Self::from_parts(positions, inv_mass, springs, settings)
    }

    /// A rope from explicit particles and springs (a hub, a loop, a file).
    ///
    /// # Errors
    /// As [`MassSpring::new`].
    pub fn from_parts(
        positions: [P; N],
        inv_mass: [P::Scalar; N],
        springs: Springs<P::Scalar, CAP>,
        settings: Settings<P, I>,
    ) -> Result<Self, Error> {
        Ok(Rope {
            system: MassSpring::new(positions, inv_mass, springs, settings)?,
        })
    }

    /// Advances by `dt` seconds with `forces`, resolving `contacts` after every substep: on
    /// the drawn curve for [`Touch::Drawn`](crate::contact::Touch::Drawn), which catches a peg
    /// thinner than the particle spacing, or at the particles. See [`contact`](crate::contact)
    /// for the response, its cost and the tunnelling bound.
    ///
    /// ```
    /// use dunas::prelude::*;
    /// use dunas::collider::Collider;
    /// use dunas::contact::{Contacts, Touch};
    ///
    /// let settings = Settings { gravity: Vec2::new(0.0, -9.8), damping: 1.0, ..Settings::default() };
    /// let material = Material { stiffness: 2000.0, damping: 1.0 };
    /// let mut rope: Rope<Vec2<f32>, 8> =
    ///     Rope::new(Vec2::new(-3.5, 0.0), Vec2::new(3.5, 0.0), 1.0, material, settings)?;
    /// rope.set_inv_mass(7, 0.0)?; // both ends held
    /// let peg = [Collider::ball(Vec2::new(0.2, -0.5), 0.05)?]; // a tenth of the spacing
    /// let contacts = Contacts::new(&peg, 0.02, Touch::Drawn(Smoothing::BSpline))?;
    /// for _ in 0..240 {
    ///     rope.step_touching(1.0 / 60.0, (), &contacts)?;
    /// }
    /// let mut curve = [Vec2::default(); 64];
    /// let n = rope.sample(Smoothing::BSpline, &mut curve)?;
    /// // The drawn rope rests on the peg instead of sagging through it.
    /// let above = curve[..n].iter().filter(|p| (p.x - 0.2).abs() < 0.05).all(|p| p.y > -0.5);
    /// assert!(above);
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`MassSpring::step_with`].
    pub fn step_touching<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
        contacts: &Contacts<'_, P>,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        match self.system.reach(dt, &forces, contacts, false) {
            Reach::Within(plan, near) if contacts.remembers() => {
                self.step_remembering(dt, forces, contacts, (plan, near))
            }
            Reach::Within(plan, near) => self.step_curve(dt, forces, contacts, (plan, near), None),
            apart => self.system.step_apart(dt, forces, apart),
        }
    }

    /// Which particles a live spring joins to the next along the chain (the last to the
    /// first only for a `closed` curve, which alone reads it).
    fn joined(springs: &Springs<P::Scalar, CAP>, closed: bool) -> [bool; N] {
        let whole = !springs.any_broken();
        core::array::from_fn(|i| match i + 1 < N {
            true => whole || springs.joins(i, i + 1),
            false => closed && springs.joins(N - 1, 0),
        })
    }

    /// [`step_touching`](Self::step_touching) with self-contact on the drawn curve: what it
    /// learns in one substep serves the next ([`PairMemory`]), kept in this function's own
    /// stack frame so that a step without it has no room to pay for.
    #[inline(never)]
    fn step_remembering<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
        contacts: &Contacts<'_, P>,
        reach: (Plan<P::Scalar>, Option<u64>),
    ) -> Result<StepInfo<P::Scalar>, Error> {
        let mut memory = PairMemory::new();
        let (plan, near) = reach;
        let reach = (plan.remembering(contacts), near);
        self.step_curve(dt, forces, contacts, reach, Some(&mut memory))
    }

    /// A step with the contacts of the drawn curve (within `reach`: the rate and key of
    /// [`MassSpring::reach`]), self-contact remembering in `memory`: one copy for both
    /// callers.
    #[inline(never)]
    fn step_curve<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: F,
        contacts: &Contacts<'_, P>,
        reach: (Plan<P::Scalar>, Option<u64>),
        mut memory: Option<&mut PairMemory<P, N>>,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        let closed = matches!(contacts.touch(), Touch::DrawnLoop(_));
        let joined = match contacts.particles_only() {
            // Particle contacts alone tell no pieces apart.
            true => [true; N],
            false => Self::joined(self.system.topology(), closed),
        };
        self.system
            .step_within(dt, forces, contacts, reach, |state, inv_mass, times| {
                let parts = (&mut state.pos, &mut state.vel, inv_mass);
                contacts.resolve_curve(parts, times, &joined, memory.as_deref_mut());
                memory.as_deref().is_some_and(PairMemory::holds)
            })
    }

    /// Draws the whole rope: the curve that `smoothing` makes of the particles, sampled into
    /// `out` with the format's default sampler, and returns the count (see
    /// [`Smoothed::sample`](smooth::Smoothed::sample): `(N-1)·s + 1` points for the splines
    /// and the polyline, `s` segments a span); the first and last points are the end
    /// particles. A rope that can snap or be cut is drawn with [`draw`](Rope::draw), one
    /// curve a piece (the same points while it is whole). For another sampler, build the
    /// curve with [`Smoothed::open`](smooth::Smoothed::open) from
    /// [`positions`](MassSpring::positions).
    ///
    /// # Errors
    /// [`Error::Cut`] once a chain spring has snapped or been cut (one curve would bridge
    /// the gap); [`Error::BufferTooSmall`] when `out` holds fewer than `N` points for the
    /// splines and the polyline, or 2 for one Bézier. Nothing is written on an error.
    pub fn sample(&self, smoothing: Smoothing, out: &mut [P]) -> Result<usize, Error> {
        let pieces = N.saturating_sub(self.system.topology().chain_links());
        if pieces > 1 {
            return Err(Error::Cut { pieces });
        }
        smooth::Smoothed::open(smoothing, self.system.position_array())?.sample(out)
    }

    /// Length of the drawn curve within `accuracy`: the pieces' lengths added once the rope
    /// is cut (each piece's curve as [`draw`](Rope::draw) draws it).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive accuracy; [`Error::OutOfRange`] when
    /// the length is beyond what the format holds (over 32 767 in `Q16`).
    pub fn drawn_length(
        &self,
        smoothing: Smoothing,
        accuracy: P::Scalar,
    ) -> Result<P::Scalar, Error> {
        check_positive(accuracy, "accuracy")?;
        let positions = self.system.position_array();
        let mut length = P::Scalar::ZERO;
        for run in self.pieces().filter(|run| run.len() > 1) {
            let mut row = [positions[run.start]; N];
            row[..run.len()].copy_from_slice(&positions[run.clone()]);
            length += smooth::Smoothed::open_first(smoothing, &row, run.len())?.length(accuracy);
        }
        if length.is_finite() {
            Ok(length)
        } else {
            Err(out_of_range::<P::Scalar>("drawn length"))
        }
    }

    /// Scales the rest lengths so that the *drawn* curve measures `target` once the rope
    /// hangs at rest, and returns the residual `|drawn - target| / target`.
    ///
    /// The springs pull on the control polygon, which is longer than the smoothed curve
    /// wherever the rope bends (a rope sagging between two pins; one hanging straight needs
    /// nothing). Four rounds of: settle for `settle_steps` steps of `dt`, measure, rescale;
    /// then a last settle and measure for the residual. Meant for load time. The tests hold
    /// the residual under 1% for a rope sagging between two pins with each smoothing.
    ///
    /// All or nothing: on an error the rope is as it was before the call.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a target that is not positive or is beyond
    /// [`Scalar::SAFE_RANGE`], or a `dt` that is not positive; the errors of
    /// [`step`](MassSpring::step).
    pub fn calibrate_length(
        &mut self,
        smoothing: Smoothing,
        target: P::Scalar,
        dt: P::Scalar,
        settle_steps: u32,
    ) -> Result<P::Scalar, Error> {
        check_positive(dt, "dt")?;
        if check_positive(target, "target")? > P::Scalar::SAFE_RANGE {
            return Err(invalid(
                "target length",
                "at most the safe range (Q16: 16 383)",
            ));
        }
        let before = self.system.clone();
        let result = self.calibrate(smoothing, target, dt, settle_steps);
        if result.is_err() {
            self.system = before;
        }
        result
    }

    fn calibrate(
        &mut self,
        smoothing: Smoothing,
        target: P::Scalar,
        dt: P::Scalar,
        settle_steps: u32,
    ) -> Result<P::Scalar, Error> {
        let accuracy = target * P::Scalar::ratio(1, 10_000);
        let mut drawn = P::Scalar::ZERO;
        for round in 0..5 {
            if round > 0 && drawn > P::Scalar::ZERO {
                let factor = target / drawn;
                self.system.with_topology(|s| s.scale_rest(factor))?;
            }
            for _ in 0..settle_steps {
                let _ = self.system.step(dt)?;
            }
            drawn = self.drawn_length(smoothing, accuracy)?;
        }
        Ok((drawn - target).abs() / target)
    }
}

impl<P: Point, const N: usize, const CAP: usize, I: Integrator> Deref for Rope<P, N, CAP, I> {
    type Target = MassSpring<P, Line<N>, Springs<P::Scalar, CAP>, I>;
    fn deref(&self) -> &Self::Target {
        &self.system
    }
}

impl<P: Point, const N: usize, const CAP: usize, I: Integrator> DerefMut for Rope<P, N, CAP, I> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.system
    }
}
