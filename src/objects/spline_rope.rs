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
//! Accuracy, against the continuum (`tests/spline_rope.rs`): with 8 control points a hanging
//! rope's first three lateral modes are within 0.01%, 0.01% and 0.02% of `(j_n / 2)·√(g/L)`
//! (measured the same way, a chain of 8 particles is 0.6%, 6.8% and 13.4% off, one of 30
//! 0.04%, 0.46% and 1.8%; linearized, a chain needs 289 particles to match mode 3:
//! `cargo run --release --example evaluate`, section (h)). Between two pins, 8 control
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
//! 2 s with 8, 12 and 16 control points (`tests/spline_rope.rs`; measured at most 0.57%).
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
/// of a substep's products, but `tests/spline_rope.rs` then measures mode 3 of a hanging
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
    /// end bends like a cantilever (`tests/spline_rope.rs`: tip deflection within 1% of
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
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for `f`; [`Error::InvalidParameter`] for
    /// a non-finite `s`.
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

    /// The stretch at each span's stretch points: the slope `x'`, `1 / |x'|` (0 where the
    /// curve stops), and the strain `|x'| − 1` projected on the quadratic splines (against
    /// locking); with velocities `v`, its rate `x'·v' / |x'|` projected too (else the rate is
    /// 0). The projected strain at the stretch points is evaluated only where a coefficient
    /// is below 0 (a quadratic spline lies within the hull of its coefficients).
    fn strains(&self, x: &[P; K], v: Option<&[P; K]>) -> Strains<P, K> {
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
    fn strain_points(&self, st: &Strains<P, K>) -> [[P::Scalar; POINTS]; K] {
        st.slack.unwrap_or_else(|| evaluate(&self.proj, &st.strain))
    }

    /// The generalized forces from outside over `m̄`: gravity and a field's accelerations
    /// `acc` through each control point's mass, `(g + a_i)·∫ ρ N_i ds / m̄`, and the
    /// applied forces.
    fn external(&self, acc: &[P; K]) -> [P; K] {
        core::array::from_fn(|i| (self.settings.gravity + acc[i]) * self.load[i] + self.extra[i])
    }

    /// The rope's own generalized forces over `m̄` at strains `st`, stretch, strain damping
    /// and bending, times `per` (1 for the forces, a substep's length for their impulses),
    /// added to `external`; with the tension over `m̄`, times `per`, at each stretch point.
    fn forces(
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
                let g = st.slope[e][q] * -(st.inv[e][q] * tension[e][q]);
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
    fn linearized(
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
    fn stiffness_times(&self, lin: &Linearized<P, K>, u: &[P; K]) -> [P; K] {
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
    fn mass_times(&self, u: &[P; K]) -> [P; K] {
        band_times(&self.mass_band, u)
    }

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
    fn backward_euler(
        &self,
        (x0, v0): (&[P; K], &[P; K]),
        h: P::Scalar,
        external: &[P; K],
        iterations: u8,
    ) -> ([P; K], Option<Ends<P, K>>) {
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
                return (w, None);
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
        (w, Some(Ends { st, potential }))
    }

    /// A backward Euler step from `x0`, `v0` (elastic potential `potential`) to velocities
    /// `w` (strains `st` at `x0 + h·w`), kept from gaining energy: `½vᵀMv + V(x) − fᵀx`
    /// with the forces `f` held, which an exact step on a convex `V` never raises (the
    /// strain's projection makes `V` not quite convex, and the Newton steps may stop short).
    /// If `w` raises it, the velocities are scaled down until it does not; if the positions
    /// alone raise it, the step is halved until they do not ([`HELD_ENERGY_HALVINGS`] at
    /// most, then not taken: the rope stays where it was, still). A strain evaluation a
    /// halving.
    fn held_energy(
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
    fn within_precision(&self, h: P::Scalar) -> bool {
        self.omega * h * self.omega * h * P::Scalar::EPSILON <= P::Scalar::ratio(1, 1024)
    }

    /// Whether BDF2 takes a step of `h`: within the format's precision, `h²·ω² ≤ 2²²` (the
    /// stiffest tested to hold its energy: a 1 m, 1 kg rope of 8 control points at
    /// `EA = 10⁷ N`, `h²·ω² ≈ 3·10⁶`, `tests/spline_rope.rs`), and never in `Q16`, whose one
    /// linearized Newton step lets BDF2 drift from `f64`.
    fn bdf2_holds(&self, h: P::Scalar) -> bool {
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
    fn implicit_step(
        &mut self,
        h: P::Scalar,
        external: &[P; K],
        (iterations, second_order): (u8, bool),
    ) {
        let (x0, v0) = (self.pos, self.free(self.vel));
        let along = |x: &[P; K], v: &[P; K], h: P::Scalar| -> [P; K] {
            core::array::from_fn(|i| x[i] + v[i] * h)
        };
        if P::Scalar::FIXED_POINT {
            // `Q16` cannot resolve the energy: the linearized step as it is.
            let (w, _) = self.backward_euler((&x0, &v0), h, external, iterations);
            return self.take_implicit((&along(&x0, &w, h), &w), (x0, v0, h), P::Scalar::ZERO);
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
            let (w, end) = self.backward_euler((&xs, &self.free(vs)), step, external, iterations);
            if let Some(Ends { st, .. }) = end {
                let x = along(&xs, &w, step);
                let potential = self.elastic_potential(&self.strains(&x0, None));
                // BDF2's energy may rise in a step (a percent or so of the motion's), but
                // not past where the last backward Euler step left it: a step that would is
                // taken as backward Euler's, held.
                let gained = self.gained((&x0, &v0, potential), (&x, &w, &st), external);
                if gained <= headroom {
                    return self.take_implicit((&x, &w), (x0, v0, h), headroom - gained);
                }
            }
        }
        let (w, end) = self.backward_euler((&x0, &v0), h, external, iterations);
        let (x, w) = match end {
            Some(Ends { st, potential }) => {
                self.held_energy((&x0, &v0, potential), (&w, &st), h, external)
            }
            None => (along(&x0, &w, h), w),
        };
        self.take_implicit((&x, &w), (x0, v0, h), P::Scalar::ZERO);
    }

    /// What a step from `x0`, `v0` (elastic potential `potential`) to `x`, `w` (strains
    /// `st`) added to `½vᵀMv + V(x) − fᵀx` with the forces `f` held (over `m̄`).
    fn gained(
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
    fn kinetic(&self, v: &[P; K]) -> P::Scalar {
        let mv = self.mass_times(v);
        (0..K).fold(P::Scalar::ZERO, |sum, i| sum + v[i].dot(mv[i])) * P::Scalar::ratio(1, 2)
    }

    /// Ends an implicit step at `x`, `w` (pinned points kept), remembering its start and
    /// the energy's `headroom` for [`Bdf2`].
    fn take_implicit(
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
    fn free(&self, mut u: [P; K]) -> [P; K] {
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
    fn conjugate_gradient(
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

    /// `B·u`: the strain that `u` adds along the directions `dir`, weighted onto the
    /// quadratic splines (`Σ w·N̂_a·(x'/|x'|)·u'` per function `a`).
    fn strain_weights(&self, dir: &[[P; POINTS]; K], u: &[P; K]) -> [P::Scalar; K] {
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
    fn strain_pull(&self, dir: &[[P; POINTS]; K], c: &[P::Scalar; K]) -> [P; K] {
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

    /// The taut stretch and its damping, `(h²·EA + h·c)·ds·Bᵀ G⁻¹ B` (`G` the quadratic
    /// splines' Gram matrix), beside the banded `M'` (factor `banded`), solved by Woodbury:
    /// `(M' + Bᵀ D⁻¹ B)⁻¹ = M'⁻¹ − M'⁻¹Bᵀ (D + B M'⁻¹ Bᵀ)⁻¹ B M'⁻¹`, `D = G / ((h²·EA + h·c)·ds)`.
    /// `K` banded solves and a dense `K × K` factor; `None` when that is not positive
    /// definite (rounding), and `M'` alone preconditions.
    fn stretch_solve(
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
    fn preconditioner(
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
    fn precondition(&self, pre: &Preconditioner<P, K>, r: &[P; K]) -> [P; K] {
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

    /// The stretch and bending energy at strains `st`, over `m̄`.
    fn elastic_potential(&self, st: &Strains<P, K>) -> P::Scalar {
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
    fn bending_times(&self, u: &[P; K]) -> [P; K] {
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

    /// Advances by `dt` seconds with the [`SplineStepper`]: symplectic Euler in substeps
    /// from [`stiffness_bound`](Self::stiffness_bound) (see
    /// [`MassSpring::step`](crate::MassSpring::step) for the plan, the cap and the errors),
    /// or one backward Euler step (in `Q16` more past `h·(ω + γ) = 8`, see
    /// [`SplineStepper`]). Applied forces are used up. In `Q16`, a generalized force over
    /// the mass unit `m̄` (see the [module](self)) past the format's range on a control
    /// point is clamped and reported in [`StepInfo::saturated`]: from gravity and a field's
    /// accelerations (gravity alone never, below `|g| = 32 767`) and from the applied
    /// forces (a force `f` at a point adds up to `|f| / m̄`); explicitly, also a substep's
    /// stretch and bending impulse or velocity change over `m̄`.
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

    fn step_resolving<F: ForceField<P>>(
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
            // The curve's points move as weighted means of the control points.
            c.rate(fastest + self.settings.gravity.length() * dt, false)
        });
        // `Q16`'s one linearized Newton step keeps its precision while the rate times the
        // step is at most 8 (see `within_precision`): past it, substeps (never slow motion).
        let floor = match self.settings.integrator.implicit() {
            Some(_) if P::Scalar::FIXED_POINT => floor.max(rate * P::Scalar::ratio(1, 8)),
            _ => floor,
        };
        let (n, h, slow) = plan(dt, rate, self.per_rate, floor)?;
        let saturated = self.substeps(n, h, forces, contacts)?;
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
    fn substeps<F: ForceField<P>>(
        &mut self,
        n: u16,
        h: P::Scalar,
        field: &mut F,
        contacts: Option<&Contacts<'_, P>>,
    ) -> Result<bool, Error> {
        let saved = (self.pos, self.vel, self.time, self.history);
        let drag = self.settings.damping;
        let mut saturated = false;
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
                self.implicit_step(h, &external, implicit);
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
                contacts.resolve_spans(pos, vel, &self.inv_load, (h, lag), &mut curve);
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
            Ok(saturated)
        } else {
            (self.pos, self.vel, self.time, self.history) = saved;
            Err(Error::Diverged)
        }
    }

    /// Draws the curve into `out` with the format's [`DefaultSampler`] (mul-free dyadic
    /// halving in `Q16`), span by span from their Bézier extraction: `(K-3)·s + 1` points,
    /// `s` points a span from `out`'s length (see [`Sampler::sample_joined`]); returns the
    /// count. The first and last points are the end control points.
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] when `out` holds fewer than `K - 2` points.
    pub fn sample(&self, out: &mut [P]) -> Result<usize, Error> {
        let spans = Spans::new(&self.ext, &self.pos);
        DefaultSampler.sample_joined(&spans.spans[..K - 3], out)
    }
}

/// The tension at stretch `l = |x'|`: `EA·(l - 1)` when taut; 0 when slack, below
/// `1 - SLACK`; in between a cubic `EA·δ·x²(x - 1)`, `x = (l - 1 + δ) / δ`, so that the force
/// has no kink (a kinked force lets symplectic Euler gain energy each time a span goes slack
/// and taut again). Its slope stays within `[-EA/3, EA]` and `|T| / l` within `EA`, so the
/// substep bound holds in every shape.
#[inline]
fn stretch_tension<S: Scalar>(ea: S, l: S) -> S {
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
fn slack_step<S: Scalar>(l: S) -> S {
    const { assert!(SLACK.1.is_multiple_of(SLACK.0) && SLACK.1 / SLACK.0 < 1 << 14) };
    (l - S::ONE) * S::from_i16((SLACK.1 / SLACK.0) as i16) + S::ONE
}

/// The slope of [`stretch_tension`] by `l`, negative slopes (the slack step's first part)
/// as 0: within `[0, EA]`.
fn stretch_slope<S: Scalar>(ea: S, l: S) -> S {
    let one = S::ONE;
    if l >= one {
        return ea;
    }
    let x = slack_step(l);
    (ea * x * (S::from_i16(3) * x - S::from_i16(2))).max(S::ZERO)
}

/// The stretch energy per unit length whose derivative is [`stretch_tension`]: 0 at the
/// rest length, `EA·SLACK²/12` when slack.
fn stretch_energy<S: Scalar>(ea: S, l: S) -> S {
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

/// A spline rope's curve as Bézier spans (its Bézier extraction), as contacts test it.
struct Spans<'a, P: Point, const K: usize> {
    ext: &'a [[[P::Scalar; 4]; 4]; K],
    /// Span `e` in `spans[e]` for `e < K - 3` (the rest unused).
    spans: [Bezier<P, 4>; K],
}

impl<'a, P: Point, const K: usize> Spans<'a, P, K> {
    fn new(ext: &'a [[[P::Scalar; 4]; 4]; K], pos: &[P; K]) -> Self {
        let mut spans = Spans {
            ext,
            spans: [Bezier::new_unchecked([P::default(); 4]); K],
        };
        spans.redraw(pos);
        spans
    }

    /// The spans' Bézier points. Span `e`'s inner two lie on the leg from `p_(e+1)` to
    /// `p_(e+2)` (at the extraction's weights: 4 products a span), and, the spans being of
    /// one length, a span ends halfway between its last inner point and the next span's
    /// first (the curve's ends are its end control points). A span starts where the last
    /// ends, exactly, in every format.
    fn redraw(&mut self, pos: &[P; K]) {
        let inner = |e: usize| {
            let leg = pos[e + 2] - pos[e + 1];
            let ext = &self.ext[e];
            (pos[e + 1] + leg * ext[1][2], pos[e + 1] + leg * ext[2][2])
        };
        let (mut start, mut here) = (pos[0], inner(0));
        for e in 0..K - 3 {
            let (next, end) = if e + 1 < K - 3 {
                let next = inner(e + 1);
                (next, here.1.midpoint(next.0))
            } else {
                (here, pos[K - 1])
            };
            self.spans[e] = Bezier::new_unchecked([start, here.0, here.1, end]);
            (start, here) = (end, next);
        }
    }
}

impl<P: Point, const K: usize> DrawnSpans<P, K> for Spans<'_, P, K> {
    fn span_count(&self) -> usize {
        K - 3
    }
    fn span_bounds(&self, span: usize) -> Aabb<P> {
        self.spans[span].bounding_box()
    }
    fn deepest(&self, span: usize, key: impl Fn(P) -> P::Scalar) -> P::Scalar {
        self.spans[span].deepest(key)
    }
    fn point(&self, span: usize, t: P::Scalar) -> P {
        self.spans[span].eval(t)
    }
    /// The Bernstein weights at `t` through the span's extraction.
    fn weights(&self, span: usize, t: P::Scalar, weights: &mut [P::Scalar; K]) {
        let mut bernstein = [P::Scalar::ZERO; 4];
        bernstein_weights(t, &mut bernstein);
        *weights = [P::Scalar::ZERO; K];
        for (r, &b) in bernstein.iter().enumerate() {
            for k in 0..4 {
                weights[span + k] += b * self.ext[span][r][k];
            }
        }
    }
    fn rebuild(&mut self, pos: &[P; K]) -> bool {
        self.redraw(pos);
        true
    }
}

/// The stretch at a rope's stretch points: see [`SplineRope::strains`].
struct Strains<P: Point, const K: usize> {
    /// The control points they were taken at.
    pos: [P; K],
    slope: [[P; POINTS]; K],
    inv: [[P::Scalar; POINTS]; K],
    /// The strain `|x'| − 1` and its rate, projected: the coefficients of their quadratic
    /// splines (entry `K − 1` is 0).
    strain: [P::Scalar; K],
    rate: [P::Scalar; K],
    /// The projected strain at the stretch points where it is below 0 at one of them (a
    /// span slack); `None` while every span is taut.
    slack: Option<[[P::Scalar; POINTS]; K]>,
}

/// The tension over the mass unit at a rope's stretch points and whether every span is taut.
struct Tensions<S, const K: usize> {
    tension: [[S; POINTS]; K],
    taut: bool,
}

/// The implicit step's preconditioner: see [`SplineRope::preconditioner`].
struct Preconditioner<P: Point, const K: usize> {
    /// The factor of `M·(1 + drag) + h²·EI·B` as [`ldl`] gives it.
    banded: [[P::Scalar; 4]; K],
    stretch: Option<StretchSolve<P, K>>,
}

/// The implicit step's preconditioner for the stretch: see [`SplineRope::stretch_solve`].
struct StretchSolve<P: Point, const K: usize> {
    /// The rope's directions at the stretch points it was built at.
    dir: [[P; POINTS]; K],
    /// `M'⁻¹ Bᵀ e_a`, one column a quadratic spline.
    columns: [[P; K]; K],
    /// The Cholesky factor of `D + B M'⁻¹ Bᵀ` ([`dense_cholesky`]).
    factor: [[P::Scalar; K]; K],
}

/// What the energy guard needs of a backward Euler step: the strains at its end and the
/// elastic potential at its start.
struct Ends<P: Point, const K: usize> {
    st: Strains<P, K>,
    potential: P::Scalar,
}

/// The last implicit step of a [`SplineRope`], for [`Bdf2`].
#[derive(Clone, Copy, Debug)]
struct History<P: Point, const K: usize> {
    /// Its start's positions and velocities, and its length.
    start: [P; K],
    velocities: [P; K],
    h: P::Scalar,
    /// How far its end's energy is below where the last backward Euler step left it (over
    /// `m̄`): what a BDF2 step may still gain (see `SplineRope::implicit_step`).
    headroom: P::Scalar,
}

/// A backward Euler step's stiffness at a rope's stretch points: see
/// [`SplineRope::linearized`].
struct Linearized<P: Point, const K: usize> {
    dir: [[P; POINTS]; K],
    axial: [[P::Scalar; POINTS]; K],
    transverse: [[P::Scalar; POINTS]; K],
    /// Every `axial` is `h²·EA`: the projected strain needs no second projection.
    uniform: bool,
    /// Whether the stretch's stiffness is in (else `dir`, `axial` and `transverse` are unused).
    stiffness: bool,
    /// `h` where the bending's `h²·EI·B` is in, else 0.
    bend: P::Scalar,
    /// `h·c`, the strain damping's share.
    damping: P::Scalar,
    /// The directions the strain damping acts along: `dir`, or those it was frozen at.
    damp_dir: [[P; POINTS]; K],
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
///   second at 60 Hz. Range (`tests/spline_rope.rs`): `f64` to `EA·h²/(ρ·ds²) ≈ 7·10⁵`
///   (`ds` a span, `ρ` the mass per length; a 10 m steel cable at 60 Hz is about 2·10³);
///   `f32` to `7·10⁴`; `Q16` for ropes in pixels (a 70 px rope ends 0.02 px from `f64`
///   after 2 s). On a soft rope it costs several explicit frames
///   (`cargo bench --bench physics -- spline_rope`); the explicit cost grows with `√EA`,
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
const NEWTON: usize = 4;

/// Where the implicit stepper's iterations stop: when the Newton decrement (what a full
/// step promises the potential), or the conjugate gradient's `r·M⁻¹r`, has fallen to `2⁻²⁰`
/// of its first value in the step, or to the format's epsilon if that is larger.
fn converged<S: Scalar>() -> S {
    S::ratio(1, 1 << 20).max(S::EPSILON)
}

/// Most halvings of a Newton step (to `2⁻³¹` of it) before the implicit stepper keeps what
/// it has.
const LINE_SEARCH: usize = 32;

/// Halvings of an implicit step whose positions gained energy, to `2⁻⁷` of it, before it
/// is not taken at all (see `SplineRope::held_energy`).
const HELD_ENERGY_HALVINGS: usize = 7;

/// Below `1 - SLACK` of its rest length a span of rope is slack: `(1, 10)`.
const SLACK: (u32, u32) = (1, 10);

/// The Greville abscissa of control point `i` in span units times the span (`0..=K-3`):
/// where a straight line puts its control point.
fn greville(i: usize, k: usize) -> f64 {
    let knot = |j: usize| (j.saturating_sub(3) as f64).min((k - 3) as f64);
    (knot(i + 1) + knot(i + 2) + knot(i + 3)) / 3.0
}

/// The clamped uniform cubic basis at `u ∈ [0, K-3]` (in spans): the four non-zero values
/// (control points `span..span+4`) and their derivatives by `u`.
fn basis(u: f64, k: usize) -> ([f64; 4], [f64; 4]) {
    let u = u.clamp(0.0, (k - 3) as f64);
    let (n, dn, _) = basis_in((u as usize).min(k - 4), u, k);
    (n, dn)
}

/// [`basis`] on span `span` (`u` may be its right end), with the clamped quadratic basis on
/// the same breaks (`K - 1` functions; the span's are `span..span+3`).
fn basis_in(span: usize, u: f64, k: usize) -> ([f64; 4], [f64; 4], [f64; 3]) {
    let spans = k - 3;
    // Knot j of the clamped vector 0,0,0,0,1,..,spans-1,spans,spans,spans,spans.
    let t = |j: isize| (j - 3).clamp(0, spans as isize) as f64;
    let i = span as isize + 3;
    let mut n = [0.0f64; 4];
    n[0] = 1.0;
    let (mut left, mut right) = ([0.0f64; 4], [0.0f64; 4]);
    let mut n2 = [0.0f64; 3];
    for j in 1..=3usize {
        left[j] = u - t(i + 1 - j as isize);
        right[j] = t(i + j as isize) - u;
        let mut saved = 0.0;
        for r in 0..j {
            let den = right[r + 1] + left[j - r];
            let temp = if den != 0.0 { n[r] / den } else { 0.0 };
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
        if j == 2 {
            n2 = [n[0], n[1], n[2]];
        }
    }
    // N'_(i-3+a),3 = 3·(N_(i-3+a),2 / (t_(i+a) - t_(i-3+a)) - N_(i-2+a),2 / (t_(i+1+a) - t_(i-2+a))).
    let deg2 = |a: isize| -> f64 {
        // N_(i-2+a'),2 is n2[a'] for a' in 0..3, zero outside.
        if (0..3).contains(&a) {
            n2[a as usize]
        } else {
            0.0
        }
    };
    let mut dn = [0.0; 4];
    for (a, d) in dn.iter_mut().enumerate() {
        let a = a as isize;
        let first = i - 3 + a;
        let den1 = t(first + 3) - t(first);
        let den2 = t(first + 4) - t(first + 1);
        let x1 = if den1 > 0.0 { deg2(a - 1) / den1 } else { 0.0 };
        let x2 = if den2 > 0.0 { deg2(a) / den2 } else { 0.0 };
        *d = 3.0 * (x1 - x2);
    }
    (n, dn, n2)
}

/// An `f64` that multiplies by a format's numbers read in `f64`: the substep bound's
/// arithmetic on the tables the steps use, without an `f64` copy of them.
#[derive(Clone, Copy, Default, PartialEq)]
struct Wide(f64);

impl<S: Scalar> Mul<S> for Wide {
    type Output = Wide;
    fn mul(self, s: S) -> Wide {
        Wide(self.0 * s.to_f64())
    }
}

impl Sub for Wide {
    type Output = Wide;
    fn sub(self, other: Wide) -> Wide {
        Wide(self.0 - other.0)
    }
}

impl core::ops::AddAssign for Wide {
    fn add_assign(&mut self, other: Wide) {
        self.0 += other.0;
    }
}

/// The control points' differences `x_(i+1) − x_i` (the last entry 0): the cubic's slope
/// is a quadratic spline on them (see [`slope_at`]).
fn differences<T, const K: usize>(x: &[T; K]) -> [T; K]
where
    T: Copy + Default + Sub<Output = T>,
{
    core::array::from_fn(|i| {
        if i + 1 < K {
            x[i + 1] - x[i]
        } else {
            T::default()
        }
    })
}

/// The slope `x'` at a stretch point of span `e` with slope weights `d`, from the
/// [`differences`] `dx`: `Σ_a d_a·dx_(e+a)` (3 products where the 4 basis slopes would
/// take 4).
#[inline]
fn slope_at<T, S: Copy, const K: usize>(d: &[S; 3], dx: &[T; K], e: usize) -> T
where
    T: Copy + Default + core::ops::AddAssign + Mul<S, Output = T>,
{
    let mut out = T::default();
    for (a, &da) in d.iter().enumerate() {
        out += dx[e + a] * da;
    }
    out
}

/// Adds to `pull` what `g` at a stretch point of span `e` does to the [`differences`]
/// through the weights `d` (the transpose of [`slope_at`]; a tension's pull takes the
/// point's pull weights); [`spread`] takes them to the control points.
#[inline]
fn add_pull<T, S: Copy, const K: usize>(pull: &mut [T; K], d: &[S; 3], e: usize, g: T)
where
    T: Copy + core::ops::AddAssign + Mul<S, Output = T>,
{
    for (a, &da) in d.iter().enumerate() {
        pull[e + a] += g * da;
    }
}

/// Adds to `out` the generalized forces of `pull`, forces on the [`differences`]:
/// `out_i += pull_(i−1) − pull_i` (the transpose of [`differences`]).
fn spread<T, const K: usize>(out: &mut [T; K], pull: &[T; K])
where
    T: Copy + core::ops::AddAssign + core::ops::SubAssign,
{
    for i in 0..K - 1 {
        out[i] -= pull[i];
        out[i + 1] += pull[i];
    }
}

/// The least-squares fit of `field` (values at the stretch points) among the quadratic
/// splines on the rope's breaks (tables from [`SplineRope::new`]): their `K − 1`
/// coefficients (entry `K − 1` is 0). With `sparse`, the field's zeros are skipped: worth a
/// test per value where most are 0.
fn fit<T, S: Copy, const K: usize>(
    proj: &[[[S; 3]; POINTS]; K],
    weights: &[S; POINTS],
    gram: &[[S; 3]; K],
    field: &[[T; POINTS]; K],
    sparse: bool,
) -> [T; K]
where
    T: Copy + Default + PartialEq + core::ops::AddAssign + Sub<Output = T> + Mul<S, Output = T>,
{
    let mut c = [T::default(); K];
    for e in 0..K - 3 {
        for q in 0..POINTS {
            if sparse && field[e][q] == T::default() {
                continue;
            }
            let weighted = field[e][q] * weights[q];
            for a in 0..3 {
                c[e + a] += weighted * proj[e][q][a];
            }
        }
    }
    solve(gram, &mut c);
    c
}

/// The values at the stretch points of the quadratic spline of coefficients `c`.
fn evaluate<T, S: Copy, const K: usize>(
    proj: &[[[S; 3]; POINTS]; K],
    c: &[T; K],
) -> [[T; POINTS]; K]
where
    T: Copy + Default + core::ops::AddAssign + Mul<S, Output = T>,
{
    let mut field = [[T::default(); POINTS]; K];
    for e in 0..K - 3 {
        for q in 0..POINTS {
            for a in 0..3 {
                field[e][q] += c[e + a] * proj[e][q][a];
            }
        }
    }
    field
}

/// Replaces `field` (values at the stretch points) by its least-squares fit among the
/// quadratic splines ([`fit`], then [`evaluate`]).
fn project<T, S: Copy, const K: usize>(
    proj: &[[[S; 3]; POINTS]; K],
    weights: &[S; POINTS],
    gram: &[[S; 3]; K],
    field: &mut [[T; POINTS]; K],
) where
    T: Copy + Default + PartialEq + core::ops::AddAssign + Sub<Output = T> + Mul<S, Output = T>,
{
    *field = evaluate(proj, &fit(proj, weights, gram, field, false));
}

/// The consistent mass matrix of a rope of density `rho` on spans of `ds`, `∫ ρ N_i N_j ds`
/// in band form (`band[i][d] = M[i][i+d]`), and its row sums `∫ ρ N_i ds` (4-point Gauss per
/// span: exact).
fn mass_matrix<const K: usize>(rho: f64, ds: f64) -> ([[f64; 4]; K], [f64; K]) {
    let (mut band, mut load) = ([[0.0; 4]; K], [0.0; K]);
    for e in 0..K - 3 {
        for &(xi, w) in &GAUSS {
            let (n, _, _) = basis_in(e, e as f64 + (xi + 1.0) / 2.0, K);
            let wds = w * ds / 2.0;
            for a in 0..4 {
                load[e + a] += rho * n[a] * wds;
                for b in a..4 {
                    band[e + a][b - a] += rho * n[a] * n[b] * wds;
                }
            }
        }
    }
    (band, load)
}

/// The Bézier extraction of span `e`: row `r` holds the weights of control points
/// `e..e+4` in the span's Bézier point `r` (from the basis at 4 points of the span and the
/// inverse Bernstein matrix at `t = 0, 1/3, 2/3, 1`).
fn extraction(e: usize, k: usize) -> [[f64; 4]; 4] {
    // Inverse of B[m][r] = C(3,r) t_m^r (1-t_m)^(3-r) at t = 0, 1/3, 2/3, 1.
    const INV: [[f64; 4]; 4] = [
        [1.0, 0.0, 0.0, 0.0],
        [-5.0 / 6.0, 3.0, -3.0 / 2.0, 1.0 / 3.0],
        [1.0 / 3.0, -3.0 / 2.0, 3.0, -5.0 / 6.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let values: [[f64; 4]; 4] =
        core::array::from_fn(|m| basis_in(e, e as f64 + m as f64 / 3.0, k).0);
    core::array::from_fn(|r| {
        core::array::from_fn(|c| (0..4).map(|m| INV[r][m] * values[m][c]).sum())
    })
}

/// `A·u` for a symmetric `band` (`band[i][d] = A[i][i+d]`).
fn band_times<T, S: Copy, const K: usize, const W: usize>(band: &[[S; W]; K], u: &[T; K]) -> [T; K]
where
    T: Copy + Default + core::ops::AddAssign + Mul<S, Output = T>,
{
    let mut out = [T::default(); K];
    for i in 0..K {
        for d in 0..W {
            let j = i + d;
            if j < K {
                let a = band[i][d];
                out[i] += u[j] * a;
                if d > 0 {
                    out[j] += u[i] * a;
                }
            }
        }
    }
    out
}

/// The bending band per unit `EI`: `∫ N_i'' N_j'' ds` (`band[i][d]` for `j = i + d`), from
/// each span's Bézier extraction (`x'' = 6·((1−t)·Δ²b_0 + t·Δ²b_1) / ds²`), by 4-point
/// Gauss (exact: the integrand is quadratic).
fn curvature_band<const K: usize>(ds: f64) -> [[f64; 4]; K] {
    let mut band = [[0.0; 4]; K];
    for e in 0..K - 3 {
        let ext = extraction(e, K);
        let second = |r: usize, k: usize| ext[r][k] - 2.0 * ext[r + 1][k] + ext[r + 2][k];
        for &(xi, w) in &GAUSS {
            let t = (xi + 1.0) / 2.0;
            let n: [f64; 4] = core::array::from_fn(|k| {
                6.0 * ((1.0 - t) * second(0, k) + t * second(1, k)) / (ds * ds)
            });
            for a in 0..4 {
                for b in a..4 {
                    band[e + a][b - a] += n[a] * n[b] * w * ds / 2.0;
                }
            }
        }
    }
    band
}

/// Banded `L D Lᵀ` (square-root-free Cholesky) of a symmetric positive-definite `band` of
/// `W` diagonals (`band[i][d] = A[i][i+d]`): the unit lower factor's `L[i][i-d]` in
/// `out[i][d]`, and `1 / D[i]` from `inverse` in `out[i][0]`; `None` when it is not
/// positive definite (or rounding makes it seem not) or `inverse` finds no `1 / D[i]` in
/// the format.
fn ldl<S, const K: usize, const W: usize>(
    band: &[[S; W]; K],
    inverse: impl Fn(S) -> Option<S>,
) -> Option<[[S; W]; K]>
where
    S: Copy + Default + PartialOrd + Sub<Output = S> + Mul<Output = S>,
{
    let zero = S::default();
    let mut l = [[zero; W]; K];
    // `L[i][j]·D[j]` for the row being factored, by `d = i − j`.
    let mut scaled = [zero; W];
    for i in 0..K {
        for d in (1..W).rev() {
            if d > i {
                continue;
            }
            let j = i - d;
            // `A[i][j] − Σ over m < j of L[i][m]·D[m]·L[j][m]`, within the band.
            let mut sum = band[j][d];
            for k in 1..W - d {
                if k <= j {
                    sum = sum - scaled[d + k] * l[j][k];
                }
            }
            scaled[d] = sum;
            l[i][d] = sum * l[j][0];
        }
        let mut pivot = band[i][0];
        for d in 1..W {
            if d <= i {
                pivot = pivot - scaled[d] * l[i][d];
            }
        }
        if pivot.partial_cmp(&zero) != Some(core::cmp::Ordering::Greater) {
            return None;
        }
        l[i][0] = inverse(pivot)?;
    }
    Some(l)
}

/// Cholesky of a dense symmetric matrix in place: `L` in the lower triangle, its diagonal
/// inverted; `false` when a pivot is not positive (not positive definite, or rounding).
fn dense_cholesky<S: Scalar, const K: usize>(a: &mut [[S; K]; K]) -> bool {
    for j in 0..K {
        let mut d = a[j][j];
        for k in 0..j {
            d -= a[j][k] * a[j][k];
        }
        if d.partial_cmp(&S::ZERO) != Some(core::cmp::Ordering::Greater) || !d.is_finite() {
            return false;
        }
        let inv = S::ONE / d.sqrt();
        a[j][j] = inv;
        for i in j + 1..K {
            let mut v = a[i][j];
            for k in 0..j {
                v -= a[i][k] * a[j][k];
            }
            a[i][j] = v * inv;
        }
    }
    true
}

/// Solves `L Lᵀ x = b` in place, `L` from [`dense_cholesky`].
fn dense_solve<S: Scalar, const K: usize>(l: &[[S; K]; K], b: &mut [S; K]) {
    for i in 0..K {
        let mut v = b[i];
        for k in 0..i {
            v -= l[i][k] * b[k];
        }
        b[i] = v * l[i][i];
    }
    for i in (0..K).rev() {
        let mut v = b[i];
        for k in i + 1..K {
            v -= l[k][i] * b[k];
        }
        b[i] = v * l[i][i];
    }
}

/// `1 / x` where it is finite (the construction's `f64`, which need not be a [`Scalar`]:
/// a `Q16`-only build has no float math).
fn finite_inverse(x: f64) -> Option<f64> {
    Some(1.0 / x).filter(|i| i.is_finite())
}

/// Solves `L D Lᵀ x = b` in place, the factor from [`ldl`] in the format: `(2W − 1)·K`
/// multiplies.
fn solve<T, S, const K: usize, const W: usize>(l: &[[S; W]; K], b: &mut [T; K])
where
    T: Copy + Sub<Output = T> + Mul<S, Output = T>,
    S: Copy,
{
    for i in 0..K {
        let mut s = b[i];
        for d in 1..W {
            if d <= i {
                s = s - b[i - d] * l[i][d];
            }
        }
        b[i] = s;
    }
    for i in (0..K).rev() {
        let mut s = b[i] * l[i][0];
        for d in 1..W {
            if i + d < K {
                s = s - b[i + d] * l[i + d][d];
            }
        }
        b[i] = s;
    }
}

/// The largest eigenvalue of `M⁻¹ K` on the free control points (`K` by its action
/// `stiffness`, `M` by its band `mass` and factor `chol`, pinned rows the identity's): the
/// largest Ritz value of at most `K` Lanczos steps in the `M` inner product, found by
/// bisection on the tridiagonal's Sturm counts. Exact in `K` steps but for rounding, and
/// never above the true value; `O(K)` memory, `K` stiffness products.
fn largest_eigenvalue<const K: usize>(
    stiffness: impl Fn(&[f64; K]) -> [f64; K],
    mass: &[[f64; 4]; K],
    chol: &[[f64; 4]; K],
    pinned: &[bool; K],
) -> f64 {
    let free = |mut x: [f64; K]| {
        for (xi, &p) in x.iter_mut().zip(pinned) {
            if p {
                *xi = 0.0;
            }
        }
        x
    };
    let dot = |a: &[f64; K], b: &[f64; K]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let m_norm = |x: &[f64; K]| crate::geometry::catenary::sqrt(dot(x, &band_times(mass, x)));
    // Alternating signs lean on the highest mode; the ramp breaks the rope's symmetries.
    let mut q = free(core::array::from_fn(|i| {
        let ramp = 1.0 + i as f64 / K as f64;
        if i % 2 == 0 { ramp } else { -ramp }
    }));
    let norm = m_norm(&q);
    if norm.is_nan() || norm <= 0.0 {
        return 0.0;
    }
    q = q.map(|v| v / norm);
    let (mut alpha, mut beta) = ([0.0; K], [0.0; K]);
    let mut previous = [0.0; K];
    let mut steps = 0;
    for j in 0..K {
        let r = free(stiffness(&q));
        alpha[j] = dot(&q, &r);
        steps = j + 1;
        let mut w = r;
        solve(chol, &mut w);
        let w = free(core::array::from_fn(|i| {
            w[i] - alpha[j] * q[i]
                - if j > 0 {
                    beta[j - 1] * previous[i]
                } else {
                    0.0
                }
        }));
        let b = m_norm(&w);
        // A Krylov space closed (or rounding's floor): the Ritz values are exact.
        if b.is_nan() || b <= 1e-12 * alpha[j].abs() {
            break;
        }
        beta[j] = b;
        previous = q;
        q = w.map(|v| v / b);
    }
    // Past `f64` (an `EA` near its range): no bound, which the caller reports as too stiff.
    if alpha[..steps]
        .iter()
        .chain(&beta[..steps])
        .any(|v| !v.is_finite())
    {
        return f64::INFINITY;
    }
    // Bisection between the largest diagonal and Gershgorin's bound of the tridiagonal.
    let (mut low, mut high) = (f64::MIN, 0.0f64);
    for j in 0..steps {
        let side =
            if j > 0 { beta[j - 1] } else { 0.0 } + if j + 1 < steps { beta[j] } else { 0.0 };
        low = low.max(alpha[j]);
        high = high.max(alpha[j] + side);
    }
    // How many eigenvalues of the tridiagonal lie above `x` (its `LDLᵀ - x` pivots).
    let above = |x: f64| {
        let (mut d, mut count) = (1.0f64, 0);
        for j in 0..steps {
            let coupling = if j > 0 {
                beta[j - 1] * beta[j - 1] / d
            } else {
                0.0
            };
            d = alpha[j] - x - coupling;
            if d == 0.0 {
                d = f64::EPSILON * (x.abs() + 1.0);
            }
            if d > 0.0 {
                count += 1;
            }
        }
        count
    };
    for _ in 0..64 {
        let mid = 0.5 * (low + high);
        if mid <= low || mid >= high || mid.is_nan() {
            break;
        }
        if above(mid) > 0 {
            low = mid;
        } else {
            high = mid;
        }
    }
    high.max(0.0)
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;

    #[test]
    fn the_banded_factor_solves_its_matrix() {
        // The mass band of 8 control points (7 diagonals), its first row and column made
        // the identity's as a pin does, and a band of 5 diagonals.
        let (mass, _) = mass_matrix::<8>(1.3, 0.7);
        let mut pinned = mass;
        pinned[0] = [1.0, 0.0, 0.0, 0.0];
        for band in [mass, pinned] {
            let l = ldl(&band, finite_inverse).unwrap();
            let x: [f64; 8] = core::array::from_fn(|i| (i as f64 * 1.7).sin() - 0.3);
            let mut b = band_times(&band, &x);
            solve(&l, &mut b);
            for (got, want) in b.iter().zip(&x) {
                assert!((got - want).abs() < 1e-12, "{got} against {want}");
            }
        }
        let narrow: [[f64; 3]; 6] = core::array::from_fn(|i| [4.0 + i as f64, -1.0, 0.5]);
        let l = ldl(&narrow, finite_inverse).unwrap();
        let x = [1.0, -2.0, 0.5, 3.0, -1.0, 2.0];
        let mut b = band_times(&narrow, &x);
        solve(&l, &mut b);
        for (got, want) in b.iter().zip(&x) {
            assert!((got - want).abs() < 1e-12, "{got} against {want}");
        }
        // Not positive definite: no factor.
        let indefinite: [[f64; 3]; 3] = [[1.0, 2.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        assert!(ldl(&indefinite, finite_inverse).is_none());
    }

    #[test]
    fn the_basis_is_a_partition_of_unity_with_matching_slopes() {
        for k in [4usize, 5, 8, 12] {
            for step in 0..=40 {
                let u = step as f64 / 40.0 * (k - 3) as f64;
                let (n, dn) = basis(u, k);
                assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{k} {u}");
                assert!(dn.iter().sum::<f64>().abs() < 1e-12, "{k} {u}");
                // Slopes against a difference quotient.
                let h = 1e-6;
                if u > h && u + h < (k - 3) as f64 && (u.fract() > 1e-3 && u.fract() < 1.0 - 1e-3) {
                    let (np, _) = basis(u + h, k);
                    let (nm, _) = basis(u - h, k);
                    for a in 0..4 {
                        assert!(
                            ((np[a] - nm[a]) / (2.0 * h) - dn[a]).abs() < 1e-5,
                            "{k} {u} {a}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn extraction_reproduces_the_curve() {
        for e in 0..5 {
            let ext = extraction(e, 8);
            let cps: [f64; 8] = core::array::from_fn(|i| (i as f64 * 1.7).sin());
            let bez: [f64; 4] =
                core::array::from_fn(|r| (0..4).map(|c| ext[r][c] * cps[e + c]).sum());
            for m in 0..=10 {
                let t = m as f64 / 10.0;
                let (n, _, _) = basis_in(e, e as f64 + t, 8);
                let exact: f64 = (0..4).map(|a| n[a] * cps[e + a]).sum();
                let b = (1.0 - t).powi(3) * bez[0]
                    + 3.0 * t * (1.0 - t).powi(2) * bez[1]
                    + 3.0 * t * t * (1.0 - t) * bez[2]
                    + t.powi(3) * bez[3];
                assert!((b - exact).abs() < 1e-12, "span {e} t {t}");
            }
        }
    }

    /// The drawn spans (inner points on a leg, ends halfway) are the extraction's.
    #[test]
    fn the_drawn_spans_are_the_extraction() {
        fn check<const K: usize>() {
            let ext: [[[f64; 4]; 4]; K] = core::array::from_fn(|e| {
                if e + 3 < K {
                    extraction(e, K)
                } else {
                    [[0.0; 4]; 4]
                }
            });
            let pos: [crate::Vec2<f64>; K] = core::array::from_fn(|i| {
                crate::Vec2::new((i as f64 * 1.7).sin(), (i as f64 * 0.9).cos())
            });
            let spans = Spans::new(&ext, &pos);
            for e in 0..K - 3 {
                for r in 0..4 {
                    let mut b = crate::Vec2::default();
                    for k in 0..4 {
                        b += pos[e + k] * ext[e][r][k];
                    }
                    let drawn = spans.spans[e].points()[r];
                    assert!(drawn.distance(b) < 1e-12, "K {K} span {e} point {r}");
                }
            }
        }
        check::<4>();
        check::<5>();
        check::<6>();
        check::<8>();
        check::<11>();
    }

    /// An undamped 1 m, 1 kg rope of 8 control points, `EA = 2000`, under `gravity`.
    /// The implicit step's stiffness product is symmetric and positive semi-definite, and
    /// where every tension pulls (stretched 7%) it is the forces' derivative; where some
    /// spans are slack (compressed to 93%), it drops what would make it indefinite.
    #[test]
    fn the_stiffness_product_is_the_force_derivative() {
        use crate::Vec2;
        for stretch in [1.07, 0.93] {
            let mut r = rope(Vec2::new(0.3, -9.81));
            r.set_bending(0.3).unwrap();
            for i in 0..8 {
                let p = r.pos[i];
                r.pos[i] = Vec2::new(
                    p.x * stretch + 0.01 * (i as f64 * 1.3).sin(),
                    0.03 * (i as f64 * 0.7).cos(),
                );
            }
            let st = r.strains(&r.pos, None);
            let (_, t) = r.forces(&st, &r.external(&Default::default()), 1.0);
            let mut lin = r.linearized(&st, &t, 1.0, true);
            lin.damping = 0.0;
            let u: [Vec2<f64>; 8] =
                core::array::from_fn(|i| Vec2::new((i as f64).sin(), (i as f64 * 2.1).cos()));
            let ku = r.stiffness_times(&lin, &u);
            let eps = 1e-7;
            let at = |sign: f64| {
                let x: [Vec2<f64>; 8] = core::array::from_fn(|i| r.pos[i] + u[i] * (sign * eps));
                r.forces(&r.strains(&x, None), &r.external(&Default::default()), 1.0)
                    .0
            };
            let (plus, minus) = (at(1.0), at(-1.0));
            let w: [Vec2<f64>; 8] =
                core::array::from_fn(|i| Vec2::new((i as f64 * 0.3).cos(), (i as f64).sin()));
            let kw = r.stiffness_times(&lin, &w);
            let dot = |a: &[Vec2<f64>; 8], b: &[Vec2<f64>; 8]| -> f64 {
                a.iter().zip(b).map(|(x, y)| x.dot(*y)).sum()
            };
            let (uku, wkw, ukw, wku) = (dot(&u, &ku), dot(&w, &kw), dot(&u, &kw), dot(&w, &ku));
            assert!(uku >= 0.0 && wkw >= 0.0, "{stretch}: {uku} {wkw}");
            assert!(
                (ukw - wku).abs() < 1e-9 * (uku + wkw),
                "{stretch}: {ukw} {wku}"
            );
            if stretch < 1.0 {
                // Slack: the dropped terms make it differ from the derivative.
                continue;
            }
            for i in 0..8 {
                let fd = (plus[i] - minus[i]) * (-0.5 / eps);
                let scale = 1.0 + fd.length();
                assert!(
                    (ku[i] - fd).length() < 1e-6 * scale,
                    "{i}: {:?} {:?}",
                    ku[i],
                    fd
                );
            }
        }
    }

    /// On a taut rope that bends, the preconditioner inverts the system but for its
    /// sideways stiffness: with that left out, `P⁻¹·A·u = u`.
    #[test]
    fn the_stretch_preconditioner_solves_the_taut_stretch() {
        use crate::Vec2;
        let mut r = rope(Vec2::new(0.3, -9.81));
        for i in 0..8 {
            let p = r.pos[i];
            r.pos[i] = Vec2::new(
                p.x * 1.03 + 0.01 * (i as f64 * 1.3).sin(),
                0.2 * (i as f64 * 0.7).cos(),
            );
        }
        let st = r.strains(&r.pos, None);
        let (_, t) = r.forces(&st, &r.external(&Default::default()), 1.0);
        for h in [1e-3, 1.0 / 60.0, 1.0] {
            let mut lin = r.linearized(&st, &t, h, true);
            assert!(lin.uniform);
            lin.transverse = [[0.0; 3]; 8];
            let drag = 0.1;
            let u = r.free(core::array::from_fn(|i| {
                Vec2::new((i as f64).sin(), (i as f64 * 2.1).cos())
            }));
            r.set_bending(0.5).unwrap();
            let (m, k) = (r.mass_times(&u), r.stiffness_times(&lin, &u));
            let au = r.free(core::array::from_fn(|i| m[i] * (1.0 + drag) + k[i]));
            let pre = r.preconditioner(&lin, h, drag);
            assert!(pre.stretch.is_some());
            let back = r.precondition(&pre, &au);
            for i in 0..8 {
                assert!(
                    (back[i] - u[i]).length() < 1e-8,
                    "{h} {i}: {:?} {:?}",
                    back[i],
                    u[i]
                );
            }
        }
    }

    fn rope(gravity: crate::Vec2<f64>) -> SplineRope<crate::Vec2<f64>, 8> {
        let s = Settings {
            gravity,
            ..Settings::default()
        };
        let m = Material {
            stiffness: 2000.0,
            damping: 0.0,
        };
        let (a, b) = (crate::Vec2::new(0.0, 0.0), crate::Vec2::new(1.0, 0.0));
        SplineRope::new(a, b, 1.0, m, s).unwrap()
    }

    /// The forces are minus the gradient of the energy (finite differences).
    #[test]
    fn forces_are_the_energy_gradient() {
        use crate::Vec2;
        let mut r = rope(Vec2::new(0.3, -9.81));
        r.set_bending(0.3).unwrap();
        for i in 0..8 {
            let p = r.pos[i];
            r.pos[i] = Vec2::new(
                p.x * 1.07 + 0.05 * (i as f64 * 1.3).sin(),
                0.2 * (i as f64 * 0.7).cos(),
            );
        }
        let f = r
            .forces(
                &r.strains(&r.pos, Some(&r.vel)),
                &r.external(&Default::default()),
                1.0,
            )
            .0;
        let h = 1e-6;
        for i in 0..8 {
            for axis in 0..2 {
                let mut plus = r.clone();
                let mut minus = r.clone();
                let mut p = plus.pos[i];
                p.set_coord(axis, p.coord(axis) + h);
                plus.pos[i] = p;
                let mut q = minus.pos[i];
                q.set_coord(axis, q.coord(axis) - h);
                minus.pos[i] = q;
                let grad = (plus.energy() - minus.energy()) / (2.0 * h);
                let force = f[i].coord(axis) * r.unit;
                assert!(
                    (force + grad).abs() < 1e-4 * (1.0 + force.abs()),
                    "{i} {axis}: force {force} grad {grad}"
                );
            }
        }
    }

    /// The substep rate is the straight rope's largest frequency: against a dense reference
    /// (finite differences of the forces along the rope, Gaussian elimination on the free
    /// control points' mass, 20 000 power iterations), with pins and bending.
    #[test]
    fn the_rate_is_the_straight_ropes_largest_frequency() {
        fn check<const K: usize>(pins: &[usize], ei: f64) {
            use crate::Vec2;
            let s = Settings::default();
            let m = Material {
                stiffness: 3000.0,
                damping: 0.0,
            };
            let (a, b) = (Vec2::new(0.0, 0.0), Vec2::new(1.5, 0.0));
            let mut r: SplineRope<Vec2<f64>, K> = SplineRope::new(a, b, 0.7, m, s).unwrap();
            for &i in pins {
                r.set_pinned(i, true).unwrap();
            }
            r.set_bending(ei).unwrap();
            let free: heapless::Vec<usize, 64> = (0..K).filter(|&i| !r.pinned[i]).collect();
            let n = free.len();
            let h = 1e-7;
            let force_x = |r: &SplineRope<Vec2<f64>, K>| {
                r.forces(
                    &r.strains(&r.pos, Some(&r.vel)),
                    &r.external(&[Vec2::default(); K]),
                    1.0,
                )
                .0
            };
            let mut stiff = [[0.0; 64]; 64];
            let mut mass = [[0.0; 64]; 64];
            for (col, &j) in free.iter().enumerate() {
                let (mut plus, mut minus) = (r.clone(), r.clone());
                plus.pos[j].x += h;
                minus.pos[j].x -= h;
                let (fp, fm) = (force_x(&plus), force_x(&minus));
                for (row, &i) in free.iter().enumerate() {
                    stiff[row][col] = -(fp[i].x - fm[i].x) / (2.0 * h);
                    let (lo, hi) = (i.min(j), i.max(j));
                    mass[row][col] = if hi - lo < 4 {
                        r.mass_band[lo][hi - lo]
                    } else {
                        0.0
                    };
                }
            }
            // x ← M⁻¹ K x by elimination, 20 000 times.
            let mut x = [0.0; 64];
            for (i, xi) in x.iter_mut().enumerate().take(n) {
                *xi = 1.0 + (i as f64 * 0.37).sin();
            }
            let mut lambda = 0.0;
            for _ in 0..20_000 {
                let mut a = mass;
                let mut y = [0.0; 64];
                for i in 0..n {
                    y[i] = (0..n).map(|j| stiff[i][j] * x[j]).sum();
                }
                for c in 0..n {
                    for i in c + 1..n {
                        let f = a[i][c] / a[c][c];
                        for j in c..n {
                            a[i][j] -= f * a[c][j];
                        }
                        y[i] -= f * y[c];
                    }
                }
                for i in (0..n).rev() {
                    let t: f64 = (i + 1..n).map(|j| a[i][j] * y[j]).sum();
                    y[i] = (y[i] - t) / a[i][i];
                }
                let norm = (0..n).map(|i| y[i] * y[i]).sum::<f64>().sqrt();
                lambda = (0..n).map(|i| y[i] * x[i]).sum::<f64>()
                    / (0..n).map(|i| x[i] * x[i]).sum::<f64>();
                for i in 0..n {
                    x[i] = y[i] / norm;
                }
            }
            let omega = r.stiffness_bound().0;
            let want = lambda.sqrt();
            assert!(
                (omega - want).abs() < 1e-5 * want,
                "K {K} pins {pins:?} EI {ei}: {omega} against {want}"
            );
        }
        check::<4>(&[], 0.0);
        check::<5>(&[4], 0.0);
        check::<8>(&[], 0.0);
        check::<8>(&[3, 7], 2.0);
        check::<8>(&[1], 40.0);
        check::<16>(&[15], 0.0);
        check::<16>(&[8], 0.5);
    }

    #[test]
    /// The largest frequency of the linearised rope, found by power iteration on finite
    /// differences of the forces along a swing, never passes the bound from the straight rope.
    fn the_bound_holds_in_motion() {
        use crate::Vec2;
        let mut r = rope(Vec2::new(0.0, -9.81));
        for frame in 0..200 {
            let _ = r.step(1.0 / 60.0).unwrap();
            if frame % 20 != 19 {
                continue;
            }
            // Power iteration on -M⁻¹ ∂f/∂x by finite differences of the forces.
            let f0 = r
                .forces(
                    &r.strains(&r.pos, None),
                    &r.external(&Default::default()),
                    1.0,
                )
                .0;
            let mut x: [Vec2<f64>; 8] = core::array::from_fn(|i| {
                if i == 0 {
                    Vec2::default()
                } else {
                    Vec2::new(((i * 7) % 3) as f64 - 1.0, ((i * 5) % 4) as f64 - 1.5)
                }
            });
            let mut lambda = 0.0;
            for _ in 0..300 {
                let h = 1e-7;
                let moved: [Vec2<f64>; 8] = core::array::from_fn(|i| r.pos[i] + x[i] * h);
                let f1 = r
                    .forces(
                        &r.strains(&moved, None),
                        &r.external(&Default::default()),
                        1.0,
                    )
                    .0;
                let mut y: [Vec2<f64>; 8] = core::array::from_fn(|i| (f0[i] - f1[i]) * (1.0 / h));
                y[0] = Vec2::default();
                solve(&r.chol, &mut y);
                y[0] = Vec2::default();
                let norm = y.iter().map(|v| v.dot(*v)).sum::<f64>().sqrt();
                let dot: f64 = y.iter().zip(&x).map(|(a, b)| a.dot(*b)).sum();
                let xx: f64 = x.iter().map(|v| v.dot(*v)).sum();
                lambda = dot / xx;
                x = y.map(|v| v * (1.0 / norm));
            }
            assert!(
                lambda.abs().sqrt() <= r.omega * 1.001,
                "frame {frame}: {} > {}",
                lambda.abs().sqrt(),
                r.omega
            );
        }
    }
}
