//! The mass-spring system: particles, springs, integrator, and a step that cannot explode.

use crate::force::{Accelerations, Bodies, ForceField};
use crate::integrator::Choice;
use crate::shape::Shape;
use crate::spring::{Material, Topology};
use crate::{Error, Integrator, Point, Scalar};

/// Most substeps one [`MassSpring::step`] takes; past this the step simulates less time than
/// asked (slow motion) instead of going unstable.
pub const MAX_SUBSTEPS: u16 = 64;

/// Per-system settings. Public fields: change them between steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings<P: Point, I = Integrator> {
    /// The time integrator: the [`Integrator`] enum, or a type of
    /// [`integrator::only`](crate::integrator::only) to link just that one.
    pub integrator: I,
    /// Gravity, an acceleration (units per second²), applied to every free particle.
    pub gravity: P,
    /// Linear damping rate (1/s): every free particle loses `damping · v` of acceleration.
    pub damping: P::Scalar,
    /// Scene half-size: a step that puts any coordinate beyond `±bounds` is refused as
    /// divergent. Defaults to [`Scalar::SAFE_RANGE`].
    pub bounds: P::Scalar,
}

impl<P: Point, I> Settings<P, I> {
    /// The same settings with another integrator: the way to fix one at compile time,
    /// `Settings { gravity, ..Settings::default() }.with_integrator(only::SymplecticEuler)`.
    pub fn with_integrator<J: Choice>(self, integrator: J) -> Settings<P, J> {
        Settings {
            integrator,
            gravity: self.gravity,
            damping: self.damping,
            bounds: self.bounds,
        }
    }
}

impl<P: Point> Default for Settings<P> {
    /// Symplectic Euler, no gravity, no damping, bounds at the format's safe range.
    fn default() -> Self {
        Settings {
            integrator: Integrator::default(),
            gravity: P::default(),
            damping: P::Scalar::ZERO,
            bounds: P::Scalar::SAFE_RANGE,
        }
    }
}

/// What a step did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepInfo<S> {
    /// Substeps taken.
    pub substeps: u16,
    /// Simulated time (seconds): the `dt` asked for, or less when the substep cap was hit.
    pub simulated: S,
}

/// Particles joined by springs, advanced by an [`Integrator`].
///
/// `Sh` is the particle layout ([`Line`](crate::shape::Line) for a rope,
/// [`Grid`](crate::shape::Grid) for a cloth) and `T` the [`Topology`]. Everything is stored
/// inline: `size_of` is the whole state.
///
/// A particle with inverse mass 0 is pinned: the integrators never move it, and the game moves
/// it with [`set_position`](Self::set_position) (a rope held by a hand).
#[derive(Clone)]
pub struct MassSpring<P: Point, Sh: Shape, T, I = Integrator> {
    pos: Sh::Of<P>,
    vel: Sh::Of<P>,
    inv_mass: Sh::Of<P::Scalar>,
    topology: T,
    time: P::Scalar,
    /// `ω + γ_springs` from the springs and masses (see `stiffness_bound`), kept current by
    /// every method that changes masses or springs so a step does not recompute it.
    spring_rate: P::Scalar,
    /// Gravity, damping, integrator and bounds.
    pub settings: Settings<P, I>,
}

impl<P: Point, Sh: Shape, T: core::fmt::Debug, I: core::fmt::Debug> core::fmt::Debug
    for MassSpring<P, Sh, T, I>
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MassSpring")
            .field("pos", &Sh::flat(&self.pos))
            .field("vel", &Sh::flat(&self.vel))
            .field("inv_mass", &Sh::flat(&self.inv_mass))
            .field("topology", &self.topology)
            .field("time", &self.time)
            .field("settings", &self.settings)
            .finish()
    }
}

/// Force on particle `a` from a spring to `b` (the opposite acts on `b`), or `None` when the
/// two are closer than the format can resolve a direction for.
#[inline]
fn spring_force<P: Point>(
    xa: P,
    xb: P,
    va: P,
    vb: P,
    rest: P::Scalar,
    m: Material<P::Scalar>,
) -> Option<P> {
    let d = xb - xa;
    let l = d.length();
    if l <= tiny_length::<P::Scalar>() {
        return None;
    }
    let inv = P::Scalar::ONE / l;
    // f/l along d: one vector scale instead of normalising first.
    let f = m.stiffness * (l - rest) + m.damping * (vb - va).dot(d) * inv;
    Some(d * (f * inv))
}

/// Springs shorter than this have no direction: 16 units of rounding.
#[inline]
fn tiny_length<S: Scalar>() -> S {
    S::EPSILON * S::from_i16(16)
}

/// Coordinates below this are flushed to 0 after every step so that damped motion never
/// decays into subnormal floats: a rope hanging still has its sideways offsets and speeds
/// shrinking geometrically, and arithmetic on subnormals is several times slower on x86.
/// `ε²` (1.4e-14 in `f32`) is far below anything visible at any game scale; `Q16` has no
/// subnormals and skips the flush.
#[inline]
fn flush_tiny<P: Point>(v: &mut P, limit: P::Scalar) -> bool {
    let tiny = P::Scalar::EPSILON * P::Scalar::EPSILON;
    let mut ok = true;
    for d in 0..P::DIM {
        let c = v.coord(d);
        let a = c.abs();
        if !P::Scalar::FIXED_POINT {
            // A select, not a branch: the loop stays branch-free.
            v.set_coord(d, if a < tiny { P::Scalar::ZERO } else { c });
        }
        ok &= (a <= limit) & c.is_finite();
    }
    ok
}

fn dot_all<P: Point>(a: &[P], b: &[P]) -> P::Scalar {
    let mut s = P::Scalar::ZERO;
    for (x, y) in a.iter().zip(b) {
        s += x.dot(*y);
    }
    s
}

impl<P: Point, Sh: Shape, T: Topology<P::Scalar>, I: Choice> MassSpring<P, Sh, T, I> {
    /// A system at rest at `positions`, with per-particle inverse masses (0 pins).
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a bad position, [`Error::InvalidParameter`]
    /// for a negative or non-finite inverse mass, [`Error::IndexOutOfRange`] for a spring that
    /// names a particle past the count.
    pub fn new(
        positions: Sh::Of<P>,
        inv_mass: Sh::Of<P::Scalar>,
        topology: T,
        settings: Settings<P, I>,
    ) -> Result<Self, Error> {
        crate::error::check_points(Sh::flat(&positions))?;
        if Sh::flat(&inv_mass)
            .iter()
            .any(|&w| !(w >= P::Scalar::ZERO && w.is_finite()))
        {
            return Err(Error::InvalidParameter);
        }
        let mut bad = None;
        topology.for_each_spring(|a, b, _, _| {
            if a.max(b) >= Sh::LEN && bad.is_none() {
                bad = Some(a.max(b));
            }
        });
        if let Some(index) = bad {
            return Err(Error::IndexOutOfRange {
                index,
                len: Sh::LEN,
            });
        }
        let mut system = MassSpring {
            pos: positions,
            vel: Sh::filled(P::default()),
            inv_mass,
            topology,
            time: P::Scalar::ZERO,
            spring_rate: P::Scalar::ZERO,
            settings,
        };
        system.spring_rate = system.compute_spring_rate();
        Ok(system)
    }

    /// Positions, in flat order.
    #[inline]
    pub fn positions(&self) -> &[P] {
        Sh::flat(&self.pos)
    }

    /// Positions in the layout's own array (`[P; N]` or `[[P; U]; V]`).
    #[inline]
    pub fn position_array(&self) -> &Sh::Of<P> {
        &self.pos
    }

    /// Velocities, in flat order.
    #[inline]
    pub fn velocities(&self) -> &[P] {
        Sh::flat(&self.vel)
    }

    /// Inverse masses, in flat order (0 = pinned).
    #[inline]
    pub fn inv_masses(&self) -> &[P::Scalar] {
        Sh::flat(&self.inv_mass)
    }

    /// The springs.
    #[inline]
    pub fn topology(&self) -> &T {
        &self.topology
    }

    pub(crate) fn topology_mut(&mut self) -> &mut T {
        &mut self.topology
    }

    /// Simulated time since creation (seconds).
    #[inline]
    pub fn time(&self) -> P::Scalar {
        self.time
    }

    /// Moves particle `i` to `p` (teleports; velocity unchanged). The way to drive a pinned
    /// particle from the game.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`], or [`Error::NonFinite`] / [`Error::OutOfRange`] for `p`.
    pub fn set_position(&mut self, i: usize, p: P) -> Result<(), Error> {
        crate::error::check_points(&[p])?;
        let slot = Sh::flat_mut(&mut self.pos)
            .get_mut(i)
            .ok_or(Error::IndexOutOfRange {
                index: i,
                len: Sh::LEN,
            })?;
        *slot = p;
        Ok(())
    }

    /// Sets the velocity of a free particle (pinned particles keep 0).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`], or [`Error::NonFinite`] / [`Error::OutOfRange`] for `v`.
    pub fn set_velocity(&mut self, i: usize, v: P) -> Result<(), Error> {
        crate::error::check_points(&[v])?;
        let w = *self.inv_masses().get(i).ok_or(Error::IndexOutOfRange {
            index: i,
            len: Sh::LEN,
        })?;
        if w > P::Scalar::ZERO {
            Sh::flat_mut(&mut self.vel)[i] = v;
        }
        Ok(())
    }

    /// An instant change of momentum `j` (mass × velocity) on particle `i`: a hit, a jump.
    ///
    /// # Errors
    /// As [`set_velocity`](Self::set_velocity).
    pub fn apply_impulse(&mut self, i: usize, j: P) -> Result<(), Error> {
        crate::error::check_points(&[j])?;
        let w = *self.inv_masses().get(i).ok_or(Error::IndexOutOfRange {
            index: i,
            len: Sh::LEN,
        })?;
        let v = Sh::flat(&self.vel)[i] + j * w;
        self.set_velocity(i, v)
    }

    /// Sets particle `i`'s inverse mass (0 pins it and stops it).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::InvalidParameter`] for a negative or non-finite value.
    pub fn set_inv_mass(&mut self, i: usize, inv_mass: P::Scalar) -> Result<(), Error> {
        if !(inv_mass >= P::Scalar::ZERO && inv_mass.is_finite()) {
            return Err(Error::InvalidParameter);
        }
        let slot = Sh::flat_mut(&mut self.inv_mass)
            .get_mut(i)
            .ok_or(Error::IndexOutOfRange {
                index: i,
                len: Sh::LEN,
            })?;
        *slot = inv_mass;
        if inv_mass == P::Scalar::ZERO {
            Sh::flat_mut(&mut self.vel)[i] = P::default();
        }
        self.spring_rate = self.compute_spring_rate();
        Ok(())
    }

    /// Total energy: kinetic + spring + gravitational (relative to the origin), for tests and
    /// diagnostics. Pinned particles count as infinitely heavy and still. Costs a division per
    /// particle and a square root per spring; may saturate in `Q16`.
    pub fn energy(&self) -> P::Scalar {
        let half = P::Scalar::ratio(1, 2);
        let (x, v, w) = (self.positions(), self.velocities(), self.inv_masses());
        let mut e = P::Scalar::ZERO;
        for i in 0..x.len() {
            if w[i] > P::Scalar::ZERO {
                let m = P::Scalar::ONE / w[i];
                e += m * (half * v[i].dot(v[i]) - self.settings.gravity.dot(x[i]));
            }
        }
        self.topology.for_each_spring(|a, b, rest, mat| {
            let s = x[a].distance(x[b]) - rest;
            e += half * mat.stiffness * s * s;
        });
        e
    }

    /// The highest angular frequency `ω` (rad/s) of the springs and the damping rate `γ` (1/s)
    /// that the substep count guards against, by Gershgorin's bound. Cached: changing masses
    /// or springs through this type's methods updates it.
    pub fn stiffness_bound(&self) -> (P::Scalar, P::Scalar) {
        let (omega, gamma) = self.bound_parts();
        (omega, gamma + self.settings.damping)
    }

    fn compute_spring_rate(&self) -> P::Scalar {
        let (omega, gamma) = self.bound_parts();
        omega + gamma
    }

    /// `(ω, γ from spring damping)`; one pass over the springs and two square roots per
    /// particle, so it is cached in `spring_rate`.
    fn bound_parts(&self) -> (P::Scalar, P::Scalar) {
        // Sums are kept divided by 64 and the roots taken separately, so that in Q16 neither
        // Σk nor w·Σk saturates before the square root (ω = 8·sqrt(w)·sqrt(Σk/64)).
        let w = self.inv_masses();
        let mut k = Sh::filled(P::Scalar::ZERO);
        let mut c = Sh::filled(P::Scalar::ZERO);
        {
            let (ks, cs) = (Sh::flat_mut(&mut k), Sh::flat_mut(&mut c));
            let (one, two) = (P::Scalar::ratio(1, 64), P::Scalar::ratio(2, 64));
            self.topology.for_each_spring(|a, b, _, m| {
                let (fa, fb) = (
                    if w[b] > P::Scalar::ZERO { two } else { one },
                    if w[a] > P::Scalar::ZERO { two } else { one },
                );
                ks[a] += m.stiffness * fa;
                ks[b] += m.stiffness * fb;
                cs[a] += m.damping * fa;
                cs[b] += m.damping * fb;
            });
        }
        let (mut omega, mut gamma) = (P::Scalar::ZERO, P::Scalar::ZERO);
        for ((&wi, &ki), &ci) in w.iter().zip(Sh::flat(&k)).zip(Sh::flat(&c)) {
            omega = omega.max(wi.sqrt() * ki.sqrt());
            gamma = gamma.max(wi * ci);
        }
        let eight = P::Scalar::from_i16(8);
        (
            omega * eight,
            gamma * P::Scalar::from_i16(64) + self.settings.damping,
        )
    }

    /// The substeps for a frame of `dt` and their length: enough that `(ω + γ)·h` stays at the
    /// integrator's target (see [`Integrator::target_omega_h`]), at most [`MAX_SUBSTEPS`].
    pub fn substeps_for(&self, dt: P::Scalar) -> (u16, P::Scalar) {
        let Some(per) = self
            .settings
            .integrator
            .integrator()
            .substeps_per_omega_dt::<P::Scalar>()
        else {
            return (1, dt);
        };
        let rate = self.spring_rate + self.settings.damping;
        if rate <= P::Scalar::ZERO {
            return (1, dt);
        }
        match (dt * rate * per)
            .ceil_count(MAX_SUBSTEPS as usize + 1)
            .max(1)
        {
            1 => (1, dt),
            n if n > MAX_SUBSTEPS as usize => (MAX_SUBSTEPS, P::Scalar::ONE / (rate * per)),
            n => (n as u16, dt / P::Scalar::from_i16(n as i16)),
        }
    }

    /// Advances by `dt` seconds with gravity, damping and springs only.
    ///
    /// # Errors
    /// See [`step_with`](Self::step_with).
    pub fn step(&mut self, dt: P::Scalar) -> Result<StepInfo<P::Scalar>, Error> {
        self.step_with(dt, ())
    }

    /// Advances by `dt` seconds, adding the forces of `forces` (a [`ForceField`], a tuple of
    /// them, or `()`).
    ///
    /// `dt = 0` does nothing. A large `dt` is split into substeps that keep the integrator
    /// stable; past [`MAX_SUBSTEPS`] the step simulates less time than asked (reported in
    /// [`StepInfo::simulated`]) rather than explode.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite `dt` (nothing changes).
    /// [`Error::Diverged`] when a position or velocity came out non-finite or beyond
    /// [`Settings::bounds`]: the state before the step is restored.
    pub fn step_with<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        mut forces: F,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        if !(dt >= P::Scalar::ZERO && dt.is_finite()) {
            return Err(Error::InvalidParameter);
        }
        if dt == P::Scalar::ZERO {
            return Ok(StepInfo {
                substeps: 0,
                simulated: P::Scalar::ZERO,
            });
        }
        let (n, h) = self.substeps_for(dt);
        self.guarded(n, h, &mut forces)?;
        Ok(StepInfo {
            substeps: n,
            simulated: h * P::Scalar::from_i16(n as i16),
        })
    }

    /// One integrator step of exactly `h`, without the substeps that keep it stable: for
    /// measuring an integrator at its limits. Respecting [`Integrator::stability_limit`] is
    /// up to the caller; divergence is still caught and undone.
    ///
    /// # Errors
    /// As [`step_with`](Self::step_with).
    pub fn step_once<F: ForceField<P>>(
        &mut self,
        h: P::Scalar,
        mut forces: F,
    ) -> Result<(), Error> {
        if !(h > P::Scalar::ZERO && h.is_finite()) {
            return if h == P::Scalar::ZERO {
                Ok(())
            } else {
                Err(Error::InvalidParameter)
            };
        }
        self.guarded(1, h, &mut forces)
    }

    /// `n` substeps of `h`, undone if the result is not sane.
    fn guarded<F: ForceField<P>>(
        &mut self,
        n: u16,
        h: P::Scalar,
        forces: &mut F,
    ) -> Result<(), Error> {
        let saved = (self.pos, self.vel, self.time);
        for _ in 0..n {
            match self.settings.integrator.integrator() {
                Integrator::ExplicitEuler => self.euler(h, forces, false),
                Integrator::SymplecticEuler => self.euler(h, forces, true),
                Integrator::Verlet => self.verlet(h, forces),
                Integrator::Rk4 => self.rk4(h, forces),
                Integrator::ImplicitEuler { iterations } => {
                    self.implicit_euler(h, iterations, forces)
                }
                Integrator::Xpbd { substeps } => self.xpbd(h, substeps, forces),
            }
            self.time += h;
        }
        if self.flush_and_check() {
            Ok(())
        } else {
            (self.pos, self.vel, self.time) = saved;
            Err(Error::Diverged)
        }
    }

    /// Flushes tiny coordinates to 0 (see [`flush_tiny`]) and checks that every position is
    /// finite and inside `±bounds` and every velocity inside the safe range. One pass, no
    /// early exit, so it stays cheap next to the step itself.
    fn flush_and_check(&mut self) -> bool {
        let limits = [
            (Sh::flat_mut(&mut self.pos), self.settings.bounds),
            (Sh::flat_mut(&mut self.vel), P::Scalar::SAFE_RANGE),
        ];
        let mut ok = true;
        for (points, limit) in limits {
            for p in points.iter_mut() {
                ok &= flush_tiny(p, limit);
            }
        }
        ok
    }

    /// Accelerations at state `(x, v)`: gravity, damping, springs (unless `springs` is false)
    /// and the force fields.
    fn accelerations<F: ForceField<P>>(
        &self,
        x: &[P],
        v: &[P],
        forces: &mut F,
        acc: &mut [P],
        springs: bool,
    ) {
        let w = self.inv_masses();
        let (g, damping) = (self.settings.gravity, self.settings.damping);
        for i in 0..acc.len() {
            acc[i] = if w[i] > P::Scalar::ZERO {
                g - v[i] * damping
            } else {
                P::default()
            };
        }
        if springs {
            self.topology.for_each_spring(|a, b, rest, m| {
                if let Some(f) = spring_force(x[a], x[b], v[a], v[b], rest, m) {
                    acc[a] += f * w[a];
                    acc[b] -= f * w[b];
                }
            });
        }
        let bodies = Bodies {
            pos: x,
            vel: v,
            inv_mass: w,
        };
        forces.apply(self.time, &bodies, &mut Accelerations { acc, inv_mass: w });
    }

    /// Accelerations at the current state.
    fn accelerations_now<F: ForceField<P>>(&self, forces: &mut F, springs: bool) -> Sh::Of<P> {
        let mut a = Sh::filled(P::default());
        self.accelerations(
            Sh::flat(&self.pos),
            Sh::flat(&self.vel),
            forces,
            Sh::flat_mut(&mut a),
            springs,
        );
        a
    }

    /// Explicit (`x` then `v`) or symplectic (`v` then `x`) Euler.
    fn euler<F: ForceField<P>>(&mut self, h: P::Scalar, forces: &mut F, symplectic: bool) {
        let a = self.accelerations_now(forces, true);
        let (x, v) = (Sh::flat_mut(&mut self.pos), Sh::flat_mut(&mut self.vel));
        let w = Sh::flat(&self.inv_mass);
        for (((x, v), a), &w) in x.iter_mut().zip(v.iter_mut()).zip(Sh::flat(&a)).zip(w) {
            // Pinned particles neither accelerate nor move: skip their multiplications where
            // they are costly (fixed point); floats keep a branch-free, vectorisable loop.
            if P::Scalar::FIXED_POINT && w <= P::Scalar::ZERO {
                continue;
            }
            if symplectic {
                *v += *a * h;
                *x += *v * h;
            } else {
                *x += *v * h;
                *v += *a * h;
            }
        }
    }

    fn verlet<F: ForceField<P>>(&mut self, h: P::Scalar, forces: &mut F) {
        let half = h * P::Scalar::ratio(1, 2);
        for kick in 0..2 {
            let a = self.accelerations_now(forces, true);
            let (x, v) = (Sh::flat_mut(&mut self.pos), Sh::flat_mut(&mut self.vel));
            for ((x, v), a) in x.iter_mut().zip(v.iter_mut()).zip(Sh::flat(&a)) {
                *v += *a * half;
                if kick == 0 {
                    *x += *v * h;
                }
            }
        }
    }

    fn rk4<F: ForceField<P>>(&mut self, h: P::Scalar, forces: &mut F) {
        let half = h * P::Scalar::ratio(1, 2);
        let sixth = h * P::Scalar::ratio(1, 6);
        let two = P::Scalar::from_i16(2);
        let (x0, v0) = (self.pos, self.vel);
        let (mut x, mut v, mut a) = (x0, v0, Sh::filled(P::default()));
        let (mut sum_x, mut sum_v) = (Sh::filled(P::default()), Sh::filled(P::default()));
        for stage in 0..4 {
            self.accelerations(
                Sh::flat(&x),
                Sh::flat(&v),
                forces,
                Sh::flat_mut(&mut a),
                true,
            );
            let weight = if stage == 0 || stage == 3 {
                P::Scalar::ONE
            } else {
                two
            };
            let reach = if stage < 2 { half } else { h };
            let rows = Sh::flat_mut(&mut x)
                .iter_mut()
                .zip(Sh::flat_mut(&mut v))
                .zip(Sh::flat(&a))
                .zip(Sh::flat(&x0).iter().zip(Sh::flat(&v0)))
                .zip(
                    Sh::flat_mut(&mut sum_x)
                        .iter_mut()
                        .zip(Sh::flat_mut(&mut sum_v)),
                );
            for ((((x, v), &a), (&x0, &v0)), (sx, sv)) in rows {
                // This stage's slopes are (v, a); the next stage starts from x0 + slope·reach.
                *sx += *v * weight;
                *sv += a * weight;
                if stage < 3 {
                    *x = x0 + *v * reach;
                    *v = v0 + a * reach;
                }
            }
        }
        let rows = Sh::flat_mut(&mut self.pos)
            .iter_mut()
            .zip(Sh::flat_mut(&mut self.vel))
            .zip(Sh::flat(&sum_x).iter().zip(Sh::flat(&sum_v)));
        for ((x, v), (&sx, &sv)) in rows {
            *x += sx * sixth;
            *v += sv * sixth;
        }
    }

    /// `out = J·p` for the springs' force Jacobian, scaled for backward Euler:
    /// `J·p = h·c·(n·δ)n + h²·k·[(n·δ)n + s·(δ - (n·δ)n)]` with `δ = p_b - p_a` and
    /// `s = max(0, 1 - rest/l)` (the compressive transverse term is dropped so the system stays
    /// positive definite). Subtracted at `a`, added at `b`.
    fn spring_jacobian_product(&self, h: P::Scalar, p: &[P], out: &mut [P], damping_too: bool) {
        let x = self.positions();
        let h2 = h * h;
        self.topology.for_each_spring(|a, b, rest, m| {
            let d = x[b] - x[a];
            let l = d.length();
            if l <= tiny_length::<P::Scalar>() {
                return;
            }
            let n = d * (P::Scalar::ONE / l);
            let s = (P::Scalar::ONE - rest / l).max(P::Scalar::ZERO);
            let delta = p[b] - p[a];
            let along = n * delta.dot(n);
            let mut j = (along + (delta - along) * s) * (h2 * m.stiffness);
            if damping_too {
                j += along * (h * m.damping);
            }
            out[a] -= j;
            out[b] += j;
        });
    }

    fn implicit_euler<F: ForceField<P>>(&mut self, h: P::Scalar, iterations: u8, forces: &mut F) {
        let zero = P::default();
        let w = Sh::flat(&self.inv_mass);
        let mut mass = Sh::filled(P::Scalar::ZERO);
        for (m, &wi) in Sh::flat_mut(&mut mass).iter_mut().zip(w) {
            *m = if wi > P::Scalar::ZERO {
                P::Scalar::ONE / wi
            } else {
                P::Scalar::ZERO
            };
        }
        let mass = Sh::flat(&mass);
        let free = |i: usize| w[i] > P::Scalar::ZERO;
        let diag = P::Scalar::ONE + h * self.settings.damping;

        // Right side b = h·M·a0 + h²·K·v0 (the spring part of K only; damping is in a0).
        let mut r = self.accelerations_now(forces, true);
        for (i, ri) in Sh::flat_mut(&mut r).iter_mut().enumerate() {
            *ri = *ri * (h * mass[i]);
        }
        // K·v0 enters with the opposite sign of the system matrix's -h²K term.
        let mut kv = Sh::filled(zero);
        self.spring_jacobian_product(h, Sh::flat(&self.vel), Sh::flat_mut(&mut kv), false);
        for (i, (ri, kvi)) in Sh::flat_mut(&mut r)
            .iter_mut()
            .zip(Sh::flat(&kv))
            .enumerate()
        {
            *ri = if free(i) { *ri - *kvi } else { zero };
        }

        // Conjugate gradient on (M(1 + hγ) - hC - h²K) Δv = b, pinned rows filtered out.
        let mut dv = Sh::filled(zero);
        let mut p = r;
        let mut ap = Sh::filled(zero);
        let mut rs = dot_all(Sh::flat(&r), Sh::flat(&r));
        for _ in 0..iterations {
            if rs <= P::Scalar::ZERO || !rs.is_finite() {
                break;
            }
            {
                let (pf, apf) = (Sh::flat(&p), Sh::flat_mut(&mut ap));
                for (i, q) in apf.iter_mut().enumerate() {
                    *q = pf[i] * (mass[i] * diag);
                }
                self.spring_jacobian_product(h, pf, apf, true);
                for (i, q) in apf.iter_mut().enumerate() {
                    if !free(i) {
                        *q = zero;
                    }
                }
            }
            let pap = dot_all(Sh::flat(&p), Sh::flat(&ap));
            if pap <= P::Scalar::ZERO || !pap.is_finite() {
                break;
            }
            let alpha = rs / pap;
            for ((d, r), (&pi, &api)) in Sh::flat_mut(&mut dv)
                .iter_mut()
                .zip(Sh::flat_mut(&mut r))
                .zip(Sh::flat(&p).iter().zip(Sh::flat(&ap)))
            {
                *d += pi * alpha;
                *r -= api * alpha;
            }
            let rs_new = dot_all(Sh::flat(&r), Sh::flat(&r));
            let beta = rs_new / rs;
            for (pi, &ri) in Sh::flat_mut(&mut p).iter_mut().zip(Sh::flat(&r)) {
                *pi = ri + *pi * beta;
            }
            rs = rs_new;
        }
        let (x, v) = (Sh::flat_mut(&mut self.pos), Sh::flat_mut(&mut self.vel));
        for ((x, v), &d) in x.iter_mut().zip(v.iter_mut()).zip(Sh::flat(&dv)) {
            *v += d;
            *x += *v * h;
        }
    }

    fn xpbd<F: ForceField<P>>(&mut self, h: P::Scalar, substeps: u8, forces: &mut F) {
        let n = substeps.max(1);
        let hs = h / P::Scalar::from_i16(n as i16);
        let inv_hs = P::Scalar::ONE / hs;
        for _ in 0..n {
            let a = self.accelerations_now(forces, false);
            let prev = self.pos;
            {
                let (x, v) = (Sh::flat_mut(&mut self.pos), Sh::flat_mut(&mut self.vel));
                for ((x, v), a) in x.iter_mut().zip(v.iter_mut()).zip(Sh::flat(&a)) {
                    *v += *a * hs;
                    *x += *v * hs;
                }
            }
            let w = Sh::flat(&self.inv_mass);
            let x = Sh::flat_mut(&mut self.pos);
            let px = Sh::flat(&prev);
            self.topology.for_each_spring(|ia, ib, rest, m| {
                let d = x[ib] - x[ia];
                let l = d.length();
                let wsum = w[ia] + w[ib];
                if l <= tiny_length::<P::Scalar>() || wsum <= P::Scalar::ZERO {
                    return;
                }
                let nrm = d * (P::Scalar::ONE / l);
                // Compliance α̃ = 1/(k h²); damping γ = c/(k h) (Macklin et al. 2016, eq. 26).
                let kh = m.stiffness * hs;
                let alpha = P::Scalar::ONE / (kh * hs);
                let gamma = m.damping / kh;
                let closing = ((x[ib] - px[ib]) - (x[ia] - px[ia])).dot(nrm);
                let c = l - rest;
                let dl = -(c + gamma * closing) / ((P::Scalar::ONE + gamma) * wsum + alpha);
                x[ia] -= nrm * (dl * w[ia]);
                x[ib] += nrm * (dl * w[ib]);
            });
            let (x, v) = (Sh::flat(&self.pos), Sh::flat_mut(&mut self.vel));
            for ((v, &x), &p) in v.iter_mut().zip(x).zip(Sh::flat(&prev)) {
                *v = (x - p) * inv_hs;
            }
        }
    }
}
