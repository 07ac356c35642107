//! Time integrators, chosen per system, each with its stability limit and cost.
//!
//! `ω` is the highest angular frequency of the spring network and `h` the substep.
//! [`MassSpring::step`](crate::MassSpring::step) estimates `ω` from the springs and masses
//! (Gershgorin: `ω² ≤ max_i w_i · Σ_{springs at i} k·(1 + [other end free])`, damping
//! added the same way) and splits each frame into enough substeps that `ω·h` stays at 90% of
//! the method's limit.
//!
//! | integrator | `ω·h` limit | force evaluations per substep | energy | notes |
//! |---|---|---|---|---|
//! | [`ExplicitEuler`](Integrator::ExplicitEuler) | none: grows at any `h` without damping | 1 | gains | kept as the textbook reference; substeps keep `ω·h ≤ 0.1` |
//! | [`SymplecticEuler`](Integrator::SymplecticEuler) | 2 | 1 | bounded | the game default: cheapest stable method |
//! | [`Verlet`](Integrator::Verlet) | 2 | 2 | bounded | velocity Verlet, second order |
//! | [`Rk4`](Integrator::Rk4) | 2√2 ≈ 2.83 | 4 | slowly loses | fourth order, the accurate choice |
//! | [`ImplicitEuler`](Integrator::ImplicitEuler) | unconditionally stable | 1 + `iterations` Jacobian products | loses (damps high frequencies) | matrix-free conjugate gradient, no heap |
//! | [`Xpbd`](Integrator::Xpbd) | unconditionally stable | 1 per XPBD substep + one projection per spring | loses a little | springs as compliant distance constraints (Macklin et al. 2016, 2019) |
//!
//! Per spring, a force evaluation costs one square root, one division and about 20
//! multiply-adds; per particle, about 6 operations.

use core::fmt::Debug;

use crate::Scalar;

/// How a system names its integrator: the [`Integrator`] enum, chosen at run time (the
/// default), or one of the zero-sized types of [`only`], chosen at compile time so that the
/// other integrators' code is never linked: what a 16 KiB flash budget needs.
///
/// ```
/// use dunas::{MassSpring, Vec2, integrator::only, shape::Line, spring::{Material, Springs}, system::Settings};
/// let pos = [Vec2::new(0.0f32, 0.0), Vec2::new(1.0, 0.0)];
/// let springs = Springs::<f32, 1>::chain(&pos, Material::new(100.0, 0.1)?)?;
/// let settings = Settings { damping: 0.1, ..Settings::default() }.with_integrator(only::SymplecticEuler);
/// let mut s: MassSpring<_, Line<2>, _, only::SymplecticEuler> = MassSpring::new(pos, [0.0, 1.0], springs, settings)?;
/// s.step(1.0 / 60.0)?;
/// # Ok::<(), dunas::Error>(())
/// ```
pub trait Choice: Copy + Default + Debug + PartialEq {
    /// The integrator to use now.
    fn integrator(&self) -> Integrator;
}

impl Choice for Integrator {
    #[inline]
    fn integrator(&self) -> Integrator {
        *self
    }
}

/// Integrators fixed at compile time (see [`Choice`]).
pub mod only {
    use super::{Choice, Integrator};

    macro_rules! fixed {
        ($(#[$doc:meta])* $name:ident) => {
            $(#[$doc])*
            #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
            pub struct $name;

            impl Choice for $name {
                #[inline(always)]
                fn integrator(&self) -> Integrator {
                    Integrator::$name
                }
            }
        };
    }

    fixed!(
        /// [`Integrator::ExplicitEuler`], and nothing else linked.
        ExplicitEuler
    );
    fixed!(
        /// [`Integrator::SymplecticEuler`], and nothing else linked.
        SymplecticEuler
    );
    fixed!(
        /// [`Integrator::Verlet`], and nothing else linked.
        Verlet
    );
    fixed!(
        /// [`Integrator::Rk4`], and nothing else linked.
        Rk4
    );

    /// [`Integrator::ImplicitEuler`], and nothing else linked.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub struct ImplicitEuler {
        /// Conjugate-gradient iteration budget.
        pub iterations: u8,
    }

    impl Default for ImplicitEuler {
        /// 16 iterations.
        fn default() -> Self {
            ImplicitEuler { iterations: 16 }
        }
    }

    impl Choice for ImplicitEuler {
        #[inline(always)]
        fn integrator(&self) -> Integrator {
            Integrator::ImplicitEuler {
                iterations: self.iterations,
            }
        }
    }

    /// [`Integrator::Xpbd`], and nothing else linked.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub struct Xpbd {
        /// XPBD substeps per step.
        pub substeps: u8,
    }

    impl Default for Xpbd {
        /// 4 substeps.
        fn default() -> Self {
            Xpbd { substeps: 4 }
        }
    }

    impl Choice for Xpbd {
        #[inline(always)]
        fn integrator(&self) -> Integrator {
            Integrator::Xpbd {
                substeps: self.substeps,
            }
        }
    }
}

/// How [`MassSpring`](crate::MassSpring) advances in time. See the [module docs](self).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Integrator {
    /// `x += v·h; v += a·h`. Unstable without damping at any step; a reference, not a choice.
    ExplicitEuler,
    /// `v += a·h; x += v·h` (semi-implicit Euler). Stable while `ω·h < 2`.
    #[default]
    SymplecticEuler,
    /// Velocity Verlet (kick, drift, kick): second order, stable while `ω·h < 2`.
    Verlet,
    /// Classic fourth-order Runge-Kutta: stable while `ω·h < 2√2`.
    Rk4,
    /// Backward Euler linearised once per substep (Baraff–Witkin) and solved by conjugate
    /// gradient with at most `iterations` steps. Stable at any step; damps what it cannot
    /// resolve. Cost per CG iteration: one spring Jacobian product (a square root per spring).
    ImplicitEuler {
        /// Conjugate-gradient iteration budget (8 to 32 is typical).
        iterations: u8,
    },
    /// Extended position-based dynamics: springs become distance constraints with compliance
    /// `1/k`, projected once per XPBD substep ("small steps"). Stable at any step.
    Xpbd {
        /// XPBD substeps per step (4 to 20 is typical); 0 counts as 1.
        substeps: u8,
    },
}

impl Integrator {
    /// The largest stable `ω·h` for an undamped spring, `None` when the method is stable at
    /// any step, `Some(0)` for explicit Euler (unstable at every step).
    pub fn stability_limit<S: Scalar>(&self) -> Option<S> {
        match self {
            Integrator::ExplicitEuler => Some(S::ZERO),
            Integrator::SymplecticEuler | Integrator::Verlet => Some(S::from_i16(2)),
            // 2·sqrt(2), the extent of RK4's stability region along the imaginary axis.
            Integrator::Rk4 => Some(S::ratio(2_828_427, 1_000_000)),
            Integrator::ImplicitEuler { .. } | Integrator::Xpbd { .. } => None,
        }
    }

    /// The `ω·h` the substep count aims for: 90% of the limit; 0.1 for explicit Euler
    /// (which then gains at most 0.5% energy per substep); `None` when any step is stable.
    pub fn target_omega_h<S: Scalar>(&self) -> Option<S> {
        match self.stability_limit::<S>()? {
            l if l > S::ZERO => Some(l * S::ratio(9, 10)),
            _ => Some(S::ratio(1, 10)),
        }
    }

    /// `1 / target_omega_h`: substeps per unit of `ω·dt`, as a constant (no division at run
    /// time). `None` when any step is stable.
    pub fn substeps_per_omega_dt<S: Scalar>(&self) -> Option<S> {
        match self {
            Integrator::ExplicitEuler => Some(S::from_i16(10)),
            // 1 / (0.9 · 2) and 1 / (0.9 · 2√2).
            Integrator::SymplecticEuler | Integrator::Verlet => Some(S::ratio(5, 9)),
            Integrator::Rk4 => Some(S::ratio(392_837, 1_000_000)),
            Integrator::ImplicitEuler { .. } | Integrator::Xpbd { .. } => None,
        }
    }

    /// Force evaluations per substep.
    pub fn force_evaluations(&self) -> u32 {
        match self {
            Integrator::ExplicitEuler
            | Integrator::SymplecticEuler
            | Integrator::ImplicitEuler { .. } => 1,
            Integrator::Verlet => 2,
            Integrator::Rk4 => 4,
            Integrator::Xpbd { substeps } => (*substeps).max(1) as u32,
        }
    }
}
