//! The spline rope's forces: the stretch law of a span, the strains and tensions at the
//! quadrature points, the elastic and bending forces and their linearization, and the energy.

use super::*;

impl<P: Point, const K: usize, I: SplineStepper> SplineRope<P, K, I> {
    /// The stretch at each span's stretch points: the slope `x'`, `1 / |x'|` (0 where the
    /// curve stops), and the strain `|x'| − 1` projected on the quadratic splines (against
    /// locking); with velocities `v`, its rate `x'·v' / |x'|` projected too (else the rate is
    /// 0). The projected strain at the stretch points is evaluated only where a coefficient
    /// is below 0 (a quadratic spline lies within the hull of its coefficients).
    pub(super) fn strains(&self, x: &[P; K], v: Option<&[P; K]>) -> Strains<P, K> {
        let zero = P::Scalar::ZERO;
        let mut out = Strains {
            pos: *x,
            slope: [[P::default(); POINTS]; K],
            inv: [[zero; POINTS]; K],
            strain: [zero; K],
            rate: [zero; K],
            slack: None,
        };
        // The strain (`x`) and its rate (`y`) at the stretch points, fitted together.
        let mut strain = [[Vec2::new(zero, zero); POINTS]; K];
        let dx = differences(x);
        let dv = v.map(differences);
        for e in 0..K - 3 {
            for (q, weights) in self.quad[e].iter().enumerate() {
                let d = slope_at(weights, &dx, e);
                // `|x'|` and its inverse from one inverse square root (in `Q16` no division).
                let square = d.dot(d);
                let inv = square.inv_sqrt();
                out.slope[e][q] = d;
                out.inv[e][q] = inv;
                strain[e][q].x = square * inv - P::Scalar::ONE;
                if let Some(dv) = &dv {
                    // The factor more often within ±½ on the right: in `Q16` the cheaper product.
                    strain[e][q].y = inv * d.dot(slope_at(weights, dv, e));
                }
            }
        }
        if v.is_some() {
            let fitted = fit(&self.proj, &self.weights, &self.gram, &strain, false);
            out.strain = fitted.map(|s| s.x);
            out.rate = fitted.map(|s| s.y);
        } else {
            let strain = strain.map(|span| span.map(|s| s.x));
            out.strain = fit(&self.proj, &self.weights, &self.gram, &strain, false);
        }
        // Rounding makes a rope at its rest length a few units of the last place long or
        // short, and its tension that many units of `EA`: pulls with no direction to them,
        // which an unloaded rope (nothing else holds its pose) would follow for ever. Strains
        // within 16 units of the format's last place count as 0, and larger ones are taken
        // that much closer to 0 so the tension stays continuous (in `Q16`, 2.4e-4 of the
        // length; in `f32`, 1.9e-6).
        let dead = P::Scalar::EPSILON * P::Scalar::from_i16(16);
        for c in &mut out.strain {
            *c = if c.abs() <= dead {
                zero
            } else if *c > zero {
                *c - dead
            } else {
                *c + dead
            };
        }
        if out.strain.iter().any(|&c| c < zero) {
            let points = evaluate(&self.proj, &out.strain);
            if points[..K - 3].iter().flatten().any(|&s| s < zero) {
                out.slack = Some(points);
            }
        }
        out
    }

    /// The projected strain at the stretch points of `st`.
    pub(super) fn strain_points(&self, st: &Strains<P, K>) -> [[P::Scalar; POINTS]; K] {
        st.slack.unwrap_or_else(|| evaluate(&self.proj, &st.strain))
    }

    /// The generalized forces from outside over `m̄`: gravity and a field's accelerations
    /// `acc` through each control point's mass, `(g + a_i)·∫ ρ N_i ds / m̄`, and the
    /// applied forces.
    pub(super) fn external(&self, acc: &[P; K]) -> [P; K] {
        core::array::from_fn(|i| (self.settings.gravity + acc[i]) * self.load[i] + self.extra[i])
    }

    /// The rope's own generalized forces over `m̄` at strains `st`, stretch, strain damping
    /// and bending, times `per` (1 for the forces, a substep's length for their impulses),
    /// added to `external`; with the tension over `m̄`, times `per`, at each stretch point.
    pub(super) fn forces(
        &self,
        st: &Strains<P, K>,
        external: &[P; K],
        per: P::Scalar,
    ) -> ([P; K], Tensions<P::Scalar, K>) {
        let mut f = *external;
        if self.bending > P::Scalar::ZERO {
            for (fi, b) in f.iter_mut().zip(self.bending_times(&st.pos)) {
                *fi -= b * per;
            }
        }
        let (ea, c) = (self.stretch.stiffness * per, self.damping * per);
        // Taut, the tension is the quadratic spline `EA·ε̂ + c·dε̂/dt`.
        let mut fitted: [P::Scalar; K] =
            core::array::from_fn(|i| ea * st.strain[i] + c * st.rate[i]);
        if let Some(points) = &st.slack {
            // Slack, it falls short of that by `EA·ε̂ − T(ε̂)` (`stretch_tension`), which is
            // projected too: the energy's gradient is the projected tension.
            let mut short = [[P::Scalar::ZERO; POINTS]; K];
            for (span, strains) in short.iter_mut().zip(points).take(K - 3) {
                for (s, &strain) in span.iter_mut().zip(strains) {
                    if strain < P::Scalar::ZERO {
                        *s = ea * strain - stretch_tension(ea, P::Scalar::ONE + strain);
                    }
                }
            }
            let short = fit(&self.proj, &self.weights, &self.gram, &short, true);
            for (f, s) in fitted.iter_mut().zip(short) {
                *f -= s;
            }
        }
        let tension = evaluate(&self.proj, &fitted);
        let mut pull = [P::default(); K];
        for e in 0..K - 3 {
            for (q, d) in self.pulls[e].iter().enumerate() {
                // Minus the energy's gradient: the stretch pulls the rope together (the
                // tension, more often within ±½, on the right: in `Q16` the cheaper product).
                // `T / |x'|` is also how stiffly the point resists turning: capped at `±EA`,
                // what the substeps were planned for (`ω`), where a fitted tension outgrows
                // the stretch (`|T| > EA·|x'|`, near a cusp of a rope stretched many times
                // its length).
                let per_length = (st.inv[e][q] * tension[e][q]).max(-ea).min(ea);
                let g = st.slope[e][q] * -per_length;
                add_pull(&mut pull, d, e, g);
            }
        }
        spread(&mut f, &pull);
        let taut = st.slack.is_none();
        (f, Tensions { tension, taut })
    }

    /// The backward Euler stiffness at strains `st` for a step of `h`: per stretch point, the
    /// axial `h²·dT/dl` (slack slopes below 0 dropped), the transverse `h²·T / |x'|` (a
    /// pushing tension dropped, capped at `h²·EA` near a cusp), the direction `x' / |x'|`,
    /// and the strain damping `h·c` along the same directions. The dropped terms would make
    /// the system indefinite. Without `stiffness`, the damping alone.
    pub(super) fn linearized(
        &self,
        st: &Strains<P, K>,
        t: &Tensions<P::Scalar, K>,
        h: P::Scalar,
        stiffness: bool,
    ) -> Linearized<P, K> {
        let zero = P::Scalar::ZERO;
        let ea = self.stretch.stiffness;
        // `h²` is formed after each product: in `Q16` `1/60²` alone would be 1.2% short.
        let mut lin = Linearized {
            dir: [[P::default(); POINTS]; K],
            axial: [[if stiffness { ea * h * h } else { zero }; POINTS]; K],
            transverse: [[zero; POINTS]; K],
            uniform: t.taut || !stiffness,
            stiffness,
            bend: if stiffness { h } else { zero },
            damping: h * self.damping,
            damp_dir: [[P::default(); POINTS]; K],
        };
        for e in 0..K - 3 {
            for q in 0..POINTS {
                let inv = st.inv[e][q];
                lin.dir[e][q] = st.slope[e][q] * inv;
                lin.damp_dir[e][q] = lin.dir[e][q];
                if stiffness {
                    lin.transverse[e][q] = (t.tension[e][q].max(zero) * inv).min(ea) * h * h;
                    if let Some(points) = &st.slack {
                        let l = P::Scalar::ONE + points[e][q];
                        lin.axial[e][q] = stretch_slope(ea, l) * h * h;
                    }
                }
            }
        }
        lin
    }

    /// `(h²·K + h·C)·u`: the stretch's and the bending's stiffness `K` and the strain
    /// damping's `C` as [`linearized`](Self::linearized), on control-point vectors `u`
    /// (matrix-free: one projection for the damping, one or two more for the stretch).
    pub(super) fn stiffness_times(&self, lin: &Linearized<P, K>, u: &[P; K]) -> [P; K] {
        let zero = P::Scalar::ZERO;
        let mut slope = [[P::default(); POINTS]; K];
        let mut along = [[zero; POINTS]; K];
        let mut rate = [[zero; POINTS]; K];
        let du = differences(u);
        for e in 0..K - 3 {
            for (q, weights) in self.quad[e].iter().enumerate() {
                let d = slope_at(weights, &du, e);
                slope[e][q] = d;
                if lin.stiffness {
                    along[e][q] = lin.dir[e][q].dot(d);
                }
                rate[e][q] = lin.damp_dir[e][q].dot(d);
            }
        }
        let c = lin.damping;
        // Without strain damping (the implicit steppers add no floor) its projection is skipped.
        if c > zero {
            project(&self.proj, &self.weights, &self.gram, &mut rate);
        }
        let mut tension = [[zero; POINTS]; K];
        if lin.stiffness {
            let mut strain = along;
            project(&self.proj, &self.weights, &self.gram, &mut strain);
            for e in 0..K - 3 {
                for q in 0..POINTS {
                    tension[e][q] = lin.axial[e][q] * strain[e][q];
                }
            }
            if !lin.uniform {
                project(&self.proj, &self.weights, &self.gram, &mut tension);
            }
        }
        let mut pull = [P::default(); K];
        for e in 0..K - 3 {
            for (q, d) in self.pulls[e].iter().enumerate() {
                let dir = lin.dir[e][q];
                let mut g = lin.damp_dir[e][q] * (c * rate[e][q]);
                if lin.stiffness {
                    g += dir * tension[e][q]
                        + (slope[e][q] - dir * along[e][q]) * lin.transverse[e][q];
                }
                add_pull(&mut pull, d, e, g);
            }
        }
        let mut out = [P::default(); K];
        spread(&mut out, &pull);
        if self.bending > zero && lin.bend > zero {
            let h = lin.bend;
            for (o, b) in out.iter_mut().zip(self.bending_times(u)) {
                *o += b * h * h;
            }
        }
        out
    }

    /// `M·u / m̄` from the band.
    pub(super) fn mass_times(&self, u: &[P; K]) -> [P; K] {
        band_times(&self.mass_band, u)
    }

    /// `B·u`: the strain that `u` adds along the directions `dir`, weighted onto the
    /// quadratic splines (`Σ w·N̂_a·(x'/|x'|)·u'` per function `a`).
    pub(super) fn strain_weights(&self, dir: &[[P; POINTS]; K], u: &[P; K]) -> [P::Scalar; K] {
        let mut out = [P::Scalar::ZERO; K];
        let du = differences(u);
        for e in 0..K - 3 {
            for (q, d) in self.quad[e].iter().enumerate() {
                let along = dir[e][q].dot(slope_at(d, &du, e)) * self.weights[q];
                for a in 0..3 {
                    out[e + a] += along * self.proj[e][q][a];
                }
            }
        }
        out
    }

    /// `Bᵀ·c`: the generalized forces of a strain field `Σ c_a N̂_a` along `dir`.
    pub(super) fn strain_pull(&self, dir: &[[P; POINTS]; K], c: &[P::Scalar; K]) -> [P; K] {
        let mut pull = [P::default(); K];
        for e in 0..K - 3 {
            for (q, d) in self.quad[e].iter().enumerate() {
                let mut strain = P::Scalar::ZERO;
                for a in 0..3 {
                    strain += c[e + a] * self.proj[e][q][a];
                }
                add_pull(&mut pull, d, e, dir[e][q] * (strain * self.weights[q]));
            }
        }
        let mut out = [P::default(); K];
        spread(&mut out, &pull);
        self.free(out)
    }

    /// The stretch and bending energy at strains `st`, over `m̄`.
    pub(super) fn elastic_potential(&self, st: &Strains<P, K>) -> P::Scalar {
        let mut e = P::Scalar::ZERO;
        for span in self.strain_points(st).iter().take(K - 3) {
            for (&strain, &w) in span.iter().zip(&self.weights) {
                e += stretch_energy(self.stretch.stiffness, P::Scalar::ONE + strain) * w * self.ds;
            }
        }
        if self.bending > P::Scalar::ZERO {
            // `½ xᵀBx = ½ (x − x₀)ᵀBx`: `B` takes a translation to zero.
            let bend = self.bending_times(&st.pos);
            for (p, b) in st.pos.iter().zip(bend) {
                e += (*p - st.pos[0]).dot(b) * P::Scalar::ratio(1, 2);
            }
        }
        e
    }

    /// `EI·B·u`, the bending's generalized forces at `u` (`B` its band), from the control
    /// points' differences: `B` takes a translation to zero, so row `i` is
    /// `Σ_j B_ij·(u_j − u_i)` and no product grows with the coordinates (in `Q16` they
    /// saturated the format from `EI` of a few hundred on a 70 px rope). 3 products a row.
    /// Out of line: a rope without bending never calls it, and inlined its table would sit
    /// on a microcontroller's stack anyway.
    #[inline(never)]
    pub(super) fn bending_times(&self, u: &[P; K]) -> [P; K] {
        let mut out = [P::default(); K];
        for i in 0..K {
            for d in 1..4 {
                let j = i + d;
                if j < K {
                    let pull = (u[j] - u[i]) * self.bend[i][d];
                    out[i] += pull;
                    out[j] -= pull;
                }
            }
        }
        out
    }

    /// Total energy: kinetic `½ vᵀMv`, stretch and bending (zero at the rest length, straight),
    /// and gravity's potential (zero at the origin), for tests and diagnostics. May saturate
    /// in `Q16` (a 70 px rope of 7 mass units falling its length under 200 px/s² changes it
    /// by 98 000, past the format's 32 768); in floats, past the format's range (a mass near
    /// its largest value), it overflows to ±∞.
    pub fn energy(&self) -> P::Scalar {
        let (x, v) = (&self.pos, &self.vel);
        let mv = self.mass_times(v);
        let mut e = self.elastic_potential(&self.strains(x, None));
        for i in 0..K {
            e += v[i].dot(mv[i]) * P::Scalar::ratio(1, 2)
                - self.settings.gravity.dot(x[i]) * self.load[i];
        }
        e * self.unit
    }
}

/// The tension at stretch `l = |x'|`: `EA·(l - 1)` when taut; 0 when slack, below
/// `1 - SLACK`; in between a cubic `EA·δ·x²(x - 1)`, `x = (l - 1 + δ) / δ`, so that the force
/// has no kink (a kinked force lets symplectic Euler gain energy each time a span goes slack
/// and taut again). Its slope stays within `[-EA/3, EA]` and `|T| / l` within `EA`, so the
/// substep bound holds in every shape.
#[inline]
pub(super) fn stretch_tension<S: Scalar>(ea: S, l: S) -> S {
    let one = S::ONE;
    if l >= one {
        return ea * (l - one);
    }
    let delta = S::ratio(SLACK.0, SLACK.1);
    let x = slack_step(l);
    if x <= S::ZERO {
        S::ZERO
    } else {
        ea * delta * x * x * (x - one)
    }
}

/// `x = (l − 1 + δ) / δ` of the slack step at stretch `l`, `δ` = [`SLACK`]: a product, no
/// division (in `Q16` a 64-bit library call on a Cortex-M0).
#[inline]
pub(super) fn slack_step<S: Scalar>(l: S) -> S {
    const { assert!(SLACK.1.is_multiple_of(SLACK.0) && SLACK.1 / SLACK.0 < 1 << 14) };
    (l - S::ONE) * S::from_i16((SLACK.1 / SLACK.0) as i16) + S::ONE
}

/// The slope of [`stretch_tension`] by `l`, negative slopes (the slack step's first part)
/// as 0: within `[0, EA]`.
pub(super) fn stretch_slope<S: Scalar>(ea: S, l: S) -> S {
    let one = S::ONE;
    if l >= one {
        return ea;
    }
    let x = slack_step(l);
    (ea * x * (S::from_i16(3) * x - S::from_i16(2))).max(S::ZERO)
}

/// The stretch energy per unit length whose derivative is [`stretch_tension`]: 0 at the
/// rest length, `EA·SLACK²/12` when slack.
pub(super) fn stretch_energy<S: Scalar>(ea: S, l: S) -> S {
    let one = S::ONE;
    let delta = S::ratio(SLACK.0, SLACK.1);
    let twelfth = S::ratio(1, 12);
    if l >= one {
        let strain = l - one;
        return S::ratio(1, 2) * ea * strain * strain;
    }
    let x = slack_step(l).max(S::ZERO);
    ea * delta * delta * (x * x * x * (S::ratio(1, 4) * x - S::ratio(1, 3)) + twelfth)
}

/// The stretch at a rope's stretch points: see [`SplineRope::strains`].
pub(super) struct Strains<P: Point, const K: usize> {
    /// The control points they were taken at.
    pub(super) pos: [P; K],
    pub(super) slope: [[P; POINTS]; K],
    pub(super) inv: [[P::Scalar; POINTS]; K],
    /// The strain `|x'| − 1` and its rate, projected: the coefficients of their quadratic
    /// splines (entry `K − 1` is 0).
    pub(super) strain: [P::Scalar; K],
    pub(super) rate: [P::Scalar; K],
    /// The projected strain at the stretch points where it is below 0 at one of them (a
    /// span slack); `None` while every span is taut.
    pub(super) slack: Option<[[P::Scalar; POINTS]; K]>,
}

/// The tension over the mass unit at a rope's stretch points and whether every span is taut.
pub(super) struct Tensions<S, const K: usize> {
    pub(super) tension: [[S; POINTS]; K],
    pub(super) taut: bool,
}

/// A backward Euler step's stiffness at a rope's stretch points: see
/// [`SplineRope::linearized`].
pub(super) struct Linearized<P: Point, const K: usize> {
    pub(super) dir: [[P; POINTS]; K],
    pub(super) axial: [[P::Scalar; POINTS]; K],
    pub(super) transverse: [[P::Scalar; POINTS]; K],
    /// Every `axial` is `h²·EA`: the projected strain needs no second projection.
    pub(super) uniform: bool,
    /// Whether the stretch's stiffness is in (else `dir`, `axial` and `transverse` are unused).
    pub(super) stiffness: bool,
    /// `h` where the bending's `h²·EI·B` is in, else 0.
    pub(super) bend: P::Scalar,
    /// `h·c`, the strain damping's share.
    pub(super) damping: P::Scalar,
    /// The directions the strain damping acts along: `dir`, or those it was frozen at.
    pub(super) damp_dir: [[P; POINTS]; K],
}

/// Below `1 - SLACK` of its rest length a span of rope is slack: `(1, 10)`.
pub(super) const SLACK: (u32, u32) = (1, 10);
