//! Forces beyond gravity, damping and springs: wind and air drag, springs to an anchor, and
//! any force field of the game's own through the [`ForceField`] trait.
//!
//! Force fields are passed to [`MassSpring::step_with`](crate::MassSpring::step_with) each
//! frame rather than stored, so a scene adds as many as it likes without a heap. Tuples of
//! fields are fields too: `(wind, anchor)`.

use crate::error::{check_non_negative, check_points};
use crate::{Error, Material, Point, Scalar};

/// Read-only view of the particles for a force field.
#[derive(Clone, Copy, Debug)]
pub struct Bodies<'a, P: Point> {
    /// Positions.
    pub pos: &'a [P],
    /// Velocities.
    pub vel: &'a [P],
    /// Inverse masses (0 for pinned particles).
    pub inv_mass: &'a [P::Scalar],
}

/// Where a force field adds its forces: turns a force on particle `i` into acceleration.
#[derive(Debug)]
pub struct Accelerations<'a, P: Point> {
    pub(crate) acc: &'a mut [P],
    pub(crate) inv_mass: &'a [P::Scalar],
    /// Set when a `Q16` force or sum saturated (reported in the step's `StepInfo`).
    pub(crate) saturated: bool,
}

impl<P: Point> Accelerations<'_, P> {
    /// Adds force `f` to particle `i` (ignored for pinned particles and indices out of range).
    /// A `Q16` force or sum that saturates is reported in
    /// [`StepInfo::saturated`](crate::system::StepInfo::saturated).
    #[inline]
    pub fn add_force(&mut self, i: usize, f: P) {
        if let (Some(a), Some(&w)) = (self.acc.get_mut(i), self.inv_mass.get(i)) {
            let fw = f * w;
            *a += fw;
            if P::Scalar::FIXED_POINT {
                self.saturated |= !(f.is_finite() && fw.is_finite() && a.is_finite());
            }
        }
    }

    /// Adds acceleration `a` to particle `i` whatever its mass (ignored for pinned particles).
    #[inline]
    pub fn add_acceleration(&mut self, i: usize, a: P) {
        if let (Some(acc), Some(&w)) = (self.acc.get_mut(i), self.inv_mass.get(i))
            && w > P::Scalar::ZERO
        {
            *acc += a;
            if P::Scalar::FIXED_POINT {
                self.saturated |= !(a.is_finite() && acc.is_finite());
            }
        }
    }

    /// Number of particles.
    #[inline]
    pub fn len(&self) -> usize {
        self.acc.len()
    }

    /// `true` when there are no particles.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.acc.is_empty()
    }
}

/// A force of the game's own, evaluated by the integrator every time it needs forces (1 to 4
/// times per substep, see [`Integrator`](crate::Integrator)).
///
/// The implicit integrators treat these forces explicitly (no Jacobian), so a very stiff
/// custom force can still need small steps.
///
/// ```
/// use dunas::force::{Accelerations, Bodies, ForceField};
/// use dunas::{Point, Vec2};
///
/// /// Pushes every particle away from a point, like a blast.
/// struct Blast { at: Vec2<f32>, strength: f32 }
///
/// impl ForceField<Vec2<f32>> for Blast {
///     fn apply(&mut self, _time: f32, bodies: &Bodies<'_, Vec2<f32>>, out: &mut Accelerations<'_, Vec2<f32>>) {
///         for (i, &p) in bodies.pos.iter().enumerate() {
///             let d = p - self.at;
///             let r2 = d.dot(d) + 1.0;
///             out.add_force(i, d * (self.strength / r2));
///         }
///     }
/// }
/// ```
pub trait ForceField<P: Point> {
    /// Adds this field's forces at simulation time `time` (seconds since the system started).
    fn apply(&mut self, time: P::Scalar, bodies: &Bodies<'_, P>, out: &mut Accelerations<'_, P>);
}

/// No extra force.
impl<P: Point> ForceField<P> for () {
    #[inline]
    fn apply(&mut self, _: P::Scalar, _: &Bodies<'_, P>, _: &mut Accelerations<'_, P>) {}
}

impl<P: Point, A: ForceField<P>, B: ForceField<P>> ForceField<P> for (A, B) {
    #[inline]
    fn apply(&mut self, t: P::Scalar, bodies: &Bodies<'_, P>, out: &mut Accelerations<'_, P>) {
        self.0.apply(t, bodies, out);
        self.1.apply(t, bodies, out);
    }
}

impl<P: Point, F: ForceField<P>> ForceField<P> for &mut F {
    #[inline]
    fn apply(&mut self, t: P::Scalar, bodies: &Bodies<'_, P>, out: &mut Accelerations<'_, P>) {
        (**self).apply(t, bodies, out);
    }
}

/// Air: linear drag toward the wind's velocity, `f = drag · (wind(t) - v)`, with an optional
/// gust that rises and falls smoothly.
///
/// The wind at time `t` is `velocity + gust · bump((t - gust_start) / gust_length)` where
/// `bump(x) = 16 x² (1 - x)²` on `[0, 1]` (0 outside): no trigonometry, so it costs the same
/// in `Q16`. Change `velocity` from the game loop for slower weather.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wind<P: Point> {
    /// Steady wind velocity (units per second).
    pub velocity: P,
    /// Drag coefficient (force per unit of relative speed); 0 disables the field.
    pub drag: P::Scalar,
    /// Extra velocity at the peak of the gust.
    pub gust: P,
    /// When the gust starts (seconds of simulation time).
    pub gust_start: P::Scalar,
    /// How long the gust lasts (seconds); 0 disables it.
    pub gust_length: P::Scalar,
}

impl<P: Point> Wind<P> {
    /// Still air with the given drag.
    pub fn still(drag: P::Scalar) -> Self {
        Wind {
            velocity: P::default(),
            drag,
            gust: P::default(),
            gust_start: P::Scalar::ZERO,
            gust_length: P::Scalar::ZERO,
        }
    }

    /// The wind velocity at time `t`.
    pub fn at(&self, t: P::Scalar) -> P {
        if self.gust_length <= P::Scalar::ZERO {
            return self.velocity;
        }
        let x = (t - self.gust_start) / self.gust_length;
        if x <= P::Scalar::ZERO || x >= P::Scalar::ONE || !x.is_finite() {
            return self.velocity;
        }
        let y = x * (P::Scalar::ONE - x);
        let sixteen = P::Scalar::from_i16(16);
        self.velocity + self.gust * (sixteen * y * y)
    }
}

impl<P: Point> ForceField<P> for Wind<P> {
    fn apply(&mut self, t: P::Scalar, bodies: &Bodies<'_, P>, out: &mut Accelerations<'_, P>) {
        let w = self.at(t);
        for (i, &v) in bodies.vel.iter().enumerate() {
            out.add_force(i, (w - v) * self.drag);
        }
    }
}

/// A damped spring from one particle to an anchor point the game can move (a hand, a mast
/// top): the thesis's anchored spring. Checked when built and when moved, so a NaN anchor is
/// an error, never a silent no-op.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnchorSpring<P: Point> {
    particle: usize,
    anchor: P,
    rest: P::Scalar,
    material: Material<P::Scalar>,
}

impl<P: Point> AnchorSpring<P> {
    /// A spring of `material` and rest length `rest` (`>= 0`) from `particle` (flat index;
    /// one past the system's count does nothing) to `anchor`. The anchor counts as still for
    /// the spring's damping.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for the anchor;
    /// [`Error::InvalidParameter`] for a negative or non-finite rest length or a bad
    /// material ([`Material::check`]).
    pub fn new(
        particle: usize,
        anchor: P,
        rest: P::Scalar,
        material: Material<P::Scalar>,
    ) -> Result<Self, Error> {
        check_points(&[anchor])?;
        check_non_negative(rest)?;
        material.check()?;
        Ok(AnchorSpring {
            particle,
            anchor,
            rest,
            material,
        })
    }

    /// Where the anchor is.
    pub fn anchor(&self) -> P {
        self.anchor
    }

    /// Moves the anchor (a hand this frame).
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`]; the anchor stays where it was.
    pub fn set_anchor(&mut self, anchor: P) -> Result<(), Error> {
        check_points(&[anchor])?;
        self.anchor = anchor;
        Ok(())
    }
}

impl<P: Point> ForceField<P> for AnchorSpring<P> {
    fn apply(&mut self, _: P::Scalar, bodies: &Bodies<'_, P>, out: &mut Accelerations<'_, P>) {
        let (Some(&x), Some(&v)) = (bodies.pos.get(self.particle), bodies.vel.get(self.particle))
        else {
            return;
        };
        let d = self.anchor - x;
        let l = d.length();
        if l <= P::Scalar::EPSILON {
            return;
        }
        let n = d * (P::Scalar::ONE / l);
        let f = self.material.stiffness * (l - self.rest) - self.material.damping * v.dot(n);
        out.add_force(self.particle, n * f);
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;

    #[test]
    fn gust_rises_and_falls() {
        let mut w = Wind::still(1.0f32);
        w.velocity = Vec2::new(1.0, 0.0);
        w.gust = Vec2::new(4.0, 0.0);
        w.gust_start = 2.0;
        w.gust_length = 1.0;
        assert_eq!(w.at(1.0), Vec2::new(1.0, 0.0));
        assert_eq!(w.at(2.5), Vec2::new(5.0, 0.0)); // the peak
        assert!(w.at(2.25).x > 1.0 && w.at(2.25).x < 5.0);
        assert_eq!(w.at(3.5), Vec2::new(1.0, 0.0));
        assert_eq!(w.at(f32::NAN), Vec2::new(1.0, 0.0));
    }

    #[test]
    fn drag_and_anchor_forces() {
        let pos = [Vec2::new(0.0f64, 0.0), Vec2::new(3.0, 0.0)];
        let vel = [Vec2::new(2.0, 0.0), Vec2::new(0.0, 0.0)];
        let inv = [0.5, 0.0];
        let bodies = Bodies {
            pos: &pos,
            vel: &vel,
            inv_mass: &inv,
        };
        let mut acc = [Vec2::default(); 2];
        let mut out = Accelerations {
            acc: &mut acc,
            inv_mass: &inv,
            saturated: false,
        };
        Wind::still(2.0).apply(0.0, &bodies, &mut out);
        let material = Material {
            stiffness: 10.0,
            damping: 0.0,
        };
        let mut anchor = AnchorSpring::new(0, Vec2::new(0.0, 4.0), 2.0, material).unwrap();
        anchor.apply(0.0, &bodies, &mut out);
        // Drag -2·2 = -4 N in x, anchor +10·2 = 20 N in y, times inverse mass 0.5; pinned stays 0.
        assert_eq!(acc[0], Vec2::new(-2.0, 10.0));
        assert_eq!(acc[1], Vec2::new(0.0, 0.0));
        // A NaN anchor is refused, when built and when moved.
        let nan = Vec2::new(f64::NAN, 0.0);
        assert_eq!(
            AnchorSpring::new(0, nan, 2.0, material),
            Err(Error::NonFinite)
        );
        assert_eq!(anchor.set_anchor(nan), Err(Error::NonFinite));
        assert_eq!(anchor.anchor(), Vec2::new(0.0, 4.0));
        let bad = AnchorSpring::new(0, Vec2::new(0.0, 4.0), f64::NAN, material);
        assert_eq!(bad, Err(Error::InvalidParameter));
    }
}
