//! A closed cloth wrapped both ways: an inner tube, a swim ring, a tyre, blown up by a gas.

use core::ops::{Deref, DerefMut};

use crate::contact::{Contacts, Touch};
use crate::curves::surface::{SurfaceTable, sample};
use crate::error::{check_positive, invalid};
use crate::physics::force::{ForceField, Pressure};
use crate::physics::integrator::{Integrator, SymplecticEuler};
use crate::physics::shape::Grid;
use crate::physics::spring::{Material, TorusSprings};
use crate::physics::system::{MassSpring, StepInfo};
use crate::{Error, Scalar, Settings, Smoothing, Vec3};

/// A `U × V` closed cloth in the shape of a torus: `U` particles round the ring, `V` round
/// the tube, every row a ring and the last row joined to the first ([`TorusSprings`],
/// `6·U·V` springs implied by the grid, `U, V ≥ 5`). Blow it up with a
/// [`Pressure`] passed to its steps, and it is an inner tube that squashes on the
/// ground, bounces and pops.
///
/// It derefs to its [`MassSpring`] (step, pin, hold, throw); it touches colliders with its
/// drawn surface or its particles ([`step_touching`](Self::step_touching));
/// particle `(i, j)` has flat index `j * U + i`. It draws itself through tables that close
/// on themselves ([`SurfaceTable::closed`]), as one surface with no seam.
///
/// ```
/// use dunas::prelude::*;
/// use dunas::{Torus, force::Pressure, surface::SurfaceTable};
///
/// let m = Material { stiffness: 400.0, damping: 0.5 };
/// let settings = Settings { gravity: Vec3::new(0.0, -9.8, 0.0), damping: 0.2, ..Settings::default() };
/// let mut tube: Torus<f32, 8, 6> = Torus::new(Vec3::new(0.0, 1.0, 0.0), 0.5, 0.2, 1.0, [m, m, m], settings)?;
/// let mut gas = Pressure::at(50.0, tube.volume())?; // 50 N/m² at its first volume
/// let floor = [Collider::half_space(Vec3::default(), Vec3::new(0.0, 1.0, 0.0))?];
/// let contacts = Contacts::new(&floor, 0.01, Touch::Particles)?;
/// for _ in 0..60 {
///     tube.step_touching_particles(1.0 / 60.0, &mut gas, &contacts)?;
/// }
/// let (tu, tv) = (
///     SurfaceTable::<f32, 8, 33>::closed(Smoothing::CatmullRom, 33)?,
///     SurfaceTable::<f32, 6, 25>::closed(Smoothing::CatmullRom, 25)?,
/// );
/// let (mut pos, mut nor) = ([Vec3::default(); 33 * 25], [Vec3::default(); 33 * 25]);
/// assert_eq!(tube.draw(&tu, &tv, &mut pos, &mut nor)?, 33 * 25);
/// assert_eq!(pos[0], pos[32]); // the seam closes
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Torus<S: Scalar, const U: usize, const V: usize, I: Integrator = SymplecticEuler> {
    system: MassSpring<Vec3<S>, Grid<U, V>, TorusSprings<S, U, V>, I>,
}

impl<S: Scalar, const U: usize, const V: usize, I: Integrator> Torus<S, U, V, I> {
    /// A torus lying flat round `centre`, its axis along `y` (up): the ring's circle of
    /// `radius` in the `x`-`z` plane, the tube's of `tube` round it (`0 < tube < radius`).
    /// Particle `(i, j)` sits at angle `−2πi/U` round the ring (from `+x` towards `−z`) and
    /// `2πj/V` round the tube (from the outer equator up), so that `∂u × ∂v` points out and
    /// [`volume`](Self::volume) is positive. Total `mass` split evenly, nothing pinned;
    /// `materials` are the structural, shear and bending springs, relaxed as built.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive or non-finite `radius`, `tube` or
    /// `mass`, or `tube ≥ radius`; and the errors of [`MassSpring::new`].
    pub fn new(
        centre: Vec3<S>,
        radius: S,
        tube: S,
        mass: S,
        materials: [Material<S>; 3],
        settings: Settings<Vec3<S>, I>,
    ) -> Result<Self, Error> {
        check_positive(radius, "radius")?;
        check_positive(tube, "tube")?;
        check_positive(mass, "mass")?;
        if tube >= radius {
            return Err(invalid("tube", "less than the ring's radius"));
        }
        let ring: [(S, S); U] = core::array::from_fn(|i| turn(i, U));
        let round: [(S, S); V] = core::array::from_fn(|j| turn(j, V));
        let positions: [[Vec3<S>; U]; V] = core::array::from_fn(|j| {
            let (cos_v, sin_v) = round[j];
            let reach = radius + tube * cos_v;
            core::array::from_fn(|i| {
                let (cos_u, sin_u) = ring[i];
                centre + Vec3::new(reach * cos_u, tube * sin_v, -(reach * sin_u))
            })
        });
        let springs = TorusSprings::measured(&positions, materials)?;
        let w = S::ratio((U * V) as u32, 1) / mass;
        let system = MassSpring::new(positions, [[w; U]; V], springs, settings)?;
        Ok(Torus { system })
    }

    /// Advances by `dt` seconds with `forces` (its gas among them), resolving `contacts`
    /// after every substep: on the drawn closed surface for
    /// [`Touch::Drawn`](crate::contact::Touch::Drawn) with a spline or
    /// [`Smoothing::Polyline`](crate::Smoothing::Polyline) (the surface [`draw`](Self::draw)
    /// draws with closed tables of that smoothing), which catches a rod thinner than the
    /// particle spacing, or at the particles (every other [`Touch`](crate::contact::Touch),
    /// and one Bézier, which cannot close). Self-contact
    /// ([`Contacts::with_self_contact`]) walks an open grid's cells and is not applied. See
    /// [`contact`](crate::contact) for the response, its cost and the tunnelling bound.
    ///
    /// # Errors
    /// As [`MassSpring::step_with`].
    pub fn step_touching<F: ForceField<Vec3<S>>>(
        &mut self,
        dt: S,
        forces: F,
        contacts: &Contacts<'_, Vec3<S>>,
    ) -> Result<StepInfo<S>, Error> {
        let closes = !matches!(contacts.touch(), Touch::Drawn(Smoothing::Bezier));
        self.system
            .step_contacts(dt, forces, contacts, closes, |state, inv_mass, times| {
                if closes {
                    let (pos, vel) = (&mut state.pos, &mut state.vel);
                    contacts.resolve_surface(pos, vel, inv_mass, times, true);
                } else {
                    contacts.resolve_particles(
                        state.pos.as_flattened_mut(),
                        state.vel.as_flattened_mut(),
                        inv_mass.as_flattened(),
                        times,
                    );
                }
            })
    }

    /// The volume the particles enclose ([`Pressure::signed_volume`]): positive while
    /// the torus is right side out.
    pub fn volume(&self) -> S {
        Pressure::signed_volume(self.system.positions(), U)
    }

    /// Draws the smooth closed surface through the particles: `tu.count() × tv.count()`
    /// positions and unit normals (see [`surface::sample`](crate::curves::surface::sample)),
    /// the last sample of each row and column on its first (a mesh's seam), normals
    /// pointing out while the torus is right side out.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when a table is not [closed](SurfaceTable::closed), and
    /// the errors of [`surface::sample`](crate::curves::surface::sample).
    pub fn draw<const NU: usize, const NV: usize>(
        &self,
        tu: &SurfaceTable<S, U, NU>,
        tv: &SurfaceTable<S, V, NV>,
        positions: &mut [Vec3<S>],
        normals: &mut [Vec3<S>],
    ) -> Result<usize, Error> {
        if !(tu.is_closed() && tv.is_closed()) {
            return Err(invalid("tables", "closed both ways (SurfaceTable::closed)"));
        }
        sample(self.system.position_array(), tu, tv, positions, normals)
    }
}

/// `(cos, sin)` of `2πk/n`, taken in `f64` ([`turn_f64`]) and rounded to the format.
fn turn<S: Scalar>(k: usize, n: usize) -> (S, S) {
    let (cos, sin) = turn_f64(k, n);
    (S::from_f64(cos), S::from_f64(sin))
}

/// `(cos, sin)` of `k/n` of a turn in `f64`, the same bits on every target (IEEE arithmetic
/// only, no backend): the angle is folded into the nearest quarter turn's `±π/4` and summed
/// by Taylor series to within 1e-16. For building shapes (a ring of particles), not per frame.
fn turn_f64(k: usize, n: usize) -> (f64, f64) {
    let (n, k) = (n.max(1), k % n.max(1));
    // The angle is q quarter turns and x: q = round(4k/n), x = (4k - q·n)/n quarter turns.
    let q = (8 * k + n) / (2 * n);
    let x = (4 * k) as f64 - (q * n) as f64;
    let x = x / n as f64 * core::f64::consts::FRAC_PI_2;
    let (mut c, mut s, mut term_c, mut term_s) = (1.0, x, 1.0, x);
    for i in 1..12 {
        let (a, b) = ((2 * i) as f64, (2 * i + 1) as f64);
        term_c *= -x * x / ((a - 1.0) * a);
        term_s *= -x * x / (a * b);
        c += term_c;
        s += term_s;
    }
    match q % 4 {
        0 => (c, s),
        1 => (-s, c),
        2 => (-c, -s),
        _ => (s, -c),
    }
}

impl<S: Scalar, const U: usize, const V: usize, I: Integrator> Deref for Torus<S, U, V, I> {
    type Target = MassSpring<Vec3<S>, Grid<U, V>, TorusSprings<S, U, V>, I>;
    fn deref(&self) -> &Self::Target {
        &self.system
    }
}

impl<S: Scalar, const U: usize, const V: usize, I: Integrator> DerefMut for Torus<S, U, V, I> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.system
    }
}

#[cfg(test)]
mod tests {
    use super::turn_f64 as turn;

    /// Exact at the quarter turns; on the unit circle, and at the angles with known values,
    /// within 2e-16 (on the circle within 1e-15).
    #[test]
    fn turn_is_exact_at_quarters_and_accurate_between() {
        assert_eq!(turn(0, 8), (1.0, 0.0));
        assert_eq!(turn(2, 8), (0.0, 1.0));
        assert_eq!(turn(4, 8), (-1.0, 0.0));
        assert_eq!(turn(6, 8), (0.0, -1.0));
        assert_eq!(turn(9, 8), turn(1, 8));
        let half = 0.5f64;
        let root_half = 0.707_106_781_186_547_5_f64;
        let root_three_halves = 0.866_025_403_784_438_6_f64;
        for ((k, n), (c, s)) in [
            ((1, 8), (root_half, root_half)),
            ((1, 6), (half, root_three_halves)),
            ((1, 12), (root_three_halves, half)),
            ((5, 12), (-root_three_halves, half)),
            ((7, 12), (-root_three_halves, -half)),
        ] {
            let (tc, ts) = turn(k, n);
            assert!((tc - c).abs() < 2e-16 && (ts - s).abs() < 2e-16, "{k}/{n}");
        }
        for n in 1..200 {
            for k in 0..n {
                let (c, s) = turn(k, n);
                assert!((c * c + s * s - 1.0).abs() < 1e-15, "{k}/{n}");
            }
        }
    }
}
