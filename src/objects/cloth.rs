//! A cloth: a grid of particles on structural, shear and bending springs, drawn as a
//! Bézier patch.

use core::ops::{Deref, DerefMut};

use crate::contact::Contacts;
use crate::error::check_positive;
use crate::physics::force::ForceField;
use crate::physics::integrator::{Integrator, SymplecticEuler};
use crate::physics::shape::Grid;
use crate::physics::spring::{GridSprings, Material};
use crate::physics::system::MassSpring;
use crate::physics::system::StepInfo;
use crate::{Error, Patch, Point, Scalar, Settings, Vec3};

/// A `U × V` cloth: a sail, a flag, a cape. The springs are implied by the grid
/// ([`GridSprings`]), so an 8×8 sail in `f32` is under 2 KiB of state.
///
/// It derefs to its [`MassSpring`] (step, pin, move particles); particle `(i, j)` has flat
/// index `j * U + i`. It draws itself through a smoothed surface ([`draw`](Cloth::draw):
/// Catmull-Rom through every particle, or B-spline) or the Bézier [`patch`](Cloth::patch).
///
/// ```
/// use dunas::prelude::*;
///
/// let settings = Settings { gravity: Vec3::new(0.0, -9.8, 0.0), damping: 0.5, ..Settings::default() };
/// let m = Material { stiffness: 200.0, damping: 0.2 };
/// let mut sail: Cloth<Vec3<f32>, 8, 8> = Cloth::rectangle(
///     Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0),
///     2.0, [m, m, m], settings,
/// )?;
/// sail.pin_row(0)?; // hang it from its first row
/// sail.step(1.0 / 60.0)?;
/// let mut pos = [Vec3::default(); 16 * 16];
/// let mut nor = [Vec3::default(); 16 * 16];
/// sail.patch()?.sample_grid_with_normals(16, 16, &mut pos, &mut nor)?;
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Cloth<P: Point, const U: usize, const V: usize, I: Integrator = SymplecticEuler> {
    system: MassSpring<P, Grid<U, V>, GridSprings<P::Scalar, U, V>, I>,
}

impl<P: Point, const U: usize, const V: usize, I: Integrator> Cloth<P, U, V, I> {
    /// A flat cloth with particle `(i, j)` at `origin + du·i/(U-1) + dv·j/(V-1)`: `du` and `dv`
    /// are the whole edges. Total `mass` split evenly, nothing pinned; `materials` are the
    /// structural, shear and bending springs, relaxed at the initial spacing.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive mass; [`Error::ZeroRestLength`] for a
    /// zero edge, naming the first spring along it (`0`-`1` for `du`, `0`-`U` for `dv`,
    /// `0`-`U+1` or `1`-`U` for a diagonal); and the other errors of [`MassSpring::new`].
    pub fn rectangle(
        origin: P,
        du: P,
        dv: P,
        mass: P::Scalar,
        materials: [Material<P::Scalar>; 3],
        settings: Settings<P, I>,
    ) -> Result<Self, Error> {
        const {
            assert!(
                U >= 3 && V >= 3,
                "a cloth needs at least 3×3 particles (bending springs)"
            )
        };
        check_positive(mass, "mass")?;
        let step_u = du * P::Scalar::ratio(1, (U - 1) as u32);
        let step_v = dv * P::Scalar::ratio(1, (V - 1) as u32);
        let positions: [[P; U]; V] = core::array::from_fn(|j| {
            core::array::from_fn(|i| {
                origin
                    + du * P::Scalar::ratio(i as u32, (U - 1) as u32)
                    + dv * P::Scalar::ratio(j as u32, (V - 1) as u32)
            })
        });
        let springs = GridSprings::new(
            step_u.length(),
            step_v.length(),
            [(step_u + step_v).length(), (step_u - step_v).length()],
            materials,
        );
        let w = P::Scalar::ratio((U * V) as u32, 1) / mass;
        let system = MassSpring::new(positions, [[w; U]; V], springs, settings)?;
        Ok(Cloth { system })
    }

    /// Pins every particle of row `j` (the edge along `u` at that `v`).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] for `j >= V`.
    pub fn pin_row(&mut self, j: usize) -> Result<(), Error> {
        crate::error::check_index(j, V)?;
        for i in 0..U {
            self.system.set_inv_mass(j * U + i, P::Scalar::ZERO)?;
        }
        Ok(())
    }

    /// Pins every particle of column `i` (a mast along `v`).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] for `i >= U`.
    pub fn pin_column(&mut self, i: usize) -> Result<(), Error> {
        crate::error::check_index(i, U)?;
        for j in 0..V {
            self.system.set_inv_mass(j * U + i, P::Scalar::ZERO)?;
        }
        Ok(())
    }

    /// Advances by `dt` seconds with `forces`, resolving `contacts` after every substep: on
    /// the drawn surface for [`Touch::Drawn`](crate::contact::Touch::Drawn) (with
    /// [`Smoothing::Bezier`](crate::Smoothing::Bezier), the [`patch`](Self::patch) the cloth
    /// is drawn with), which catches a pole thinner than the particle spacing, or at the
    /// particles. See [`contact`](crate::contact) for the response, its cost and the
    /// tunnelling bound.
    ///
    /// ```
    /// use dunas::prelude::*;
    /// use dunas::collider::Collider;
    /// use dunas::contact::{Contacts, Touch};
    ///
    /// let settings = Settings { gravity: Vec3::new(0.0, -9.8, 0.0), damping: 0.5, ..Settings::default() };
    /// let m = Material { stiffness: 300.0, damping: 0.2 };
    /// let mut sheet: Cloth<Vec3<f32>, 6, 6> = Cloth::rectangle(
    ///     Vec3::new(-1.0, 1.0, -1.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 2.0),
    ///     1.0, [m, m, m], settings,
    /// )?;
    /// let ball = [Collider::ball(Vec3::new(0.0, 0.0, 0.0), 0.6)?];
    /// let contacts = Contacts::new(&ball, 0.02, Touch::Drawn(Smoothing::Bezier))?;
    /// for _ in 0..60 {
    ///     sheet.step_touching(1.0 / 60.0, (), &contacts)?;
    /// }
    /// let centre = sheet.patch()?.eval(0.5, 0.5);
    /// assert!(centre.length() > 0.6); // the sheet lies on the ball, not through it
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
        self.system
            .step_contacts(dt, forces, contacts, true, |state, inv_mass, times| {
                contacts.resolve_surface(&mut state.pos, &mut state.vel, inv_mass, times, false)
            })
    }

    /// The particles as a Bézier patch, ready to sample.
    ///
    /// # Errors
    /// Never after a successful step (the step keeps positions in range).
    pub fn patch(&self) -> Result<Patch<P, U, V>, Error> {
        Patch::new(*self.system.position_array())
    }
}

impl<S: Scalar, const U: usize, const V: usize, I: Integrator> Cloth<Vec3<S>, U, V, I> {
    /// Samples the single Bézier patch through the particles as control points (see
    /// [`patch`](Self::patch)): an `nu × nv` grid of positions and unit normals (see
    /// [`Patch::sample_grid_with_normals`]); returns the point count. The surface a game
    /// draws through its particles is [`draw`](Self::draw)'s.
    ///
    /// # Errors
    /// As [`Patch::sample_grid_with_normals`].
    pub fn sample_patch(
        &self,
        nu: usize,
        nv: usize,
        positions: &mut [Vec3<S>],
        normals: &mut [Vec3<S>],
    ) -> Result<usize, Error> {
        self.patch()?
            .sample_grid_with_normals(nu, nv, positions, normals)
    }
}

impl<S: Scalar, const U: usize, const V: usize, I: Integrator> Cloth<Vec3<S>, U, V, I> {
    /// Draws the cloth's smoothed surface through the tables' smoothing (see
    /// [`surface`](crate::curves::surface)): `tu.count() × tv.count()` positions and unit normals,
    /// evaluated separably. Catmull-Rom passes through every particle; the tables are built
    /// once and reused every frame.
    ///
    /// # Errors
    /// As [`surface::sample`](crate::curves::surface::sample).
    pub fn draw<const NU: usize, const NV: usize>(
        &self,
        tu: &crate::curves::surface::SurfaceTable<S, U, NU>,
        tv: &crate::curves::surface::SurfaceTable<S, V, NV>,
        positions: &mut [Vec3<S>],
        normals: &mut [Vec3<S>],
    ) -> Result<usize, Error> {
        crate::curves::surface::sample(self.system.position_array(), tu, tv, positions, normals)
    }
}

impl<P: Point, const U: usize, const V: usize, I: Integrator> Deref for Cloth<P, U, V, I> {
    type Target = MassSpring<P, Grid<U, V>, GridSprings<P::Scalar, U, V>, I>;
    fn deref(&self) -> &Self::Target {
        &self.system
    }
}

impl<P: Point, const U: usize, const V: usize, I: Integrator> DerefMut for Cloth<P, U, V, I> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.system
    }
}
