//! The gas inside a closed loop of particles: a jelly, a balloon, a tyre.

use super::force::{Accelerations, Bodies, ForceField};
use crate::error::check_non_negative;
use crate::{Error, Scalar, Vec2};

/// The gas inside a closed loop of particles (a 2D soft body): it pushes every edge of the
/// loop outwards with the pressure `p = amount / area`, Boyle's law at a constant temperature
/// (`amount` is `n R T`, pressure times area, in force × length in 2D). Squeezed to half its
/// area, the gas pushes twice as hard; the force is the gradient of `−amount · ln(area)`, so
/// it stores and returns energy as a spring does.
///
/// The loop is the system's particles in order, the last joined back to the first (a
/// [`Springs::closed_loop`](crate::spring::Springs::closed_loop) ring), in either direction.
/// The pushes of a closed loop sum to zero, so the gas never moves the body as a whole: held
/// and thrown, a jelly's centre of mass flies the ballistic arc.
/// Each edge's push, `p` times its length along its outward normal, is shared by its two
/// ends. A loop whose area is within rounding of 0 (collapsed, or turned inside out through
/// zero) gets no push that evaluation, never an infinite one; so does a `Q16` loop whose
/// area does not fit the format (past 32 767 square units), and the step reports it
/// `saturated`. A loop that crosses itself (a
/// figure eight) counts its lobes' areas with opposite signs, and the gas pushes as if their
/// difference were its area: build the ring without crossings. Cost: one cross product and
/// three multiply-adds a particle, and one division.
///
/// Measured (`tests/suite/pressure.rs`): a ring of 16 particles comes to rest at the radius
/// where its springs balance its gas (the closed form, by bisection) within 1% (to 5
/// digits); rolled along a floor it keeps its area within 2% (1.1% touching with its
/// particles, 0.4% with its drawn closed curve, `Touch::DrawnLoop`, which stays above the
/// floor). On a Cortex-M0 in
/// Q16.16 (`examples/mcu_jelly.rs`, 8 particles on a floor) a frame with its closed curve
/// takes 26 660 instructions on average and up to 47 155 while it bounces (two substeps).
///
/// ```
/// use dunas::force::Pressure;
/// use dunas::prelude::*;
/// use dunas::spring::Springs;
///
/// // A ring of 16 particles, radius 1 m, 1 kg, in no gravity, blown up by its gas.
/// let ring: [Vec2<f32>; 16] = core::array::from_fn(|i| {
///     let a = core::f32::consts::TAU * i as f32 / 16.0;
///     Vec2::new(a.cos(), a.sin())
/// });
/// let springs = Springs::<f32, 16>::closed_loop(&ring, Material { stiffness: 200.0, damping: 1.0 })?;
/// let settings = Settings { damping: 1.0, ..Settings::default() };
/// let mut jelly = Rope::from_parts(ring, [16.0; 16], springs, settings)?;
/// let mut gas = Pressure::new(10.0)?; // 10 N·m: 3.2 N/m of pressure at its first area
/// for _ in 0..300 {
///     let _ = jelly.step_with(1.0 / 60.0, &mut gas)?;
/// }
/// assert!(Pressure::area(jelly.positions()) > 3.2); // blown up past π m²
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pressure<S> {
    amount: S,
}

impl<S: Scalar> Pressure<S> {
    /// Gas of `amount` (`n R T`: pressure × area, ≥ 0; 0 is no gas).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite amount.
    pub fn new(amount: S) -> Result<Self, Error> {
        Ok(Pressure {
            amount: check_non_negative(amount, "amount")?,
        })
    }

    /// The gas that pushes with `pressure` at `area`: `amount = pressure · area`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite pressure, area or product
    /// (a `Q16` product past the format's range).
    pub fn at(pressure: S, area: S) -> Result<Self, Error> {
        check_non_negative(pressure, "pressure")?;
        check_non_negative(area, "area")?;
        Self::new(pressure * area)
    }

    /// The gas's amount, `n R T`.
    pub fn amount(&self) -> S {
        self.amount
    }

    /// Lets the gas out: a balloon that bursts. The field cannot see the springs, so when a
    /// step reports a torn loop ([`StepInfo::snapped`](crate::system::StepInfo::snapped), or
    /// a cut) the game calls this, and the loop goes limp.
    pub fn pop(&mut self) {
        self.amount = S::ZERO;
    }

    /// The area the loop `points` encloses (the shoelace formula, taken about the first
    /// point so that `Q16` sums stay small): positive counter-clockwise, negative clockwise;
    /// in `Q16`, the format's limit (not finite) when it does not fit.
    pub fn signed_area(points: &[Vec2<S>]) -> S {
        let Some(&origin) = points.first() else {
            return S::ZERO;
        };
        let mut twice = S::ZERO;
        for pair in points.windows(2) {
            twice += (pair[0] - origin).cross(pair[1] - origin);
            if !twice.is_finite() {
                // A `Q16` sum past the format stays at its limit (a saturated value is not
                // sticky: later terms could bring it back inside).
                return twice;
            }
        }
        twice * S::ratio(1, 2)
    }

    /// The area the loop `points` encloses, whichever way round it goes.
    pub fn area(points: &[Vec2<S>]) -> S {
        Self::signed_area(points).abs()
    }
}

impl<S: Scalar> ForceField<Vec2<S>> for Pressure<S> {
    fn apply(&mut self, _: S, bodies: &Bodies<'_, Vec2<S>>, out: &mut Accelerations<'_, Vec2<S>>) {
        let x = bodies.pos;
        let area = Self::signed_area(x);
        if !area.is_finite() {
            // A `Q16` loop too large for its area to fit the format: no push, reported.
            out.saturated = true;
            return;
        }
        // A signed area: the outward normal of a clockwise loop's edge points the other way,
        // and so does its pressure, so the push is outwards either way.
        if area.abs() <= S::EPSILON * S::from_i16(16) || self.amount == S::ZERO {
            return;
        }
        let half = self.amount / area * S::ratio(1, 2);
        if !half.is_finite() {
            out.saturated = true;
            return;
        }
        let n = x.len();
        for i in 0..n {
            let j = if i + 1 == n { 0 } else { i + 1 };
            let e = x[j] - x[i];
            // The edge's outward normal for a counter-clockwise loop, its length |e|.
            let push = Vec2::new(e.y, -e.x) * half;
            out.add_force(i, push);
            out.add_force(j, push);
        }
    }
}
