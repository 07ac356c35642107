//! How the spline rope steps: the [`SplineStepper`]s (symplectic Euler, backward Euler, BDF2),
//! the implicit step's Newton iterations, line search and conjugate gradient, and the frame's
//! substeps.

use super::*;
use crate::contact::PairMemory;

impl<P: Point, const K: usize, I: SplineStepper> SplineRope<P, K, I> {
    /// The new velocities `w` of one backward Euler step of `h` from `x0`, `v0` with the
    /// generalized forces `external` held (see [`external`](Self::external)), with what the
    /// energy guard needs (the strains at the new positions `x₀ + h·w` and the elastic
    /// potential at `x0`; `None` in `Q16`, which has no guard): `w` minimizes the step's
    /// incremental potential
    /// `½|w − v₀|²_M + ½|w|²_D + V(x₀ + h·w) − fᵀ(x₀ + h·w)`, `D = h·(γ·M + C₀)` (air drag,
    /// and the strain damping linearized at the start), `V` the stretch and bending energy
    /// and `f` the external forces; the positions are `x₀ + h·w`. Newton
    /// steps ([`NEWTON`] at most) from `w = v₀`, each solved by [`conjugate_gradient`]
    /// (`iterations` at most) and halved until the potential falls (in `Q16` one, whole).
    ///
    /// [`conjugate_gradient`]: Self::conjugate_gradient
    pub(super) fn backward_euler(
        &self,
        (x0, v0): (&[P; K], &[P; K]),
        h: P::Scalar,
        external: &[P; K],
        iterations: u8,
    ) -> ([P; K], Option<Ends<P, K>>, bool) {
        let zero = P::Scalar::ZERO;
        let (x0, v0) = (*x0, *v0);
        let start = self.strains(&x0, Some(&v0));
        let (_, t0) = self.forces(&start, external, P::Scalar::ONE);
        // `D·u`: the drag and the strain damping, linear, frozen at the start.
        let damping = self.linearized(&start, &t0, h, false);
        let drag = h * self.settings.damping;
        let damp = |u: &[P; K]| -> [P; K] {
            let (m, c) = (self.mass_times(u), self.stiffness_times(&damping, u));
            core::array::from_fn(|i| m[i] * drag + c[i])
        };
        let dot = |a: &[P; K], b: &[P; K]| a.iter().zip(b).fold(zero, |s, (x, y)| s + x.dot(*y));
        let at = |w: &[P; K]| -> [P; K] { core::array::from_fn(|i| x0[i] + w[i] * h) };
        let mut w = v0;
        let mut st = self.strains(&at(&w), None);
        let mut first = zero;
        let mut pre = None;
        let mut settled = false;
        for _ in 0..NEWTON {
            let (f, t) = self.forces(&st, external, P::Scalar::ONE);
            let change: [P; K] = core::array::from_fn(|i| w[i] - v0[i]);
            let (m, d) = (self.mass_times(&change), damp(&w));
            // `∇Φ`: the stretch's and bending's share of it is in `f`.
            let gradient = self.free(core::array::from_fn(|i| m[i] + d[i] - f[i] * h));
            // The Hessian of `Φ`: the damping in it is `D`'s, frozen at the start. (The
            // iterate's, as `Φ` does not have it, sent heavily damped ropes flying.)
            let mut lin = self.linearized(&st, &t, h, true);
            lin.damp_dir = damping.dir;
            // Built once a step: a preconditioner needs no update.
            let pre = pre.get_or_insert_with(|| self.preconditioner(&lin, h, drag));
            let mut step = self.conjugate_gradient((&lin, pre), drag, &gradient, iterations);
            if P::Scalar::FIXED_POINT {
                // `Q16` cannot resolve the potential's changes: one Newton step, taken
                // whole (linearized backward Euler).
                w = core::array::from_fn(|i| w[i] + step[i]);
                return (w, None, true);
            }
            // `−slope` is the Newton decrement: what a full step promises the potential.
            let mut slope = dot(&step, &gradient);
            if slope >= zero {
                // Rounding spoilt the solve (`h²·ω²` far past the format): the preconditioned
                // gradient still goes downhill.
                step = self.precondition(pre, &gradient.map(|g| -g));
                slope = dot(&step, &gradient);
            }
            if first == zero {
                first = -slope;
            }
            if slope >= zero || !slope.is_finite() || -slope <= first * converged::<P::Scalar>() {
                // Nothing left to gain downhill (or rounding's floor reached): converged.
                settled = slope.is_finite();
                break;
            }
            // `Φ` along the step, less its value at `w`:
            // `α·linear + ½α²·curve + V(x + α·h·δ) − V(x)`.
            let (md, dd) = (self.mass_times(&step), damp(&step));
            let linear = (0..K).fold(zero, |sum, i| {
                sum + step[i].dot(m[i] + d[i] - external[i] * h)
            });
            let curve = dot(&step, &md) + dot(&step, &dd);
            let energy = self.elastic_potential(&st);
            let mut alpha = P::Scalar::ONE;
            let mut accepted = false;
            for _ in 0..LINE_SEARCH {
                let trial: [P; K] = core::array::from_fn(|i| w[i] + step[i] * alpha);
                let trial_st = self.strains(&at(&trial), None);
                let change = alpha * linear
                    + P::Scalar::ratio(1, 2) * alpha * alpha * curve
                    + (self.elastic_potential(&trial_st) - energy);
                // Armijo: a quarter of what the slope promises.
                if change <= alpha * slope * P::Scalar::ratio(1, 4) {
                    (w, st, accepted) = (trial, trial_st, true);
                    break;
                }
                alpha = alpha * P::Scalar::ratio(1, 2);
            }
            if !accepted {
                break;
            }
        }
        let potential = self.elastic_potential(&start);
        (w, Some(Ends { st, potential }), settled)
    }

    /// A backward Euler step from `x0`, `v0` (elastic potential `potential`) to velocities
    /// `w` (strains `st` at `x0 + h·w`), kept from gaining energy: `½vᵀMv + V(x) − fᵀx`
    /// with the forces `f` held, which an exact step on a convex `V` never raises (the
    /// strain's projection makes `V` not quite convex, and the Newton steps may stop short).
    /// If `w` raises it, the velocities are scaled down until it does not; if the positions
    /// alone raise it, the step is halved until they do not ([`HELD_ENERGY_HALVINGS`] at
    /// most, then not taken: the rope stays where it was, still). A strain evaluation a
    /// halving.
    pub(super) fn held_energy(
        &self,
        (x0, v0, potential): (&[P; K], &[P; K], P::Scalar),
        (w, st): (&[P; K], &Strains<P, K>),
        h: P::Scalar,
        external: &[P; K],
    ) -> ([P; K], [P; K]) {
        let zero = P::Scalar::ZERO;
        let half = P::Scalar::ratio(1, 2);
        let kinetic = self.kinetic(v0);
        let work = (0..K).fold(zero, |sum, i| sum + external[i].dot(w[i])) * h;
        // The full step's kinetic energy.
        let moving = self.kinetic(w);
        let (mut alpha, mut halvings) = (P::Scalar::ONE, 0);
        loop {
            let x: [P; K] = core::array::from_fn(|i| x0[i] + w[i] * (h * alpha));
            let elastic = if halvings == 0 {
                self.elastic_potential(st)
            } else {
                self.elastic_potential(&self.strains(&x, None))
            };
            // The kinetic energy the step may end with: the start's, less what the
            // positions gained (none where they did not move).
            let allowed = kinetic - (elastic - potential - work * alpha);
            if allowed >= zero || alpha == zero {
                let kept = moving * alpha * alpha;
                let scale = if kept > allowed && kept > zero {
                    (allowed.max(zero) / kept).sqrt() * alpha
                } else {
                    alpha
                };
                return (x, w.map(|wi| wi * scale));
            }
            halvings += 1;
            alpha = if halvings <= HELD_ENERGY_HALVINGS {
                alpha * half
            } else {
                zero
            };
        }
    }

    /// Whether `h²·ω²·ε ≤ 2⁻¹⁰` (`ε` the format's epsilon; in `f32`, `h²·ω² ≤ 8·10³`): where
    /// the stretch's exact solve, which subtracts terms `h²·ω²` times larger than its result,
    /// keeps its precision, and BDF2 was tested to hold its energy.
    pub(super) fn within_precision(&self, h: P::Scalar) -> bool {
        self.omega * h * self.omega * h * P::Scalar::EPSILON <= P::Scalar::ratio(1, 1024)
    }

    /// Whether BDF2 takes a step of `h`: within the format's precision, `h²·ω² ≤ 2²²` (the
    /// stiffest tested to hold its energy: a 1 m, 1 kg rope of 8 control points at
    /// `EA = 10⁷ N`, `h²·ω² ≈ 3·10⁶`, `tests/suite/spline_rope.rs`), and never in `Q16`, whose one
    /// linearized Newton step lets BDF2 drift from `f64`.
    pub(super) fn bdf2_holds(&self, h: P::Scalar) -> bool {
        !P::Scalar::FIXED_POINT
            && (self.omega * h * self.omega * h).to_f64() <= f64::from(1u32 << 22)
            && self.within_precision(h)
    }

    /// One implicit step of `h` with the generalized forces `external` held: backward Euler, or
    /// with `second_order` BDF2 when the last step was one of the same `h` and
    /// [`bdf2_holds`](Self::bdf2_holds) (else backward Euler). BDF2 is a
    /// [`backward_euler`](Self::backward_euler) solve of `⅔·h`
    /// from `(4·x₀ − x₋₁)/3` and `(4·v₀ − v₋₁)/3`: the same cost, second order, and it still
    /// damps what a step cannot resolve. In `f32` and `f64` a backward Euler step never
    /// gains energy ([`held_energy`](Self::held_energy)), and a BDF2 step that would end
    /// with more than the last backward Euler step left is taken as backward Euler's.
    pub(super) fn implicit_step(
        &mut self,
        h: P::Scalar,
        external: &[P; K],
        (iterations, second_order): (u8, bool),
    ) -> bool {
        let (x0, v0) = (self.pos, self.free(self.vel));
        let along = |x: &[P; K], v: &[P; K], h: P::Scalar| -> [P; K] {
            core::array::from_fn(|i| x[i] + v[i] * h)
        };
        if P::Scalar::FIXED_POINT {
            // `Q16` cannot resolve the energy: the linearized step as it is.
            let (w, _, converged) = self.backward_euler((&x0, &v0), h, external, iterations);
            self.take_implicit((&along(&x0, &w, h), &w), (x0, v0, h), P::Scalar::ZERO);
            return converged;
        }
        if let Some(History {
            start: xp,
            velocities: vp,
            h: hp,
            headroom,
        }) = self.history
            && second_order
            && hp == h
            && self.bdf2_holds(h)
        {
            let step = h * P::Scalar::ratio(2, 3);
            let third = P::Scalar::ratio(1, 3);
            let four = P::Scalar::from_i16(4);
            let xs: [P; K] = core::array::from_fn(|i| (x0[i] * four - xp[i]) * third);
            let vs: [P; K] = core::array::from_fn(|i| (v0[i] * four - vp[i]) * third);
            let (w, end, converged) =
                self.backward_euler((&xs, &self.free(vs)), step, external, iterations);
            if let Some(Ends { st, .. }) = end {
                let x = along(&xs, &w, step);
                let potential = self.elastic_potential(&self.strains(&x0, None));
                // BDF2's energy may rise in a step (a percent or so of the motion's), but
                // not past where the last backward Euler step left it: a step that would is
                // taken as backward Euler's, held.
                let gained = self.gained((&x0, &v0, potential), (&x, &w, &st), external);
                if gained <= headroom {
                    self.take_implicit((&x, &w), (x0, v0, h), headroom - gained);
                    return converged;
                }
            }
        }
        let (w, end, converged) = self.backward_euler((&x0, &v0), h, external, iterations);
        let (x, w) = match end {
            Some(Ends { st, potential }) => {
                self.held_energy((&x0, &v0, potential), (&w, &st), h, external)
            }
            None => (along(&x0, &w, h), w),
        };
        self.take_implicit((&x, &w), (x0, v0, h), P::Scalar::ZERO);
        converged
    }

    /// What a step from `x0`, `v0` (elastic potential `potential`) to `x`, `w` (strains
    /// `st`) added to `½vᵀMv + V(x) − fᵀx` with the forces `f` held (over `m̄`).
    pub(super) fn gained(
        &self,
        (x0, v0, potential): (&[P; K], &[P; K], P::Scalar),
        (x, w, st): (&[P; K], &[P; K], &Strains<P, K>),
        external: &[P; K],
    ) -> P::Scalar {
        let work = (0..K).fold(P::Scalar::ZERO, |sum, i| {
            sum + external[i].dot(x[i] - x0[i])
        });
        self.kinetic(w) - self.kinetic(v0) + self.elastic_potential(st) - potential - work
    }

    /// `½vᵀMv / m̄`.
    pub(super) fn kinetic(&self, v: &[P; K]) -> P::Scalar {
        let mv = self.mass_times(v);
        (0..K).fold(P::Scalar::ZERO, |sum, i| sum + v[i].dot(mv[i])) * P::Scalar::ratio(1, 2)
    }

    /// Ends an implicit step at `x`, `w` (pinned points kept), remembering its start and
    /// the energy's `headroom` for [`Bdf2`].
    pub(super) fn take_implicit(
        &mut self,
        (x, w): (&[P; K], &[P; K]),
        (x0, v0, h): ([P; K], [P; K], P::Scalar),
        headroom: P::Scalar,
    ) {
        if self
            .settings
            .integrator
            .implicit()
            .is_some_and(|(_, second)| second)
        {
            self.history = Some(History {
                start: x0,
                velocities: v0,
                h,
                headroom,
            });
        }
        for i in 0..K {
            if !self.pinned[i] {
                (self.pos[i], self.vel[i]) = (x[i], w[i]);
            }
        }
    }

    /// `u` with its pinned entries zero.
    pub(super) fn free(&self, mut u: [P; K]) -> [P; K] {
        for (ui, &p) in u.iter_mut().zip(&self.pinned) {
            if p {
                *ui = P::default();
            }
        }
        u
    }

    /// `δ` with `(M·(1 + drag) + h²·K + h·C)·δ = −b` on the free control points, `K` and `C`
    /// from `lin`: conjugate gradient, at most `iterations` steps, stopped early when
    /// `r·P⁻¹r` has fallen to [`converged`] of its start. The preconditioner `P` is the mass,
    /// and the taut stretch with its damping solved exactly when `stretch` is there: what is
    /// then left to iterate on is the sideways stiffness and the slack spans.
    pub(super) fn conjugate_gradient(
        &self,
        (lin, pre): (&Linearized<P, K>, &Preconditioner<P, K>),
        drag: P::Scalar,
        b: &[P; K],
        iterations: u8,
    ) -> [P; K] {
        let zero = P::Scalar::ZERO;
        let dot = |a: &[P; K], b: &[P; K]| a.iter().zip(b).fold(zero, |s, (x, y)| s + x.dot(*y));
        // Solved for `δ / s` (see `solve_scale`).
        let scale = solve_scale(b);
        let shrink = P::Scalar::ONE / scale;
        let mut r = self.free(b.map(|bi| bi * -shrink));
        let mut out = [P::default(); K];
        let mut z = self.precondition(pre, &r);
        let mut p = z;
        let mut rz = dot(&r, &z);
        let tolerance = rz * converged::<P::Scalar>();
        for _ in 0..iterations {
            if rz <= tolerance || !rz.is_finite() {
                break;
            }
            let (m, k) = (self.mass_times(&p), self.stiffness_times(lin, &p));
            let ap = self.free(core::array::from_fn(|i| {
                m[i] * (P::Scalar::ONE + drag) + k[i]
            }));
            let pap = dot(&p, &ap);
            if pap <= zero || !pap.is_finite() {
                break;
            }
            let alpha = rz / pap;
            for i in 0..K {
                out[i] += p[i] * alpha;
                r[i] -= ap[i] * alpha;
            }
            z = self.precondition(pre, &r);
            let next = dot(&r, &z);
            let beta = next / rz;
            for i in 0..K {
                p[i] = z[i] + p[i] * beta;
            }
            rz = next;
        }
        out.map(|o| o * scale)
    }

    /// The taut stretch and its damping, `(h²·EA + h·c)·ds·Bᵀ G⁻¹ B` (`G` the quadratic
    /// splines' Gram matrix), beside the banded `M'` (factor `banded`), solved by Woodbury:
    /// `(M' + Bᵀ D⁻¹ B)⁻¹ = M'⁻¹ − M'⁻¹Bᵀ (D + B M'⁻¹ Bᵀ)⁻¹ B M'⁻¹`, `D = G / ((h²·EA + h·c)·ds)`.
    /// `K` banded solves and a dense `K × K` factor; `None` when that is not positive
    /// definite (rounding), and `M'` alone preconditions.
    pub(super) fn stretch_solve(
        &self,
        lin: &Linearized<P, K>,
        h: P::Scalar,
        banded: &[[P::Scalar; 4]; K],
    ) -> Option<StretchSolve<P, K>> {
        let zero = P::Scalar::ZERO;
        let scale = (self.stretch.stiffness * h * h + lin.damping) * self.ds;
        let mut out = StretchSolve {
            dir: lin.dir,
            columns: [[P::default(); K]; K],
            factor: [[zero; K]; K],
        };
        // D: the Gram matrix, over the stretch's scale.
        out.factor[K - 1][K - 1] = P::Scalar::ONE / scale;
        for e in 0..K - 3 {
            for q in 0..POINTS {
                let n = self.proj[e][q];
                for a in 0..3 {
                    for b in 0..3 {
                        out.factor[e + a][e + b] += self.weights[q] * n[a] * n[b] / scale;
                    }
                }
            }
        }
        for a in 0..K {
            let mut unit = [zero; K];
            unit[a] = P::Scalar::ONE;
            let mut column = self.strain_pull(&lin.dir, &unit);
            solve(banded, &mut column);
            let strains = self.strain_weights(&lin.dir, &column);
            for (b, &s) in strains.iter().enumerate() {
                out.factor[b][a] += s;
            }
            out.columns[a] = column;
        }
        dense_cholesky(&mut out.factor).then_some(out)
    }

    /// The conjugate gradient's preconditioner for a step of `h`: the banded
    /// `M' = M·(1 + drag) + h²·EI·B` factored (the mass's factor if rounding stops that), and
    /// the taut stretch beside it ([`stretch_solve`](Self::stretch_solve)) while
    /// [`within_precision`](Self::within_precision).
    pub(super) fn preconditioner(
        &self,
        lin: &Linearized<P, K>,
        h: P::Scalar,
        drag: P::Scalar,
    ) -> Preconditioner<P, K> {
        let one = P::Scalar::ONE;
        let mut band = self.mass_band.map(|row| row.map(|m| m * (one + drag)));
        if self.bending > P::Scalar::ZERO {
            for (row, bend) in band.iter_mut().zip(&self.bend) {
                for (a, &b) in row.iter_mut().zip(bend) {
                    *a += b * h * h;
                }
            }
        }
        let band = self.reduced(&band, (P::Scalar::ZERO, one));
        let banded = ldl(&band, |x| Some(one / x).filter(|i| i.is_finite())).unwrap_or(self.chol);
        let stretch = if self.within_precision(h) {
            self.stretch_solve(lin, h, &banded)
        } else {
            None
        };
        Preconditioner { banded, stretch }
    }

    /// `P⁻¹·r` for the conjugate gradient.
    pub(super) fn precondition(&self, pre: &Preconditioner<P, K>, r: &[P; K]) -> [P; K] {
        let mut z = self.free(*r);
        solve(&pre.banded, &mut z);
        if let Some(stretch) = &pre.stretch {
            let mut c = self.strain_weights(&stretch.dir, &z);
            dense_solve(&stretch.factor, &mut c);
            for (column, &ca) in stretch.columns.iter().zip(&c) {
                for i in 0..K {
                    z[i] -= column[i] * ca;
                }
            }
        }
        self.free(z)
    }

    /// Advances by `dt` seconds with the [`SplineStepper`]: symplectic Euler in substeps
    /// from [`stiffness_bound`](Self::stiffness_bound) (see
    /// [`MassSpring::step`](crate::MassSpring::step) for the plan, the cap and the errors),
    /// or one backward Euler step (in `Q16` more past `h·(ω + γ) = 8`, see
    /// [`SplineStepper`]). Applied forces are used up. In `Q16`, a generalized force over
    /// the mass unit `m̄` (see the [module](crate::spline_rope)) past the format's range on a control
    /// point is clamped and reported in [`StepInfo::saturated`]: from gravity and a field's
    /// accelerations (gravity alone never, below `|g| = 32 767`) and from the applied
    /// forces (a force `f` at a point adds up to `|f| / m̄`); explicitly, also a substep's
    /// stretch and bending impulse or velocity change over `m̄`. With an implicit
    /// [`SplineStepper`] in `f32` or `f64`, [`StepInfo::converged`] is `false` when a
    /// step's Newton steps stopped (after 4, or at a line search that found no descent)
    /// before what a full step promises fell to `2⁻²⁰` of its first value: a 1 m, 1 kg
    /// rope of 8 control points released level converges in every frame at `EA = 100 N`
    /// and none at `10⁷ N` with one conjugate gradient step a solve
    /// (`tests/suite/converge.rs`). `Q16`'s one linearized step and the explicit substeps
    /// always report `true`; `residual` and `stretch` are 0.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite `dt`; [`Error::TooStiff`];
    /// [`Error::Diverged`] when a coordinate came out non-finite or beyond the bounds (the
    /// state is then as before the call).
    pub fn step(&mut self, dt: P::Scalar) -> Result<StepInfo<P::Scalar>, Error> {
        self.step_with(dt, ())
    }

    /// As [`step`](Self::step), adding the forces of `forces` (a [`ForceField`], a tuple of
    /// them, or `()`) every substep. The field sees the control points as its bodies, each
    /// with the mass the curve gives it, `∫ ρ N_i ds` (`inv_mass` 0 when pinned): an
    /// acceleration `a` it adds becomes the generalized force `∫ ρ N_i ds · a` (exact for a
    /// uniform field such as gravity), a force `f` acts on that control point as it is.
    ///
    /// # Errors
    /// As [`step`](Self::step).
    pub fn step_with<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        mut forces: F,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        self.step_resolving(dt, &mut forces, None)
    }

    /// As [`step_with`](Self::step_with), pushing the drawn curve (the state's own, whatever
    /// [`Contacts::touch`] says) out of `contacts`' colliders after every substep, with
    /// restitution and friction, and enough substeps that no point of it moves more than
    /// the thickness in one (see [`contact`](crate::contact)). A correction `d` at a point of
    /// the curve with basis weights `w` moves control point `i` by
    /// `(w_i / m_i) · d / Σ_j w_j² / m_j`, `m_i = ∫ ρ N_i ds`: the least change that moves
    /// that point by `d`.
    ///
    /// # Errors
    /// As [`step`](Self::step); the impulses reported are then zero.
    pub fn step_touching<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        mut forces: F,
        contacts: &Contacts<'_, P>,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        contacts.clear_pushes();
        contacts.finish_report(self.step_resolving(dt, &mut forces, Some(contacts)))
    }

    pub(super) fn step_resolving<F: ForceField<P>>(
        &mut self,
        dt: P::Scalar,
        forces: &mut F,
        contacts: Option<&Contacts<'_, P>>,
    ) -> Result<StepInfo<P::Scalar>, Error> {
        check_non_negative(dt, "dt")?;
        let rate = self.omega + self.gamma + self.settings.damping;
        let floor = contacts.map_or(P::Scalar::ZERO, |c| {
            let fastest = self
                .vel
                .iter()
                .map(|v| v.length())
                .fold(P::Scalar::ZERO, P::Scalar::max);
            // The curve's points move as weighted means of the control points, and lie in
            // their box.
            let object = Aabb::from_points(&self.pos).unwrap_or(Aabb::point(P::default()));
            c.rate(
                (fastest + self.settings.gravity.length() * dt, false),
                (object, dt),
            )
            .0
        });
        // `Q16`'s one linearized Newton step keeps its precision while the rate times the
        // step is at most 8 (see `within_precision`): past it, substeps (never slow motion).
        let floor = match self.settings.integrator.implicit() {
            Some(_) if P::Scalar::FIXED_POINT => floor.max(rate * P::Scalar::ratio(1, 8)),
            _ => floor,
        };
        let (n, h, slow) = plan(dt, rate, self.per_rate, floor)?;
        let (saturated, converged) = self.substeps(n, h, forces, contacts)?;
        Ok(StepInfo {
            substeps: n,
            simulated: if slow {
                h * P::Scalar::from_i16(n as i16)
            } else {
                dt
            },
            slow_motion: slow,
            saturated,
            snapped: 0,
            converged,
            stretch: P::Scalar::ZERO,
            residual: P::Scalar::ZERO,
            asleep: false,
        })
    }

    /// One step of exactly `h` with the [`SplineStepper`], for measuring the method at its
    /// limit (symplectic Euler's stability bound is `ω·h < 2`).
    ///
    /// # Errors
    /// As [`step`](Self::step).
    pub fn step_once(&mut self, h: P::Scalar) -> Result<(), Error> {
        check_non_negative(h, "h")?;
        self.substeps(1, h, &mut (), None).map(drop)
    }

    /// `n` substeps of `h`, each ending with the contacts; whether a `Q16` force or velocity
    /// change was clamped (see [`step`](Self::step)).
    pub(super) fn substeps<F: ForceField<P>>(
        &mut self,
        n: u16,
        h: P::Scalar,
        field: &mut F,
        contacts: Option<&Contacts<'_, P>>,
    ) -> Result<(bool, bool), Error> {
        let saved = (self.pos, self.vel, self.time, self.history);
        let drag = self.settings.damping;
        let (mut saturated, mut converged) = (false, true);
        // What self-contact learns in one substep serves the next.
        let mut memory = contacts
            .filter(|c| c.remembers())
            .map(|_| PairMemory::new());
        for step in 0..n {
            let mut added = [P::default(); K];
            let mut out = Accelerations {
                acc: &mut added,
                inv_mass: &self.inv_load,
                saturated: false,
            };
            let bodies = Bodies {
                pos: &self.pos,
                vel: &self.vel,
                inv_mass: &self.inv_load,
                columns: K,
            };
            field.apply(self.time, &bodies, &mut out);
            saturated |= out.saturated;
            let external = self.external(&added);
            let fits = |u: &[P; K]| u.iter().all(|x| x.is_finite());
            saturated |= P::Scalar::FIXED_POINT && !fits(&external);
            if let Some(implicit) = self.settings.integrator.implicit() {
                converged &= self.implicit_step(h, &external, implicit);
            } else {
                // In impulses, velocity changes by the mass unit: in `Q16` the format holds
                // accelerations hundreds of times its range (a whipping end's).
                let impulses = external.map(|f| f * h);
                let st = self.strains(&self.pos, Some(&self.vel));
                let (j, _) = self.forces(&st, &impulses, h);
                let mut dv = self.free(j);
                solve(&self.chol, &mut dv);
                saturated |= P::Scalar::FIXED_POINT && !(fits(&j) && fits(&dv));
                let slowed = drag * h;
                for i in 0..K {
                    if !self.pinned[i] {
                        self.vel[i] += dv[i] - self.vel[i] * slowed;
                        self.pos[i] += self.vel[i] * h;
                    }
                }
            }
            self.time += h;
            if let Some(contacts) = contacts {
                let lag = h * P::Scalar::from_i16((n - 1 - step) as i16);
                let mut curve = Spans::new(&self.ext, &self.pos);
                let (pos, vel) = (&mut self.pos, &mut self.vel);
                contacts.advance_bodies(h);
                let parts = (pos, vel, &self.inv_load);
                let timing = crate::contact::Timing::substep((h, lag));
                contacts.resolve_spans(parts, timing, &mut curve, memory.as_mut());
            }
        }
        let bounds = self.settings.bounds;
        // A NaN or an infinity is beyond any bounds.
        let sane = check_inside(&self.pos, bounds, "control point").is_ok()
            && check_inside(&self.vel, bounds, "velocity").is_ok();
        if sane {
            // The applied forces are spent; on a refused step they stay for the next.
            self.extra = [P::default(); K];
            // A held point ends the step where its hand put it.
            for i in 0..K {
                if self.pinned[i] {
                    (self.pos[i], self.vel[i]) = (saved.0[i], P::default());
                }
            }
            Ok((saturated, converged))
        } else {
            (self.pos, self.vel, self.time, self.history) = saved;
            Err(Error::Diverged)
        }
    }
}

/// The implicit step's preconditioner: see [`SplineRope::preconditioner`].
pub(super) struct Preconditioner<P: Point, const K: usize> {
    /// The factor of `M·(1 + drag) + h²·EI·B` as [`ldl`] gives it.
    pub(super) banded: [[P::Scalar; 4]; K],
    pub(super) stretch: Option<StretchSolve<P, K>>,
}

/// The implicit step's preconditioner for the stretch: see [`SplineRope::stretch_solve`].
pub(super) struct StretchSolve<P: Point, const K: usize> {
    /// The rope's directions at the stretch points it was built at.
    pub(super) dir: [[P; POINTS]; K],
    /// `M'⁻¹ Bᵀ e_a`, one column a quadratic spline.
    pub(super) columns: [[P; K]; K],
    /// The Cholesky factor of `D + B M'⁻¹ Bᵀ` ([`dense_cholesky`]).
    pub(super) factor: [[P::Scalar; K]; K],
}

/// What the energy guard needs of a backward Euler step: the strains at its end and the
/// elastic potential at its start.
pub(super) struct Ends<P: Point, const K: usize> {
    pub(super) st: Strains<P, K>,
    pub(super) potential: P::Scalar,
}

/// The last implicit step of a [`SplineRope`], for [`Bdf2`].
#[derive(Clone, Copy, Debug)]
pub(super) struct History<P: Point, const K: usize> {
    /// Its start's positions and velocities, and its length.
    pub(super) start: [P; K],
    pub(super) velocities: [P; K],
    pub(super) h: P::Scalar,
    /// How far its end's energy is below where the last backward Euler step left it (over
    /// `m̄`): what a BDF2 step may still gain (see `SplineRope::implicit_step`).
    pub(super) headroom: P::Scalar,
}

/// How a [`SplineRope`] steps, chosen by the type of its [`Settings::integrator`]:
///
/// - [`SymplecticEuler`] (the default): explicit, in substeps from
///   [`SplineRope::stiffness_bound`] at the [`Accuracy`]'s fraction of `ω·h < 2`. One force
///   evaluation and two banded solves a substep; bounded energy.
/// - [`ImplicitEuler`]: backward Euler, one step a frame at any stiffness (more only for
///   contacts, and in `Q16` past `h·(ω + γ) = 8`), for stiff ropes and cables where the explicit substeps would pass
///   [`MAX_SUBSTEPS`](crate::physics::system::MAX_SUBSTEPS) and slow time down. The new velocities
///   minimize the step's incremental potential: at most 4 Newton steps, each solved by
///   conjugate gradient ([`iterations`](ImplicitEuler::iterations) at most) preconditioned
///   by the mass, the bending and the taut stretch solved exactly, and halved until the
///   potential falls (in `Q16`, whose resolution cannot tell, one step taken whole:
///   linearized backward Euler, which can gain energy on a stiff, fast-turning rope; it
///   keeps its precision while `h·(ω + γ) ≤ 8`, [`SplineRope::stiffness_bound`], and takes
///   substeps past that, so a stiff rope in `Q16` costs about an eighth of the explicit
///   substeps, each several times dearer). Its
///   fixed point is the equilibrium: 8 control points sag within 0.12% of the catenary at
///   `EA = 10⁸ N` on 1.2 kg. In `f32` and `f64` a step never gains energy
///   (`½vᵀMv + V − fᵀx` with the step's forces held): where the Newton steps stop short (a
///   rope stretched far past its length, damped hundreds of times past critical, or stepped
///   far slower than it swings) and the step would gain, its velocities are scaled down,
///   or the step is shortened (at most 7 halvings, then not taken), until it does not; such
///   a rope moves slower than it should instead of blowing up. It damps what a frame cannot
///   resolve, the swing too: a mode of `ω` loses `1 − 1/(1 + (ω·h)²)` of its energy a
///   step, and a rope released level loses 37% to 43% of the fall's energy in the first
///   second at 60 Hz. Range (`tests/suite/spline_rope.rs`): `f64` to `EA·h²/(ρ·ds²) ≈ 7·10⁵`
///   (`ds` a span, `ρ` the mass per length; a 10 m steel cable at 60 Hz is about 2·10³);
///   `f32` to `7·10⁴`; `Q16` for ropes in pixels (a 70 px rope ends 0.02 px from `f64`
///   after 2 s). On a soft rope it costs several explicit frames
///   (`cargo bench -p dunas-evaluate --bench physics -- spline_rope`); the explicit cost grows with `√EA`,
///   this one does not. No damping floor is needed.
/// - [`Bdf2`]: the same solve on BDF2's shifted start, second order: a rope released level
///   loses 6% to 8% of the fall's energy in its first second (`EA` from 2·10³ to 10⁷ N on
///   1 m, 1 kg, `f64`). Its energy may rise in a step, but in `f32` and `f64` never above
///   where the last backward Euler step left it: a step that would end higher is taken as
///   backward Euler's. Past the stiffness it was tested at, and in `Q16`, it takes
///   backward Euler steps.
///
/// Sealed: the three above are all.
pub trait SplineStepper: Copy + core::fmt::Debug + PartialEq + sealed::Sealed {
    /// `None` for an explicit stepper; else its conjugate-gradient budget and whether it is
    /// second order ([`Bdf2`]).
    fn implicit(&self) -> Option<(u8, bool)>;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::SymplecticEuler {}
    impl Sealed for super::ImplicitEuler {}
    impl Sealed for super::Bdf2 {}
}

impl SplineStepper for SymplecticEuler {
    fn implicit(&self) -> Option<(u8, bool)> {
        None
    }
}

impl SplineStepper for ImplicitEuler {
    fn implicit(&self) -> Option<(u8, bool)> {
        Some((self.iterations, false))
    }
}

/// A second-order implicit stepper for a [`SplineRope`]: BDF2, each step solved as
/// [`ImplicitEuler`] solves its own (Newton on the incremental potential, conjugate
/// gradient with at most `iterations` steps) at about the same cost, with far less damping
/// on the motion a step resolves (see [`SplineStepper`]). It remembers the last step; a step
/// of another length, or a change to the state from outside (positions, velocities, pins),
/// starts it again with one backward Euler step. Past the stiffness it was tested to hold
/// its energy at (`h²·ω²` past `2²²`, or past `8·10³` in `f32`: a very stiff rope), and in
/// `Q16`, it takes backward Euler steps; and in `f32` and `f64` where its step would end
/// with more energy than the last backward Euler step left. The strain's projection leaves the length free to wiggle between its
/// quadratic-spline averages; BDF2, damping less, lets a stiff rope's drawn length pass its
/// rest length by up to 0.7% (backward Euler: 0.04%).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bdf2 {
    /// Conjugate-gradient iteration budget per Newton step.
    pub iterations: u8,
}

impl Default for Bdf2 {
    /// 16 iterations.
    fn default() -> Self {
        Bdf2 { iterations: 16 }
    }
}

impl SplineStepper for Bdf2 {
    fn implicit(&self) -> Option<(u8, bool)> {
        Some((self.iterations, true))
    }
}

/// The least damping ratio of the fastest stretch wave, 2%: below it, symplectic Euler near
/// its limit (`Accuracy::Fast`, `Balanced`) pumps energy into those waves until an
/// undamped rope diverges. On a rope's own motion the floor is negligible: mode `n` gets
/// `2%·ω_n / ω` (0.005% on a 1 m rope's fundamental at `EA = 2000 N`).
pub const MIN_DAMPING_RATIO: f64 = 0.02;

/// Most Newton steps of the implicit stepper in one step.
pub(super) const NEWTON: usize = 4;

/// Where the implicit stepper's iterations stop: when the Newton decrement (what a full
/// step promises the potential), or the conjugate gradient's `r·M⁻¹r`, has fallen to `2⁻²⁰`
/// of its first value in the step, or to the format's epsilon if that is larger.
pub(super) fn converged<S: Scalar>() -> S {
    S::ratio(1, 1 << 20).max(S::EPSILON)
}

/// Most halvings of a Newton step (to `2⁻³¹` of it) before the implicit stepper keeps what
/// it has.
pub(super) const LINE_SEARCH: usize = 32;

/// Halvings of an implicit step whose positions gained energy, to `2⁻⁷` of it, before it
/// is not taken at all (see `SplineRope::held_energy`).
pub(super) const HELD_ENERGY_HALVINGS: usize = 7;
