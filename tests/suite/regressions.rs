//! One test per bug found by driving the public API from outside: each fails on the code
//! that had the bug.
#![cfg(feature = "std")]

use dunas::integrator::AnyIntegrator;
use dunas::prelude::*;
use dunas::shape::Line;
use dunas::spring::Springs;
use dunas::{FixedTimestep, MassSpring};

fn material() -> Material<f64> {
    Material {
        stiffness: 500.0,
        damping: 0.5,
    }
}

fn hanging_rope(damping: f64) -> Rope<Vec2<f64>, 8> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping,
        ..Settings::default()
    };
    Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(7.0, 0.0),
        1.0,
        material(),
        settings,
    )
    .unwrap()
}

#[test]
fn a_refused_calibration_leaves_the_rope_as_it_was() {
    let mut rope = hanging_rope(1.0);
    for _ in 0..30 {
        let _ = rope.step(1.0 / 60.0).unwrap();
    }
    let before = (
        rope.positions().to_vec(),
        rope.topology().as_slice().to_vec(),
    );
    for target in [
        <f64 as Scalar>::SAFE_RANGE * 2.0,
        -1.0,
        f64::NAN,
        f64::INFINITY,
    ] {
        assert!(
            matches!(
                rope.calibrate_length(Smoothing::BSpline, target, 1.0 / 60.0, 10),
                Err(Error::InvalidParameter { .. })
            ),
            "{target}"
        );
        assert_eq!(rope.positions(), &before.0[..]);
        assert_eq!(rope.topology().as_slice(), &before.1[..]);
    }
    // A target the rope cannot reach without blowing up fails mid-way: still all or nothing.
    let settings = Settings {
        bounds: 20.0,
        ..*rope.settings()
    };
    rope.set_settings(settings).unwrap();
    let far = rope.calibrate_length(Smoothing::BSpline, 5000.0, 1.0 / 60.0, 60);
    assert_eq!(far, Err(Error::Diverged));
    assert_eq!(rope.positions(), &before.0[..]);
    assert_eq!(rope.topology().as_slice(), &before.1[..]);
    // And the rope still steps.
    let _ = rope.step(1.0 / 60.0).unwrap();
}

#[test]
fn damping_is_counted_once_and_never_from_a_stale_cache() {
    let mut rope = hanging_rope(0.0);
    let (omega, spring_gamma) = rope.stiffness_bound();
    let settings = Settings {
        damping: 100.0,
        ..*rope.settings()
    };
    rope.set_settings(settings).unwrap();
    let (omega_damped, gamma) = rope.stiffness_bound();
    assert_eq!(omega_damped, omega);
    assert!((gamma - (spring_gamma + 100.0)).abs() < 1e-9, "{gamma}");
    // Back to no damping: the same plan as a rope that never had any.
    rope.set_settings(Settings {
        damping: 0.0,
        ..settings
    })
    .unwrap();
    let fresh = hanging_rope(0.0);
    for dt in [1.0 / 240.0, 1.0 / 60.0, 0.1] {
        assert_eq!(rope.substeps_for(dt), fresh.substeps_for(dt));
    }
}

#[test]
fn settings_are_checked_on_entry() {
    let good = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping: 0.5,
        ..Settings::default()
    };
    let bad = [
        Settings {
            damping: f64::NAN,
            ..good
        },
        Settings {
            damping: -1.0,
            ..good
        },
        Settings {
            gravity: Vec2::new(f64::NAN, 0.0),
            ..good
        },
        Settings {
            gravity: Vec2::new(0.0, 1e300),
            ..good
        },
        Settings {
            bounds: f64::NAN,
            ..good
        },
        Settings {
            bounds: 0.0,
            ..good
        },
        Settings {
            bounds: f64::MAX,
            ..good
        },
    ];
    let pos = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)];
    let springs = Springs::<f64, 1>::chain(&pos, material()).unwrap();
    let mut system: MassSpring<_, Line<2>, _> =
        MassSpring::new(pos, [0.0, 1.0], springs.clone(), good).unwrap();
    for settings in bad {
        assert!(settings.check().is_err(), "{settings:?}");
        let built = MassSpring::<_, Line<2>, _>::new(pos, [0.0, 1.0], springs.clone(), settings);
        assert!(built.is_err(), "{settings:?}");
        assert!(system.set_settings(settings).is_err(), "{settings:?}");
        assert_eq!(system.settings(), &good, "the old settings stay");
    }
    let _ = system.step(1.0 / 60.0).unwrap();
}

#[test]
fn springs_too_stiff_for_the_format_are_reported_not_frozen() {
    // Q16: the capped substep rounds to zero, a step that would simulate nothing.
    let pos = [Vec2::<Q16>::from_f64(0.0, 0.0), Vec2::from_f64(1.0, 0.0)];
    let stiff = Material {
        stiffness: Q16::from_f64(30_000.0),
        damping: Q16::ZERO,
    };
    let springs = Springs::<Q16, 1>::chain(&pos, stiff).unwrap();
    // A very light particle (inverse mass 30 000): ω ≈ 30 000 rad/s, and at `Fine` the
    // substep planner would need 150 000 substeps a second, past what Q16 can hold.
    let light = Q16::from_f64(30_000.0);
    let fine = Settings {
        accuracy: Accuracy::Fine,
        ..Settings::default()
    };
    let mut system: MassSpring<_, Line<2>, _> =
        MassSpring::new(pos, [Q16::ZERO, light], springs, fine).unwrap();
    system.set_velocity(1, Vec2::from_f64(1.0, 0.0)).unwrap();
    let before = system.positions().to_vec();
    assert_eq!(system.step(Q16::from_f64(1.0 / 60.0)), Err(Error::TooStiff));
    assert_eq!(system.positions(), &before[..]);
    assert_eq!(system.time(), Q16::ZERO);

    // f32: the step still advances, in slow motion, and says so.
    let pos = [Vec2::new(0.0f32, 0.0), Vec2::new(1.0, 0.0)];
    let stiff = Material {
        stiffness: 1e12f32,
        damping: 0.0,
    };
    let springs = Springs::<f32, 1>::chain(&pos, stiff).unwrap();
    let mut system: MassSpring<_, Line<2>, _> =
        MassSpring::new(pos, [0.0, 1.0], springs, Settings::default()).unwrap();
    let info = system.step(1.0 / 60.0).unwrap();
    assert!(info.slow_motion && info.simulated < 1.0 / 60.0, "{info:?}");
    assert!(info.simulated > 0.0);
    let soft = hanging_rope(0.0).clone().step(1.0 / 60.0).unwrap();
    assert!(
        !soft.slow_motion && soft.simulated == 1.0 / 60.0,
        "{soft:?}"
    );
}

/// A hand dragging a `Q16` rope toward the edge of the format: every step that reports no
/// saturation matches an `f64` rope on the same path, and the first one whose forces
/// saturate says so in `StepInfo::saturated` instead of clamping silently.
#[test]
fn q16_saturation_reaches_the_caller() {
    let settings = |g: f64| Settings {
        gravity: Vec2::new(0.0, g),
        damping: 1.0,
        ..Settings::default()
    };
    let m = Material {
        stiffness: 400.0,
        damping: 1.0,
    };
    let mq = Material {
        stiffness: Q16::from_f64(400.0),
        damping: Q16::ONE,
    };
    let mut exact: Rope<Vec2<f64>, 8> = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(70.0, 0.0),
        1.0,
        m,
        settings(-50.0),
    )
    .unwrap();
    let mut fixed: Rope<Vec2<Q16>, 8> = Rope::new(
        Vec2::from_f64(0.0, 0.0),
        Vec2::from_f64(70.0, 0.0),
        Q16::ONE,
        mq,
        Settings {
            gravity: Vec2::from_f64(0.0, -50.0),
            damping: Q16::ONE,
            ..Settings::default()
        },
    )
    .unwrap();
    let mut saturated_at = None;
    for frame in 1..=2000 {
        // The hand accelerates away along x until it reaches the format's edge.
        let x = (frame as f64 * 0.5).powi(2).min(16_000.0);
        exact.set_position(0, Vec2::new(x, 0.0)).unwrap();
        fixed.set_position(0, Vec2::from_f64(x, 0.0)).unwrap();
        let _ = exact.step(1.0 / 60.0).unwrap();
        let info = fixed.step(Q16::from_f64(1.0 / 60.0)).unwrap();
        if info.saturated {
            saturated_at = Some(frame);
            break;
        }
        for (q, f) in fixed.positions().iter().zip(exact.positions()) {
            let (qx, qy) = (q.x.to_f64(), q.y.to_f64());
            let d = ((qx - f.x).powi(2) + (qy - f.y).powi(2)).sqrt();
            assert!(d < 2.0, "frame {frame} (hand at {x}): {d} from f64");
        }
    }
    assert!(saturated_at.is_some(), "the drag reaches the limit of Q16");
}

#[test]
fn a_zero_cloth_edge_names_its_own_spring() {
    let m = Material {
        stiffness: 100.0f32,
        damping: 0.1,
    };
    let (o, x, z) = (
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
    );
    let settings = Settings::default();
    let cloth = |du, dv| Cloth::<Vec3<f32>, 4, 3>::rectangle(o, du, dv, 1.0, [m; 3], settings);
    assert_eq!(
        cloth(Vec3::default(), z).err(),
        Some(Error::ZeroRestLength { a: 0, b: 1 })
    );
    assert_eq!(
        cloth(x, Vec3::default()).err(),
        Some(Error::ZeroRestLength { a: 0, b: 4 })
    );
    // Steps of 0.5 along both edges, parallel: the second diagonal has no length.
    assert_eq!(
        cloth(x * 1.5, x).err(),
        Some(Error::ZeroRestLength { a: 1, b: 4 })
    );
}

#[test]
fn fixed_timestep_never_returns_more_than_its_maximum() {
    for (step, max_frame) in [(0.1f32, 0.25), (1.0 / 60.0, 0.25), (0.3, 0.9), (0.01, 0.1)] {
        let mut clock = FixedTimestep::new(step, max_frame).unwrap();
        let most = (max_frame / step).ceil() as u32;
        assert_eq!(clock.max_steps(), most);
        for k in 0..500 {
            let frame = [max_frame, 10.0, step * 0.999, max_frame * 0.7][k % 4];
            let n = clock.advance(frame);
            assert!(n <= most, "{step} {max_frame}: {n} > {most}");
        }
    }
}

#[test]
fn a_pinned_particle_refuses_a_velocity_and_ignores_an_impulse() {
    let mut rope = hanging_rope(0.0);
    assert_eq!(
        rope.set_velocity(0, Vec2::new(1.0, 0.0)),
        Err(Error::Pinned { index: 0 })
    );
    assert_eq!(rope.apply_impulse(0, Vec2::new(1.0, 0.0)), Ok(()));
    assert_eq!(rope.velocities()[0], Vec2::new(0.0, 0.0));
    assert_eq!(rope.set_velocity(3, Vec2::new(1.0, 0.0)), Ok(()));
}

#[test]
fn any_integrator_runs_every_method() {
    use dunas::integrator::{ImplicitEuler, Xpbd};
    for integrator in [
        AnyIntegrator::ExplicitEuler,
        AnyIntegrator::SymplecticEuler,
        AnyIntegrator::Verlet,
        AnyIntegrator::Rk4,
        AnyIntegrator::ImplicitEuler(ImplicitEuler::default()),
        AnyIntegrator::Xpbd(Xpbd::default()),
    ] {
        let settings = Settings {
            gravity: Vec2::new(0.0, -9.81),
            damping: 1.0,
            ..Settings::default()
        }
        .with_integrator(integrator);
        let mut rope: Rope<Vec2<f64>, 8, 8, AnyIntegrator> = Rope::new(
            Vec2::new(0.0, 0.0),
            Vec2::new(7.0, 0.0),
            1.0,
            material(),
            settings,
        )
        .unwrap();
        for _ in 0..60 {
            let _ = rope.step(1.0 / 60.0).unwrap();
        }
        assert!(rope.positions()[7].y < -1.0, "{integrator:?} fell");
    }
}

/// A rope held by a hand moving in a circle, swinging onto a floor it touches with its drawn
/// B-spline, cut at its middle after 2 s: neither before nor after the cut does any drawn
/// point of any piece go into the floor by more than half the rope's thickness (the
/// contacts used to keep one curve bridging the cut, while the drawn pieces sank through).
fn cut_rope_on_a_floor<S: Scalar>() -> (u32, f64) {
    let v = |x: f64, y: f64| Vec2::new(S::from_f64(x), S::from_f64(y));
    let hand = |t: f64| {
        let a = core::f64::consts::TAU * t / 2.0;
        v(0.4 * a.cos(), 0.5 + 0.4 * a.sin())
    };
    let settings = Settings {
        gravity: v(0.0, -9.81),
        damping: S::from_f64(0.1),
        ..Settings::default()
    };
    let material = Material {
        stiffness: S::from_f64(500.0),
        damping: S::ONE,
    };
    let mut rope: Rope<Vec2<S>, 8> = Rope::new(
        hand(0.0),
        hand(0.0) + v(0.0, -2.3),
        S::from_f64(0.5),
        material,
        settings,
    )
    .unwrap();
    let (floor, thickness) = (-2.0, 0.02);
    let ground = [Collider::half_space(v(0.0, floor), v(0.0, 1.0))
        .unwrap()
        .with_friction(S::from_f64(0.5), S::from_f64(0.4))
        .unwrap()];
    let contacts = Contacts::new(
        &ground,
        S::from_f64(thickness),
        Touch::Drawn(Smoothing::BSpline),
    )
    .unwrap();
    let dt = S::from_f64(1.0 / 60.0);
    let (mut points, mut pieces) = ([v(0.0, 0.0); 64], [dunas::breaking::Piece::EMPTY; 8]);
    let (mut sunk, mut deepest) = (0, 0.0f64);
    for frame in 1..=240 {
        rope.move_pinned(0, hand(frame as f64 / 60.0), dt).unwrap();
        let _ = rope.step_touching(dt, (), &contacts).unwrap();
        let count = rope
            .draw(Smoothing::BSpline, &mut points, &mut pieces)
            .unwrap();
        let drawn = &points[..pieces[count - 1].points.end];
        let lowest = drawn.iter().map(|p| p.y.to_f64()).fold(f64::MAX, f64::min);
        if lowest < floor - thickness / 2.0 {
            sunk += 1;
        }
        deepest = deepest.max(floor - lowest);
        if frame == 120 {
            // A swipe across the middle of the drawn rope.
            let mid = drawn[drawn.len() / 2];
            let cut = rope
                .cut(
                    &points,
                    &pieces[..count],
                    mid + v(-1.0, 0.0),
                    mid + v(1.0, 0.0),
                )
                .unwrap();
            assert!(cut.is_some(), "the swipe cuts the rope");
            assert_eq!(rope.pieces().count(), 2);
        }
    }
    (sunk, deepest)
}

#[test]
fn a_cut_ropes_pieces_stay_on_the_floor() {
    let (sunk, deepest) = cut_rope_on_a_floor::<f32>();
    assert_eq!(sunk, 0, "f32: drawn pieces {deepest} m into the floor");
    let (sunk, deepest) = cut_rope_on_a_floor::<Q16>();
    assert_eq!(sunk, 0, "Q16: drawn pieces {deepest} m into the floor");
}

/// `sample` draws one curve through every particle: on a cut rope it refuses, naming the
/// pieces and pointing at `draw`, instead of bridging the cut.
#[test]
fn sample_refuses_a_cut_rope() {
    let mut rope = hanging_rope(1.0);
    let mut points = [Vec2::default(); 64];
    assert_eq!(rope.sample(Smoothing::BSpline, &mut points), Ok(64));
    let mut pieces = [dunas::breaking::Piece::EMPTY; 8];
    rope.draw(Smoothing::BSpline, &mut points, &mut pieces)
        .unwrap();
    let cut = rope
        .cut(
            &points,
            &pieces[..1],
            Vec2::new(3.2, 1.0),
            Vec2::new(3.2, -1.0),
        )
        .unwrap();
    assert_eq!(cut, Some(3));
    let before = points;
    assert_eq!(
        rope.sample(Smoothing::BSpline, &mut points),
        Err(Error::Cut { pieces: 2 })
    );
    assert_eq!(points, before, "a refused call writes nothing");
    assert!(Error::Cut { pieces: 2 }.to_string().contains("draw"));
    // The drawn length is the pieces' lengths added, without the gap between them.
    let whole = 7.0;
    let length = rope.drawn_length(Smoothing::Polyline, 1e-6).unwrap();
    assert!((length - 6.0).abs() < 1e-9, "{length} of {whole}");
}

/// `SailWind` reads the sail's layout from the system it blows on: the total force on a flat
/// 8×8 sail square to the wind is the closed form `½ρC · w² · area` (it used to take the
/// column count as a type parameter, and a wrong one ran silently on the wrong facets).
#[test]
fn sail_wind_fits_the_sail_it_blows_on() {
    use dunas::force::{SailWind, Wind};
    let settings = Settings {
        gravity: Vec3::new(0.0, 0.0, 0.0),
        damping: 0.0,
        ..Settings::default()
    };
    let m = Material {
        stiffness: 2000.0,
        damping: 1.0,
    };
    // 3 m by 4 m in the x-y plane, the wind along z at 8 m/s, ½ρC = 0.7.
    let mut sail: Cloth<Vec3<f64>, 8, 8> = Cloth::rectangle(
        Vec3::new(0.0, 4.0, 0.0),
        Vec3::new(3.0, 0.0, 0.0),
        Vec3::new(0.0, -4.0, 0.0),
        2.0,
        [m, m, m],
        settings,
    )
    .unwrap();
    let mut air = Wind::still(0.0);
    air.velocity = Vec3::new(0.0, 0.0, 8.0);
    let mut wind = SailWind::new(air, 0.7).unwrap();
    let dt = 1e-4;
    let _ = sail.step_with(dt, &mut wind).unwrap();
    let momentum: f64 = sail
        .velocities()
        .iter()
        .zip(sail.inv_masses())
        .map(|(v, w)| v.z / w)
        .sum();
    let expected = 0.7 * 64.0 * 12.0;
    assert!(
        (momentum / dt / expected - 1.0).abs() < 1e-3,
        "{} N against {expected} N",
        momentum / dt
    );
}

/// A `Q16` rope held far past what its springs can pull (their forces saturate) comes back
/// once the hand does: within 40 s every particle is within 2 px of a rope that only ever
/// hung there (it used to swing thousands of pixels out for good, gaining energy from its
/// clamped forces).
#[test]
fn a_q16_rope_yanked_past_the_format_comes_back() {
    let q = Q16::from_f64;
    let rope = || -> Rope<Vec2<Q16>, 10> {
        let settings = Settings {
            gravity: Vec2::new(q(0.0), q(-150.0)),
            damping: q(0.3),
            ..Settings::default()
        };
        let material = Material {
            stiffness: q(300.0),
            damping: Q16::ONE,
        };
        let (start, end) = (Vec2::new(q(0.0), q(0.0)), Vec2::new(q(90.0), q(0.0)));
        Rope::new(start, end, q(2.0), material, settings).unwrap()
    };
    let dt = Q16::ratio(1, 60);
    let origin = Vec2::new(q(0.0), q(0.0));
    let mut hung = rope();
    for _ in 0..2400 {
        let _ = hung.step(dt).unwrap();
    }
    for far in [1500.0, 3000.0] {
        let mut yanked = rope();
        let mut saturated = 0;
        for _ in 0..600 {
            yanked.set_position(0, Vec2::new(q(far), q(-far))).unwrap();
            saturated += u32::from(yanked.step(dt).unwrap().saturated);
        }
        assert!(saturated > 0, "the hand at {far} px saturates the springs");
        for _ in 0..2400 {
            yanked.set_position(0, origin).unwrap();
            let _ = yanked.step(dt).unwrap();
        }
        for (p, r) in yanked.positions().iter().zip(hung.positions()) {
            let off = (*p - *r).length().to_f64();
            assert!(off < 2.0, "held at {far} px: {off} px from the rest shape");
        }
    }
}

/// Every error a first program met says which value and which limit (they all used to read
/// "parameter is zero, negative or not finite", whatever the cause).
#[test]
fn errors_name_the_value_and_the_limit() {
    let text = |e: Error| e.to_string();
    let steps = FixedTimestep::new(1.0f32 / 60.0, 100.0).unwrap_err();
    assert!(text(steps).contains("max_frame") && text(steps).contains("4 096"));
    let far = Rope::<Vec2<Q16>, 8>::new(
        Vec2::from_f64(0.0, 0.0),
        Vec2::from_f64(20_000.0, 0.0),
        Q16::ONE,
        Material {
            stiffness: Q16::ONE,
            damping: Q16::ZERO,
        },
        Settings::default(),
    )
    .unwrap_err();
    let far = text(far);
    assert!(
        far.contains("16383") && far.contains("smaller units"),
        "{far}"
    );
    let same = hanging_rope_at(Vec2::new(1.0, 1.0)).unwrap_err();
    assert!(
        text(same).contains("end") && text(same).contains("start"),
        "{same}"
    );
    let mut rope = hanging_rope(1.0);
    let (mut points, mut pieces) = ([Vec2::default(); 64], [dunas::breaking::Piece::EMPTY; 8]);
    rope.draw(Smoothing::BSpline, &mut points, &mut pieces)
        .unwrap();
    let whole = rope
        .cut(&points, &pieces, Vec2::new(3.2, 1.0), Vec2::new(3.2, -1.0))
        .unwrap_err();
    assert!(text(whole).contains("&pieces[..count]"), "{whole}");
    let tolerance = dunas::lod::segments(
        &Bezier::new([Vec2::new(0.0f32, 0.0), Vec2::new(1.0, 1.0)]).unwrap(),
        -1.0,
    )
    .unwrap_err();
    assert_eq!(text(tolerance), "tolerance must be finite and > 0");
}

fn hanging_rope_at(end: Vec2<f64>) -> Result<Rope<Vec2<f64>, 8>, Error> {
    Rope::new(end, end, 1.0, material(), Settings::default())
}
