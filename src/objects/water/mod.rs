//! Water boats ride: a row of columns whose heights carry waves for a 2D game ([`Water`]),
//! a grid of them for a 3D one ([`Sea`]), and bodies that float on them by buoyancy and
//! make waves.

mod sea;

pub use sea::{Hull, Sea};

use crate::curves::smooth::Smoothed;
use crate::error::{check_non_negative, check_points, check_positive, invalid};
use crate::physics::system::{MAX_SUBSTEPS, StepInfo};
use crate::{Error, Scalar, Smoothing, Vec2};

/// A body floating on [`Water`]: a box `width` wide and `height` tall, its bottom at
/// `bottom`, centred on `x`, of `mass`; it moves up and down (buoyancy, gravity) and
/// sideways only as the game moves it (`x` is the game's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Floater<S> {
    /// Centre, across (units).
    pub x: S,
    /// Height of its bottom (units).
    pub bottom: S,
    /// Vertical velocity (units per second).
    pub speed: S,
    /// Width (units, > 0).
    pub width: S,
    /// Height of the box (units, > 0): a body under water no deeper than this is buoyed by
    /// what it displaces.
    pub height: S,
    /// Mass (> 0).
    pub mass: S,
}

impl<S: Scalar> Floater<S> {
    /// A box of `width × height` and `mass`, its bottom at `bottom`, centred on `x`, at rest.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a width, height or mass not positive and finite;
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a position that is NaN, infinite or
    /// beyond the safe range.
    pub fn new(x: S, bottom: S, width: S, height: S, mass: S) -> Result<Self, Error> {
        check_points(&[Vec2::new(x, bottom)], "x or bottom")?;
        Ok(Floater {
            x,
            bottom,
            speed: S::ZERO,
            width: check_positive(width, "width")?,
            height: check_positive(height, "height")?,
            mass: check_positive(mass, "mass")?,
        })
    }
}

/// A row of `N` water columns (a mass-spring height field): column `i` stands at
/// `left + i · spacing`, its surface at `heights()[i]`. Each column is pulled towards its
/// neighbours' heights, `ḧᵢ = (c / spacing)² (hᵢ₋₁ − 2hᵢ + hᵢ₊₁) − damping · ḣᵢ`, so waves
/// travel at `c` (long waves; the discrete chain's closed form
/// `ω = (2c / spacing) · sin(κ · spacing / 2)` for a wave of wavenumber `κ`) and reflect at
/// both ends (walls). Floating bodies ([`Floater`]) are pushed up by the water they displace
/// (Archimedes: `density · gravity · area under the surface`) and push the columns under
/// them down by as much, so they make waves as they bob; the water they push down rises
/// everywhere else, so the row keeps its volume.
///
/// Stepped by symplectic Euler in substeps that keep `c · h / spacing ≤ 0.9` (its stability
/// limit is 1). Undamped, the waves' energy stays bounded, swinging by about `ω·h / 2` of
/// each wave's share: a long wave within 1% (0.83% measured, 64 columns at 60 Hz), a splash
/// that excites every wave within 35% (30%), with no drift (`tests/suite/water.rs`, with the
/// standing wave's period as the discrete chain's to 0.001% and a floating box at
/// Archimedes' depth to 0.01%, 1% in `Q16`). No heap: `N` columns of two scalars.
///
/// ```
/// use dunas::water::{Floater, Water};
/// use dunas::Vec2;
///
/// // A 4 m pool of 16 columns, 1 m deep, waves at 2 m/s; a 0.5 m box of 100 kg (water 1000 kg/m²).
/// let mut pool = Water::<f32, 16>::new(0.0, 0.25, 1.0, 2.0, 1000.0)?.with_damping(2.0)?;
/// let mut boat = [Floater::new(2.0, 1.2, 0.5, 0.4, 100.0)?];
/// for _ in 0..1200 {
///     let _ = pool.step(1.0 / 60.0, 9.81, &mut boat)?;
/// }
/// // At rest it floats as deep below the surface under it as Archimedes says: 0.2 m.
/// let depth = pool.surface_under(2.0, 0.5) - boat[0].bottom;
/// assert!((depth - 100.0 / (1000.0 * 0.5)).abs() < 0.002);
/// let mut curve = [Vec2::default(); 61];
/// let n = pool.draw(dunas::Smoothing::CatmullRom, &mut curve)?; // the surface, drawn smooth
/// assert_eq!(n, 61);
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Water<S, const N: usize> {
    left: S,
    spacing: S,
    level: S,
    speed_of_waves: S,
    density: S,
    damping: S,
    heights: [S; N],
    velocities: [S; N],
}

impl<S: Scalar, const N: usize> Water<S, N> {
    /// Still water at `level`, its columns `spacing` apart from `left`, waves at
    /// `wave_speed`, of `density` (mass per unit area in 2D); no damping.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for fewer than 2 columns, a spacing, wave speed or density
    /// not positive and finite; [`Error::NonFinite`] / [`Error::OutOfRange`] for a `left` or
    /// `level` that is NaN, infinite or beyond the safe range.
    pub fn new(left: S, spacing: S, level: S, wave_speed: S, density: S) -> Result<Self, Error> {
        if N < 2 {
            return Err(invalid("N", "at least 2 columns"));
        }
        check_points(&[Vec2::new(left, level)], "left or level")?;
        Ok(Water {
            left,
            spacing: check_positive(spacing, "spacing")?,
            level,
            speed_of_waves: check_positive(wave_speed, "wave_speed")?,
            density: check_positive(density, "density")?,
            damping: S::ZERO,
            heights: [level; N],
            velocities: [S::ZERO; N],
        })
    }

    /// The same water, its waves calmed at `damping` per second (≥ 0).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite damping.
    pub fn with_damping(mut self, damping: S) -> Result<Self, Error> {
        self.damping = check_non_negative(damping, "damping")?;
        Ok(self)
    }

    /// The surface's height at each column.
    pub fn heights(&self) -> &[S; N] {
        &self.heights
    }

    /// The surface's vertical velocity at each column.
    pub fn velocities(&self) -> &[S; N] {
        &self.velocities
    }

    /// Where column `i` stands across.
    pub fn column_x(&self, i: usize) -> S {
        self.left + self.spacing * S::from_i16(i as i16)
    }

    /// How much of the strip of column `i` (a spacing wide around it) lies within `half` of
    /// `x`.
    fn shared(&self, i: usize, x: S, half: S) -> S {
        overlap(self.column_x(i), self.spacing, x, half)
    }

    /// The mean height of the surface over `width` around `x` (each column's strip weighted
    /// by how much of it lies there): where a body of that width floats. The still level
    /// when no column is there.
    pub fn surface_under(&self, x: S, width: S) -> S {
        let half = width.abs() * S::ratio(1, 2);
        let (mut sum, mut total) = (S::ZERO, S::ZERO);
        for i in 0..N {
            let shared = self.shared(i, x, half);
            sum += self.heights[i] * shared;
            total += shared;
        }
        if total > S::ZERO {
            sum / total
        } else {
            self.level
        }
    }

    /// Raises column `i` to `height` (a splash, a wave the game starts).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] for a column past the row; [`Error::NonFinite`] /
    /// [`Error::OutOfRange`] for a height that is NaN, infinite or beyond the safe range.
    /// Nothing changes then.
    pub fn set_height(&mut self, i: usize, height: S) -> Result<(), Error> {
        crate::error::check_index(i, N)?;
        check_points(&[Vec2::new(S::ZERO, height)], "height")?;
        self.heights[i] = height;
        Ok(())
    }

    /// The waves' energy per unit of `gravity`-free measure: kinetic `½ ρ Σ ḣ² · spacing` and
    /// elastic `½ ρ (c / spacing)² Σ (hᵢ₊₁ − hᵢ)² · spacing` (what an undamped step keeps).
    pub fn energy(&self) -> S {
        let half = S::ratio(1, 2);
        let k = self.speed_of_waves / self.spacing;
        let kinetic: S = self.velocities.iter().fold(S::ZERO, |s, &v| s + v * v);
        let elastic: S = self
            .heights
            .windows(2)
            .fold(S::ZERO, |s, w| s + (w[1] - w[0]) * k * ((w[1] - w[0]) * k));
        half * self.density * self.spacing * (kinetic + elastic)
    }

    /// Advances the water and the `bodies` on it by `dt` seconds under `gravity` (downwards,
    /// units per second², ≥ 0), in as many substeps as stability asks (at most 64; a `dt`
    /// that would need more simulates 64 stable substeps, less than `dt`, and says so in
    /// `slow_motion`, as a system's step does). A body's buoyancy is `density · gravity ·`
    /// the area of its box under the surface of the columns it spans; the columns under it
    /// are pushed down by as much, shared by their mass (`density · spacing ·` depth below
    /// `level`, at least one spacing deep). Returns what the step did (`saturated` and
    /// `snapped` are always `false` and 0 here).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite `dt` or gravity, or a body
    /// as heavy as the water its whole box displaces or heavier (it would sink through the
    /// row); [`Error::Diverged`] when a height or body left the safe range (the water and bodies
    /// are left as they were).
    pub fn step<const B: usize>(
        &mut self,
        dt: S,
        gravity: S,
        bodies: &mut [Floater<S>; B],
    ) -> Result<StepInfo<S>, Error> {
        check_non_negative(dt, "dt")?;
        check_non_negative(gravity, "gravity")?;
        if bodies
            .iter()
            .any(|b| b.mass >= self.density * b.width * b.height)
        {
            return Err(invalid(
                "bodies",
                "each lighter than the water its box displaces (density · width · height)",
            ));
        }
        if dt == S::ZERO {
            return Ok(stepped(0, S::ZERO, false));
        }
        // Substeps keep `c · h / spacing ≤ 0.9`.
        let rate = self.speed_of_waves / self.spacing;
        let (n, h, slow) = plan(dt, rate, (9, 10));
        let saved = (self.heights, self.velocities, *bodies);
        for _ in 0..n {
            self.substep(h, rate * rate, gravity, bodies);
        }
        let sane = |x: S| x.in_safe_range();
        let fine = self
            .heights
            .iter()
            .chain(&self.velocities)
            .all(|&x| sane(x))
            && bodies.iter().all(|b| sane(b.bottom) && sane(b.speed));
        if !fine {
            (self.heights, self.velocities, *bodies) = saved;
            return Err(Error::Diverged);
        }
        Ok(stepped(n, h, slow))
    }

    /// One substep of `h`; `stiffness` is `(c / spacing)²`.
    fn substep(&mut self, h: S, stiffness: S, gravity: S, bodies: &mut [Floater<S>]) {
        let mut acc = [S::ZERO; N];
        for i in 0..N {
            let left = self.heights[i.saturating_sub(1)];
            let right = self.heights[(i + 1).min(N - 1)];
            let h_i = self.heights[i];
            acc[i] = (left - h_i + (right - h_i)) * stiffness - self.velocities[i] * self.damping;
        }
        // Buoyancy: each body and the columns under it push on each other. Column `i` is the
        // strip a spacing wide around it; a body is lifted by the water above its bottom over
        // the width it shares with each strip.
        let column_mass = self.density * self.spacing;
        let mut pressed = S::ZERO;
        for body in bodies.iter_mut() {
            let half = body.width * S::ratio(1, 2);
            // A push on a column moves the water above the body's bottom: its mass.
            let deep = (self.level - body.bottom).max(self.spacing);
            let per_mass = S::ONE / (column_mass * deep);
            let mut lift = S::ZERO;
            for i in 0..N {
                let shared = self.shared(i, body.x, half);
                if shared == S::ZERO {
                    continue;
                }
                let under = (self.heights[i] - body.bottom)
                    .max(S::ZERO)
                    .min(body.height);
                let force = self.density * gravity * under * shared;
                lift += force;
                let push = force * per_mass;
                acc[i] -= push;
                pressed += push;
            }
            body.speed += (lift / body.mass - gravity) * h;
            body.bottom += body.speed * h;
        }
        // The water a body pushes down rises everywhere else: the row keeps its volume.
        let share = pressed / S::from_i16(N as i16);
        for a in acc.iter_mut() {
            *a += share;
        }
        for i in 0..N {
            self.velocities[i] += acc[i] * h;
            self.heights[i] += self.velocities[i] * h;
        }
    }

    /// The surface drawn smooth: its columns' tops as points of a curve through them
    /// (`smoothing`), sampled into `out`; returns how many points were written.
    ///
    /// # Errors
    /// As [`Smoothed::open`] and its `sample`.
    pub fn draw(&self, smoothing: Smoothing, out: &mut [Vec2<S>]) -> Result<usize, Error> {
        let tops: [Vec2<S>; N] =
            core::array::from_fn(|i| Vec2::new(self.column_x(i), self.heights[i]));
        Smoothed::open(smoothing, &tops)?.sample(out)
    }
}

/// How much of the strip `width` wide centred on `c` lies within `half` of `x`.
fn overlap<S: Scalar>(c: S, width: S, x: S, half: S) -> S {
    let strip = width * S::ratio(1, 2);
    ((c + strip).min(x + half) - (c - strip).max(x - half)).max(S::ZERO)
}

/// The substeps of a `dt` that keep `rate · h ≤ num / den`: their count and length, and
/// whether time slows down (past [`MAX_SUBSTEPS`], each substep is the longest stable one).
fn plan<S: Scalar>(dt: S, rate: S, (num, den): (u32, u32)) -> (usize, S, bool) {
    let needed = dt * rate * S::ratio(den, num);
    let n = needed.ceil_usize(usize::from(MAX_SUBSTEPS)).max(1);
    if needed > S::from_i16(MAX_SUBSTEPS as i16) {
        (n, S::ratio(num, den) / rate, true)
    } else {
        (n, dt / S::from_i16(n as i16), false)
    }
}

/// What a water step of `n` substeps of `h` did (`slow_motion` when they are less than its
/// `dt`); water never saturates or snaps.
fn stepped<S: Scalar>(n: usize, h: S, slow_motion: bool) -> StepInfo<S> {
    StepInfo {
        substeps: n as u16,
        simulated: h * S::from_i16(n as i16),
        slow_motion,
        saturated: false,
        snapped: 0,
        converged: true,
        stretch: S::ZERO,
        residual: S::ZERO,
        asleep: false,
    }
}
