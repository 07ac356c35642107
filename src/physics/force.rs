//! Forces beyond gravity, damping and springs: wind and air drag, springs to an anchor, and
//! any force field of the game's own through the [`ForceField`] trait.
//!
//! Force fields are passed to [`MassSpring::step_with`](crate::MassSpring::step_with) each
//! frame rather than stored, so a scene adds as many as it likes without a heap. Tuples of
//! fields are fields too: `(wind, anchor)`.

use crate::error::{check_non_negative, check_points};
use crate::physics::hash::StateHash;
use crate::{Error, Material, Point, Scalar, Vec3};

pub use super::pressure::Pressure;

/// Read-only view of the particles for a force field.
#[derive(Clone, Copy, Debug)]
pub struct Bodies<'a, P: Point> {
    /// Positions.
    pub pos: &'a [P],
    /// Velocities.
    pub vel: &'a [P],
    /// Inverse masses (0 for pinned particles).
    pub inv_mass: &'a [P::Scalar],
    /// Particles a row of the layout, row by row in `pos`: a cloth's `U`; a rope's every
    /// particle (one row).
    pub columns: usize,
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
    /// [`StepInfo::saturated`](crate::physics::system::StepInfo::saturated).
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

    /// `true` when the force depends on nothing but the bodies (their positions, velocities
    /// and layout) and what this adds to `key` (the field's own parameters); `false` when it
    /// changes with time or cannot tell, the default. An object stepped under a field that
    /// is not steady never falls asleep ([`Sleep`](crate::Sleep)); one
    /// asleep wakes when the key changes. Cost: a few words hashed.
    fn steady(&self, key: &mut StateHash) -> bool {
        let _ = key;
        false
    }
}

/// No extra force.
impl<P: Point> ForceField<P> for () {
    #[inline]
    fn apply(&mut self, _: P::Scalar, _: &Bodies<'_, P>, _: &mut Accelerations<'_, P>) {}

    #[inline]
    fn steady(&self, _: &mut StateHash) -> bool {
        true
    }
}

impl<P: Point, A: ForceField<P>, B: ForceField<P>> ForceField<P> for (A, B) {
    #[inline]
    fn apply(&mut self, t: P::Scalar, bodies: &Bodies<'_, P>, out: &mut Accelerations<'_, P>) {
        self.0.apply(t, bodies, out);
        self.1.apply(t, bodies, out);
    }

    #[inline]
    fn steady(&self, key: &mut StateHash) -> bool {
        self.0.steady(key) && self.1.steady(key)
    }
}

impl<P: Point, F: ForceField<P>> ForceField<P> for &mut F {
    #[inline]
    fn apply(&mut self, t: P::Scalar, bodies: &Bodies<'_, P>, out: &mut Accelerations<'_, P>) {
        (**self).apply(t, bodies, out);
    }

    #[inline]
    fn steady(&self, key: &mut StateHash) -> bool {
        (**self).steady(key)
    }
}

/// Air: linear drag toward the wind's velocity, `f = drag · (wind(t) - v)`, with optional
/// gusts that rise and fall smoothly.
///
/// The wind at time `t` is `velocity + gust · bump((t - start) / gust_length)` where
/// `bump(x) = 16 x² (1 - x)²` on `[0, 1]` (0 outside) and `start` is `gust_start`, or the
/// latest of `gust_start + k · gust_every` when `gust_every > 0` (a gust every so often): no
/// trigonometry, so it costs the same in `Q16`. Change `velocity` from the game loop for
/// slower weather. A sail takes the wind on its facets: see [`SailWind`].
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
    /// Seconds from one gust's start to the next; 0 (or less) for a single gust.
    pub gust_every: P::Scalar,
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
            gust_every: P::Scalar::ZERO,
        }
    }

    /// The wind velocity at time `t`.
    pub fn at(&self, t: P::Scalar) -> P {
        if self.gust_length <= P::Scalar::ZERO {
            return self.velocity;
        }
        let mut since = t - self.gust_start;
        if self.gust_every > P::Scalar::ZERO && since > P::Scalar::ZERO {
            // Back to the latest start: since - every · (⌈since / every⌉ - 1).
            let periods = (since / self.gust_every)
                .ceil_usize(1 << 20)
                .saturating_sub(1);
            since -= self.gust_every * P::Scalar::ratio(periods as u32, 1);
        }
        let x = since / self.gust_length;
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

    /// Steady without gusts (`gust_length <= 0` or no `gust`): its velocity and drag.
    fn steady(&self, key: &mut StateHash) -> bool {
        key.add_point(self.velocity);
        key.add_scalar(self.drag);
        self.gust_length <= P::Scalar::ZERO || self.gust == P::default()
    }
}

/// Wind that fills a sail: the air's pressure on every facet of the grid of particles it
/// blows on (the layout of [`Cloth`](crate::Cloth), read from [`Bodies::columns`], so it
/// fits any sail), plus the [`Wind`]'s own linear drag on
/// each particle.
///
/// For a facet (the quad between particles `(i, j)` and `(i+1, j+1)`) with vector area `A`
/// (area times unit normal `n`, from the cross product of its diagonals) and the wind
/// relative to its mean velocity `w`, the force is `pressure · (w·n)·|w·n| · A`, shared
/// equally by its four corners: a facet facing the wind takes it all, one edge-on takes none,
/// and a sail tied to a mast and a boom bellies out. `pressure` is `½ ρ C`, about
/// `0.7 kg/m³` for sailcloth in air (newtons per square metre per (m/s)²). Cost per
/// evaluation: one square root and about 40 multiply-adds a facet.
///
/// ```
/// use dunas::force::{SailWind, Wind};
/// use dunas::prelude::*;
/// let settings = Settings { gravity: Vec3::new(0.0, -9.8, 0.0), damping: 0.5, ..Settings::default() };
/// let m = Material { stiffness: 2000.0, damping: 1.0 };
/// // 4 m of mast along y, 3 m of boom along x: the sail is the x-y plane, the wind blows along z.
/// let mut sail: Cloth<Vec3<f32>, 6, 6> = Cloth::rectangle(
///     Vec3::new(0.0, 4.0, 0.0), Vec3::new(3.0, 0.0, 0.0), Vec3::new(0.0, -4.0, 0.0),
///     0.5, [m, m, m], settings,
/// )?;
/// sail.pin_column(0)?; // the luff, on the mast
/// sail.pin_row(5)?; // the foot, on the boom
/// let mut air = Wind::still(0.0);
/// air.velocity = Vec3::new(0.0, 0.0, 8.0);
/// let mut wind = SailWind::new(air, 0.7)?;
/// for _ in 0..120 {
///     sail.step_with(1.0 / 60.0, &mut wind)?;
/// }
/// assert!(sail.positions()[2 * 6 + 3].z > 0.05); // the sail bellies downwind
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SailWind<S: Scalar> {
    air: Wind<Vec3<S>>,
    pressure: S,
}

impl<S: Scalar> SailWind<S> {
    /// Wind `air` on a sail, with `pressure` (`½ ρ C`, see the type's docs).
    ///
    /// # Errors
    /// [`Error::NonFinite`] when a field of `air` or `pressure` is NaN or infinite;
    /// [`Error::InvalidParameter`] for a negative `pressure`, drag or gust length.
    pub fn new(air: Wind<Vec3<S>>, pressure: S) -> Result<Self, Error> {
        let mut wind = SailWind {
            air: Wind::still(S::ZERO),
            pressure: check_non_negative(pressure, "pressure")?,
        };
        wind.set_air(air)?;
        Ok(wind)
    }

    /// The wind.
    pub fn air(&self) -> &Wind<Vec3<S>> {
        &self.air
    }

    /// Changes the wind (weather from the game loop); a refused wind leaves the old one.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn set_air(&mut self, air: Wind<Vec3<S>>) -> Result<(), Error> {
        check_points(&[air.velocity, air.gust], "velocity or gust")?;
        for x in [air.drag, air.gust_length] {
            check_non_negative(x, "drag or gust length")?;
        }
        if !(air.gust_start.is_finite() && air.gust_every.is_finite()) {
            return Err(Error::NonFinite {
                name: "gust start or period",
            });
        }
        self.air = air;
        Ok(())
    }

    /// The pressure coefficient `½ ρ C`.
    pub fn pressure(&self) -> S {
        self.pressure
    }
}

impl<S: Scalar> ForceField<Vec3<S>> for SailWind<S> {
    /// Steady when its air is ([`Wind`]'s rule).
    fn steady(&self, key: &mut StateHash) -> bool {
        key.add_scalar(self.pressure);
        self.air.steady(key)
    }

    fn apply(&mut self, t: S, bodies: &Bodies<'_, Vec3<S>>, out: &mut Accelerations<'_, Vec3<S>>) {
        self.air.apply(t, bodies, out);
        let wind = self.air.at(t);
        let (pos, vel) = (bodies.pos, bodies.vel);
        let quarter = S::ratio(1, 4);
        // A corner's share, `pressure · (w·n)·|w·n| · A / 4`, from the diagonals' cross
        // product, twice `A`: an eighth of the pressure.
        let share = self.pressure * S::ratio(1, 8);
        let u = bodies.columns;
        let rows = pos.len().min(vel.len()).checked_div(u).unwrap_or(0);
        for j in 0..rows.saturating_sub(1) {
            for i in 0..u.saturating_sub(1) {
                let corners = [
                    j * u + i,
                    j * u + i + 1,
                    (j + 1) * u + i,
                    (j + 1) * u + i + 1,
                ];
                let [a, b, c, d] = corners;
                let twice_area = (pos[d] - pos[a]).cross(pos[c] - pos[b]);
                let size = twice_area.length();
                if size <= S::ZERO {
                    continue;
                }
                let mean = (vel[a] + vel[b] + vel[c] + vel[d]) * quarter;
                let normal_speed = (wind - mean).dot(twice_area) / size;
                let f = twice_area * (share * normal_speed * normal_speed.abs());
                for k in corners {
                    out.add_force(k, f);
                }
            }
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
        check_points(&[anchor], "anchor")?;
        check_non_negative(rest, "rest")?;
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
        check_points(&[anchor], "anchor")?;
        self.anchor = anchor;
        Ok(())
    }
}

impl<P: Point> ForceField<P> for AnchorSpring<P> {
    /// Always steady: its particle, anchor, rest length and material.
    fn steady(&self, key: &mut StateHash) -> bool {
        key.add_u64(self.particle as u64);
        key.add_point(self.anchor);
        for value in [self.rest, self.material.stiffness, self.material.damping] {
            key.add_scalar(value);
        }
        true
    }

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
    fn gusts_repeat() {
        let mut w = Wind::still(1.0f64);
        w.gust = Vec2::new(4.0, 0.0);
        w.gust_start = 2.0;
        w.gust_length = 1.0;
        w.gust_every = 5.0;
        for t in [2.5, 3.2, 4.9] {
            for k in 1..4 {
                let later = t + 5.0 * k as f64;
                assert!((w.at(t) - w.at(later)).length() < 1e-9, "{t} {later}");
            }
        }
        assert_eq!(w.at(2.5), Vec2::new(4.0, 0.0));
        assert_eq!(w.at(1.5), Vec2::default()); // nothing before the first gust
    }

    /// The total force of `wind` on a flat 3×3 sheet of particles of mass 1 in the x-y plane
    /// (2 m square), moving at `v`.
    fn sail_force(wind: Vec3<f64>, v: Vec3<f64>) -> Vec3<f64> {
        let pos: [Vec3<f64>; 9] =
            core::array::from_fn(|k| Vec3::new((k % 3) as f64, (k / 3) as f64, 0.0));
        let vel = [v; 9];
        let inv_mass = [1.0; 9];
        let mut acc = [Vec3::default(); 9];
        let mut air = Wind::still(0.0);
        air.velocity = wind;
        let mut sail = SailWind::new(air, 0.7).unwrap();
        let bodies = Bodies {
            pos: &pos,
            vel: &vel,
            inv_mass: &inv_mass,
            columns: 3,
        };
        let mut out = Accelerations {
            acc: &mut acc,
            inv_mass: &inv_mass,
            saturated: false,
        };
        sail.apply(0.0, &bodies, &mut out);
        acc.iter().fold(Vec3::default(), |a, &b| a + b)
    }

    /// Flat-plate pressure, closed form: `½ρC · (w·n)² · area` along the normal, nothing
    /// edge-on, nothing for a sail moving with the air.
    #[test]
    fn sail_wind_is_the_pressure_on_each_facet() {
        let face_on = sail_force(Vec3::new(0.0, 0.0, 5.0), Vec3::default());
        assert!((face_on - Vec3::new(0.0, 0.0, 0.7 * 25.0 * 4.0)).length() < 1e-9);
        let backwards = sail_force(Vec3::new(0.0, 0.0, -5.0), Vec3::default());
        assert!((backwards + face_on).length() < 1e-9);
        let oblique = sail_force(Vec3::new(3.0, 0.0, 4.0), Vec3::default());
        assert!((oblique - Vec3::new(0.0, 0.0, 0.7 * 16.0 * 4.0)).length() < 1e-9);
        assert_eq!(
            sail_force(Vec3::new(5.0, 2.0, 0.0), Vec3::default()),
            Vec3::default()
        );
        let w = Vec3::new(1.0, 2.0, 3.0);
        assert_eq!(sail_force(w, w), Vec3::default());
    }

    #[test]
    fn bad_sail_wind_is_an_error() {
        let mut air = Wind::still(0.0f32);
        assert!(SailWind::<f32>::new(air, -1.0).is_err());
        assert!(SailWind::<f32>::new(air, f32::NAN).is_err());
        let mut sail = SailWind::<f32>::new(air, 0.7).unwrap();
        air.velocity.y = f32::NAN;
        assert!(matches!(sail.set_air(air), Err(Error::NonFinite { .. })));
        air.velocity.y = 0.0;
        air.gust_every = f32::INFINITY;
        assert!(matches!(sail.set_air(air), Err(Error::NonFinite { .. })));
        air.gust_every = 0.0;
        air.gust_length = -1.0;
        assert!(sail.set_air(air).is_err());
        assert_eq!(sail.air(), &Wind::still(0.0));
    }

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
            columns: 2,
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
        assert!(matches!(
            AnchorSpring::new(0, nan, 2.0, material),
            Err(Error::NonFinite { .. })
        ));
        assert!(matches!(
            anchor.set_anchor(nan),
            Err(Error::NonFinite { .. })
        ));
        assert_eq!(anchor.anchor(), Vec2::new(0.0, 4.0));
        let bad = AnchorSpring::new(0, Vec2::new(0.0, 4.0), f64::NAN, material);
        assert!(matches!(bad, Err(Error::InvalidParameter { .. })));
    }
}
