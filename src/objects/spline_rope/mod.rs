//! A rope whose state is the control points of its drawn curve: the physics acts on the
//! curve itself (isogeometric analysis), not on a chain of particles.
//!
//! The rope is `x(s) = Σ N_i(s) p_i`, a clamped uniform cubic B-spline over the material
//! coordinate `s ∈ [0, L]` (arc length at rest), with `K ≥ 4` control points `p_i`. Its
//! equations of motion come from its energies, integrated over the curve by Gauss
//! quadrature on each of its `K - 3` spans:
//!
//! - **mass** `M_ij = ∫ ρ N_i N_j ds`, the consistent matrix (banded, 7 diagonals), factored
//!   once as `L D Lᵀ` (in `f64`, stored in the format);
//! - **gravity** `f_i = ∫ ρ N_i ds · g`;
//! - **stretch** `½ ∫ EA ε̄² ds` while taut, where `ε̄` is the strain `|x'| − 1` at 3 Gauss
//!   points a span, projected (least squares) on the quadratic splines of the same breaks
//!   (`K − 1` functions). A few cubic spans cannot bend like a hanging rope and keep
//!   `|x'| = 1` at every point, so the raw strain locks them stiff; its projection asks
//!   the length to hold on `K − 1` averages only (a "B-bar" strain). A rope does not push:
//!   below 90% of its length it is slack, with a smooth step between (see
//!   `stretch_tension`);
//! - **bending** (optional, [`SplineRope::set_bending`]) `½ ∫ EI |x''|² ds`, a constant
//!   banded matrix;
//! - **damping** on the projected strain rate, `c · dε̄/dt`, plus air drag `γ·M·v`
//!   ([`Settings::damping`]);
//! - **pins** on control points: a clamped end interpolates its control point, so pinning
//!   `p_0` holds the rope's end;
//! - **force fields and contacts** as a [`Rope`](crate::Rope) takes them
//!   ([`step_with`](SplineRope::step_with), [`step_touching`](SplineRope::step_touching)):
//!   a force `f` at a point of the curve acts on the control points as `w_i f`, its basis
//!   weights (`Jᵀ f`), and contacts push the drawn curve itself out of the colliders.
//!
//! Steps are symplectic Euler with substeps from the largest generalized eigenvalue of the
//! projected stretch stiffness against the mass (found by Lanczos steps at construction
//! and when pins change), at the [`Accuracy`]'s fraction of the limit; or, chosen by type,
//! backward Euler or BDF2 by Newton's method on the step's incremental potential, one step a
//! frame at any stiffness (see [`SplineStepper`]).
//!
//! Accuracy, against the continuum (`tests/suite/spline_rope.rs`): with 8 control points a hanging
//! rope's first three lateral modes are within 0.01%, 0.01% and 0.02% of `(j_n / 2)·√(g/L)`
//! (measured the same way, a chain of 8 particles is 0.6%, 6.8% and 13.4% off, one of 30
//! 0.04%, 0.46% and 1.8%; linearized, a chain needs 289 particles to match mode 3:
//! `cargo run --release -p dunas-evaluate`, section (h)). Between two pins, 8 control
//! points sag within 0.1% of the catenary (3.2% short without the projection).
//!
//! Stability: the substep bound holds in every shape (the tension's stiffness never passes
//! `EA`). At [`Accuracy::Fast`] and `Balanced`, symplectic Euler
//! near its limit pumps energy from the swing into the fastest stretch waves until an
//! undamped rope diverges; so at those accuracies the strain damping is at least
//! [`MIN_DAMPING_RATIO`] (2%) of critical on those waves, `c ≥ 0.04·EA / ω`, which takes
//! 0.005% of critical from a 1 m rope's swing. At [`Accuracy::Fine`]
//! nothing is added. Either way a rope released level keeps its energy over 10⁵ frames
//! (Fine: within 2.5% of `m·g·L`; Fast: never 0.1% above the start).
//!
//! Cost per substep: `3·(K - 3)` inverse square roots ([`Scalar::inv_sqrt`]: in `Q16` no
//! division), two banded solves and about `114·(K − 3) + 34·K` multiplies while every span
//! is taut (38 a stretch point, 34 a control point, less a few where the bands end: 805 at
//! `K = 8`), up to a fifth more while one is slack (a third solve; the projected strain at
//! the stretch points, which a taut rope skips); in `Q16` no division.
//! Formats: `f32` and `f64` for any rope in [`Scalar::SAFE_RANGE`]; `Q16` for ropes
//! measured in pixels (a 70 px rope of 7 mass units at `EA = 3000` ends 0.10 px from `f64`
//! after 2 s); the construction (mass matrix, factors, bound) runs in `f64` and is stored
//! in the format.
//!
//! Units: a step divides its equations by a mass unit `m̄`, a span's mass (`mass / (K − 3)`),
//! or `EA / 2¹⁴` or `c / 2¹⁴` where more; explicit substeps are taken in velocity changes, not
//! accelerations. So in `Q16` a rope's precision does not depend on its mass, and a whip far
//! past the format's range is held: the `mcu_spline` rope 30 times lighter or 3 times
//! heavier, or 2 to 7 times larger (up to 490 px under 1 400 px/s², its end whipping past
//! 100 000 px/s² with 16 control points), stays within 1% of its length from `f64` for
//! 2 s with 8, 12 and 16 control points (`tests/suite/spline_rope.rs`; measured at most 0.57%).
//! What `Q16` clamps and reports is in [`SplineRope::step`].
//!
//! ```
//! use dunas::prelude::*;
//! use dunas::spline_rope::SplineRope;
//!
//! let settings = Settings { gravity: Vec2::new(0.0, -9.81), damping: 0.1, ..Settings::default() };
//! // 2 m, 1 kg, EA = 2000 N, strain damping 2 N·s: the drawn curve is the state.
//! let stretch = Material { stiffness: 2000.0, damping: 2.0 };
//! let mut rope: SplineRope<Vec2<f64>, 8> =
//!     SplineRope::new(Vec2::new(0.0, 0.0), Vec2::new(2.0, 0.0), 1.0, stretch, settings)?;
//! for _ in 0..120 {
//!     rope.step(1.0 / 60.0)?;
//! }
//! let mut curve = [Vec2::default(); 50];
//! let n = rope.sample(&mut curve)?;
//! assert_eq!(curve[0], Vec2::new(0.0, 0.0)); // pinned at its start
//! assert!(curve[n - 1].y < -1.0); // swung down
//! # Ok::<(), dunas::Error>(())
//! ```
//!
//! A cable 5000 times stiffer, stepped implicitly: one step a frame.
//!
//! ```
//! use dunas::integrator::ImplicitEuler;
//! use dunas::prelude::*;
//! use dunas::spline_rope::SplineRope;
//!
//! let settings = Settings { gravity: Vec2::new(0.0, -9.81), ..Settings::default() }
//!     .with_integrator(ImplicitEuler::default());
//! let cable = Material { stiffness: 1.0e7, damping: 0.0 };
//! let mut rope: SplineRope<Vec2<f32>, 8, ImplicitEuler> =
//!     SplineRope::new(Vec2::new(0.0, 0.0), Vec2::new(2.0, 0.0), 1.0, cable, settings)?;
//! for _ in 0..60 {
//!     let info = rope.step(1.0 / 60.0)?;
//!     assert_eq!(info.substeps, 1);
//! }
//! let mut curve = [Vec2::default(); 100];
//! let n = rope.sample(&mut curve)?;
//! let length: f32 = curve[..n].windows(2).map(|w| w[0].distance(w[1])).sum();
//! assert!(curve[n - 1].y < -1.0 && (length - 2.0).abs() < 0.01); // swung, kept its length
//! # Ok::<(), dunas::Error>(())
//! ```

use crate::error::invalid;
use crate::error::{check_index, check_inside, check_non_negative, check_points, check_positive};
use core::ops::{Mul, Sub};

use crate::contact::{Contacts, DrawnSpans};
use crate::curves::sampler::bernstein_weights;
use crate::curves::sampler::{DefaultSampler, Sampler};
use crate::physics::force::{Accelerations, Bodies, ForceField};
use crate::physics::hash::StateHash;
use crate::physics::integrator::{ImplicitEuler, SymplecticEuler, solve_scale};
use crate::physics::substeps::{plan, substeps_per_rate};
use crate::physics::system::StepInfo;
use crate::{Aabb, Accuracy, Bezier, Error, Material, Point, Scalar, Settings, Vec2};

/// Gauss-Legendre points and weights on `[-1, 1]`: exact to degree 7 (the mass integrand
/// `N_i N_j` is degree 6).
const GAUSS: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

/// Stretch points a span: [`STRETCH_GAUSS`]'s. (Two, exact to degree 3, would save a third
/// of a substep's products, but `tests/suite/spline_rope.rs` then measures mode 3 of a hanging
/// rope of 8 control points 1.2% off the continuum, against 0.015% with three.)
const POINTS: usize = 3;

/// The stretch's quadrature: 3-point Gauss-Legendre, exact for the projection's Gram matrix
/// (quadratic times quadratic) and for a straight rope's stretch stiffness.
const STRETCH_GAUSS: [(f64, f64); POINTS] = [
    (-0.774_596_669_241_483_4, 0.555_555_555_555_556),
    (0.0, 0.888_888_888_888_889),
    (0.774_596_669_241_483_4, 0.555_555_555_555_556),
];

/// A rope of `K` control points whose drawn curve is its state, stepped by `I` (see
/// [`SplineStepper`]). See the [module](self).
#[derive(Clone, Debug)]
pub struct SplineRope<P: Point, const K: usize, I = SymplecticEuler> {
    pos: [P; K],
    vel: [P; K],
    pinned: [bool; K],
    /// At each span's stretch points, the slope's weights on the control points'
    /// differences, by `s` (see [`slope_at`]).
    quad: [[[P::Scalar; 3]; POINTS]; K],
    /// The same weights times the point's quadrature weight over the span, `d_a·w/2` (the
    /// slope weights times `w·ds/2`): what a tension's pull at the point does to the
    /// differences, the quadrature taken in the table (see [`add_pull`]).
    pulls: [[[P::Scalar; 3]; POINTS]; K],
    /// A span's length `ds`, for the stretch energy's quadrature and the implicit step's
    /// preconditioner. (The pulls carry theirs in `pulls`: no product in a step grows with
    /// a span's length, where in `Q16` a long span's pull saturated.)
    ds: P::Scalar,
    /// The mass unit `m̄` the step's equations are divided by (see the [module](self)).
    unit: P::Scalar,
    /// `∫ ρ N_i ds / m̄`: the gravity load per unit of `g`, per unit of a span's mass.
    load: [P::Scalar; K],
    /// `1 / ∫ ρ N_i ds`, 0 where pinned: the inverse masses a force field and the contacts
    /// see.
    inv_load: [P::Scalar; K],
    /// The banded `L D Lᵀ` factor of the mass matrix over `m̄`, pinned rows made identity:
    /// `chol[i][d]` is `L[i][i - d]`, except `chol[i][0] = 1 / D[i]`.
    chol: [[P::Scalar; 4]; K],
    /// Each span's Bézier extraction: Bézier point `r` is `Σ_k ext[e][r][k] · p_(e+k)`.
    ext: [[[P::Scalar; 4]; 4]; K],
    /// The strain's projection: at each span's stretch points the quadratic basis
    /// `N̂_e..N̂_(e+2)`; the stretch points' weights in a span (`w/2`); the `L D Lᵀ` factor
    /// of the Gram matrix `Σ (w/2)·N̂_a·N̂_b` (`1 / D` on the diagonal, unit past `K - 2`).
    proj: [[[P::Scalar; 3]; POINTS]; K],
    weights: [P::Scalar; POINTS],
    gram: [[P::Scalar; 3]; K],
    /// The mass matrix over `m̄` in band form (`mass_band[i][d] = M[i][i+d] / m̄`), for the
    /// implicit stepper's products.
    mass_band: [[P::Scalar; 4]; K],
    /// `EI / m̄` times it, in the format: the bending force over `m̄` is `−bend·x`.
    bend: [[P::Scalar; 4]; K],
    /// The bending stiffness `EI` (force · length²).
    bending: P::Scalar,
    /// The stretch's `EA` and `c` over `m̄` (force over mass: 1/s² and 1/s).
    stretch: Material<P::Scalar>,
    settings: Settings<P, I>,
    length: P::Scalar,
    mass: P::Scalar,
    /// `ω` of the stretch and bending against the mass (rad/s), from Lanczos steps.
    omega: P::Scalar,
    /// The same for the stretch alone: what the strain damping acts on.
    stretch_omega: P::Scalar,
    /// The strain damping over `m̄`: `stretch.damping`, at least [`MIN_DAMPING_RATIO`] of
    /// critical on the fastest stretch wave (1/s).
    damping: P::Scalar,
    /// The strain damping's rate, `(c / EA)·ω²` (1/s).
    gamma: P::Scalar,
    /// Substeps per unit of `rate·dt` at the accuracy (0 for an implicit stepper).
    per_rate: P::Scalar,
    /// The last implicit step, for [`Bdf2`]; `None` after a change from outside.
    history: Option<History<P, K>>,
    /// Generalized forces over `m̄` applied for the next step
    /// ([`apply_force`](Self::apply_force)).
    extra: [P; K],
    time: P::Scalar,
}

mod draw;
mod forces;
mod matrix;
mod steppers;
#[cfg(all(test, dunas_floats))]
mod tests;

use draw::*;
use forces::*;
use matrix::*;
use steppers::*;
pub use steppers::{Bdf2, MIN_DAMPING_RATIO, SplineStepper};

impl<P: Point, const K: usize, I: SplineStepper> SplineRope<P, K, I> {
    /// A straight rope from `start` (its first control point pinned) to `end`, of total
    /// `mass`, unstretched; `material.stiffness` is the axial stiffness `EA` (force units),
    /// `material.damping` the strain-rate damping `c` (force · seconds).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a non-positive or non-finite mass or stiffness, a
    /// mass beyond [`Scalar::SAFE_RANGE`] (so that a momentum fits the format), a
    /// negative damping, or a mass unit (see the [module](self)) that rounds to zero in the
    /// format (in `Q16`, a span's mass and `EA` and `c` over `2¹⁴` all below `2⁻¹⁷`);
    /// [`Error::ZeroRestLength`] when `start == end`; as
    /// [`Settings::check`]; [`Error::NonFinite`] / [`Error::OutOfRange`] for the ends
    /// (beyond the safe range or [`Settings::bounds`]); [`Error::TooStiff`] when the substep
    /// bound is beyond the format.
    pub fn new(
        start: P,
        end: P,
        mass: P::Scalar,
        material: Material<P::Scalar>,
        settings: Settings<P, I>,
    ) -> Result<Self, Error> {
        const {
            assert!(
                K >= 4,
                "a cubic spline rope needs at least 4 control points"
            )
        };
        check_points(&[start, end], "start or end")?;
        if !check_positive(mass, "mass")?.in_safe_range() {
            return Err(invalid("mass", "at most the safe range (Q16: 16 383)"));
        }
        material.check()?;
        settings.check()?;
        check_inside(&[start, end], settings.bounds, "start or end")?;
        let length = start.distance(end);
        if !(length > P::Scalar::EPSILON && length.is_finite()) {
            return Err(Error::ZeroRestLength { a: 0, b: K - 1 });
        }
        let spans = K - 3;
        let l = length.to_f64();
        let ds = l / spans as f64;
        // A span's mass, or more where `EA` or `c` over it would pass `2¹⁴` (in `Q16` a
        // stiff rope of light spans).
        let most = |x: P::Scalar| x.to_f64() / f64::from(1u32 << 14);
        let unit = P::Scalar::from_f64(
            (mass.to_f64() / spans as f64)
                .max(most(material.stiffness))
                .max(most(material.damping)),
        );
        let zero = P::Scalar::ZERO;
        if unit <= zero {
            // A mass below the format's resolution.
            return Err(invalid(
                "mass",
                "large enough for the format to resolve a control point's share",
            ));
        }
        let per_mass = |x: P::Scalar| P::Scalar::from_f64(x.to_f64() / unit.to_f64());
        // Both within `2¹⁴`.
        let stretch = Material {
            stiffness: per_mass(material.stiffness),
            damping: per_mass(material.damping),
        };
        let mut rope = SplineRope {
            pos: [start; K],
            vel: [P::default(); K],
            pinned: [false; K],
            quad: [[[zero; 3]; POINTS]; K],
            pulls: [[[zero; 3]; POINTS]; K],
            ds: P::Scalar::from_f64(ds),
            unit,
            load: [zero; K],
            inv_load: [zero; K],
            chol: [[zero; 4]; K],
            ext: [[[zero; 4]; 4]; K],
            proj: [[[zero; 3]; POINTS]; K],
            weights: STRETCH_GAUSS.map(|(_, w)| P::Scalar::from_f64(w / 2.0)),
            gram: [[zero; 3]; K],
            mass_band: [[zero; 4]; K],
            bend: [[zero; 4]; K],
            bending: zero,
            stretch,
            settings,
            length,
            mass,
            omega: zero,
            stretch_omega: zero,
            damping: zero,
            gamma: zero,
            per_rate: zero,
            history: None,
            extra: [P::default(); K],
            time: zero,
        };
        // Control points at the Greville abscissae: a straight, evenly parametrised line.
        for (i, p) in rope.pos.iter_mut().enumerate() {
            *p = start.lerp(end, P::Scalar::from_f64(greville(i, K) / l * ds));
        }
        // The tables are written in place, one entry at a time: on a 16 KB microcontroller
        // every table-sized temporary counts.
        let (band, load) = mass_matrix::<K>(rope.density_over_unit(), ds);
        for i in 0..K {
            rope.load[i] = P::Scalar::from_f64(load[i]);
            for d in 0..4 {
                rope.mass_band[i][d] = P::Scalar::from_f64(band[i][d]);
            }
        }
        // The Gram matrix of the quadratic splines at the stretch points, row `K - 1` (past
        // the `K - 1` functions) the identity's.
        let mut gram = [[0.0; 3]; K];
        gram[K - 1][0] = 1.0;
        for e in 0..spans {
            for (q, &(xi, w)) in STRETCH_GAUSS.iter().enumerate() {
                let (_, dn, n) = basis_in(e, e as f64 + (xi + 1.0) / 2.0, K);

                // `Σ_k N'_k x_k = Σ_a d_a·(x_(a+1) − x_a)` with `d_a = −Σ_(k≤a) N'_k`
                // (the slopes sum to 0).
                let mut d = 0.0;
                for a in 0..3 {
                    d -= dn[a];
                    rope.quad[e][q][a] = P::Scalar::from_f64(d / ds);
                    rope.pulls[e][q][a] = P::Scalar::from_f64(d * w / 2.0);
                }
                for a in 0..3 {
                    rope.proj[e][q][a] = P::Scalar::from_f64(n[a]);
                    for b in a..3 {
                        gram[e + a][b - a] += w / 2.0 * n[a] * n[b];
                    }
                }
            }
            let ext = extraction(e, K);
            for r in 0..4 {
                for k in 0..4 {
                    rope.ext[e][r][k] = P::Scalar::from_f64(ext[r][k]);
                }
            }
        }
        let gram = ldl(&gram, finite_inverse).ok_or(invalid(
            "length",
            "long enough for the strain projection to be resolved",
        ))?;
        for i in 0..K {
            for d in 0..3 {
                rope.gram[i][d] = P::Scalar::from_f64(gram[i][d]);
            }
        }
        rope.pinned[0] = true;
        rope.refactor()?;
        Ok(rope)
    }

    /// Factors the mass matrix with the pinned rows and columns made identity, and finds the
    /// stable substep's rate. `f64`, `O(K)` for the factor, `O(K²)` for the rate (at most
    /// `K` Lanczos steps).
    fn refactor(&mut self) -> Result<(), Error> {
        let spans = (K - 3) as f64;
        let ds = self.length.to_f64() / spans;
        let (band, load) = mass_matrix::<K>(self.density_over_unit(), ds);
        for i in 0..K {
            self.inv_load[i] = if self.pinned[i] {
                P::Scalar::ZERO
            } else {
                P::Scalar::from_f64(1.0 / (self.unit.to_f64() * load[i]))
            };
        }
        let m = self.reduced(&band, (0.0, 1.0));
        // `1/D` is kept: a step multiplies where it would divide. The reduced matrix is
        // positive definite, so a failure is the mass over `m̄` underflowing `f64`: a mass far
        // below its stiffness.
        let chol = ldl(&m, finite_inverse).ok_or(Error::TooStiff)?;
        for i in 0..K {
            for d in 0..4 {
                self.chol[i][d] = P::Scalar::from_f64(chol[i][d]);
            }
        }
        // The stretch's stiffness on the straight rope over `m̄`, `EA·Bᵀ W Π B / m̄`: the
        // strain of a displacement along the rope, projected, back through the slopes; and
        // the bending.
        // From the tables the steps use (the bound is the stepped operator's), read in `f64`
        // where they are used ([`Wide`]): a copy of them would cost a microcontroller's stack
        // 2 KB.
        let ea = self.stretch.stiffness.to_f64();
        // `EI` 0 for the stretch alone; one closure type, so one eigenvalue search is linked.
        let ei = self.bending.to_f64() / self.unit.to_f64();
        let curvature = if ei > 0.0 {
            curvature_band::<K>(ds)
        } else {
            [[0.0; 4]; K]
        };
        let (quad, pulls) = (&self.quad, &self.pulls);
        let (proj, weights, gram) = (&self.proj, &self.weights, &self.gram);
        let curvature = &curvature;
        let stiffness = |ei: f64| {
            move |x: &[f64; K]| -> [f64; K] {
                let mut strain = [[Wide(0.0); POINTS]; K];
                let dx = differences(x);
                for e in 0..K - 3 {
                    for (q, d) in quad[e].iter().enumerate() {
                        strain[e][q] = Wide(slope_at(&d.map(|d| d.to_f64()), &dx, e));
                    }
                }
                project(proj, weights, gram, &mut strain);
                let mut y = if ei > 0.0 {
                    band_times(curvature, x).map(|b| ei * b)
                } else {
                    [0.0; K]
                };
                let mut pull = [0.0; K];
                for e in 0..K - 3 {
                    for (q, d) in pulls[e].iter().enumerate() {
                        add_pull(&mut pull, &d.map(|d| d.to_f64()), e, ea * strain[e][q].0);
                    }
                }
                spread(&mut y, &pull);
                y
            }
        };
        let stretch = largest_eigenvalue(stiffness(0.0), &m, &chol, &self.pinned);
        self.stretch_omega = P::Scalar::from_f64(crate::geometry::catenary::sqrt(stretch));
        let lambda = if ei > 0.0 {
            largest_eigenvalue(stiffness(ei), &m, &chol, &self.pinned)
        } else {
            stretch
        };
        self.omega = P::Scalar::from_f64(crate::geometry::catenary::sqrt(lambda));
        self.plan_damping()
    }

    /// The strain damping over `m̄` and its rate, from the stretch's `ω`, the material and
    /// the accuracy; and the substeps per unit of rate.
    fn plan_damping(&mut self) -> Result<(), Error> {
        let explicit = self.settings.integrator.implicit().is_none();
        self.per_rate = if explicit {
            substeps_per_rate(&SymplecticEuler, self.settings.accuracy)
        } else {
            P::Scalar::ZERO
        };
        let (ea, omega) = (self.stretch.stiffness.to_f64(), self.stretch_omega.to_f64());
        let mut c = self.stretch.damping.to_f64();
        if explicit && self.settings.accuracy != Accuracy::Fine {
            c = c.max(MIN_DAMPING_RATIO * 2.0 * ea / omega);
        }
        self.damping = P::Scalar::from_f64(c);
        self.gamma = P::Scalar::from_f64(c / ea * omega * omega);
        if self.omega.is_finite() && self.gamma.is_finite() && self.damping.is_finite() {
            Ok(())
        } else {
            Err(Error::TooStiff)
        }
    }

    /// The density over the mass unit, `ρ / m̄` (1/length), in `f64`.
    fn density_over_unit(&self) -> f64 {
        self.mass.to_f64() / self.length.to_f64() / self.unit.to_f64()
    }

    /// `band` with pinned rows and columns made those of the identity.
    fn reduced<T: Copy>(&self, band: &[[T; 4]; K], (zero, one): (T, T)) -> [[T; 4]; K] {
        let mut out = *band;
        for i in 0..K {
            for d in 0..4 {
                let j = i + d;
                if j < K && (self.pinned[i] || self.pinned[j]) {
                    out[i][d] = if d == 0 { one } else { zero };
                }
            }
        }
        out
    }

    /// The control points: the drawn curve's, in order (the first and last are its ends).
    pub fn positions(&self) -> &[P; K] {
        &self.pos
    }

    /// The control points' velocities.
    pub fn velocities(&self) -> &[P; K] {
        &self.vel
    }

    /// Total mass.
    pub fn mass(&self) -> P::Scalar {
        self.mass
    }

    /// Rest length (the material coordinate runs over `0..=length`).
    pub fn length(&self) -> P::Scalar {
        self.length
    }

    /// Simulated time since creation (seconds).
    pub fn time(&self) -> P::Scalar {
        self.time
    }

    /// A checksum of everything that shapes the steps to come, for rollback netplay (as
    /// [`MassSpring::state_hash`](crate::MassSpring::state_hash), which states what keeps
    /// it equal across platforms): the clock, every control point's position, velocity,
    /// pin and mass, the stretch's and bending's stiffness and damping, gravity, the drag,
    /// the forces applied for the next step, and the last implicit step that
    /// [`Bdf2`] starts from. A snapshot is a clone.
    pub fn state_hash(&self) -> u64 {
        let mut hash = StateHash::new();
        hash.add_scalar(self.time);
        for i in 0..K {
            hash.add_point(self.pos[i]);
            hash.add_point(self.vel[i]);
            hash.add_u32(u32::from(self.pinned[i]));
            hash.add_scalar(self.inv_load[i]);
            hash.add_point(self.extra[i]);
        }
        for value in [self.stretch.stiffness, self.stretch.damping, self.bending] {
            hash.add_scalar(value);
        }
        hash.add_point(self.settings.gravity);
        hash.add_scalar(self.settings.damping);
        match &self.history {
            Some(last) => {
                hash.add_u32(1);
                last.start.iter().for_each(|&p| hash.add_point(p));
                last.velocities.iter().for_each(|&v| hash.add_point(v));
                hash.add_scalar(last.h);
                hash.add_scalar(last.headroom);
            }
            None => hash.add_u32(0),
        }
        hash.finish()
    }

    /// The highest angular frequency of the stretch and bending against the mass (rad/s, by
    /// Lanczos steps on the straight rope) and the strain damping's rate on the fastest
    /// stretch wave (1/s): what the substeps are planned from, at the [`Accuracy`]'s fraction of
    /// symplectic Euler's limit `ω·h < 2`.
    pub fn stiffness_bound(&self) -> (P::Scalar, P::Scalar) {
        (self.omega, self.gamma)
    }

    /// The settings in force.
    pub fn settings(&self) -> &Settings<P, I> {
        &self.settings
    }

    /// Replaces the settings (gravity, air drag, bounds, accuracy) between steps; a change of
    /// accuracy adds or removes the damping floor (see `MIN_DAMPING_RATIO`).
    ///
    /// # Errors
    /// As [`Settings::check`], and [`Error::OutOfRange`] for bounds that a control point is
    /// already beyond; the old settings stay.
    pub fn set_settings(&mut self, settings: Settings<P, I>) -> Result<(), Error> {
        settings.check()?;
        check_inside(&self.pos, settings.bounds, "control point")?;
        let before = core::mem::replace(&mut self.settings, settings);
        if let Err(e) = self.plan_damping() {
            self.settings = before;
            self.plan_damping()?;
            return Err(e);
        }
        Ok(())
    }

    /// The bending stiffness `EI` (force · length²; 0, the default, for a rope).
    pub fn bending(&self) -> P::Scalar {
        self.bending
    }

    /// Sets the bending stiffness `EI` (force · length²): the energy `½ ∫ EI |x''|² ds`, a
    /// constant banded matrix on the control points (a cable, a hose, a wire). A hanging
    /// end bends like a cantilever (`tests/suite/spline_rope.rs`: tip deflection within 1% of
    /// `ρ·g·L⁴ / (8·EI)`). The substep bound is found again (at most `K` Lanczos
    /// steps, `O(K²)`): a stiff `EI` on short spans asks for many substeps, `ω² ∝ EI / (ρ·ds⁴)`;
    /// the implicit stepper takes it in one. The forces are formed from the control points'
    /// differences, so `Q16` holds `EI` up to its range (a 70 px rope of 16 control points
    /// at `EI = 3000` ends within 0.1 px of `f64` after 2 s).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite `ei`; [`Error::TooStiff`]
    /// when the bound, or the bending's band over the mass unit (`EI / m̄` times entries
    /// up to `36 / ds³`), is beyond the format. Nothing changes on an error.
    pub fn set_bending(&mut self, ei: P::Scalar) -> Result<(), Error> {
        check_non_negative(ei, "bending stiffness EI")?;
        let before = (self.bending, self.bend);
        self.bending = ei;
        let ds = self.length.to_f64() / (K - 3) as f64;
        let per_mass = ei.to_f64() / self.unit.to_f64();
        self.bend =
            curvature_band::<K>(ds).map(|row| row.map(|c| P::Scalar::from_f64(c * per_mass)));
        let fits = self.bend.iter().flatten().all(|b| b.is_finite());
        let planned = if fits {
            self.refactor()
        } else {
            Err(Error::TooStiff)
        };
        if let Err(e) = planned {
            (self.bending, self.bend) = before;
            self.refactor()?;
            return Err(e);
        }
        Ok(())
    }

    /// Pins (`true`) or frees control point `i`; a pinned point stops. Pinning the first or
    /// last holds the rope's end exactly; an inner one holds a point near the curve.
    ///
    /// Cost: the mass matrix is factored and the substep bound found again, in `f64`
    /// (`O(K²)`): with 8 control points 3.5 million instructions on a Cortex-M0 (software
    /// `f64`, about a quarter of a second at 16 MHz) and 0.86 million on a Cortex-M4F
    /// (`examples/mcu_spline.rs`). Pin between frames, not every frame.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::InvalidParameter`] when nothing would be left
    /// free. Nothing changes on an error.
    pub fn set_pinned(&mut self, i: usize, pinned: bool) -> Result<(), Error> {
        check_index(i, K)?;
        let before = self.pinned;
        self.pinned[i] = pinned;
        if self.pinned.iter().all(|&p| p) {
            self.pinned = before;
            return Err(invalid("pins", "leaving at least one control point free"));
        }
        if let Err(e) = self.refactor() {
            self.pinned = before;
            self.refactor()?;
            return Err(e);
        }
        if pinned {
            self.vel[i] = P::default();
        }
        self.history = None;
        Ok(())
    }

    /// Moves control point `i` to `p` (teleports; velocity unchanged).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::NonFinite`] / [`Error::OutOfRange`] for `p`
    /// (beyond the safe range or [`Settings::bounds`]).
    pub fn set_position(&mut self, i: usize, p: P) -> Result<(), Error> {
        check_index(i, K)?;
        check_points(&[p], "position")?;
        check_inside(&[p], self.settings.bounds, "position")?;
        self.pos[i] = p;
        self.history = None;
        Ok(())
    }

    /// Sets control point `i`'s velocity (a pinned point keeps 0 after the next step).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::NonFinite`] / [`Error::OutOfRange`] for `v`.
    pub fn set_velocity(&mut self, i: usize, v: P) -> Result<(), Error> {
        check_index(i, K)?;
        check_points(&[v], "velocity")?;
        self.vel[i] = v;
        self.history = None;
        Ok(())
    }

    /// Moves control point `i` to `p` over the last `dt` seconds (a hand): see
    /// [`MassSpring::move_pinned`](crate::MassSpring::move_pinned).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`]; [`Error::InvalidParameter`] for a `dt` that is not
    /// positive; [`Error::NonFinite`] / [`Error::OutOfRange`] for `p` (beyond the safe range
    /// or [`Settings::bounds`]) or its velocity.
    pub fn move_pinned(&mut self, i: usize, p: P, dt: P::Scalar) -> Result<(), Error> {
        check_index(i, K)?;
        check_positive(dt, "dt")?;
        check_points(&[p], "position")?;
        check_inside(&[p], self.settings.bounds, "position")?;
        let v = (p - self.pos[i]) * (P::Scalar::ONE / dt);
        check_points(&[v], "velocity")?;
        (self.pos[i], self.vel[i]) = (p, v);
        self.history = None;
        Ok(())
    }

    /// The basis weights at material coordinate `s` (clamped to `0..=length`, NaN as 0): the first
    /// control point they apply to and the four weights, which sum to 1. A point of the
    /// curve is `Σ w_k p_(first + k)`; a force `f` there acts on those control points as
    /// `w_k f` (`Jᵀ f`).
    pub fn weights_at(&self, s: P::Scalar) -> (usize, [P::Scalar; 4]) {
        let (first, w) = self.basis_at(s);
        (first, w.map(P::Scalar::from_f64))
    }

    /// [`weights_at`](Self::weights_at) in `f64`.
    fn basis_at(&self, s: P::Scalar) -> (usize, [f64; 4]) {
        let spans = (K - 3) as f64;
        let along = s.to_f64() / self.length.to_f64();
        // NaN counts as the start.
        let u = if along > 0.0 {
            along.min(1.0) * spans
        } else {
            0.0
        };
        ((u as usize).min(K - 4), basis(u, K).0)
    }

    /// Applies force `f` at material coordinate `s` during the next step (a hit, a pull,
    /// a contact), through the basis weights there.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for `f`; [`Error::NonFinite`] (named
    /// `"arc length"`) for a non-finite `s`.
    pub fn apply_force(&mut self, s: P::Scalar, f: P) -> Result<(), Error> {
        check_points(&[f], "force")?;
        if !s.is_finite() {
            return Err(Error::NonFinite { name: "arc length" });
        }
        // The weights over the mass unit, in `f64`: no division in the format.
        let (first, w) = self.basis_at(s);
        let unit = self.unit.to_f64();
        for (k, &wk) in w.iter().enumerate() {
            self.extra[first + k] += f * P::Scalar::from_f64(wk / unit);
        }
        Ok(())
    }
}
