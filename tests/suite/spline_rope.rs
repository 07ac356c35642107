//! The spline rope against references nobody tuned: the hanging chain's modes (zeros of
//! J₀), the catenary, free fall, rest, energy, and symplectic Euler's stability limit.

use dunas::Error;
use dunas::integrator::{ImplicitEuler, SymplecticEuler};
use dunas::prelude::*;
use dunas::spline_rope::{Bdf2, SplineRope, SplineStepper};

use crate::common::{
    J0_ZEROS, cantilever_first_mode, cantilever_sag, cantilever_sag_exact, catenary_sag, j0,
    released_spline_rope, spline_rope_sag,
};

const G: f64 = 9.81;

fn settings(gravity: f64, drag: f64) -> Settings<Vec2<f64>> {
    Settings {
        gravity: Vec2::new(0.0, -gravity),
        damping: drag,
        ..Settings::default()
    }
}

/// A 1 m, 1 kg rope of `K` control points hanging from the origin, settled (heavy strain
/// damping and drag) for 8 s, then left with no drag.
fn hanging<const K: usize>(ea: f64) -> SplineRope<Vec2<f64>, K> {
    let stretch = Material {
        stiffness: ea,
        damping: 0.02 * ea.sqrt(),
    };
    let mut rope = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(0.0, -1.0),
        1.0,
        stretch,
        settings(G, 5.0),
    )
    .unwrap();
    for _ in 0..480 {
        let _ = rope.step(1.0 / 60.0).unwrap();
    }
    let mut still = settings(G, 0.0);
    still.accuracy = Accuracy::Balanced;
    rope.set_settings(still).unwrap();
    rope
}

/// The lateral mode `n` (0-based) of the drawn curve: its sideways displacement projected
/// on the continuum's shape `J₀(j_n·√((L - s)/L))`.
fn projection<const K: usize>(rope: &SplineRope<Vec2<f64>, K>, n: usize) -> f64 {
    let mut curve = [Vec2::default(); 201];
    let count = rope.sample(&mut curve).unwrap();
    (0..count)
        .map(|k| {
            let s = k as f64 / (count - 1) as f64;
            curve[k].x * j0(J0_ZEROS[n] * (1.0 - s).max(0.0).sqrt())
        })
        .sum::<f64>()
}

/// The angular frequency of lateral mode `n` of a hanging rope of `K` control points, from
/// the zero crossings of its projection over a few periods, started in the continuum's shape.
fn mode_frequency<const K: usize>(n: usize) -> f64 {
    let mut rope = hanging::<K>(50_000.0);
    let length = 1.0;
    // The shape at the control points' Greville abscissae (their places on a straight rope).
    let ys: Vec<f64> = rope.positions().iter().map(|p| -p.y).collect();
    for (i, &s) in ys.iter().enumerate() {
        let shape = j0(J0_ZEROS[n] * ((length - s) / length).max(0.0).sqrt());
        let p = rope.positions()[i];
        rope.set_position(i, Vec2::new(1e-3 * shape, p.y)).unwrap();
    }
    let (omega, _) = rope.stiffness_bound();
    let h = 0.5 / omega;
    let expected = J0_ZEROS[n] / 2.0 * (G / length).sqrt();
    let steps = (6.0 * std::f64::consts::TAU / expected / h) as usize;
    let mut last = projection(&rope, n);
    let mut crossings = Vec::new();
    for k in 1..=steps {
        rope.step_once(h).unwrap();
        let now = projection(&rope, n);
        if (last > 0.0) != (now > 0.0) {
            crossings.push((k as f64 - 1.0 + last / (last - now)) * h);
        }
        last = now;
    }
    assert!(
        crossings.len() >= 6,
        "mode {n}: {} crossings",
        crossings.len()
    );
    let half = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    std::f64::consts::PI / half
}

#[test]
fn eight_control_points_ring_like_the_continuum_hanging_chain() {
    for (n, tolerance) in [(0, 0.002), (1, 0.005), (2, 0.01)] {
        let expected = J0_ZEROS[n] / 2.0 * G.sqrt();
        let got = mode_frequency::<8>(n);
        let error = got / expected - 1.0;
        eprintln!(
            "mode {}: {got:.5} rad/s against {expected:.5}: {:+.4}%",
            n + 1,
            error * 100.0
        );
        assert!(
            error.abs() < tolerance,
            "mode {}: {:+.4}%",
            n + 1,
            error * 100.0
        );
    }
}

#[test]
fn its_own_weight_stretches_it_by_at_most_two_tenths_of_a_percent() {
    // EA = 5000 N for a 1 kg, 1 m rope: m·g / EA = 0.196% at the top, half that on average.
    let rope = hanging::<8>(5_000.0);
    let bottom = -rope.positions()[7].y;
    let stretch = bottom - 1.0;
    assert!(stretch > 0.0 && stretch <= 0.002 * 0.5 * 1.05, "{stretch}");
}

/// Within 0.2% of the catenary with 8 control points (measured -0.10%) and with 16
/// (measured -0.01%). Without the strain's projection, 8 lock at -3.2%.
#[test]
fn between_two_pins_it_sags_like_the_catenary() {
    let exact = catenary_sag(1.0, 1.2);
    for (got, tolerance, k) in [
        (spline_rope_sag::<8, _>(SymplecticEuler, 1e5), 0.002, 8),
        (spline_rope_sag::<16, _>(SymplecticEuler, 1e5), 0.002, 16),
    ] {
        let error = got / exact - 1.0;
        eprintln!(
            "{k} control points: sag {got:.6} m against the catenary's {exact:.6} m: {:+.3}%",
            error * 100.0
        );
        assert!(error.abs() < tolerance, "{k}: {:+.4}%", error * 100.0);
    }
}

#[test]
fn a_free_rope_falls_at_g_and_a_straight_one_rests() {
    let stretch = Material {
        stiffness: 1000.0,
        damping: 1.0,
    };
    let mut free: SplineRope<Vec2<f64>, 6> = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(2.0, 0.0),
        3.0,
        stretch,
        settings(G, 0.0),
    )
    .unwrap();
    free.set_pinned(0, false).unwrap();
    for _ in 0..60 {
        let _ = free.step(1.0 / 60.0).unwrap();
    }
    // The mass matrix's rows sum to the gravity load: every control point falls at g.
    for v in free.velocities() {
        assert!((v.y + G).abs() < 1e-9 && v.x.abs() < 1e-9, "{v:?}");
    }
    let mut still: SplineRope<Vec2<f64>, 6> = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(2.0, 0.0),
        3.0,
        stretch,
        settings(0.0, 0.0),
    )
    .unwrap();
    let before = *still.positions();
    for _ in 0..600 {
        let _ = still.step(1.0 / 60.0).unwrap();
    }
    for (a, b) in before.iter().zip(still.positions()) {
        assert!((*a - *b).length() < 1e-12);
    }
}

#[test]
fn a_point_force_is_shared_by_the_basis() {
    let stretch = Material {
        stiffness: 1000.0,
        damping: 0.0,
    };
    let rope: SplineRope<Vec2<f64>, 8> = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(2.0, 0.0),
        1.0,
        stretch,
        settings(G, 0.0),
    )
    .unwrap();
    for k in 0..=20 {
        let s = 2.0 * k as f64 / 20.0;
        let (first, w) = rope.weights_at(s);
        assert!(first + 4 <= 8);
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12, "s {s}");
        // The curve point they make lies at s along the straight rope.
        let p: Vec2<f64> = (0..4).fold(Vec2::default(), |acc, j| {
            acc + rope.positions()[first + j] * w[j]
        });
        assert!((p.x - s).abs() < 1e-12, "s {s}: {p:?}");
    }
    assert_eq!(rope.weights_at(f64::NAN), rope.weights_at(0.0));
}

/// 10⁵ frames (half an hour) of a rope released level with no damping given: at
/// `Accuracy::Fine` (no damping at all) the energy stays within 5% of `m·g·L`; at the
/// default `Accuracy::Fast`, with the damping floor of 2% on the fastest stretch wave, it
/// never gains more than 1% of it.
#[test]
fn energy_stays_bounded() {
    let run = |accuracy: Accuracy| -> (f64, f64) {
        let mut s = settings(G, 0.0);
        s.accuracy = accuracy;
        let stretch = Material {
            stiffness: 2000.0,
            damping: 0.0,
        };
        let mut rope: SplineRope<Vec2<f64>, 8> =
            SplineRope::new(Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), 1.0, stretch, s).unwrap();
        let e0 = rope.energy();
        let (mut gain, mut swing): (f64, f64) = (0.0, 0.0);
        for _ in 0..100_000 {
            let _ = rope.step(1.0 / 60.0).unwrap();
            let de = rope.energy() - e0;
            gain = gain.max(de);
            swing = swing.max(de.abs());
        }
        (gain, swing)
    };
    let scale = 1.0 * G * 1.0; // m·g·L
    let (_, swing) = run(Accuracy::Fine);
    eprintln!(
        "undamped, Fine: energy within {:.2}% of m·g·L",
        swing / scale * 100.0
    );
    assert!(swing < 0.05 * scale, "{swing}");
    let (gain, _) = run(Accuracy::Fast);
    eprintln!(
        "damping floor, Fast: largest gain {:.4}% of m·g·L",
        gain / scale * 100.0
    );
    assert!(gain < 0.01 * scale, "{gain}");
}

/// Symplectic Euler at 0.99× the computed limit `2 / ω` stays bounded; at 1.01× it blows up
/// (a rope held taut at both ends, 1% stretched, nudged by 0.1 mm/s: its stretch waves are
/// linear until they grow).
#[test]
fn the_step_bound_is_where_the_method_fails() {
    let stretch = Material {
        stiffness: 1000.0,
        damping: 0.0,
    };
    let run = |factor: f64| -> f64 {
        let mut rope: SplineRope<Vec2<f64>, 8> = SplineRope::new(
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            1.0,
            stretch,
            // At `Fine` no damping floor is added: the step is the undamped method's.
            Settings {
                accuracy: Accuracy::Fine,
                ..settings(0.0, 0.0)
            },
        )
        .unwrap();
        rope.set_pinned(7, true).unwrap();
        for i in 0..8 {
            let p = rope.positions()[i];
            rope.set_position(i, Vec2::new(p.x * 1.01, 0.0)).unwrap();
            if i > 0 && i < 7 {
                rope.set_velocity(
                    i,
                    Vec2::new(1e-4 * ((i * 7) % 5) as f64, 1e-4 * (i % 3) as f64),
                )
                .unwrap();
            }
        }
        let (omega, _) = rope.stiffness_bound();
        let fastest = |r: &SplineRope<Vec2<f64>, 8>| {
            r.velocities()
                .iter()
                .map(|v| v.length())
                .fold(0.0, f64::max)
        };
        let v0 = fastest(&rope);
        let mut worst: f64 = 0.0;
        for _ in 0..400 {
            if rope.step_once(factor * 2.0 / omega).is_err() {
                return f64::INFINITY;
            }
            worst = worst.max(fastest(&rope));
        }
        worst / v0
    };
    let stable = run(0.99);
    let unstable = run(1.01);
    eprintln!(
        "fastest point over 400 steps: {stable:.1}× the start at 0.99×, {unstable:.3e}× at 1.01×"
    );
    assert!(stable < 100.0, "{stable}");
    assert!(unstable > 1e4, "{unstable}");
}

#[test]
fn bad_input_is_an_error() {
    let ok = Material {
        stiffness: 100.0,
        damping: 0.0,
    };
    let new = |start, end, mass, m| {
        SplineRope::<Vec2<f64>, 5>::new(start, end, mass, m, settings(G, 0.0)).map(|_| ())
    };
    let (a, b) = (Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0));
    assert!(matches!(
        new(a, b, 0.0, ok),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        new(a, b, f64::NAN, ok),
        Err(Error::InvalidParameter { .. })
    ));
    let soft = Material {
        stiffness: 0.0,
        damping: 0.0,
    };
    assert!(matches!(
        new(a, b, 1.0, soft),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        new(a, a, 1.0, ok),
        Err(Error::ZeroRestLength { .. })
    ));
    assert!(new(Vec2::new(f64::NAN, 0.0), b, 1.0, ok).is_err());
    // A stiffness whose frequency is past the format: too stiff, no panic.
    let beyond = Material {
        stiffness: 1e300,
        damping: 0.0,
    };
    assert_eq!(new(a, b, 1e-20, beyond), Err(Error::TooStiff));
    let mut rope = SplineRope::<Vec2<f64>, 5>::new(a, b, 1.0, ok, settings(G, 0.0)).unwrap();
    assert!(rope.step(-1.0).is_err());
    assert!(rope.step(f64::NAN).is_err());
    assert!(rope.set_pinned(5, true).is_err());
    assert!(rope.apply_force(f64::NAN, Vec2::new(1.0, 0.0)).is_err());
    let bound = rope.stiffness_bound();
    for ei in [-1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            rope.set_bending(ei),
            Err(Error::InvalidParameter { .. })
        ));
    }
    assert_eq!((rope.bending(), rope.stiffness_bound()), (0.0, bound));
    // Bounds hold the control points: no setting or move puts one beyond them.
    let tight = Settings {
        bounds: 0.5,
        ..*rope.settings()
    };
    assert!(matches!(
        rope.set_settings(tight),
        Err(Error::OutOfRange { .. })
    ));
    assert!(matches!(
        rope.set_position(1, Vec2::new(2e150, 0.0)),
        Err(Error::OutOfRange { .. })
    ));
    let near = Settings {
        bounds: 2.0,
        ..*rope.settings()
    };
    rope.set_settings(near).unwrap();
    assert!(matches!(
        rope.set_position(1, Vec2::new(3.0, 0.0)),
        Err(Error::OutOfRange { .. })
    ));
    assert!(matches!(
        rope.move_pinned(0, Vec2::new(0.0, -3.0), 0.1),
        Err(Error::OutOfRange { .. })
    ));
    // A refused step leaves everything as it was, the force applied for it too.
    rope.apply_force(0.5, Vec2::new(0.0, 1e9)).unwrap();
    let before = format!("{rope:?}");
    assert_eq!(rope.step(1.0 / 60.0), Err(Error::Diverged));
    assert_eq!(format!("{rope:?}"), before);
    let mut all = SplineRope::<Vec2<f64>, 4>::new(a, b, 1.0, ok, settings(G, 0.0)).unwrap();
    for i in 1..3 {
        all.set_pinned(i, true).unwrap();
    }
    assert!(matches!(
        all.set_pinned(3, true),
        Err(Error::InvalidParameter { .. })
    ));
    // In `Q16` a mass unit below the format's resolution: a span's share of the least mass,
    // and `EA / 2¹⁴` too.
    let (start, end) = (
        Vec2::new(Q16::ZERO, Q16::ZERO),
        Vec2::new(Q16::from_i16(70), Q16::ZERO),
    );
    let faint = |stiffness| {
        let stretch = Material {
            stiffness,
            damping: Q16::ZERO,
        };
        let s = Settings {
            gravity: Vec2::new(Q16::ZERO, Q16::from_i16(-200)),
            ..Settings::default()
        };
        SplineRope::<Vec2<Q16>, 8>::new(start, end, Q16::from_bits(1), stretch, s)
    };
    assert!(matches!(
        faint(Q16::ratio(1, 16)).map(drop),
        Err(Error::InvalidParameter { .. })
    ));
    // A bending band past the format over the mass unit: a 70 px rope of 0.07 mass units
    // and 16 control points at `EI = 2000` has entries up to `24 / ds³ · EI / m̄`, 57 000.
    let stretch = Material {
        stiffness: Q16::from_i16(3),
        damping: Q16::ZERO,
    };
    let mut light = SplineRope::<Vec2<Q16>, 16>::new(
        start,
        end,
        Q16::ratio(7, 100),
        stretch,
        Settings::default(),
    )
    .unwrap();
    let bound = light.stiffness_bound();
    assert_eq!(light.set_bending(Q16::from_i16(2000)), Err(Error::TooStiff));
    assert_eq!(
        (light.bending(), light.stiffness_bound()),
        (Q16::ZERO, bound)
    );
    assert_eq!(light.set_bending(Q16::from_i16(10)), Ok(()));
    // With a stiffness the unit is `EA / 2¹⁴`, and so light a rope's stretch waves are past
    // the format: too stiff.
    assert_eq!(faint(Q16::from_i16(3000)).map(drop), Err(Error::TooStiff));
}

/// A 70 px rope of 7 mass units under gravity 200 px/s², released level, in `Q16` and in
/// `f64`, with `EA`, strain damping `c` and bending `EI`, all scaled to a rope `λ` times as
/// long and `μ` times as heavy (`scale = (λ, μ)`: the same motion, `λ` times as large):
/// `Q16` first, then `f64` in as many steps as `Q16` took substeps (in `Q16` the implicit
/// step takes more of them, see [`SplineStepper`]), so that both step the same scheme.
/// Returns the two ends and drawn lengths after each frame; `flick` throws the end up at
/// `400·λ` px/s after a second. No `Q16` step saturates.
fn q16_beside_f64<I: SplineStepper, const K: usize>(
    stepper: I,
    (ea, c, ei): (i16, i16, i16),
    (lam, mu): (f64, f64),
    flick: bool,
) -> Vec<[(Vec2<f64>, f64); 2]> {
    let sized = |x: i16, length_power: i32| f64::from(x) * mu * lam.powi(length_power);
    let (ea, c, ei) = (sized(ea, 1), sized(c, 1), sized(ei, 3));
    fn rope<S: Scalar, I: SplineStepper, const K: usize>(
        stepper: I,
        (ea, c, ei): (f64, f64, f64),
        (lam, mu): (f64, f64),
    ) -> SplineRope<Vec2<S>, K, I> {
        let s = Settings {
            gravity: Vec2::new(S::ZERO, S::from_f64(-200.0 * lam)),
            damping: S::ratio(1, 10),
            ..Settings::default()
        }
        .with_integrator(stepper);
        let stretch = Material {
            stiffness: S::from_f64(ea),
            damping: S::from_f64(c),
        };
        let (start, end) = (
            Vec2::new(S::ZERO, S::ZERO),
            Vec2::new(S::from_f64(70.0 * lam), S::ZERO),
        );
        let mut rope = SplineRope::new(start, end, S::from_f64(7.0 * mu), stretch, s).unwrap();
        rope.set_bending(S::from_f64(ei)).unwrap();
        rope
    }
    fn seen<S: Scalar, I: SplineStepper, const K: usize>(
        rope: &SplineRope<Vec2<S>, K, I>,
    ) -> (Vec2<f64>, f64) {
        let wide = |p: Vec2<S>| Vec2::new(p.x.to_f64(), p.y.to_f64());
        let mut curve = [Vec2::new(S::ZERO, S::ZERO); 200];
        let n = rope.sample(&mut curve).unwrap();
        let length = curve[..n]
            .windows(2)
            .map(|w| wide(w[0]).distance(wide(w[1])))
            .sum();
        (wide(rope.positions()[K - 1]), length)
    }
    let mut wide = rope::<f64, I, K>(stepper, (ea, c, ei), (lam, mu));
    let mut fixed = rope::<Q16, I, K>(stepper, (ea, c, ei), (lam, mu));
    (0..120)
        .map(|frame| {
            if flick && frame == 60 {
                wide.set_velocity(K - 1, Vec2::new(0.0, 400.0 * lam))
                    .unwrap();
                let up = Vec2::new(Q16::ZERO, Q16::from_f64(400.0 * lam));
                fixed.set_velocity(K - 1, up).unwrap();
            }
            let info = fixed.step(Q16::ratio(1, 60)).unwrap();
            assert!(
                !info.saturated,
                "{K} control points, scale {lam} {mu}, frame {frame}"
            );
            for _ in 0..info.substeps {
                let _ = wide.step(1.0 / 60.0 / f64::from(info.substeps)).unwrap();
            }
            [seen(&wide), seen(&fixed)]
        })
        .collect()
}

/// `Q16` follows `f64` after two seconds of swinging, within 2 px, explicit and implicit,
/// from one span (4 control points, where a long span's pull must not saturate the format)
/// to 13 (8 control points: measured 0.17 px and 0.02 px; `Bdf2` takes backward Euler
/// steps in `Q16`).
#[test]
fn q16_follows_f64_in_pixels() {
    fn both<const K: usize>() {
        for implicit in [false, true] {
            let path = if implicit {
                q16_beside_f64::<_, K>(ImplicitEuler::default(), (3000, 20, 0), (1.0, 1.0), false)
            } else {
                q16_beside_f64::<_, K>(SymplecticEuler, (3000, 20, 0), (1.0, 1.0), false)
            };
            let [(a, _), (b, _)] = path[path.len() - 1];
            eprintln!(
                "{K}, implicit {implicit}: {a:?} and {b:?}, {:.3} px",
                a.distance(b)
            );
            assert!(
                a.distance(b) < 2.0,
                "{K} control points, implicit {implicit}: {a:?} {b:?}"
            );
        }
    }
    both::<4>();
    both::<5>();
    both::<8>();
    both::<16>();
}

/// `Q16` stepped implicitly, a flick and a stiff rope: the drawn rope stays within 5% of
/// `f64`'s length every frame and its end within 10 px of `f64`'s. Its conjugate gradient's
/// inner products (squares of momenta) saturated the format: a flicked end (400 px/s) grew
/// the drawn rope past 700 px with 16 control points; and past `rate·h = 8` its one
/// linearized step loses its precision (24 control points at `EA = 30 000` stretched the
/// rope by 43%).
#[test]
fn q16_implicit_holds_a_flick() {
    fn check<const K: usize>(ea: i16, c: i16, flick: bool) {
        let path = q16_beside_f64::<_, K>(ImplicitEuler::default(), (ea, c, 0), (1.0, 1.0), flick);
        for (frame, [(end_a, len_a), (end_b, len_b)]) in path.iter().enumerate() {
            assert!(
                (len_b / len_a - 1.0).abs() < 0.05 && end_a.distance(*end_b) < 10.0,
                "{K} control points, EA {ea}, frame {frame}: length {len_a} against \
                 {len_b}, ends {end_a:?} and {end_b:?}"
            );
        }
    }
    check::<8>(3000, 5, true);
    check::<16>(3000, 5, true);
    check::<24>(3000, 5, true);
    check::<16>(30000, 50, true);
    check::<24>(30000, 50, false);
}

/// `Q16` bends as `f64` does: 16 control points and `EI = 3 000` (px³ a mass unit per s²),
/// explicit and implicit, end within 2 px of `f64`'s after two seconds. The bending's
/// products of its band with the coordinates saturated the format (spans of 5.4 px, band
/// entries near 700, coordinates near 70 px).
#[test]
fn q16_bends_like_f64() {
    for implicit in [false, true] {
        let path = if implicit {
            q16_beside_f64::<_, 16>(ImplicitEuler::default(), (3000, 5, 3000), (1.0, 1.0), false)
        } else {
            q16_beside_f64::<_, 16>(SymplecticEuler, (3000, 5, 3000), (1.0, 1.0), false)
        };
        let [(a, _), (b, _)] = path[path.len() - 1];
        eprintln!(
            "implicit {implicit}: {a:?} and {b:?}, {:.3} px",
            a.distance(b)
        );
        assert!(a.distance(b) < 2.0, "implicit {implicit}: {a:?} {b:?}");
    }
}

/// A force field's uniform acceleration is gravity: a rope with no gravity stepped with a
/// field that adds `g` to every control point moves as the rope under gravity.
#[test]
fn a_uniform_field_acts_as_gravity() {
    use dunas::force::{Accelerations, Bodies, ForceField};
    struct Fall;
    impl ForceField<Vec2<f64>> for Fall {
        fn apply(
            &mut self,
            _: f64,
            b: &Bodies<'_, Vec2<f64>>,
            out: &mut Accelerations<'_, Vec2<f64>>,
        ) {
            for i in 0..b.pos.len() {
                out.add_acceleration(i, Vec2::new(0.0, -G));
            }
        }
    }
    let stretch = Material {
        stiffness: 2000.0,
        damping: 1.0,
    };
    let make = |g: f64| -> SplineRope<Vec2<f64>, 8> {
        SplineRope::new(
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            1.0,
            stretch,
            settings(g, 0.1),
        )
        .unwrap()
    };
    let (mut gravity, mut field) = (make(G), make(0.0));
    for _ in 0..60 {
        let _ = gravity.step(1.0 / 60.0).unwrap();
        let _ = field.step_with(1.0 / 60.0, Fall).unwrap();
    }
    for (a, b) in gravity.positions().iter().zip(field.positions()) {
        assert!((*a - *b).length() < 1e-9, "{a:?} {b:?}");
    }
    // It fell and swung: the end is far from where it started.
    assert!((field.positions()[7] - Vec2::new(1.0, 0.0)).length() > 0.5);
}

/// A rope released level onto a peg far thinner than its control points' spacing: with
/// either stepper, the drawn curve comes to the peg and never passes into it over 4 s.
#[test]
fn a_thin_peg_holds_the_drawn_curve() {
    peg_holds(SymplecticEuler);
    peg_holds(ImplicitEuler::default());
    peg_holds(Bdf2::default());
}

/// The peg test with `stepper`.
fn peg_holds<I: SplineStepper>(stepper: I) {
    use dunas::collider::Collider;
    use dunas::contact::{Contacts, Touch};
    let stretch = Material {
        stiffness: 5000.0,
        damping: 2.0,
    };
    let mut rope: SplineRope<Vec2<f64>, 8, I> = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        1.0,
        stretch,
        settings(G, 0.5).with_integrator(stepper),
    )
    .unwrap();
    // A peg of 5 mm under the middle of the rope, 10 cm down: the control points are 20 cm
    // apart, so it fits between them.
    let centre = Vec2::new(0.5, -0.1);
    let peg = [Collider::ball(centre, 0.005).unwrap()];
    let thickness = 0.002;
    // A spline rope tests its drawn curve whatever the `Touch`: the curve is its state.
    let contacts = Contacts::new(&peg, thickness, Touch::Particles).unwrap();
    let mut curve = [Vec2::default(); 400];
    let mut deepest: f64 = f64::INFINITY;
    for _ in 0..240 {
        let _ = rope.step_touching(1.0 / 60.0, (), &contacts).unwrap();
        let n = rope.sample(&mut curve).unwrap();
        for p in &curve[..n] {
            deepest = deepest.min((*p - centre).length() - 0.005);
        }
    }
    eprintln!(
        "{stepper:?}: closest the drawn curve came to the peg: {deepest:.5} m (thickness {thickness})"
    );
    // It touched the peg (came within 1 mm of the contact distance) and never went in.
    assert!(deepest > 0.0 && deepest < thickness + 0.001, "{deepest}");
}

/// The drawn curve's length (200 chords).
fn drawn_length<const K: usize, I: SplineStepper>(rope: &SplineRope<Vec2<f64>, K, I>) -> f64 {
    let mut curve = [Vec2::default(); 201];
    let n = rope.sample(&mut curve).unwrap();
    curve[..n].windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// A 1 m, 1 kg rope of axial stiffness `ea`, released level with no damping, stepped by
/// `stepper` at 60 Hz for 10 s; every frame one step, never slow motion. Returns the largest
/// energy gain and the energy lost in the first second (both over `m·g·L/2`, what the fall
/// releases), and the longest the drawn curve got (m).
fn implicit_release<S: Scalar, I: SplineStepper>(ea: f64, stepper: I) -> (f64, f64, f64) {
    let mut rope = released_spline_rope::<S, I>(ea, stepper);
    let scale = 0.5 * G;
    let e0 = rope.energy().to_f64();
    let (mut gain, mut longest, mut lost) = (f64::MIN, 0.0f64, 0.0);
    let mut curve = [Vec2::default(); 201];
    for frame in 0..600 {
        let info = rope.step(S::ratio(1, 60)).unwrap();
        assert!(info.substeps == 1 && !info.slow_motion, "{ea}: {info:?}");
        let e = rope.energy().to_f64();
        gain = gain.max(e - e0);
        let n = rope.sample(&mut curve).unwrap();
        let length: f64 = curve[..n]
            .windows(2)
            .map(|w| w[0].distance(w[1]).to_f64())
            .sum();
        longest = longest.max(length);
        if frame == 59 {
            lost = (e0 - e) / scale;
        }
    }
    (gain / scale, lost, longest)
}

/// The implicit steppers take one step a frame at any stiffness the format holds, released
/// level with no damping given: never in slow motion, their energy never above the start,
/// a stiff rope's drawn curve never 0.5% longer than its rest length (BDF2: 1%, measured
/// 0.64%). `f64` from `EA = 2000 N` on 1 m,
/// 1 kg to `10⁸ N` (`h²·EA/(ρ·ds²)` to 7·10⁵); `f32` to `10⁷ N`, within 10⁻⁴ of `m·g·L/2`
/// (its energy's own rounding). Backward Euler damps the swing: within the first second
/// it loses under half of the energy the fall releases (measured 37% to 43%); BDF2, up to
/// `10⁷ N` in `f64`, under a tenth (measured 6% to 8%). 16 conjugate-gradient iterations.
#[test]
fn implicit_steps_any_stiffness_once_a_frame() {
    fn check<I: SplineStepper>(stepper: I, most_lost: f64, lost_up_to: f64, stretch: f64) {
        for (ea, f32_too) in [(2e3, true), (1e5, true), (1e7, true), (1e8, false)] {
            let (gain, lost, longest) = implicit_release::<f64, _>(ea, stepper);
            eprintln!(
                "{stepper:?}, EA {ea:e} N: largest energy gain {gain:+.2e} of m·g·L/2, \
                 longest {longest:.5} m, lost {:.1}% in the first second",
                lost * 100.0
            );
            assert!(gain <= 1e-9, "{ea}: {gain}");
            assert!(ea < 1e5 || longest <= 1.0 + stretch, "{ea}: {longest}");
            assert!(ea > lost_up_to || lost < most_lost, "{ea}: {lost}");
            if f32_too {
                let (gain, _, longest) = implicit_release::<f32, _>(ea, stepper);
                eprintln!("  f32: gain {gain:+.2e}, longest {longest:.5} m");
                assert!(gain <= 1e-4, "f32 {ea}: {gain}");
                assert!(ea < 1e5 || longest <= 1.0 + stretch, "f32 {ea}: {longest}");
            }
        }
    }
    check(ImplicitEuler::default(), 0.5, 1e8, 0.005);
    check(Bdf2::default(), 0.1, 1e7, 0.01);
}

/// The implicit steppers' fixed point is the equilibrium: 8 control points sag within 0.2%
/// of the catenary (measured −0.10%), and so does a cable 1000× stiffer (`EA = 10⁸ N`,
/// measured −0.12%), with 16 conjugate-gradient iterations.
#[test]
fn implicit_settles_on_the_catenary() {
    let exact = catenary_sag(1.0, 1.2);
    for ea in [1e5, 1e8] {
        for (name, got) in [
            (
                "implicit",
                spline_rope_sag::<8, _>(ImplicitEuler::default(), ea),
            ),
            ("BDF2", spline_rope_sag::<8, _>(Bdf2::default(), ea)),
        ] {
            let error = got / exact - 1.0;
            eprintln!("EA {ea:e} N, {name}: {:+.3}%", error * 100.0);
            assert!(error.abs() < 0.002, "{name} {ea}: {:+.4}%", error * 100.0);
        }
    }
}

/// A hitch: one implicit step of half a second, or of 1000 s, from a level release is taken
/// whole and stays sane: energy not above the start, length within 1%. (After 1000 s the
/// Newton steps, each cut back until the potential falls, have barely moved it.)
#[test]
fn implicit_takes_a_hitch_whole() {
    for dt in [0.5, 1000.0] {
        let s = settings(G, 0.0).with_integrator(ImplicitEuler::default());
        let stretch = Material {
            stiffness: 1e6,
            damping: 0.0,
        };
        let mut rope: SplineRope<Vec2<f64>, 8, ImplicitEuler> =
            SplineRope::new(Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), 1.0, stretch, s).unwrap();
        let e0 = rope.energy();
        let info = rope.step(dt).unwrap();
        assert!(info.substeps == 1 && !info.slow_motion && info.simulated == dt);
        assert!(rope.energy() <= e0, "{dt}: {} > {e0}", rope.energy());
        assert!(drawn_length(&rope) < 1.01, "{dt}: {}", drawn_length(&rope));
        eprintln!("after {dt} s: end at {:?}", rope.positions()[7]);
    }
}

/// Strain damping hundreds of times critical (`c = 5` on a 1 m, 10 g rope of `EA` 1 down
/// to 0.001, swinging from level for 2 s), stepped implicitly: damping only takes energy out,
/// so the energy never rises above the start's. (The damping in Newton's matrix was once
/// taken along the iterate's directions, not the frozen ones the potential uses: these
/// ropes flew off to 10³⁰ m.)
#[test]
fn heavy_strain_damping_only_takes_energy_out() {
    fn swing<const K: usize>(ea: f64) {
        let s = settings(1.0, 0.0).with_integrator(ImplicitEuler::default());
        let stretch = Material {
            stiffness: ea,
            damping: 5.0,
        };
        let mut rope: SplineRope<Vec2<f64>, K, ImplicitEuler> =
            SplineRope::new(Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), 0.01, stretch, s).unwrap();
        let e0 = rope.energy();
        for frame in 0..120 {
            let _ = rope.step(1.0 / 60.0).unwrap();
            let e = rope.energy();
            assert!(
                e <= e0 + 1e-9 * e0.abs(),
                "K {K} EA {ea} frame {frame}: {e} > {e0}"
            );
        }
    }
    for ea in [1.0, 0.1, 0.01, 0.001] {
        swing::<8>(ea);
        // 16 control points: from `EA` 0.1 down the rope's own weight stretches it by a
        // tenth or more and the slack spans' Newton steps stop short; held, the step still
        // gains nothing.
        swing::<16>(ea);
    }
}

/// A step whose Newton steps stop short is held to the energy it started with: a 1 m, 3.6 g
/// rope at `EA = 1284 N`, strain damping 0.65 N·s, drag 4.5/s, 16 control points, under
/// 757 m/s² pointing down and back, at 30 Hz with 4 and 16 conjugate-gradient iterations
/// (unheld, its energy went from 0.97 to 74 J in 8 frames with 4, to 10 J with 16), in
/// `f64` and `f32` (within `10⁻⁴` of its starting energy: rounding).
#[test]
fn a_solve_stopped_short_never_gains_energy() {
    fn check<S: Scalar>(iterations: u8, tolerance: f64) {
        let angle = 3.932_391_028_f64;
        let g = 757.246_867_f64;
        let s = S::from_f64;
        let settings = Settings {
            gravity: Vec2::new(s(g * angle.cos()), s(g * angle.sin())),
            damping: s(4.502_856_5),
            ..Settings::default()
        }
        .with_integrator(ImplicitEuler { iterations });
        let stretch = Material {
            stiffness: s(1_284.153_267),
            damping: s(0.649_166_775),
        };
        let origin = Vec2::new(S::ZERO, S::ZERO);
        let mut rope: SplineRope<Vec2<S>, 16, ImplicitEuler> = SplineRope::new(
            origin,
            Vec2::new(s(1.0), S::ZERO),
            s(0.003_636_757),
            stretch,
            settings,
        )
        .unwrap();
        let e0 = rope.energy().to_f64();
        for frame in 0..30 {
            let _ = rope.step(S::ratio(1, 30)).unwrap();
            let e = rope.energy().to_f64();
            assert!(
                e <= e0 + tolerance * e0.abs(),
                "{iterations} iterations, frame {frame}: {e} > {e0}"
            );
        }
    }
    for iterations in [4, 16] {
        check::<f64>(iterations, 1e-9);
        check::<f32>(iterations, 1e-4);
    }
}

/// `Q16` takes any mass and a whip: the step divides its equations by a mass unit (a
/// span's mass) and steps explicitly in velocity changes, so the `mcu_spline` rope 30 times
/// lighter or 3 times heavier, or 2 to 7 times larger (up to 490 px under 1 400 px/s², its
/// end whipping past 100 000 px/s²), stays within 1% of its length from `f64` for two
/// seconds, explicit and implicit, 8, 12 and 16 control points, and nothing saturates. (In forces, a 16-point
/// rope 0.2 units heavy ended 140 px from `f64` stepped implicitly, and the large one's
/// accelerations saturated.)
#[test]
fn q16_holds_any_mass_and_a_whip() {
    fn check<const K: usize>(scale: (f64, f64)) {
        for implicit in [false, true] {
            let path = if implicit {
                q16_beside_f64::<_, K>(ImplicitEuler::default(), (3000, 5, 0), scale, false)
            } else {
                q16_beside_f64::<_, K>(SymplecticEuler, (3000, 5, 0), scale, false)
            };
            let worst = path
                .iter()
                .map(|[(a, _), (b, _)]| a.distance(*b))
                .fold(0.0, f64::max);
            let length = 70.0 * scale.0;
            eprintln!(
                "{K}, scale {scale:?}, implicit {implicit}: {:.3}%",
                100.0 * worst / length
            );
            assert!(
                worst < 0.01 * length,
                "{K}, scale {scale:?}, implicit {implicit}: {worst} px"
            );
        }
    }
    for scale in [(1.0, 1.0 / 30.0), (1.0, 3.0)]
        .into_iter()
        .chain((2..=7).map(|lam| (f64::from(lam), 1.0)))
    {
        check::<8>(scale);
        check::<12>(scale);
        check::<16>(scale);
    }
}

/// In `Q16` a force applied past the format (16 000 at the middle of a rope of 0.35 mass
/// units at `EA = 3000`: over the mass unit, `EA / 2¹⁴`, 1.3 times the format's range) is
/// clamped and reported, by either stepper; the `mcu_spline` rope never saturates.
#[test]
fn q16_reports_a_saturated_load() {
    fn saturates<I: SplineStepper>(stepper: I, mass: Q16, hit: i16) -> bool {
        let s = Settings {
            gravity: Vec2::new(Q16::ZERO, Q16::from_i16(-200)),
            ..Settings::default()
        }
        .with_integrator(stepper);
        let stretch = Material {
            stiffness: Q16::from_i16(3000),
            damping: Q16::from_i16(5),
        };
        let (start, end) = (
            Vec2::new(Q16::ZERO, Q16::ZERO),
            Vec2::new(Q16::from_i16(70), Q16::ZERO),
        );
        let mut rope: SplineRope<Vec2<Q16>, 8, I> =
            SplineRope::new(start, end, mass, stretch, s).unwrap();
        (0..60).any(|frame| {
            if frame == 30 {
                let down = Vec2::new(Q16::ZERO, Q16::from_i16(-hit));
                rope.apply_force(Q16::from_i16(35), down).unwrap();
            }
            rope.step(Q16::ratio(1, 60)).unwrap().saturated
        })
    }
    let light = Q16::ratio(7, 20);
    assert!(saturates(SymplecticEuler, light, 16_000));
    assert!(saturates(ImplicitEuler::default(), light, 16_000));
    assert!(!saturates(SymplecticEuler, Q16::from_i16(7), 0));
    assert!(!saturates(ImplicitEuler::default(), Q16::from_i16(7), 0));
}

/// Bending: a cantilever sags under its own weight by `ρ·g·L⁴ / (8·EI)` at its tip (beam
/// theory, small deflection: here 1.2% of its length), within 1% with every stepper
/// (measured −0.01%).
#[test]
fn a_stiff_end_bends_like_a_cantilever() {
    let exact = cantilever_sag_exact();
    for (name, got) in [
        ("explicit", cantilever_sag(SymplecticEuler)),
        ("implicit", cantilever_sag(ImplicitEuler::default())),
        ("BDF2", cantilever_sag(Bdf2::default())),
    ] {
        let error = got / exact - 1.0;
        eprintln!(
            "{name}: tip {got:.6} m against {exact:.6} m: {:+.3}%",
            error * 100.0
        );
        assert!(error.abs() < 0.01, "{name}: {:+.3}%", error * 100.0);
    }
}

/// Bending: released from its sag with gravity off and no damping, the cantilever's tip
/// swings at its first mode, `1.8751²·√(EI / (ρ·L⁴))`, within 1% (measured +0.02%).
#[test]
fn a_cantilever_rings_at_its_first_mode() {
    let (got, exact) = cantilever_first_mode();
    let error = got / exact - 1.0;
    eprintln!(
        "first mode {got:.4} rad/s against {exact:.4}: {:+.3}%",
        error * 100.0
    );
    assert!(error.abs() < 0.01, "{:+.3}%", error * 100.0);
}

/// A straight, unloaded rope stays where it is: no gravity, nothing but its first control
/// point holds it, so rounding in its strain (a few units of the last place of tension, with
/// no direction to them) would set it turning for ever. Over 10⁴ frames (167 s) its free end
/// moves less than 1e-4 of its length in `Q16` (it used to turn through 86% to 116%) and
/// in `f32`, along a diagonal where no coordinate is exact.
#[test]
fn a_straight_unloaded_rope_does_not_creep() {
    fn creep<S: Scalar>(length: f64, ea: f64, c: f64, mass: f64) -> f64 {
        let q = S::from_f64;
        let settings = Settings {
            gravity: Vec2::new(q(0.0), q(0.0)),
            ..Settings::default()
        };
        let material = Material {
            stiffness: q(ea),
            damping: q(c),
        };
        let end = Vec2::new(q(0.6 * length), q(0.8 * length));
        let mut rope: SplineRope<Vec2<S>, 8> =
            SplineRope::new(Vec2::new(q(0.0), q(0.0)), end, q(mass), material, settings).unwrap();
        let start = rope.positions()[7];
        for _ in 0..10_000 {
            let _ = rope.step(q(1.0 / 60.0)).unwrap();
        }
        let (x, y) = (
            rope.positions()[7].x - start.x,
            rope.positions()[7].y - start.y,
        );
        (x.to_f64().hypot(y.to_f64())) / length
    }
    for (length, ea, c, mass) in [
        (1.6, 4000.0, 1.0, 0.4),
        (1.0, 1e4, 0.0, 0.1),
        (3.0, 50.0, 0.1, 0.5),
    ] {
        let (fixed, float) = (
            creep::<Q16>(length, ea, c, mass),
            creep::<f32>(length, ea, c, mass),
        );
        eprintln!("EA {ea}: the free end moved {fixed:.1e} (Q16), {float:.1e} (f32) of the length");
        assert!(fixed < 1e-4 && float < 1e-4, "EA {ea}: {fixed}, {float}");
    }
}
