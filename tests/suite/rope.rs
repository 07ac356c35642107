//! Ropes and cloth end to end: number formats against f64, fixed-point overflow, drawn-length
//! calibration, the thesis's other topologies, and the game-loop clock.
#![cfg(any(feature = "std", feature = "libm"))]

use crate::common;
use dunas::Settings;
use dunas::integrator::{Integrator, Rk4};
use dunas::smooth::Smoothing;
use dunas::spring::{Material, Springs};
use dunas::{Accuracy, Cloth, Error, FixedTimestep, Point, Rope, Scalar, Vec2, Vec3};

/// The catapult rope of the thesis: 8 particles from a pin, a heavy weight at the end, in
/// pixel units (y up), released horizontally.
fn catapult<S: Scalar>(damping: f64) -> Rope<Vec2<S>, 8, 7> {
    let settings = Settings {
        gravity: Vec2::from_f64(0.0, -200.0),
        damping: S::from_f64(damping),
        ..Settings::default()
    };
    let material = Material {
        stiffness: S::from_f64(400.0),
        damping: S::from_f64(2.0),
    };
    let mut rope = Rope::new(
        Vec2::from_f64(0.0, 0.0),
        Vec2::from_f64(70.0, 0.0),
        S::from_f64(7.0),
        material,
        settings,
    )
    .unwrap();
    rope.set_inv_mass(7, S::from_f64(0.25)).unwrap(); // the penguin
    rope
}

fn max_distance<S: Scalar, T: Scalar>(a: &[Vec2<S>], b: &[Vec2<T>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p.x.to_f64() - q.x.to_f64()).hypot(p.y.to_f64() - q.y.to_f64()))
        .fold(0.0, f64::max)
}

fn run<S: Scalar>(rope: &mut Rope<Vec2<S>, 8, 7>, steps: usize) {
    for _ in 0..steps {
        let _ = rope.step(S::from_f64(1.0 / 60.0)).unwrap();
    }
}

#[test]
fn f32_follows_f64_while_swinging_and_at_rest() {
    let (mut a, mut b) = (catapult::<f64>(0.0), catapult::<f32>(0.0));
    run(&mut a, 60);
    run(&mut b, 60);
    let swing = max_distance(a.positions(), b.positions());
    let (mut a, mut b) = (catapult::<f64>(4.0), catapult::<f32>(4.0));
    run(&mut a, 600);
    run(&mut b, 600);
    let rest = max_distance(a.positions(), b.positions());
    eprintln!("f32 vs f64: {swing:.2e} px after 1 s of swing, {rest:.2e} px at rest");
    assert!(swing < 0.01 && rest < 0.01, "{swing} {rest}");
}

#[cfg(feature = "fixed")]
mod q16 {
    use super::*;
    use dunas::Q16;

    #[test]
    fn q16_rope_runs_end_to_end_and_tracks_f64() {
        let (mut a, mut b) = (catapult::<f64>(0.0), catapult::<Q16>(0.0));
        run(&mut a, 60);
        run(&mut b, 60);
        let swing = max_distance(a.positions(), b.positions());
        let (mut a, mut b) = (catapult::<f64>(4.0), catapult::<Q16>(4.0));
        run(&mut a, 600);
        run(&mut b, 600);
        let rest = max_distance(a.positions(), b.positions());
        eprintln!("Q16 vs f64: {swing:.2e} px after 1 s of swing, {rest:.2e} px at rest");
        assert!(swing < 0.5 && rest < 0.1, "{swing} {rest}");
        let mut out = [Vec2::<Q16>::default(); 33];
        assert_eq!(b.sample(Smoothing::Bezier, &mut out), Ok(33));
        assert_eq!(out[0], b.positions()[0]);
    }

    /// Backward Euler in `Q16` tracks `f64` (30 particles, springs of 3000, released level,
    /// the end thrown up at 400 px/s after a second): within 2 px every frame. Its conjugate
    /// gradient's inner products, squares of momenta, saturated the format and the rope
    /// grew to 340 px, 700 px with the throw.
    #[test]
    fn q16_implicit_rope_tracks_f64_through_a_throw() {
        use dunas::integrator::ImplicitEuler;
        fn rope<S: Scalar>() -> Rope<Vec2<S>, 30, 30, ImplicitEuler> {
            let settings = Settings {
                gravity: Vec2::from_f64(0.0, -200.0),
                damping: S::from_f64(0.1),
                ..Settings::default()
            }
            .with_integrator(ImplicitEuler::default());
            let material = Material {
                stiffness: S::from_f64(3000.0),
                damping: S::from_f64(5.0),
            };
            let (start, end) = (Vec2::from_f64(0.0, 0.0), Vec2::from_f64(70.0, 0.0));
            Rope::new(start, end, S::from_f64(7.0), material, settings).unwrap()
        }
        let (mut a, mut b) = (rope::<f64>(), rope::<Q16>());
        let mut worst: f64 = 0.0;
        for frame in 0..120 {
            if frame == 60 {
                a.set_velocity(29, Vec2::from_f64(0.0, 400.0)).unwrap();
                b.set_velocity(29, Vec2::from_f64(0.0, 400.0)).unwrap();
            }
            let _ = a.step(1.0 / 60.0).unwrap();
            let _ = b.step(Q16::from_f64(1.0 / 60.0)).unwrap();
            worst = worst.max(max_distance(a.positions(), b.positions()));
        }
        eprintln!("Q16 vs f64, implicit: {worst:.3} px at worst");
        assert!(worst < 2.0, "{worst}");
    }

    #[test]
    fn q16_rejects_coordinates_beyond_its_safe_range() {
        let m = Material {
            stiffness: Q16::from_f64(10.0),
            damping: Q16::ZERO,
        };
        let far = Rope::<Vec2<Q16>, 4, 3>::new(
            Vec2::from_f64(0.0, 0.0),
            Vec2::from_f64(20_000.0, 0.0),
            Q16::ONE,
            m,
            Settings::default(),
        );
        assert!(matches!(far.err(), Some(Error::OutOfRange { .. })));
        let mut rope = catapult::<Q16>(0.0);
        assert!(matches!(
            rope.set_position(0, Vec2::from_f64(30_000.0, 0.0)),
            Err(Error::OutOfRange { .. })
        ));
    }

    #[test]
    fn q16_overflow_from_huge_stiffness_is_reported_not_wrapped() {
        // k near the top of Q16's range: a stretch of 2 px saturates the force.
        let m = Material {
            stiffness: Q16::from_f64(30_000.0),
            damping: Q16::ZERO,
        };
        let settings = Settings {
            bounds: Q16::from_f64(1000.0),
            ..Settings::default()
        };
        let mut rope = Rope::<Vec2<Q16>, 8, 7>::new(
            Vec2::from_f64(0.0, 0.0),
            Vec2::from_f64(70.0, 0.0),
            Q16::ONE,
            m,
            settings,
        )
        .unwrap();
        rope.set_position(7, Vec2::from_f64(200.0, 50.0)).unwrap(); // a 130 px stretch
        let mut outcomes = (0, 0);
        for _ in 0..120 {
            let before = rope.clone();
            match rope.step(Q16::from_f64(1.0 / 60.0)) {
                Ok(info) => outcomes.0 += info.saturated as usize,
                Err(e) => {
                    assert_eq!(e, Error::Diverged);
                    assert_eq!(rope.positions(), before.positions(), "state kept");
                    outcomes.1 += 1;
                }
            }
            for p in rope.positions() {
                assert!(
                    p.is_finite()
                        && p.x.abs() <= Q16::from_f64(1000.0)
                        && p.y.abs() <= Q16::from_f64(1000.0)
                );
            }
        }
        // A blow that would take the velocity past the safe range is refused up front...
        let v7 = rope.velocities()[7];
        let blow = rope.apply_impulse(7, Vec2::from_f64(16_000.0, 0.0));
        assert!(
            matches!(
                blow,
                Err(Error::NonFinite { .. } | Error::OutOfRange { .. })
            ),
            "{blow:?}"
        );
        assert_eq!(rope.velocities()[7], v7);
        // ...and the whole rope, let go and thrown out of bounds, is refused, the state kept
        // (a particle thrown alone is slowed by the saturated steps its spring pulls in).
        rope.set_inv_mass(0, Q16::from_f64(14.0)).unwrap();
        for i in 0..8 {
            rope.set_velocity(i, Vec2::from_f64(16_000.0, 0.0)).unwrap();
        }
        let diverged = (0..20).any(|_| {
            let before = rope.clone();
            let r = rope.step(Q16::from_f64(1.0 / 60.0));
            if let Err(e) = r {
                assert_eq!(e, Error::Diverged);
                assert_eq!(rope.positions(), before.positions());
            }
            r.is_err()
        });
        assert!(diverged);
        eprintln!(
            "huge stiffness in Q16: {} steps saturated, {} refused as divergent",
            outcomes.0, outcomes.1
        );
        assert!(outcomes.0 > 0, "the clamped forces are reported");
    }

    #[test]
    fn q16_coincident_particles_give_no_force_and_no_garbage() {
        let mut rope = catapult::<Q16>(0.0);
        let p2 = rope.positions()[2];
        rope.set_position(3, p2).unwrap();
        rope.set_position(4, p2).unwrap();
        run(&mut rope, 30);
        assert!(rope.positions().iter().all(|p| p.in_safe_range()));
    }
}

/// A rope pinned at both ends, sagging: the drawn curve is shorter than the spring polygon.
fn sagging(smoothing: Smoothing) -> (Rope<Vec2<f64>, 8, 7, Rk4>, f64) {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping: 4.0,
        ..Settings::default()
    }
    .with_integrator(Rk4);
    let mut rope = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(7.0, 0.0),
        1.0,
        Material {
            stiffness: 2000.0,
            damping: 1.0,
        },
        settings,
    )
    .unwrap();
    rope.set_inv_mass(7, 0.0).unwrap();
    rope.set_position(7, Vec2::new(5.0, 0.0)).unwrap();
    for _ in 0..300 {
        let _ = rope.step(1.0 / 60.0).unwrap();
    }
    let before = rope.drawn_length(smoothing, 1e-6).unwrap();
    (rope, before)
}

#[test]
fn calibration_makes_the_drawn_curve_the_intended_length() {
    for smoothing in [Smoothing::Bezier, Smoothing::BSpline, Smoothing::CatmullRom] {
        let (mut rope, before) = sagging(smoothing);
        let target = 7.0;
        let residual = rope
            .calibrate_length(smoothing, target, 1.0 / 60.0, 200)
            .unwrap();
        let after = rope.drawn_length(smoothing, 1e-6).unwrap();
        eprintln!(
            "{smoothing:?}: drawn {before:.4} before, {after:.4} after calibration (residual {residual:.1e})"
        );
        assert!(
            (before - target).abs() / target > 5.0 * residual,
            "calibration had work to do"
        );
        assert!(residual < 1e-2 && ((after - target) / target).abs() < 1e-2);
    }
    let (mut rope, _) = sagging(Smoothing::Bezier);
    assert!(matches!(
        rope.calibrate_length(Smoothing::Bezier, -1.0, 0.1, 1),
        Err(Error::InvalidParameter { .. })
    ));
}

#[test]
fn hub_and_loop_ropes_simulate() {
    let pos: [Vec2<f64>; 8] = core::array::from_fn(|i| Vec2::new(i as f64, 0.0));
    let mut inv = [1.0; 8];
    inv[0] = 0.0;
    let material = Material {
        stiffness: 300.0,
        damping: 1.0,
    };
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping: 0.5,
        ..Settings::default()
    };
    // Merlin's rope: the hub springs hold every particle at its distance from the holder.
    let hub = Springs::<f64, 13>::hub(&pos, material).unwrap();
    let mut merlin = Rope::from_parts(pos, inv, hub, settings).unwrap();
    let chain = Springs::<f64, 13>::chain(&pos, material).unwrap();
    let mut plain = Rope::from_parts(pos, inv, chain, settings).unwrap();
    for _ in 0..240 {
        let _ = merlin.step(1.0 / 60.0).unwrap();
        let _ = plain.step(1.0 / 60.0).unwrap();
    }
    let reach = |r: &Rope<Vec2<f64>, 8, 13>| r.positions()[7].length();
    assert!(
        reach(&merlin) > 6.5 && reach(&plain) > 6.5,
        "both hang near full length"
    );
    // The hub makes it stiffer against bending: its middle sags less, and its end stays at
    // its hub spring's rest length (7) but for the stretch under a particle's weight.
    assert!(merlin.positions()[4].y > plain.positions()[4].y);
    assert!((reach(&merlin) - 7.0).abs() < 0.1, "{}", reach(&merlin));

    let ring: [Vec2<f64>; 8] = core::array::from_fn(|i| {
        let a = i as f64 * std::f64::consts::TAU / 8.0;
        Vec2::new(a.cos(), a.sin())
    });
    let springs = Springs::<f64, 16>::surface_line(&ring, 2, material).unwrap();
    let mut looped = Springs::<f64, 16>::closed_loop(&ring, material).unwrap();
    looped.connect(&ring, 0, 4).unwrap();
    assert_eq!(springs.as_slice().len(), 13);
    let mut ring_rope = Rope::from_parts(ring, [1.0; 8], looped, Settings::default()).unwrap();
    ring_rope.apply_impulse(2, Vec2::new(0.5, 0.0)).unwrap();
    for _ in 0..120 {
        let _ = ring_rope.step(1.0 / 60.0).unwrap();
    }
    let mut out = [Vec2::default(); 40]; // 7 spans of 5 segments: 36 points
    assert_eq!(ring_rope.sample(Smoothing::CatmullRom, &mut out), Ok(36));
    // A free ring of 8 unit masses: the impulse moves its centre at 0.5/8 per second and
    // spins nothing out of it; springs are internal forces.
    let momentum = ring_rope
        .velocities()
        .iter()
        .fold(Vec2::default(), |m, &v| m + v);
    assert!(
        (momentum - Vec2::new(0.5, 0.0)).length() < 1e-9,
        "{momentum:?}"
    );
    let centre = ring_rope
        .positions()
        .iter()
        .fold(Vec2::default(), |c, &p| c + p * 0.125);
    let expected = Vec2::new(0.5 / 8.0 * ring_rope.time(), 0.0);
    assert!((centre - expected).length() < 1e-9, "{centre:?}");
}

#[test]
fn cloth_hangs_in_the_wind_and_samples_smoothly() {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.3,
        ..Settings::default()
    };
    let m = Material {
        stiffness: 500.0,
        damping: 0.5,
    };
    let mut sail: Cloth<Vec3<f32>, 8, 8> = Cloth::rectangle(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, -2.0, 0.0),
        1.0,
        [m, m, m],
        settings,
    )
    .unwrap();
    sail.pin_row(0).unwrap();
    let mut wind = dunas::force::Wind::still(0.05f32);
    wind.velocity = Vec3::new(0.0, 0.0, 3.0);
    for _ in 0..300 {
        let _ = sail.step_with(1.0 / 60.0, &mut wind).unwrap();
    }
    // The free edge blows downwind; the pinned edge stays.
    assert!(sail.positions()[63].z > 0.2);
    assert_eq!(sail.positions()[0], Vec3::new(0.0, 0.0, 0.0));
    let mut pos = [Vec3::default(); 256];
    let mut nor = [Vec3::default(); 256];
    assert_eq!(sail.sample_patch(16, 16, &mut pos, &mut nor), Ok(256));
    for n in &nor {
        assert!((n.length() - 1.0).abs() < 1e-4);
    }
    // The drawn surface meets the particles at the corners.
    assert_eq!(pos[0], sail.positions()[0]);
    assert_eq!(pos[255], sail.positions()[63]);
    assert_eq!(
        sail.pin_row(8),
        Err(Error::IndexOutOfRange { index: 8, len: 8 })
    );
}

#[test]
fn fixed_timestep_clamps_hitches_and_ignores_bad_frames() {
    // Steps of 1/64 s keep the sums exact in binary.
    let mut clock = FixedTimestep::new(1.0 / 64.0, 5.0 / 64.0).unwrap();
    assert_eq!(clock.advance(2.5 / 64.0), 2);
    assert_eq!(clock.alpha(), 0.5);
    assert_eq!(clock.advance(0.5 / 64.0), 1);
    assert_eq!(clock.advance(1.0), 5); // a 1 s hitch runs at most 5 steps
    for bad in [f64::NAN, -1.0, f64::INFINITY, 0.0] {
        assert_eq!(clock.advance(bad), 0);
    }
    assert!(matches!(
        FixedTimestep::new(0.0f64, 1.0),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        FixedTimestep::new(0.1f64, 0.05),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        FixedTimestep::new(0.1f64, f64::NAN),
        Err(Error::InvalidParameter { .. })
    ));
    // A step so small against the longest frame that `acc - step` would round to `acc`:
    // refused, instead of a frame that never ends.
    assert!(matches!(
        FixedTimestep::new(1e-10f32, 1.0),
        Err(Error::InvalidParameter { .. })
    ));
    let mut fine = FixedTimestep::new(1.0f32 / 4096.0, 1.0).unwrap();
    assert_eq!(fine.advance(1.0), 4096);
}

#[test]
fn state_sizes_meet_the_budgets() {
    use core::mem::size_of;
    let rope = size_of::<Rope<Vec2<f32>, 8>>();
    let cloth = size_of::<Cloth<Vec3<f32>, 8, 8>>();
    eprintln!("Rope<Vec2<f32>, 8>: {rope} B, Cloth<Vec3<f32>, 8, 8>: {cloth} B");
    // The documented size, 20·N + 16·CAP + 80 bytes.
    assert!(rope <= 20 * 8 + 16 * 8 + 80, "{rope}");
    assert!(cloth <= 4096, "{cloth}");
}

/// A released, undamped 8-particle rope (70 units, 7 mass units, stiff springs): the
/// largest swing of its total energy over 3 s, relative to the energy its fall releases
/// (`m·g·L/2`), for an integrator at an accuracy.
fn energy_swing<I: Integrator>(integrator: I, accuracy: Accuracy) -> (f64, u16) {
    let mut rope = common::released_rope(integrator, accuracy);
    let e0 = rope.energy();
    let scale = common::RELEASED_ROPE_FALL_ENERGY;
    let (mut swing, mut substeps) = (0.0f64, 0);
    for _ in 0..180 {
        substeps = rope.step(1.0 / 60.0).unwrap().substeps;
        swing = swing.max((rope.energy() - e0).abs() / scale);
    }
    (swing, substeps)
}

/// The figures `Accuracy`'s docs quote, held as upper bounds with a margin for rounding.
#[test]
fn accuracy_levels_bound_the_energy_swing() {
    use dunas::integrator::{SymplecticEuler, Verlet};
    let levels = [
        (Accuracy::Fast, 0.025, 0.005),
        (Accuracy::Balanced, 0.01, 0.0012),
        (Accuracy::Fine, 0.002, 0.0001),
    ];
    for (accuracy, euler_bound, verlet_bound) in levels {
        let (euler, n_euler) = energy_swing(SymplecticEuler, accuracy);
        let (verlet, n_verlet) = energy_swing(Verlet, accuracy);
        eprintln!(
            "{accuracy:?}: symplectic Euler {euler:.4} ({n_euler} substeps), Verlet {verlet:.4} ({n_verlet} substeps)"
        );
        assert!(euler <= euler_bound, "{accuracy:?}: {euler}");
        assert!(verlet <= verlet_bound, "{accuracy:?}: {verlet}");
    }
}

/// The released rope of [`energy_swing`] over 10 s from three starts that put energy in
/// every mode (from rest, where the swing feeds the stiff modes over time; alternating
/// velocities, the stiffest mode; scattered velocities): the largest swing of its total
/// energy, relative to the energy of its motion (what its fall releases plus its starting
/// kinetic energy).
fn worst_energy_swing<I: Integrator + Copy>(integrator: I, accuracy: Accuracy) -> f64 {
    let mut worst = 0.0f64;
    for start in 0..3 {
        let mut rope = common::released_rope(integrator, accuracy);
        let mut kinetic = 0.0;
        for i in 1..8 {
            let speed = match start {
                0 => 0.0,
                1 => 30.0 * if i % 2 == 0 { 1.0 } else { -1.0 },
                _ => 30.0 * ((i * 7919 % 13) as f64 / 6.0 - 1.0),
            };
            let v = Vec2::new(0.3 * speed, speed);
            rope.set_velocity(i, v).unwrap();
            kinetic += 0.5 * v.dot(v) / rope.inv_masses()[i];
        }
        let (e0, scale) = (rope.energy(), common::RELEASED_ROPE_FALL_ENERGY + kinetic);
        for _ in 0..600 {
            let _ = rope.step(1.0 / 60.0).unwrap();
            worst = worst.max((rope.energy() - e0).abs() / scale);
        }
    }
    worst
}

/// The worst-case figures `Accuracy`'s docs state, over starts that excite every mode.
#[test]
fn accuracy_levels_bound_the_energy_swing_from_any_start() {
    use dunas::integrator::{SymplecticEuler, Verlet};
    let levels = [
        (Accuracy::Fast, 0.65, 0.16),
        (Accuracy::Balanced, 0.15, 0.035),
        (Accuracy::Fine, 0.04, 0.0025),
    ];
    for (accuracy, euler_bound, verlet_bound) in levels {
        let euler = worst_energy_swing(SymplecticEuler, accuracy);
        let verlet = worst_energy_swing(Verlet, accuracy);
        eprintln!("{accuracy:?}, any start: symplectic Euler {euler:.4}, Verlet {verlet:.4}");
        assert!(euler <= euler_bound, "{accuracy:?}: {euler}");
        assert!(verlet <= verlet_bound, "{accuracy:?}: {verlet}");
    }
}

/// A rope at rest looks at rest: an `f32` rope of 30 particles (1 m, 1 kg, EA 1000 N,
/// damping 2/s) settled for 10 s then watched for 2 s. What remains is rounding noise in
/// its stiffest mode: speeds of a few 1e-4 m/s whose amplitude, `v/ω` with `ω` in the
/// thousands of rad/s, is below a micrometre. The bounds are the ones `Rope`'s docs state.
#[test]
fn a_resting_f32_rope_stays_still() {
    let mut rope = common::settled_hanging_rope::<f32, _>(dunas::integrator::SymplecticEuler);
    let start = rope.positions().to_vec();
    let (mut speed, mut drift) = (0.0f32, 0.0f32);
    for _ in 0..120 {
        let _ = rope.step(1.0 / 60.0).unwrap();
        for (p, q) in rope.positions().iter().zip(&start) {
            drift = drift.max(p.distance(*q));
        }
        for v in rope.velocities() {
            speed = speed.max(v.length());
        }
    }
    eprintln!("at rest: speed up to {speed:.1e} m/s, drift up to {drift:.1e} m over 2 s");
    assert!(drift <= 2e-6, "{drift}");
    assert!(speed <= 1e-3, "{speed}");
}

/// `Rope::new` lumps the mass: inner particles `m/(N-1)`, ends half that, summing to `m`.
#[test]
fn rope_masses_add_up_to_the_mass_asked_for() {
    let rope: Rope<Vec2<f64>, 8> = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(7.0, 0.0),
        3.5,
        Material {
            stiffness: 100.0,
            damping: 0.0,
        },
        Settings::default(),
    )
    .unwrap();
    let w = rope.inv_masses();
    assert_eq!(w[0], 0.0, "the first particle is pinned");
    let free: f64 = w[1..].iter().map(|w| 1.0 / w).sum();
    // The pinned end's half share (3.5 / 7 / 2) is carried by the hand.
    assert!((free + 3.5 / 14.0 - 3.5).abs() < 1e-12, "{free}");
    assert!((1.0 / w[7] - 0.25).abs() < 1e-12 && (1.0 / w[3] - 0.5).abs() < 1e-12);
}

/// `Rope::hanging` starts on the catenary of the asked length: ends where asked, the right
/// length, and the sag of the closed-form catenary; stepping it keeps it there to within
/// the springs' stretch under the rope's weight.
#[test]
fn a_hanging_rope_starts_and_stays_on_its_catenary() {
    let (span, length, mass, k) = (10.0f64, 12.0, 1.0, 20_000.0);
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping: 2.0,
        ..Settings::default()
    };
    let material = Material {
        stiffness: k,
        damping: 1.0,
    };
    let mut rope: Rope<Vec2<f64>, 40> = Rope::hanging(
        Vec2::new(-span / 2.0, 0.0),
        Vec2::new(span / 2.0, 0.0),
        length,
        mass,
        material,
        settings,
    )
    .unwrap();
    let p = rope.positions();
    assert_eq!(p[0], Vec2::new(-span / 2.0, 0.0));
    assert_eq!(p[39], Vec2::new(span / 2.0, 0.0));
    let polygon: f64 = p.windows(2).map(|w| w[0].distance(w[1])).sum();
    assert!((polygon - length).abs() < 0.01 * length, "{polygon}");
    // Closed form: y = a·cosh(x/a) - a·cosh(span/2a), with 2a·sinh(span/2a) = length.
    let (mut lo, mut hi) = (0.1f64, 100.0f64);
    for _ in 0..200 {
        let a = 0.5 * (lo + hi);
        if 2.0 * a * (span / (2.0 * a)).sinh() > length {
            lo = a;
        } else {
            hi = a;
        }
    }
    let a = 0.5 * (lo + hi);
    let sag = a * (span / (2.0 * a)).cosh() - a;
    let lowest = |r: &Rope<Vec2<f64>, 40>| r.positions().iter().map(|q| q.y).fold(0.0, f64::min);
    assert!(
        (lowest(&rope) + sag).abs() < 0.005 * sag,
        "{} vs {sag}",
        lowest(&rope)
    );
    for _ in 0..300 {
        let _ = rope.step(1.0 / 60.0).unwrap();
    }
    // Tension at most m·g·(1 + sag/span)-ish, stretch T/k per spring over 39 springs: under
    // 1% of the sag here.
    assert!(
        (lowest(&rope) + sag).abs() < 0.01 * sag,
        "{} vs {sag}",
        lowest(&rope)
    );
    // Bad input: too short, vertical, no gravity.
    let too_short = Rope::<Vec2<f64>, 8>::hanging(
        Vec2::new(0.0, 0.0),
        Vec2::new(5.0, 0.0),
        4.0,
        mass,
        material,
        settings,
    );
    assert!(matches!(
        too_short.err(),
        Some(Error::InvalidParameter { .. })
    ));
    let vertical = Rope::<Vec2<f64>, 8>::hanging(
        Vec2::new(0.0, 0.0),
        Vec2::new(0.0, -5.0),
        6.0,
        mass,
        material,
        settings,
    );
    assert!(matches!(
        vertical.err(),
        Some(Error::InvalidParameter { .. })
    ));
    let weightless = Rope::<Vec2<f64>, 8>::hanging(
        Vec2::new(0.0, 0.0),
        Vec2::new(5.0, 0.0),
        6.0,
        mass,
        material,
        Settings::default(),
    );
    assert!(matches!(
        weightless.err(),
        Some(Error::InvalidParameter { .. })
    ));
}

/// A particle mass beyond the safe range is refused wherever it comes in (as an inverse
/// mass, a weight hung on, a rope's total), and a refused call changes nothing: a step's
/// impulses, mass times velocity, must fit the format.
#[test]
fn masses_beyond_the_safe_range_are_refused() {
    let settings = Settings::<Vec2<f64>>::default();
    let material = Material {
        stiffness: 100.0,
        damping: 0.0,
    };
    let mut rope: Rope<Vec2<f64>, 8> = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(7.0, 0.0),
        1.0,
        material,
        settings,
    )
    .unwrap();
    let before = rope.inv_masses().to_vec();
    assert!(matches!(
        rope.set_inv_mass(3, 1e-310),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        rope.let_go(3, 1e-310),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        rope.hang(3, f64::MAX),
        Err(Error::InvalidParameter { .. })
    ));
    assert_eq!(rope.inv_masses(), &before[..]);
    assert!(matches!(
        rope.set_inv_mass(3, 1e-151),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(rope.set_inv_mass(3, 1e-149).is_ok() && rope.hang(4, 1e149).is_ok());
    let heavy = Rope::<Vec2<f64>, 8>::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(7.0, 0.0),
        1e200,
        material,
        Settings::default(),
    );
    assert!(matches!(heavy.err(), Some(Error::InvalidParameter { .. })));
    #[cfg(feature = "fixed")]
    {
        use dunas::Q16;
        let q = Q16::from_f64;
        let material = Material {
            stiffness: q(100.0),
            damping: q(0.0),
        };
        let mut rope: Rope<Vec2<Q16>, 8> = Rope::new(
            Vec2::new(q(0.0), q(0.0)),
            Vec2::new(q(7.0), q(0.0)),
            q(1.0),
            material,
            Settings::default(),
        )
        .unwrap();
        assert!(matches!(
            rope.set_inv_mass(3, Q16::from_bits(4)),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(rope.set_inv_mass(3, Q16::from_bits(5)).is_ok());
        assert!(matches!(
            rope.hang(4, q(15_000.0)),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(rope.hang(4, q(14_000.0)).is_ok());
    }
}

/// What `Accuracy`'s docs say of a symplectic method's energy over a long run: its mean
/// over each 100 s wanders as the motion spreads between the modes (the methods keep a
/// nearby "shadow" energy, whose offset from the energy grows with the share in the stiff
/// modes), but stays within the any-start bound of the swing (95% of the motion's energy
/// for symplectic Euler at `Fast`, 81% for Verlet). The released rope, its stiffest mode
/// excited (alternating velocities), 10 minutes at `Fast`.
#[test]
fn a_symplectic_energy_wanders_within_its_bound() {
    use dunas::integrator::{SymplecticEuler, Verlet};
    fn means<I: Integrator + Copy>(integrator: I) -> [f64; 6] {
        let mut rope = common::released_rope(integrator, Accuracy::Fast);
        let mut kinetic = 0.0;
        for i in 1..8 {
            let v = Vec2::new(9.0, 30.0) * if i % 2 == 0 { 1.0 } else { -1.0 };
            rope.set_velocity(i, v).unwrap();
            kinetic += 0.5 * v.dot(v) / rope.inv_masses()[i];
        }
        let (e0, scale) = (rope.energy(), common::RELEASED_ROPE_FALL_ENERGY + kinetic);
        let mut means = [0.0f64; 6];
        for mean in &mut means {
            for _ in 0..6000 {
                let _ = rope.step(1.0 / 60.0).unwrap();
                *mean += (rope.energy() - e0) / scale / 6000.0;
            }
        }
        means
    }
    for (name, means, bound) in [
        ("symplectic Euler", means(SymplecticEuler), 0.95),
        ("Verlet", means(Verlet), 0.81),
    ] {
        eprintln!(
            "{name}: the energy's mean over each 100 s, in % of the motion's energy: {:?}",
            means.map(|m| (m * 1000.0).round() / 10.0)
        );
        assert!(means.iter().all(|m| m.abs() <= bound), "{name}: {means:?}");
    }
}
