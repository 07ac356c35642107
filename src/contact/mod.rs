//! Contacts: ropes and sails pushed out of colliders, with restitution and Coulomb friction,
//! at their particles or on the curve or surface the game draws.
//!
//! [`Contacts`] names the colliders, the thickness (radius) of the rope or cloth, and where to
//! test ([`Touch`]). Stepping with it ([`Rope::step_touching`](crate::Rope::step_touching),
//! [`Cloth::step_touching`](crate::Cloth::step_touching),
//! [`MassSpring::step_touching_particles`](crate::MassSpring::step_touching_particles)) resolves the contacts at
//! the end of its substeps (which ones: **When** below), whatever the integrator: a point
//! closer to a collider than the thickness is
//! moved out along the collider's normal, and its velocity relative to the collider loses its
//! inward part (times `1 + restitution`) and, by Coulomb's law, its sliding part: all of it
//! while that stays within static friction times the normal change, else kinetic friction
//! times it. Every integrator keeps positions and velocities (Verlet's and XPBD's velocities
//! are what the next substep's positions are built from), so the same projection plus impulse
//! serves them all.
//!
//! - [`Touch::Particles`] tests the particles only: cheap (a box test per particle and
//!   collider, and a distance for a particle within the collider's box grown by the
//!   thickness), and enough when every collider is wider than the particle spacing.
//! - [`Touch::Drawn`] tests what the game draws ([`Touch::DrawnLoop`]: a loop's closed
//!   curve). A rope's curve: each span's control-point box first (the convex hull property)
//!   against the collider's box and its distance from the box's centre, then the deepest
//!   point of the span: in a half-space exactly (an end of the span, or where the slope of
//!   its height, a quadratic, is zero: a square root and up to 4 divisions); in a ball, in
//!   floats, the point nearest its centre by 9 samples and up to 6 Newton steps on the
//!   squared distance (to the format's precision); in the other solids, and in a ball in
//!   `Q16`, by 5 samples and 8 rounds that halve the bracket around the deepest (to 1/1024
//!   of a cubic span; halving only, so shifts and additions in `Q16`). A
//!   cloth's surface: each cell between four neighbouring particles, its supporting
//!   particles' box grown by the basis's overshoot (Catmull-Rom: 25/16), then the deepest
//!   point of the cell by 3×3 samples and 8 halving rounds of a compass search (its last
//!   step 1/512 of the cell). The correction `d` found at a point with particle weights `w`
//!   (see [`Smoothed::weights`](crate::curves::smooth::Smoothed::weights); a product of the two
//!   directions' weights on a surface) moves particle `i` by
//!   `(w_i / m_i) · d / Σ_j w_j² / m_j`: the smallest mass-weighted change that moves the
//!   drawn point by exactly `d` (with equal masses, `w_i · d / Σ w_j²`). Friction and
//!   restitution go the same way. This catches pegs and poles far thinner than the particle
//!   spacing; a frame whose drawn rope touches a collider takes about 1.7 times one whose
//!   particles do (`docs/summary.md` (g): 550 against 322 ns for an 8-particle rope drawn
//!   as a B-spline on a peg 0.1× its spacing, at a thickness of 0). In floats a ball near a cubic
//!   span is first judged against the capsule round the span's chord that holds its
//!   control points: a ball clear of it by the thickness takes no search.
//!
//! **When.** A step's substeps come from its springs' stiffness; its contacts need only run
//! so often that no point moves further than the thickness between two runs against a
//! collider it can reach (its centre line then never goes into the collider), judged as the
//! substeps are (below), and at the step's end. With a thickness of 0 that allowance is an
//! eighth of the least depth `d` of a collider within reach (a ball's or capsule's radius,
//! a box's least half side; **No tunnelling** below) or a sixty-fourth of the shortest
//! spring's rest length, the less: a point may then go that far into a collider between
//! runs (never so far that a run pushes it out of the far side), and is out of it at the
//! step's end. Four pegs under an 8-particle rope drawn as a B-spline at a thickness of 0
//! meet it once a frame where they met it at every one of its 4 substeps, and add 2.17
//! times its bare step where they added 8.72 times (2.30 and 2.52 times in two runs before,
//! of nearly the same code), and 0.36 times at its particles where they added 0.75 times
//! (`docs/summary.md`, targets). They run sooner when a particle gets faster than that
//! judgement allowed for, and at every substep with self-contact (on a rope's drawn curve
//! with a thickness above 0, only while its last pass of self-contact pushed
//! two spans apart; else as often as keeps two parts of the rope, meeting head on, from
//! closing by more than the thickness between runs), on a natural spline or with a collider
//! that has a mass. A 16-particle rope lying on a floor, its springs asking for 7 substeps,
//! meets the floor once a frame: the floor adds 1.90 times its bare step (1.88 and 1.67 times
//! in the runs before, of the same code), where it added 12.8 times when the contacts ran at every
//! substep (`docs/summary.md`, targets). After
//! waited substeps, friction that holds a point still takes back all it slid since the
//! contacts last ran (its particles' moves, weighted as in the point), so that a rope on a
//! slope stays put as it did, but no more than its static limit could have stopped over
//! that time (`h (n + 1) / 2` after `n` substeps of `h`); a point that slid farther (a
//! direct solver's links pulled it across the floor) is braked as kinetic friction would
//! brake it over that time. Kinetic friction takes back its braking times that time, what
//! it would have taken back of a steady slide at the end of each substep. Rounds of
//! contacts after the first in the same substep take back nothing more.
//!
//! **Self-contact.** [`Contacts::with_self_contact`] also keeps a rope's curve or a cloth's
//! surface off itself: spans (cells) that are not neighbours are pushed a diameter apart,
//! found by a sweep over their control-point boxes (the convex hull property) and pushed
//! apart through both points' particle weights. A pile keeps them within 2% of it; a rope
//! whose tension pulls its spans across each other (whipped by its held end) can end a frame
//! up to 15% short of it, never through itself ([`Contacts::with_self_contact`]).
//!
//! **Reach.** A collider whose path over the frame (from where its velocity puts it at the
//! frame's start to its place at the end) stays further from the drawn object's box than
//! the thickness and what the object's fastest point covers in the frame cannot be touched
//! this frame: it asks for no substeps, and when no collider can be touched and
//! self-contact is off the frame tests no contact at all. That box is the particles' for a
//! polyline, a Bézier and a B-spline (each inside its particles' convex hull), grown for a
//! Catmull-Rom or natural spline by the largest step between neighbouring particles along
//! an axis. What the test costs, a pass over the particles (their box and top speed) and a
//! box test per collider (a collider keeps its box), is 6.1% of an 8-particle rope's bare
//! step in the last run (`docs/summary.md`, targets; 6.0%, 1.2%, 2.4% and 6.1% in four runs
//! before of the same code: the machine's noise is of that size; 4.7% by instructions).
//!
//! **Two-way coupling.** [`Contacts::with_pushes`] reports, after each step, the impulse the
//! rope or cloth gave each collider and, for a collider with a mass
//! ([`Collider::with_mass`]), how far its body was moved: add them to the velocity (divided
//! by the mass) and the position of the ball, crate or bat the collider stands for. Each
//! contact is then resolved between the rope and a body of that mass in the same substep:
//! with restitution 0 the pair gains no energy for bodies up to 5 times the rope's mass (see
//! the limit there).
//!
//! **No tunnelling.** With a thickness `r > 0`, a step takes enough substeps that no particle
//! moves more than `r + d` against a collider in one substep, where `d` is how deep a point
//! can go into that collider and still be nearest the side it came in by (a ball's or
//! capsule's radius, a box's least half side, a polygon's distance from its corners' mean to
//! its nearest edge; a half-space has no far side and asks for no substeps), judged from the
//! speeds at the start of the frame plus what gravity adds during it (Catmull-Rom's drawn
//! points move up to 5/4 as fast as its particles on a curve, 25/16 on a surface, which the
//! count allows for), within [`MAX_SUBSTEPS`]; with self-contact, no two parts of a rope
//! close by more than `r` a substep. A point that moves less than that a substep cannot cross
//! a collider unseen nor come out of its far side. Past the cap the frame still simulates its
//! whole `dt` (contacts never slow time), and a point faster than `(r + d) · MAX_SUBSTEPS /
//! dt` may cross a collider thinner than its step. A thickness of 0 gives no such guarantee.
//!
//! [`MAX_SUBSTEPS`]: crate::physics::system::MAX_SUBSTEPS

use crate::error::invalid;
use core::cell::Cell;

pub mod collider;
mod curve;
mod drawn;
mod itself;
mod memory;
mod reach;
mod solid;
mod span_pairs;
mod step;
mod surface;
mod timing;

use crate::curves::smooth::Smoothing;
use crate::error::check_non_negative;
use crate::physics::system::StepInfo;
use crate::{Error, Point, Scalar};
use collider::{Collider, coulomb};
pub(crate) use drawn::DrawnSpans;
pub(crate) use memory::PairMemory;
use reach::weight_sum;
pub(crate) use step::{Plan, Reach};
use timing::Braking;
pub(crate) use timing::Timing;

/// Where contacts are tested.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Touch {
    /// At the particles only.
    #[default]
    Particles,
    /// On what this smoothing draws through the particles: a rope's curve, or a cloth's
    /// surface (the smoothing along both grid directions; [`Smoothing::Bezier`] is the
    /// cloth's [`patch`](crate::Cloth::patch)), or a [`Torus`](crate::Torus)'s closed surface
    /// (its particles for [`Smoothing::Bezier`], which cannot close). Other systems test
    /// their particles.
    Drawn(Smoothing),
    /// On the closed curve this smoothing draws through a rope whose particles form a loop
    /// ([`Smoothed::closed`](crate::smooth::Smoothed::closed)); the particles for
    /// [`Smoothing::Bezier`], which cannot close, and for fewer than 3 particles. Other
    /// systems test their particles.
    DrawnLoop(Smoothing),
}

/// The colliders a step resolves contacts against, the thickness of what touches them, and
/// where it touches.
#[derive(Clone, Copy, Debug)]
pub struct Contacts<'a, P: Point> {
    colliders: &'a [Collider<P>],
    thickness: P::Scalar,
    touch: Touch,
    pushes: &'a [Cell<Push<P>>],
    /// The friction between touching parts of a rope with self-contact on; `None`: off.
    self_friction: Option<P::Scalar>,
    /// The most a touched point's velocity weighs in the particles', on a curve and on a
    /// surface ([`weight_sum`](reach::weight_sum) of `touch`), for each frame's reach.
    weight_sums: (P::Scalar, P::Scalar),
}

/// What a step's contacts did to one collider: the report
/// [`Contacts::with_pushes`] fills, for the game to move the body the collider stands for.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Push<P> {
    /// The impulse (mass × velocity, in the system's units) the contacts gave the collider:
    /// the opposite of what they gave the rope or cloth. Divided by the body's mass, it is
    /// the velocity change the body gets back.
    pub impulse: P,
    /// For a collider with a mass ([`Collider::with_mass`]): how far its body moved during
    /// the step beyond the path its velocity set (each impulse acting from the substep it
    /// came in, and its share of each push out of the rope); add it to the body's position.
    /// Zero for a kinematic collider.
    pub shift: P,
}

impl<'a, P: Point> Contacts<'a, P> {
    /// Contacts of a rope or cloth of radius `thickness` with `colliders`. At a thickness of
    /// 0 the drawn centre line itself touches: between the runs of a frame's contacts a point
    /// may go up to an eighth of a collider's depth into it, or a sixty-fourth of the
    /// shortest spring, and it is out of it at the step's end (module docs, **When**).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite thickness, or one beyond
    /// [`Scalar::SAFE_RANGE`].
    pub fn new(
        colliders: &'a [Collider<P>],
        thickness: P::Scalar,
        touch: Touch,
    ) -> Result<Self, Error> {
        if check_non_negative(thickness, "thickness")? > P::Scalar::SAFE_RANGE {
            return Err(invalid("thickness", "at most the safe range (Q16: 16 383)"));
        }
        Ok(Contacts {
            colliders,
            thickness,
            touch,
            pushes: &[],
            self_friction: None,
            weight_sums: (weight_sum(touch, false), weight_sum(touch, true)),
        })
    }

    /// Also keeps a rope's curve or a cloth's surface off itself: every two of its spans (a
    /// cloth's cells, each between four neighbouring particles) that are not neighbours
    /// (for cells: that share no particle row and column) stay at least twice the thickness
    /// apart (the diameter), so a rope coils and piles and a cloth folds instead of passing
    /// through itself. Tested where the colliders are ([`Touch`]): on the drawn curve or
    /// surface ([`Touch::Drawn`], [`Touch::DrawnLoop`]: round the loop), or, with
    /// [`Touch::Particles`], on the straight segments (a cloth: the flat quadrilaterals)
    /// between the particles. `friction` is the Coulomb coefficient between touching parts
    /// (static and kinetic alike). Each piece of a cut rope keeps off itself, not off the
    /// other pieces.
    ///
    /// The spans that can touch are found from their control points' boxes (the convex
    /// hull property): sorted and swept along x, so the cost grows with the spans that
    /// are near each other, not with the square of the spans. Each pair near each other
    /// takes a search for its nearest points (each span sampled at 5 points once for
    /// all its pairs; the chords between them measured exactly, segment to segment,
    /// which bound the spans' distance within how far a cubic can bend away from its
    /// chords, so a pair they hold apart costs no more; then up to 8 Newton steps with
    /// the spans' exact tangents and curvatures from the nearest chord pair, and from a
    /// second one where the spans could come near in two places; an exact
    /// segment-to-segment distance for straight spans) and a push through the particles
    /// that weigh in both points. On a rope's drawn curve, a step keeps what it learns from
    /// one substep to the next. A span's points move no farther than its control points, so
    /// self-contact runs in a substep only when some span has moved an eighth of the
    /// diameter since it last ran, and always in the step's last substep (and in its first
    /// when three substeps or more follow): two spans cannot close by more than a quarter of
    /// the diameter in between, let alone pass through each other, and a pile at rest is
    /// kept off itself once or twice a frame. In the substeps between, the points the last
    /// pass pushed apart are pushed apart again where they came nearer, at the same places
    /// on their spans (no search): the upper turns of a heap rest on the lower ones instead
    /// of sinking into them under their weight until the next pass. A step whose last pass
    /// pushed nothing apart (a rope lying straight or in a loose spiral) lets its contacts
    /// wait as a step without self-contact does, for no longer than two of its parts
    /// meeting head on could close by the thickness: a 24-particle rope still in a flat
    /// spiral costs 47% fewer instructions a frame than when its floor ran at every substep,
    /// lying straight 60% fewer (callgrind, on copies of the evaluation's scenes). A pair found apart by
    /// more than the diameter is not searched again while the moves of its spans' control
    /// points add up to less than that margin, and a pair found near each other in one or
    /// two places (and by the chords farther everywhere else) is followed from those places
    /// by Newton steps alone, for at most a diameter of such moves, and while nowhere else
    /// could come nearer; found clear of the diameter by `c` where they come nearest, it
    /// takes no Newton step while those moves add up to less than `c`. A pile is a stack of
    /// such contacts, so colliders and self-contact take up to 12 rounds a substep, until no
    /// overlap is over 1% of the diameter; a particle a collider pushed in a substep's
    /// rounds moves by 3/10 of its inverse mass in self-contact (the floor holds what rests
    /// on it), so the rounds do not undo in one what the floor pushed back in the last. The
    /// colliders have the last word: when the last round pushed two spans
    /// apart, the colliders are resolved once more, so that a floor is never passed (two
    /// spans may then stay within the rounds' tolerance). A step with self-contact takes
    /// substeps for twice the particles' top speed (two parts of the rope can meet head on).
    ///
    /// Measured (`tests/suite/contacts.rs`; the evaluation's section (g), `cargo run --release
    /// -p dunas-evaluate -- --only contacts`): a 16-particle 3D rope falling into a pile on a
    /// floor, dropped from five slightly different starts (a pile is chaotic), never has two
    /// spans closer than the diameter less 2% over 10 s (0.9% to 1.2% less at the closest:
    /// the rounds stop once no overlap is over 1%, and a push later in a round can undo part
    /// of an earlier one) and never a particle into the floor. Whipped round by its held end
    /// (`a_whipped_rope_never_passes_through_itself`), the rope's tension pulls spans pressed
    /// across each other back together after every round of pushes, and the rounds do not
    /// converge. In 10 s two spans that are not neighbours come up to 15% short of the
    /// diameter at the end of a frame (32% before a rope that holds nothing apart let its
    /// contacts wait), and 145 of the 600 frames end more than 2% short (a copy of the test
    /// kept outside the repository), never through each other. Settled in those five piles,
    /// where about 40 pairs of spans are near each other, the floor and self-contact together
    /// cost 42 times the rope's bare step (46 µs a frame on the development machine), on
    /// average 52 times while it falls into the pile and 125 times while it is whipped
    /// round by its held end, 6 times lying straight on the floor, and 9 times for a
    /// 24-particle rope lying still in a flat spiral (37, 44, 102, 5 and 9 times in the run
    /// before: the machine's runs move by a fifth): a heap of rope is costly, keep its
    /// particles few. Section (l) gives these for every integrator (settled in the pile 3
    /// to 27 times its bare step, still in the spiral 1.7 to 9.1 times: the dearer the
    /// integrator's own step, the less).
    /// A cloth's cells are boxed by their Bézier control points and searched from 3×3
    /// samples a side: a 10×10 towel folded over a rod, one half pushed into the other, never
    /// has an edge of its drawn surface through itself (`tests/suite/contacts.rs`) and steps
    /// at 1.2 times its cost without self-contact.
    ///
    /// ```
    /// use dunas::prelude::*;
    /// use dunas::collider::Collider;
    /// use dunas::contact::{Contacts, Touch};
    ///
    /// let settings = Settings { gravity: Vec2::new(0.0, -9.8), damping: 0.5, ..Settings::default() };
    /// let material = Material { stiffness: 2000.0, damping: 1.0 };
    /// // A rope let fall in a loose S onto the floor.
    /// let mut rope: Rope<Vec2<f32>, 12> = Rope::new(Vec2::new(0.0, 1.0), Vec2::new(2.2, 1.0), 0.5, material, settings)?;
    /// let floor = [Collider::half_space(Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0))?];
    /// let contacts = Contacts::new(&floor, 0.02, Touch::Drawn(Smoothing::CatmullRom))?.with_self_contact(0.3)?;
    /// for _ in 0..120 {
    ///     let _ = rope.step_touching(1.0 / 60.0, (), &contacts)?;
    /// }
    /// assert!(rope.positions().iter().all(|p| p.y > 0.0));
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite `friction`; nothing changes
    /// then.
    pub fn with_self_contact(self, friction: P::Scalar) -> Result<Self, Error> {
        check_non_negative(friction, "friction")?;
        Ok(Contacts {
            self_friction: Some(friction),
            ..self
        })
    }

    /// Reports what the contacts did to each collider: after each step, `pushes[k]` holds
    /// collider `k`'s [`Push`]: the impulse the contacts gave it and, for a collider with a
    /// mass, how far its body moved beyond its planned path. A step sets every entry (zero
    /// for a collider it did not touch, and all zero when it returns an error); entries past
    /// the last collider are left alone, and colliders past the last entry are not
    /// reported. In `Q16` a push past the format's range is clamped at its limit, and the
    /// step's [`StepInfo::saturated`] says so.
    ///
    /// **Two-way coupling.** Add the frame's gravity (and other forces) to the body's
    /// velocity first, place the collider where the body will be at the end of the frame at
    /// that velocity, give it that velocity ([`Collider::moving`]) and the body's mass
    /// ([`Collider::with_mass`]); after the step add `shift` to the body's position and
    /// `impulse / mass` to its velocity. The body is then stepped as the rope is
    /// (semi-implicit Euler; moving it before adding gravity gains `m·g²·dt²/2` a frame in
    /// free fall, 3% of a 1.2 m drop at 60 Hz), and each contact is resolved between the
    /// rope or cloth and a body of that mass, whose velocity and place take each push at
    /// once, in the same substep. With restitution 0, a ball from half to 5 times the mass
    /// of a rope held at both ends, soft to stiff, dropped on it at 60 Hz, never raises the
    /// pair's energy by more than 1% of the drop (`tests/suite/contacts.rs`). **Limit:** a
    /// body 10 or more times the rope's mass stretching a soft rope far can gain energy (up
    /// to 6% of the drop at 10×, 63% at 20× and more at 30× and 100×, on a 2 m, 10-particle
    /// rope, k from 1 500 to 30 000 N/m) and can slip through it; give such a body a stiffer rope, or
    /// make it one of the rope's particles ([`set_inv_mass`](crate::MassSpring::set_inv_mass))
    /// where it hangs on it. A collider without a
    /// mass is kinematic (infinitely heavy): its `impulse` is still reported, its `shift`
    /// stays 0.
    ///
    /// ```
    /// use dunas::prelude::*;
    /// use dunas::collider::Collider;
    /// use dunas::contact::{Contacts, Push, Touch};
    ///
    /// let settings = Settings { gravity: Vec2::new(0.0, -9.8), ..Settings::default() };
    /// let material = Material { stiffness: 400.0, damping: 0.5 };
    /// let mut rope: Rope<Vec2<f32>, 8> = Rope::new(Vec2::new(0.0, 0.0), Vec2::new(7.0, 0.0), 1.0, material, settings)?;
    /// rope.set_inv_mass(7, 0.0)?; // both ends held
    /// let (mut ball, mut velocity, mass) = (Vec2::new(3.5, 1.0), Vec2::new(0.0, -4.0), 3.0);
    /// let mut pushes = [Push::default(); 1];
    /// for _ in 0..60 {
    ///     velocity += Vec2::new(0.0, -9.8) * (1.0 / 60.0); // gravity first
    ///     ball += velocity * (1.0 / 60.0); // where the ball will be at the end of the frame
    ///     let colliders = [Collider::ball(ball, 0.3)?.moving(velocity)?.with_mass(mass)?];
    ///     let contacts = Contacts::new(&colliders, 0.02, Touch::Drawn(Smoothing::BSpline))?
    ///         .with_pushes(&mut pushes);
    ///     let _ = rope.step_touching(1.0 / 60.0, (), &contacts)?;
    ///     ball += pushes[0].shift;
    ///     velocity += pushes[0].impulse / mass;
    /// }
    /// assert!(ball.y > -3.0); // the rope caught it
    /// # Ok::<(), dunas::Error>(())
    /// ```
    pub fn with_pushes(self, pushes: &'a mut [Push<P>]) -> Self {
        Contacts {
            pushes: Cell::from_mut(pushes).as_slice_of_cells(),
            ..self
        }
    }

    /// Sets every report to zero (at the start of a step, and after a refused one).
    pub(crate) fn clear_pushes(&self) {
        for cell in self.pushes.iter().take(self.colliders.len()) {
            cell.set(Push::default());
        }
    }

    /// Ends a step's report: all zero after a refused step, and a `Q16` push clamped at the
    /// format's limit marks the step [`saturated`](StepInfo::saturated).
    pub(crate) fn finish_report(
        &self,
        info: Result<StepInfo<P::Scalar>, Error>,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        let Ok(mut info) = info else {
            self.clear_pushes();
            return info;
        };
        let reported = self.pushes.iter().take(self.colliders.len());
        info.saturated |= reported
            .map(Cell::get)
            .any(|push| !(push.impulse.is_finite() && push.shift.is_finite()));
        Ok(info)
    }

    /// Adds to collider `k`'s report the momentum `given` to the rope or cloth and the
    /// distance `moved` its body was pushed.
    fn report(&self, k: usize, given: P, moved: P) {
        if let Some(cell) = self.pushes.get(k) {
            let push = cell.get();
            cell.set(Push {
                impulse: push.impulse - given,
                shift: push.shift + moved,
            });
        }
    }

    /// Collider `k` as a body now: its velocity and inverse mass. A collider with a mass
    /// whose push is reported has taken every impulse of this step so far; any other moves
    /// as the game moves it, infinitely heavy (inverse mass 0).
    fn body(&self, k: usize, collider: &Collider<P>) -> (P, P::Scalar) {
        match self.pushes.get(k) {
            Some(cell) if collider.inv_mass() > P::Scalar::ZERO => (
                collider.velocity() + cell.get().impulse * collider.inv_mass(),
                collider.inv_mass(),
            ),
            _ => (collider.velocity(), P::Scalar::ZERO),
        }
    }

    /// What carries a point into collider `k`'s frame at its end-of-step pose, `lag` seconds
    /// before the step ends: its planned motion over the lag, less how far its body has
    /// been moved beyond that plan.
    fn offset(&self, k: usize, collider: &Collider<P>, lag: P::Scalar) -> P {
        let planned = collider.velocity() * lag;
        match self.pushes.get(k) {
            Some(cell) if collider.inv_mass() > P::Scalar::ZERO => planned - cell.get().shift,
            _ => planned,
        }
    }

    /// Moves every body with a mass over a substep of `h` at its velocity now, beyond its
    /// planned path (called before each substep's contacts).
    pub(crate) fn advance_bodies(&self, h: P::Scalar) {
        // Only a collider whose push is reported can be a body.
        for (k, collider) in self.colliders.iter().enumerate().take(self.pushes.len()) {
            let (velocity, inv_mass) = self.body(k, collider);
            if inv_mass > P::Scalar::ZERO {
                self.report(k, P::default(), (velocity - collider.velocity()) * h);
            }
        }
    }

    /// Whether the contacts test the particles alone ([`Touch::Particles`], no
    /// self-contact): nothing drawn to test, nothing to keep from one substep to the next.
    pub(crate) fn particles_only(&self) -> bool {
        matches!(self.touch, Touch::Particles) && self.self_friction.is_none()
    }

    /// Whether self-contact is on and tested on a drawn curve of spans: a step then keeps a
    /// [`PairMemory`] from one substep to the next. (Between the particles, self-contact
    /// runs at every substep: a pass on straight segments costs less than what waiting
    /// would leave it to undo.)
    pub(crate) fn remembers(&self) -> bool {
        let on_curve = match self.touch {
            Touch::Drawn(_) => true,
            Touch::DrawnLoop(s) => s != Smoothing::Bezier,
            Touch::Particles => false,
        };
        self.self_friction.is_some() && on_curve
    }

    /// Where the contacts are tested.
    #[inline]
    pub fn touch(&self) -> Touch {
        self.touch
    }

    /// Pushes every particle with a mass out of every collider at `timing`.
    pub(crate) fn resolve_particles(
        &self,
        pos: &mut [P],
        vel: &mut [P],
        inv_mass: &[P::Scalar],
        timing: Timing<'_, P>,
    ) {
        for (k, collider) in self.colliders.iter().enumerate() {
            // A point outside the collider's box grown by the thickness is farther than the
            // thickness from it: no distance to measure (a half-space's box holds everything).
            let reach = collider
                .outward()
                .is_none()
                .then(|| collider.bounds().grown(self.thickness));
            // A body with a mass moves as the particles push it: its offset is read again
            // for each particle; any other collider's holds for the pass.
            let pushed = collider.inv_mass() > P::Scalar::ZERO;
            let mut offset = self.offset(k, collider, timing.lag);
            let particles = pos.iter_mut().zip(vel.iter_mut()).zip(inv_mass);
            for (i, ((x, v), &w)) in particles.enumerate() {
                if w <= P::Scalar::ZERO {
                    continue;
                }
                if pushed {
                    offset = self.offset(k, collider, timing.lag);
                }
                if reach.is_some_and(|r| !r.contains(*x + offset)) {
                    continue;
                }
                self.push_particle((k, collider), (i, x, v, w), offset, timing);
            }
        }
    }

    /// Pushes particle `i` (at `x`, moving at `v`, inverse mass `w`; `offset` carries it
    /// into collider `k`'s frame) out of `collider` when within the thickness of it.
    fn push_particle(
        &self,
        (k, collider): (usize, &Collider<P>),
        (i, x, v, w): (usize, &mut P, &mut P, P::Scalar),
        offset: P,
        timing: Timing<'_, P>,
    ) {
        let Some(touch) = self.touching(collider, *x + offset) else {
            return;
        };
        let body = self.body(k, collider);
        let braking = || timing.braking([(i, P::Scalar::ONE)], body.0);
        let (dx, dv, moved) = self.response(collider, body, (touch, *v, w), braking);
        *x += dx;
        *v += dv;
        self.report(k, dv * (P::Scalar::ONE / w), moved);
    }

    /// The distance and outward normal of `collider` at `p` (a point plus its
    /// [`offset`](Self::offset)); `None` when clear by the thickness (or not finite).
    fn touching(&self, collider: &Collider<P>, p: P) -> Option<(P::Scalar, P)> {
        let (d, n) = collider.distance(p);
        (d < self.thickness && d.is_finite()).then_some((d, n))
    }

    /// The position and velocity change for a point at distance `d` from `collider` along
    /// its outward normal `n` ([`touching`](Self::touching)), moving at `v`, with inverse
    /// mass `w` (a drawn point's: `Σ w_i² / m_i`), at the end of a substep of `h`, and how
    /// far the collider's body moves; `(body_velocity, body_inv_mass)` is the collider now
    /// ([`body`](Self::body)). Against a body of finite mass the point takes its share
    /// `w / (w + 1/M)` of the push out and of the velocity change, the body the rest: an
    /// inelastic two-body contact. Friction also takes back the sliding it stops from this
    /// substep's move (`brake · h`), so a sticking contact does not creep.
    fn response(
        &self,
        collider: &Collider<P>,
        (body_velocity, body_inv_mass): (P, P::Scalar),
        ((d, n), v, w): ((P::Scalar, P), P, P::Scalar),
        braking: impl FnOnce() -> Braking<P>,
    ) -> (P, P, P) {
        let zero = P::Scalar::ZERO;
        let mut dx = n * (self.thickness - d);
        let relative = v - body_velocity;
        let vn = relative.dot(n);
        let (mut dv, mut moved) = (P::default(), P::default());
        if vn < zero {
            let push = -vn * (P::Scalar::ONE + collider.restitution());
            let (stick, kinetic) = collider.friction();
            let slide = relative - n * vn;
            let limits = (stick * push, kinetic * push);
            let brake = coulomb(slide, limits);
            let back = braking().take_back((slide, brake), n, limits);
            (dx, dv) = (dx - back, n * push - brake);
        }
        if body_inv_mass > zero {
            let share = w / (w + body_inv_mass);
            moved = dx * (share - P::Scalar::ONE);
            (dx, dv) = (dx * share, dv * share);
        }
        (dx, dv, moved)
    }
}
