//! The sea a 3D game's boats ride: a grid of water columns whose heights carry waves, drawn
//! as a smooth surface, and the hulls that float on it.

use super::{overlap, plan, stepped};
use crate::curves::surface::{SurfaceTable, sample};
use crate::error::{check_non_negative, check_points, check_positive, invalid};
use crate::physics::system::StepInfo;
use crate::{Error, Scalar, Vec3};

/// A box-shaped body floating on a [`Sea`]: `width` across (x), `length` along (z) and
/// `height` tall, its bottom at `bottom`, centred on `(x, z)`, of `mass`. It moves up and
/// down (buoyancy, gravity); across and along only as the game moves it (`x` and `z` are
/// the game's). A boat's hull, a crate, a buoy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hull<S> {
    /// Centre, across (units).
    pub x: S,
    /// Centre, along (units).
    pub z: S,
    /// Height of its bottom (units).
    pub bottom: S,
    /// Vertical velocity (units per second).
    pub speed: S,
    /// Width, across (units, > 0).
    pub width: S,
    /// Length, along (units, > 0).
    pub length: S,
    /// Height of the box (units, > 0): a hull under water no deeper than this is buoyed by
    /// what it displaces.
    pub height: S,
    /// Mass (> 0).
    pub mass: S,
}

impl<S: Scalar> Hull<S> {
    /// A box of `width × length × height` and `mass`, its bottom at `bottom`, centred on
    /// `(x, z)`, at rest.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a width, length, height or mass not positive and
    /// finite; [`Error::NonFinite`] / [`Error::OutOfRange`] for a position that is NaN,
    /// infinite or beyond the safe range.
    pub fn new(
        (x, z): (S, S),
        bottom: S,
        (width, length, height): (S, S, S),
        mass: S,
    ) -> Result<Self, Error> {
        check_points(&[Vec3::new(x, bottom, z)], "x, z or bottom")?;
        Ok(Hull {
            x,
            z,
            bottom,
            speed: S::ZERO,
            width: check_positive(width, "width")?,
            length: check_positive(length, "length")?,
            height: check_positive(height, "height")?,
            mass: check_positive(mass, "mass")?,
        })
    }
}

/// A `U × V` grid of water columns (a mass-spring height field): column `(i, j)` stands at
/// `x = left + i · spacing`, `z = front + j · spacing`, its surface at `heights()[j][i]`.
/// Each column is pulled towards its four neighbours' heights,
/// `ḧ = (c / spacing)² (Σ neighbours − 4h) − damping · ḣ`, so waves travel at `c` in every
/// direction (long waves; a plane wave of wavenumber `κ` along a row swings at the discrete
/// chain's `ω = (2c / spacing) · sin(κ · spacing / 2)`) and reflect at the four walls.
/// [`Hull`]s are pushed up by the water they displace (Archimedes:
/// `density · gravity · volume under the surface`) and push the columns under them down by as
/// much, so they make waves as they bob; the water they push down rises everywhere else, so
/// the sea keeps its volume. A hull whose footprint covers no column is off the sea and is
/// left where it is: park the hulls a game does not use there (the hulls are an array, so
/// that a refused step can restore them without a heap). The 2D row of the same model is
/// [`Water`](super::Water).
///
/// A hull with little reserve buoyancy sinks deep into the waves it makes: one whose mass
/// is 8% or 31% of the water its box displaces rests at Archimedes' depth within 0.1%, one at
/// 83% was still bobbing by half a metre after a minute, below the columns' still level
/// (the model has no sea floor).
///
/// Stepped by symplectic Euler in substeps that keep `c · h / spacing ≤ 0.64` (its stability
/// limit on a grid is `1/√2`). Undamped, the waves' energy stays bounded, swinging by about
/// `ω·h / 2` of each wave's share, with no drift (`tests/suite/water.rs`: a standing wave's
/// period as the discrete grid's closed form to 0.01%, a floating hull at Archimedes' depth
/// to 0.1%). No heap: `U·V` columns of two scalars. A step costs about 15 operations a column
/// a substep, and a hull a few a column under it.
///
/// ```
/// use dunas::water::{Hull, Sea};
/// use dunas::surface::SurfaceTable;
/// use dunas::{Smoothing, Vec3};
///
/// // A 16 m square of 8 × 8 columns 2 m apart, 3 m deep, waves at 5 m/s, sea water.
/// let mut sea = Sea::<f32, 8, 8>::new((0.0, 0.0), 2.0, 3.0, 5.0, 1025.0)?.with_damping(2.0)?;
/// // A 2 × 4 × 1 m hull of 2 tonnes, let go 0.2 m deep.
/// let mut hulls = [Hull::new((7.0, 7.0), 2.8, (2.0, 4.0, 1.0), 2000.0)?];
/// for _ in 0..1800 {
///     let _ = sea.step(1.0 / 60.0, 9.81, &mut hulls)?;
/// }
/// // It floats as deep below the surface under it as Archimedes says: 2000 / (1025 · 8) m.
/// let depth = sea.surface_under((7.0, 7.0), (2.0, 4.0)) - hulls[0].bottom;
/// assert!((depth - 2000.0 / (1025.0 * 8.0)).abs() < 0.005);
/// // The surface drawn smooth, 16 × 16 points with their normals (pointing up).
/// let table = SurfaceTable::<f32, 8, 16>::new(Smoothing::CatmullRom, 16)?;
/// let (mut points, mut normals) = ([Vec3::default(); 256], [Vec3::default(); 256]);
/// let n = sea.draw(&table, &table, &mut points, &mut normals)?;
/// assert!(n == 256 && normals[0].y > 0.9);
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Sea<S, const U: usize, const V: usize> {
    corner: (S, S),
    spacing: S,
    level: S,
    speed_of_waves: S,
    density: S,
    damping: S,
    heights: [[S; U]; V],
    velocities: [[S; U]; V],
}

impl<S: Scalar, const U: usize, const V: usize> Sea<S, U, V> {
    /// Still water at `level`, column `(0, 0)` at `(left, front)` and the others `spacing`
    /// apart, waves at `wave_speed`, of `density` (mass per unit volume); no damping.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for fewer than 2 columns a side, a spacing, wave speed or
    /// density not positive and finite; [`Error::NonFinite`] / [`Error::OutOfRange`] for a
    /// corner or level that is NaN, infinite or beyond the safe range.
    pub fn new(
        (left, front): (S, S),
        spacing: S,
        level: S,
        wave_speed: S,
        density: S,
    ) -> Result<Self, Error> {
        if U < 2 || V < 2 {
            return Err(invalid("U, V", "at least 2 columns a side"));
        }
        check_points(&[Vec3::new(left, level, front)], "corner or level")?;
        Ok(Sea {
            corner: (left, front),
            spacing: check_positive(spacing, "spacing")?,
            level,
            speed_of_waves: check_positive(wave_speed, "wave_speed")?,
            density: check_positive(density, "density")?,
            damping: S::ZERO,
            heights: [[level; U]; V],
            velocities: [[S::ZERO; U]; V],
        })
    }

    /// The same sea, its waves calmed at `damping` per second (≥ 0).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite damping.
    pub fn with_damping(mut self, damping: S) -> Result<Self, Error> {
        self.damping = check_non_negative(damping, "damping")?;
        Ok(self)
    }

    /// The surface's height at each column: row `j` (along z) is `heights()[j]`.
    pub fn heights(&self) -> &[[S; U]; V] {
        &self.heights
    }

    /// The surface's vertical velocity at each column.
    pub fn velocities(&self) -> &[[S; U]; V] {
        &self.velocities
    }

    /// Where column `(i, j)` stands: `(x, z)`.
    pub fn column_at(&self, i: usize, j: usize) -> (S, S) {
        let at = |k: usize| self.spacing * S::from_i16(k as i16);
        (self.corner.0 + at(i), self.corner.1 + at(j))
    }

    /// How much of each column's row and each row's cell, a spacing wide, lies within the
    /// footprint `width × length` centred on `(x, z)`.
    fn footprint(&self, (x, z): (S, S), (width, length): (S, S)) -> ([S; U], [S; V]) {
        let half = S::ratio(1, 2);
        let across = core::array::from_fn(|i| {
            overlap(self.column_at(i, 0).0, self.spacing, x, width.abs() * half)
        });
        let along = core::array::from_fn(|j| {
            overlap(self.column_at(0, j).1, self.spacing, z, length.abs() * half)
        });
        (across, along)
    }

    /// The mean height of the surface over the footprint `width × length` centred on
    /// `(x, z)` (each column's cell weighted by how much of it lies there): where a hull of
    /// that footprint floats. The still level when no column is there.
    pub fn surface_under(&self, at: (S, S), size: (S, S)) -> S {
        let (across, along) = self.footprint(at, size);
        let (mut sum, mut total) = (S::ZERO, S::ZERO);
        for (row, &b) in self.heights.iter().zip(&along) {
            for (&h, &a) in row.iter().zip(&across) {
                sum += h * (a * b);
                total += a * b;
            }
        }
        if total > S::ZERO {
            sum / total
        } else {
            self.level
        }
    }

    /// Raises column `(i, j)` to `height` (a splash, a wave the game starts).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] for a column past the grid; [`Error::NonFinite`] /
    /// [`Error::OutOfRange`] for a height that is NaN, infinite or beyond the safe range.
    /// Nothing changes then.
    pub fn set_height(&mut self, i: usize, j: usize, height: S) -> Result<(), Error> {
        crate::error::check_index(i, U)?;
        crate::error::check_index(j, V)?;
        check_points(&[Vec3::new(S::ZERO, height, S::ZERO)], "height")?;
        self.heights[j][i] = height;
        Ok(())
    }

    /// The waves' energy: kinetic `½ ρ s² Σ ḣ²` and elastic `½ ρ c² Σ (Δh)²` over the
    /// neighbouring pairs (`s` the spacing; what an undamped step keeps).
    pub fn energy(&self) -> S {
        let k = self.speed_of_waves / self.spacing;
        let square = |d: S| (d * k) * (d * k);
        let mut kinetic = S::ZERO;
        let mut elastic = S::ZERO;
        for (j, row) in self.heights.iter().enumerate() {
            for (i, &h) in row.iter().enumerate() {
                kinetic += self.velocities[j][i] * self.velocities[j][i];
                if i + 1 < U {
                    elastic += square(row[i + 1] - h);
                }
                if j + 1 < V {
                    elastic += square(self.heights[j + 1][i] - h);
                }
            }
        }
        S::ratio(1, 2) * self.density * self.spacing * self.spacing * (kinetic + elastic)
    }

    /// Advances the sea and the `hulls` on it by `dt` seconds under `gravity` (downwards,
    /// units per second², ≥ 0), in as many substeps as stability asks (at most 64; a `dt`
    /// that would need more simulates 64 stable substeps, less than `dt`, and says so in
    /// `slow_motion`). A hull's buoyancy is `density · gravity ·` the volume of its box under
    /// the surface of the columns it covers; those columns are pushed down by as much,
    /// shared by their mass (`density · spacing² ·` depth below `level`, at least one
    /// spacing deep). Returns what the step did (`saturated` and `snapped` are always
    /// `false` and 0 here).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite `dt` or gravity, or a hull
    /// as heavy as the water its whole box displaces or heavier (it would sink through the
    /// sea); [`Error::Diverged`] when a height or hull left the safe range (the sea and the
    /// hulls are left as they were).
    pub fn step<const B: usize>(
        &mut self,
        dt: S,
        gravity: S,
        hulls: &mut [Hull<S>; B],
    ) -> Result<StepInfo<S>, Error> {
        check_non_negative(dt, "dt")?;
        check_non_negative(gravity, "gravity")?;
        if hulls
            .iter()
            .any(|b| b.mass >= self.density * b.width * b.length * b.height)
        {
            return Err(invalid(
                "hulls",
                "each lighter than the water its box displaces (density · width · length · height)",
            ));
        }
        if dt == S::ZERO {
            return Ok(stepped(0, S::ZERO, false));
        }
        // Substeps keep `c · h / spacing ≤ 7/11`, just under `0.9 / √2`.
        let rate = self.speed_of_waves / self.spacing;
        let (n, h, slow) = plan(dt, rate, (7, 11));
        let saved = (self.heights, self.velocities, *hulls);
        for _ in 0..n {
            self.substep(h, rate * rate, gravity, hulls);
        }
        let sane = |x: S| x.in_safe_range();
        let fine = self
            .heights
            .iter()
            .chain(&self.velocities)
            .all(|row| row.iter().all(|&x| sane(x)))
            && hulls.iter().all(|b| sane(b.bottom) && sane(b.speed));
        if !fine {
            (self.heights, self.velocities, *hulls) = saved;
            return Err(Error::Diverged);
        }
        Ok(stepped(n, h, slow))
    }

    /// One substep of `h`; `stiffness` is `(c / spacing)²`.
    fn substep(&mut self, h: S, stiffness: S, gravity: S, hulls: &mut [Hull<S>]) {
        let heights = &self.heights;
        let mut acc = [[S::ZERO; U]; V];
        for (j, (acc, row)) in acc.iter_mut().zip(heights).enumerate() {
            let (before, after) = (&heights[j.saturating_sub(1)], &heights[(j + 1).min(V - 1)]);
            for (i, a) in acc.iter_mut().enumerate() {
                let hi = row[i];
                let sum = (row[i.saturating_sub(1)] - hi)
                    + (row[(i + 1).min(U - 1)] - hi)
                    + (before[i] - hi)
                    + (after[i] - hi);
                *a = sum * stiffness - self.velocities[j][i] * self.damping;
            }
        }
        // Buoyancy: each hull and the columns under it push on each other, through the part
        // of each column's cell the hull covers.
        let cell = self.spacing * self.spacing;
        let mut pressed = S::ZERO;
        for hull in hulls.iter_mut() {
            let (across, along) = self.footprint((hull.x, hull.z), (hull.width, hull.length));
            if across.iter().all(|&a| a == S::ZERO) || along.iter().all(|&b| b == S::ZERO) {
                // Off the sea: parked, left where it is.
                continue;
            }
            // A push on a column moves the water above the hull's bottom: its mass.
            let deep = (self.level - hull.bottom).max(self.spacing);
            let per_mass = S::ONE / (self.density * cell * deep);
            let mut lift = S::ZERO;
            for (j, &b) in along.iter().enumerate() {
                if b == S::ZERO {
                    continue;
                }
                for (i, &a) in across.iter().enumerate() {
                    if a == S::ZERO {
                        continue;
                    }
                    let under = (self.heights[j][i] - hull.bottom)
                        .max(S::ZERO)
                        .min(hull.height);
                    let force = self.density * gravity * under * (a * b);
                    lift += force;
                    let push = force * per_mass;
                    acc[j][i] -= push;
                    pressed += push;
                }
            }
            hull.speed += (lift / hull.mass - gravity) * h;
            hull.bottom += hull.speed * h;
        }
        // The water a hull pushes down rises everywhere else: the sea keeps its volume.
        let share = pressed / S::from_i16((U * V).min(i16::MAX as usize) as i16);
        for ((acc, v), x) in acc.iter().zip(&mut self.velocities).zip(&mut self.heights) {
            for ((&a, v), x) in acc.iter().zip(v.iter_mut()).zip(x.iter_mut()) {
                *v += (a + share) * h;
                *x += *v * h;
            }
        }
    }

    /// The surface drawn smooth: the columns' tops as the particles of a surface
    /// (`tu` along x, `tv` along z, one smoothing), sampled into `positions` with unit
    /// normals pointing up into `normals`, row by row; returns how many points were written.
    ///
    /// # Errors
    /// As [`surface::sample`](crate::surface::sample).
    pub fn draw<const NU: usize, const NV: usize>(
        &self,
        tu: &SurfaceTable<S, U, NU>,
        tv: &SurfaceTable<S, V, NV>,
        positions: &mut [Vec3<S>],
        normals: &mut [Vec3<S>],
    ) -> Result<usize, Error> {
        let tops: [[Vec3<S>; U]; V] = core::array::from_fn(|j| {
            core::array::from_fn(|i| {
                let (x, z) = self.column_at(i, j);
                Vec3::new(x, self.heights[j][i], z)
            })
        });
        let n = sample(&tops, tu, tv, positions, normals)?;
        // `∂x × ∂z` points down: turned up, out of the water.
        for normal in &mut normals[..n] {
            *normal = -*normal;
        }
        Ok(n)
    }
}
