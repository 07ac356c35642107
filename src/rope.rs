//! A rope: a row of particles on springs, drawn as a smooth curve.

use core::ops::{Deref, DerefMut};

use crate::integrator::Choice;
use crate::sampler::Sampler;
use crate::shape::Line;
use crate::smooth::{self, Smoothing};
use crate::spring::{Material, Springs};
use crate::system::{MassSpring, Settings};
use crate::{Bezier, Error, Integrator, Point, Scalar};

/// A rope of `N` particles with room for `CAP` springs of one material.
///
/// It derefs to its [`MassSpring`], so `rope.step(dt)`, `rope.set_position(0, hand)` and
/// `rope.positions()` work directly. Drawing goes through [`sample`](Rope::sample), which
/// smooths the particles into a curve with as many points as the buffer holds.
///
/// State size in `f32` 2D: `20·N + 8·CAP + 40` bytes; 256 for 8 particles on a chain.
///
/// ```
/// use dunas::{Rope, Vec2, smooth::Smoothing, spring::Material, system::Settings};
///
/// let settings = Settings { gravity: Vec2::new(0.0, -9.8), damping: 0.2, ..Settings::default() };
/// let mut rope: Rope<Vec2<f32>, 8, 7> =
///     Rope::new(Vec2::new(0.0, 0.0), Vec2::new(7.0, 0.0), 1.0, Material::new(400.0, 0.5)?, settings)?;
/// for _ in 0..60 {
///     rope.step(1.0 / 60.0)?;
/// }
/// let mut screen = [Vec2::default(); 32];
/// let n = rope.sample(Smoothing::Bezier, &mut screen)?;
/// assert_eq!(screen[0], Vec2::new(0.0, 0.0)); // still pinned
/// assert!(screen[n - 1].y < -1.0); // the free end swung down
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Rope<P: Point, const N: usize, const CAP: usize, I = Integrator> {
    system: MassSpring<P, Line<N>, Springs<P::Scalar, CAP>, I>,
}

impl<P: Point, const N: usize, const CAP: usize, I: Choice> Rope<P, N, CAP, I> {
    /// A straight rope from `start` (pinned) to `end`, of total `mass` split evenly, its
    /// springs relaxed at the initial spacing.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive mass, [`Error::CapacityExceeded`] when
    /// `CAP < N - 1`, [`Error::ZeroRestLength`] when `start == end`, and the errors of
    /// [`MassSpring::new`].
    pub fn new(
        start: P,
        end: P,
        mass: P::Scalar,
        material: Material<P::Scalar>,
        settings: Settings<P, I>,
    ) -> Result<Self, Error> {
        const { assert!(N >= 2, "a rope needs at least 2 particles") };
        crate::error::check_points(&[start, end])?;
        if !(mass > P::Scalar::ZERO && mass.is_finite()) {
            return Err(Error::InvalidParameter);
        }
        let last = (N - 1) as u32;
        let positions: [P; N] =
            core::array::from_fn(|i| start.lerp(end, P::Scalar::ratio(i as u32, last)));
        let w = P::Scalar::ratio(N as u32, 1) / mass;
        let mut inv_mass = [w; N];
        inv_mass[0] = P::Scalar::ZERO;
        let springs = Springs::chain(&positions, material)?;
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

    /// Samples the smoothed rope into `out` and returns the count (see [`smooth::sample`]).
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] when `out` holds fewer than 2 points.
    pub fn sample(&self, smoothing: Smoothing, out: &mut [P]) -> Result<usize, Error> {
        smooth::sample(smoothing, self.system.position_array(), out)
    }

    /// Samples the particles as one Bézier curve with a chosen sampler, e.g. a
    /// [`BernsteinTable`](crate::sampler::BernsteinTable) built once for the frame's point count.
    ///
    /// # Errors
    /// As the sampler's [`sample`](Sampler::sample).
    pub fn sample_with(&self, sampler: &impl Sampler<P, N>, out: &mut [P]) -> Result<usize, Error> {
        sampler.sample(&self.curve()?, out)
    }

    /// The particles as one Bézier curve.
    ///
    /// # Errors
    /// Never after a successful step (the step keeps positions in range).
    pub fn curve(&self) -> Result<Bezier<P, N>, Error> {
        Bezier::new(*self.system.position_array())
    }

    /// Length of the drawn curve within `accuracy`.
    ///
    /// # Errors
    /// As [`curve`](Self::curve).
    pub fn drawn_length(
        &self,
        smoothing: Smoothing,
        accuracy: P::Scalar,
    ) -> Result<P::Scalar, Error> {
        smooth::length(smoothing, self.system.position_array(), accuracy)
    }

    /// Scales the rest lengths so that the *drawn* curve measures `target` once the rope
    /// hangs at rest, and returns the residual `|drawn - target| / target`.
    ///
    /// The springs pull on the control polygon, which is longer than the smoothed curve
    /// wherever the rope bends (a rope sagging between two pins; one hanging straight needs
    /// nothing). Four rounds of: settle for `settle_steps` steps of `dt`, measure, rescale;
    /// then a last settle and measure for the residual.
    /// Meant for load time. The tests hold the residual under 1% for a rope sagging between
    /// two pins with each smoothing.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive target, and the errors of
    /// [`step`](MassSpring::step).
    pub fn calibrate_length(
        &mut self,
        smoothing: Smoothing,
        target: P::Scalar,
        dt: P::Scalar,
        settle_steps: u32,
    ) -> Result<P::Scalar, Error> {
        if !(target > P::Scalar::ZERO && target.is_finite()) {
            return Err(Error::InvalidParameter);
        }
        let accuracy = target * P::Scalar::ratio(1, 10_000);
        for round in 0..5 {
            for _ in 0..settle_steps {
                self.system.step(dt)?;
            }
            let drawn = self.drawn_length(smoothing, accuracy)?;
            if round == 4 {
                return Ok((drawn - target).abs() / target);
            }
            if drawn > P::Scalar::ZERO {
                self.system.topology_mut().scale_rest(target / drawn);
            }
        }
        Ok(P::Scalar::ZERO)
    }
}

impl<P: Point, const N: usize, const CAP: usize, I> Deref for Rope<P, N, CAP, I> {
    type Target = MassSpring<P, Line<N>, Springs<P::Scalar, CAP>, I>;
    fn deref(&self) -> &Self::Target {
        &self.system
    }
}

impl<P: Point, const N: usize, const CAP: usize, I> DerefMut for Rope<P, N, CAP, I> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.system
    }
}
