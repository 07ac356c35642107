//! What a system is told once: gravity, damping, scene bounds, integrator and accuracy.

use crate::error::invalid;
use crate::physics::integrator::SymplecticEuler;
use crate::{Error, Point, Scalar};

/// How close to its stability limit an explicit integrator runs: the one knob that trades
/// cost for accuracy. [`MassSpring::step`](crate::MassSpring::step) picks the substeps so
/// that `ω·h` stays at this fraction of [`Integrator::stability_limit`](crate::Integrator::stability_limit) (`ω` the stiffest
/// spring's angular frequency, `h` the substep). Substeps, and so the cost, grow as
/// `1 / fraction`. Implicit Euler and XPBD are stable at any step and take one substep
/// whatever the level.
///
/// The swing of total energy of a released, undamped 8-particle rope over 3 s, relative to
/// the energy its fall releases (`tests/suite/rope.rs`, `accuracy_levels_bound_the_energy_swing`;
/// charted against cost by `cargo run --release -p dunas-evaluate`), and the bound for any
/// start:
///
/// | level | `ω·h` (symplectic Euler, Verlet) | substeps | symplectic Euler | Verlet | any start: symplectic Euler | Verlet |
/// |---|---|---|---|---|---|---|
/// | `Fast` | 1.8 | 1× | 2.1% | 0.42% | ≤ 95% (58% measured) | ≤ 81% (14%) |
/// | `Balanced` | 1.0 | 1.8× | 0.83% | 0.10% | ≤ 67% (13%) | ≤ 25% (3.0%) |
/// | `Fine` | 0.2 | 9× | 0.18% | < 0.01% | ≤ 18% (3.5%) | ≤ 1% (0.18%) |
///
/// The last two columns are of the energy of the motion, whatever the start: a mode near
/// the stability limit carries its energy round a stretched ellipse, and in a mode of
/// frequency `ω` symplectic Euler's energy swings by up to `2a / (1 + a)` of the mode's
/// energy (`a = ω·h / 2`), Verlet's by `(ω·h)² / 4`; the bound is reached when all the
/// motion is in the stiffest mode. In brackets, the largest swing measured on the same rope
/// over 10 s from three starts that excite every mode (from rest, where the swing feeds the
/// stiff modes over time; alternating velocities; scattered ones:
/// `accuracy_levels_bound_the_energy_swing_from_any_start`); other ropes land elsewhere
/// under the bound (an 11-particle rope over 100 000 frames: 67% for symplectic Euler at
/// `Fast`). Over a long run the energy's mean wanders as the motion spreads between the
/// modes (the methods keep a nearby "shadow" energy, whose offset from the energy grows
/// with the share in the stiff modes), within the same bound: from the stiffest mode, its
/// mean over each 100 s of 10 minutes sat 5% to 13% above the start for symplectic Euler
/// and rose from 1% to 22% for Verlet (`a_symplectic_energy_wanders_within_its_bound`). So
/// the stiff modes wobble while the visible swing stays close.
/// `Fast` is the default: the wobble is in the stiffest modes, and any spring damping
/// removes those first; for a long, undamped swing whose energy shows, use `Balanced` or
/// `Fine`. Symplectic Euler's error falls about linearly with `ω·h`, Verlet's about
/// quadratically.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Accuracy {
    /// 90% of the limit (`ω·h ≈ 1.8` for symplectic Euler and Verlet): the fewest substeps
    /// that stay stable. The default.
    #[default]
    Fast,
    /// Half the limit (`ω·h ≈ 1`): 1.8× `Fast`'s substeps, energy errors 2.5× (symplectic
    /// Euler) to 4× (Verlet) smaller.
    Balanced,
    /// A tenth of the limit (`ω·h ≈ 0.2`): 9× `Fast`'s substeps. For reference runs and slow,
    /// lightly damped scenes.
    Fine,
}

impl Accuracy {
    /// The fraction of the stability limit, as `(numerator, denominator)`.
    pub const fn fraction(self) -> (u32, u32) {
        match self {
            Accuracy::Fast => (9, 10),
            Accuracy::Balanced => (1, 2),
            Accuracy::Fine => (1, 10),
        }
    }
}

/// Per-system settings, checked when they enter a system ([`MassSpring::new`] or
/// [`MassSpring::set_settings`]): a system never holds settings that would make every step
/// fail.
///
/// ```
/// use dunas::{Settings, Vec2};
/// let settings = Settings { gravity: Vec2::new(0.0, -9.8), damping: 0.2, ..Settings::default() };
/// assert!(settings.check().is_ok());
/// assert!(Settings { damping: -1.0, ..settings }.check().is_err());
/// ```
///
/// [`MassSpring::new`]: crate::MassSpring::new
/// [`MassSpring::set_settings`]: crate::MassSpring::set_settings
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings<P: Point, I = SymplecticEuler> {
    /// The time integrator, chosen by type (see [`integrator`](crate::physics::integrator)); the
    /// default [`SymplecticEuler`] links no other integrator's code.
    pub integrator: I,
    /// Substeps from the stability limit: see [`Accuracy`].
    pub accuracy: Accuracy,
    /// Gravity, an acceleration (units per second²), applied to every free particle. Finite,
    /// each coordinate within [`Scalar::SAFE_RANGE`].
    pub gravity: P,
    /// Linear damping rate (1/s, finite, `>= 0`): every free particle loses `damping · v` of
    /// acceleration.
    pub damping: P::Scalar,
    /// Scene half-size (`0 < bounds <= SAFE_RANGE`): a step that puts any coordinate beyond
    /// `±bounds` is refused as divergent. Defaults to [`Scalar::SAFE_RANGE`].
    pub bounds: P::Scalar,
}

impl<P: Point, I> Settings<P, I> {
    /// The same settings with another integrator (an [`Integrator`](crate::Integrator) for a
    /// `MassSpring`, a [`SplineStepper`](crate::objects::spline_rope::SplineStepper) for a
    /// `SplineRope`): the way to pick one other than the default,
    /// `Settings { gravity, ..Settings::default() }.with_integrator(Verlet)`.
    pub fn with_integrator<J>(self, integrator: J) -> Settings<P, J> {
        Settings {
            integrator,
            accuracy: self.accuracy,
            gravity: self.gravity,
            damping: self.damping,
            bounds: self.bounds,
        }
    }

    /// Checks every field.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for gravity; [`Error::InvalidParameter`]
    /// for a negative or non-finite damping, or bounds that are not in `(0, SAFE_RANGE]`.
    pub fn check(&self) -> Result<(), Error> {
        crate::error::check_points(&[self.gravity], "gravity")?;
        crate::error::check_non_negative(self.damping, "damping")?;
        let bounds_ok = self.bounds > P::Scalar::ZERO
            && self.bounds.is_finite()
            && self.bounds <= P::Scalar::SAFE_RANGE;
        if bounds_ok {
            Ok(())
        } else {
            Err(invalid("bounds", "finite, > 0 and at most the safe range"))
        }
    }
}

impl<P: Point> Default for Settings<P> {
    /// [`SymplecticEuler`], [`Accuracy::Fast`], no gravity, no damping, bounds at the
    /// format's safe range. Another integrator: [`with_integrator`](Settings::with_integrator).
    fn default() -> Self {
        Settings {
            integrator: SymplecticEuler,
            accuracy: Accuracy::default(),
            gravity: P::default(),
            damping: P::Scalar::ZERO,
            bounds: P::Scalar::SAFE_RANGE,
        }
    }
}
