//! The closed cloth (`Torus`) and the gas inside it (`force::Pressure`) against
//! closed forms: the volume of a torus, the virial balance of springs and gas at rest,
//! energy kept by an undamped oscillation, a ballistic throw, the drawn surface's seam, and
//! bad input.
#![cfg(any(feature = "std", feature = "libm"))]

use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::force::Pressure;
use dunas::integrator::DirectSprings;
use dunas::spring::{Material, Snap, Topology};
use dunas::surface::SurfaceTable;
use dunas::{Error, Integrator, Point, Q16, Scalar, Settings, Smoothing, Torus, Vec3};

const RADIUS: f64 = 1.0;
const TUBE: f64 = 0.35;

fn material(k: f64, damping: f64) -> [Material<f64>; 3] {
    let m = Material {
        stiffness: k,
        damping,
    };
    [m, m, m]
}

/// An 8×8 torus of 2 kg lying flat round `(0, y, 0)`, its springs `springs`.
fn tube_at<I: Integrator>(
    y: f64,
    springs: [Material<f64>; 3],
    settings: Settings<Vec3<f64>, I>,
) -> Torus<f64, 8, 8, I> {
    Torus::new(Vec3::new(0.0, y, 0.0), RADIUS, TUBE, 2.0, springs, settings).unwrap()
}

/// [`tube_at`] the origin, its springs of `k` damped by 0.5.
fn tube<I: Integrator>(k: f64, settings: Settings<Vec3<f64>, I>) -> Torus<f64, 8, 8, I> {
    tube_at(0.0, material(k, 0.5), settings)
}

/// `Σ k (l − rest) l` over the springs: what the gas's `3 · amount` balances at rest (the
/// virial: scaling the body by `1 + ε` changes the springs' energy by `ε` times this and
/// the gas's by `−3ε · amount`, and at rest the energy is stationary).
fn spring_virial<I: Integrator>(t: &Torus<f64, 8, 8, I>) -> f64 {
    let x = t.positions();
    let mut sum = 0.0;
    t.topology().for_each_spring(|a, b, rest, m| {
        let l = x[a].distance(x[b]);
        sum += m.stiffness * (l - rest) * l;
    });
    sum
}

/// The grid's volume converges on the torus's `2π²Rr²`: within 0.1% at 256×256 particles,
/// the same whichever way round the grid goes (signed).
#[test]
fn a_fine_torus_grid_holds_the_torus_volume() {
    let (u, v) = (256, 256);
    let points: Vec<Vec3<f64>> = (0..v)
        .flat_map(|j| {
            (0..u).map(move |i| {
                let (a, b) = (
                    -std::f64::consts::TAU * i as f64 / u as f64,
                    std::f64::consts::TAU * j as f64 / v as f64,
                );
                let reach = RADIUS + TUBE * b.cos();
                Vec3::new(reach * a.cos(), TUBE * b.sin(), reach * a.sin())
            })
        })
        .collect();
    let want = 2.0 * std::f64::consts::PI.powi(2) * RADIUS * TUBE * TUBE;
    let got = Pressure::signed_volume(&points, u);
    eprintln!("256×256: {got:.6} m³ against {want:.6} m³");
    assert!((got - want).abs() <= 1e-3 * want, "{got} against {want}");
    // Mirrored (z → −z) the grid turns inside out.
    let mirrored: Vec<_> = points.iter().map(|p| Vec3::new(p.x, p.y, -p.z)).collect();
    let back = Pressure::signed_volume(&mirrored, u);
    assert!((back + got).abs() <= 1e-9 * want);
    // Not a closed grid of rows of `u`: no volume.
    assert_eq!(Pressure::signed_volume(&points[..u * 2], u), 0.0);
    assert_eq!(Pressure::signed_volume(&points[..100], 7), 0.0);
}

/// Blown up and damped to rest in no gravity, the springs balance the gas by the virial
/// identity within 1%, for three amounts of gas and for the explicit and the direct solver.
#[test]
fn a_blown_up_torus_rests_where_its_springs_balance_its_gas() {
    fn check<I: Integrator>(settings: Settings<Vec3<f64>, I>, name: &str) {
        for amount in [5.0, 20.0, 60.0] {
            let mut t = tube(400.0, settings);
            let before = t.volume();
            let mut gas = Pressure::new(amount).unwrap();
            for _ in 0..900 {
                let _ = t.step_with(1.0 / 60.0, &mut gas).unwrap();
            }
            let (springs, gas_side) = (spring_virial(&t), 3.0 * amount);
            let speed = t
                .velocities()
                .iter()
                .map(|v| v.length())
                .fold(0.0, f64::max);
            eprintln!(
                "{name}, amount {amount}: Σk(l−r)l {springs:.4} against 3·amount {gas_side:.4}; \
                 volume {:.4} m³ from {before:.4}; fastest particle {speed:.1e} m/s",
                t.volume()
            );
            assert!(speed < 1e-4, "{name} {amount}: not at rest ({speed} m/s)");
            assert!(
                (springs - gas_side).abs() <= 0.01 * gas_side,
                "{name} {amount}: {springs} against {gas_side}"
            );
            assert!(t.volume() > before);
        }
    }
    let settings = Settings {
        damping: 2.0,
        ..Settings::default()
    };
    check(settings, "symplectic Euler");
    check(
        Settings {
            damping: 2.0,
            ..Settings::default()
        }
        .with_integrator(DirectSprings::default()),
        "DirectSprings",
    );
}

/// The gas's pushes are the gradient of its energy `−amount · ln V`: undamped, with the
/// particles moving every which way, one step of `h` changes the springs', gas's and
/// motion's energy by `O(h²)` (a push off the gradient would leave an `O(h)` change), so
/// ten times shorter a step changes it at least 50 times less. Over 5 s of breathing the
/// gas gives the body no momentum.
#[test]
fn the_gas_pushes_down_its_energy_and_gives_no_momentum() {
    let settings = Settings {
        damping: 0.0,
        ..Settings::default()
    };
    let amount = 20.0;
    let build = || {
        let mut t = tube_at(0.0, material(400.0, 0.0), settings);
        let mut seed = 7u64;
        let mut random = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for i in 0..64 {
            let v = Vec3::new(random(), random(), random());
            let p = t.positions()[i] + Vec3::new(random(), random(), random()) * 0.05;
            t.set_position(i, p).unwrap();
            t.set_velocity(i, v).unwrap();
        }
        t
    };
    let total = |t: &Torus<f64, 8, 8>| t.energy() - amount * t.volume().ln();
    let change = |h: f64| {
        let mut t = build();
        let before = total(&t);
        let _ = t.step_with(h, &mut Pressure::new(amount).unwrap()).unwrap();
        (total(&t) - before).abs()
    };
    let (coarse, fine) = (change(1e-4), change(1e-5));
    eprintln!("one step's energy change: {coarse:.3e} J at 1e-4 s, {fine:.3e} J at 1e-5 s");
    assert!(fine * 50.0 <= coarse, "{coarse} then {fine}");

    let mut t = build();
    let mut gas = Pressure::new(amount).unwrap();
    let momentum =
        |t: &Torus<f64, 8, 8>| t.velocities().iter().fold(Vec3::default(), |s, &v| s + v);
    let start = momentum(&t);
    for _ in 0..300 {
        let _ = t.step_with(1.0 / 60.0, &mut gas).unwrap();
        assert!((momentum(&t) - start).length() < 1e-9);
    }
}

/// Dropped on a floor it bounces and settles with its particles above it, its volume kept
/// within 5% of its blown-up volume (the gas resists the squash); thrown, its centre of
/// mass flies the ballistic arc.
#[test]
fn a_dropped_torus_bounces_and_a_thrown_one_flies_the_arc() {
    let g = Vec3::new(0.0, -9.81, 0.0);
    let settings = Settings {
        gravity: g,
        damping: 0.3,
        ..Settings::default()
    };
    let mut t = tube_at(1.5, material(2000.0, 0.5), settings);
    let mut gas = Pressure::at(400.0, t.volume()).unwrap();
    let floor = [Collider::half_space(Vec3::default(), Vec3::new(0.0, 1.0, 0.0)).unwrap()];
    let contacts = Contacts::new(&floor, 0.01, Touch::Particles).unwrap();
    let (mut low, mut blown, mut lowest, mut bounce) = (f64::MAX, 0.0, f64::MAX, 0.0f64);
    for frame in 0..240 {
        let _ = t
            .step_touching_particles(1.0 / 60.0, &mut gas, &contacts)
            .unwrap();
        // Blown up in the fall; the floor is first touched at about frame 28.
        if frame == 15 {
            blown = t.volume();
        }
        low = low.min(t.volume());
        let bottom = t.positions().iter().map(|p| p.y).fold(f64::MAX, f64::min);
        lowest = lowest.min(bottom);
        assert!(bottom >= -1e-9);
        let rising = t.velocities().iter().map(|v| v.y).sum::<f64>() / 64.0;
        bounce = bounce.max(rising);
    }
    eprintln!("dropped: it rises again at up to {bounce:.2} m/s");
    assert!(bounce > 0.5, "it bounces: {bounce}");
    assert!(lowest < 0.011, "it reached the floor: {lowest}");
    eprintln!("dropped: volume down to {low:.4} m³ from {blown:.4} m³");
    assert!(low >= 0.95 * blown, "{low} against {blown}");

    // Air drag (`damping`) would slow the throw: none.
    let mut thrown = tube(
        2000.0,
        Settings {
            damping: 0.0,
            ..settings
        },
    );
    let v0 = Vec3::new(2.0, 4.0, 0.0);
    for i in 0..64 {
        thrown.set_velocity(i, v0).unwrap();
    }
    let centre = |t: &Torus<f64, 8, 8>| {
        t.positions().iter().fold(Vec3::default(), |s, &p| s + p) * (1.0 / 64.0)
    };
    let mut gas = Pressure::new(20.0).unwrap();
    for _ in 0..60 {
        let _ = thrown.step_with(1.0 / 60.0, &mut gas).unwrap();
    }
    let want = v0 + g * 0.5; // after 1 s from the origin
    let got = centre(&thrown);
    eprintln!("thrown: centre {got:?} against {want:?}");
    assert!(
        got.distance(want) < 0.02 * want.length(),
        "{got:?} against {want:?}"
    );
}

/// The drawn surface closes on itself: its last row and column lie on its first, normals
/// point out of the tube, and the natural spline's seam is as smooth as anywhere else.
#[test]
fn the_drawn_torus_has_no_seam_and_faces_out() {
    let t = tube(400.0, Settings::default());
    for smoothing in [
        Smoothing::CatmullRom,
        Smoothing::BSpline,
        Smoothing::NaturalSpline,
    ] {
        let tu = SurfaceTable::<f64, 8, 33>::closed(smoothing, 33).unwrap();
        let tv = SurfaceTable::<f64, 8, 17>::closed(smoothing, 17).unwrap();
        let (mut pos, mut nor) = (
            vec![Vec3::default(); 33 * 17],
            vec![Vec3::default(); 33 * 17],
        );
        assert_eq!(t.draw(&tu, &tv, &mut pos, &mut nor).unwrap(), 33 * 17);
        for b in 0..17 {
            assert!(pos[b * 33].distance(pos[b * 33 + 32]) < 1e-12);
            assert!(
                nor[b * 33].distance(nor[b * 33 + 32]) < 1e-9,
                "{smoothing:?}"
            );
        }
        for a in 0..33 {
            assert!(pos[a].distance(pos[16 * 33 + a]) < 1e-12);
        }
        for (p, n) in pos.iter().zip(&nor) {
            // Out of the tube: away from the nearest point of the ring's circle.
            let flat = (p.x * p.x + p.z * p.z).sqrt();
            let core = Vec3::new(p.x / flat * RADIUS, 0.0, p.z / flat * RADIUS);
            assert!(n.dot(*p - core) > 0.0, "{smoothing:?}: {n:?} at {p:?}");
            // The splines through the particles lie on the torus within their bulge (the
            // B-spline cuts inside them).
            if smoothing != Smoothing::BSpline {
                assert!(
                    ((*p - core).length() - TUBE).abs() < 0.05 * TUBE,
                    "{smoothing:?}"
                );
            }
        }
    }
    // An open table, or one Bézier round a ring, is refused.
    let open = SurfaceTable::<f64, 8, 17>::new(Smoothing::CatmullRom, 17).unwrap();
    let (mut pos, mut nor) = ([Vec3::default(); 17 * 17], [Vec3::default(); 17 * 17]);
    assert!(matches!(
        t.draw(&open, &open, &mut pos, &mut nor),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(SurfaceTable::<f64, 8, 17>::closed(Smoothing::Bezier, 17).is_err());
}

/// Bad shapes and bad gas are refused; a gas on a system that is not a closed grid pushes
/// nothing; a `Q16` torus blows up as the `f64` one does.
#[test]
fn bad_input_is_refused_and_q16_follows_f64() {
    let s = Settings::<Vec3<f64>>::default();
    let m = material(100.0, 0.1);
    for (radius, tube, mass) in [
        (1.0, 1.0, 1.0),
        (1.0, 2.0, 1.0),
        (0.0, 0.1, 1.0),
        (1.0, f64::NAN, 1.0),
        (1.0, 0.2, -1.0),
    ] {
        let t = Torus::<f64, 6, 5>::new(Vec3::default(), radius, tube, mass, m, s);
        assert!(
            matches!(t, Err(Error::InvalidParameter { .. })),
            "{radius} {tube} {mass}"
        );
    }
    for amount in [-1.0, f64::NAN, f64::INFINITY] {
        assert!(Pressure::new(amount).is_err());
    }
    assert!(Pressure::at(1.0, -1.0).is_err());

    // A rope's row is not a closed grid: the gas leaves it alone.
    let mut rope: dunas::Rope<Vec3<f64>, 8> =
        dunas::Rope::new(Vec3::default(), Vec3::new(7.0, 0.0, 0.0), 1.0, m[0], s).unwrap();
    let before = rope.positions().to_vec();
    let _ = rope
        .step_with(1.0 / 60.0, &mut Pressure::new(10.0).unwrap())
        .unwrap();
    assert_eq!(rope.positions(), &before[..]);

    // Q16 against f64, 1 s of blowing up in no gravity.
    let q = Q16::from_f64;
    let mq = Material {
        stiffness: q(400.0),
        damping: q(0.5),
    };
    let sq = Settings::<Vec3<Q16>> {
        damping: q(2.0),
        ..Settings::default()
    };
    let mut fixed =
        Torus::<Q16, 8, 8>::new(Vec3::default(), q(RADIUS), q(TUBE), q(2.0), [mq; 3], sq).unwrap();
    let mut float = tube(
        400.0,
        Settings {
            damping: 2.0,
            ..Settings::default()
        },
    );
    let (mut gas_q, mut gas_f) = (
        Pressure::new(q(20.0)).unwrap(),
        Pressure::new(20.0).unwrap(),
    );
    for _ in 0..60 {
        let info = fixed.step_with(q(1.0 / 60.0), &mut gas_q).unwrap();
        assert!(!info.saturated);
        let _ = float.step_with(1.0 / 60.0, &mut gas_f).unwrap();
    }
    let (vq, vf) = (fixed.volume().to_f64(), float.volume());
    eprintln!("Q16 volume {vq:.5} m³ against f64 {vf:.5} m³");
    assert!((vq - vf).abs() <= 0.01 * vf, "{vq} against {vf}");
}

/// Pumped past what its springs hold (its gas growing every frame), a torus whose springs
/// snap (`Snap::Stretch`) bursts: the step reports the torn springs, the game lets the gas
/// out (`pop`), and the torus shrinks back to the shape its springs hold, nothing turning
/// NaN.
#[test]
fn an_overblown_torus_bursts_and_shrinks() {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.5,
        ..Settings::default()
    };
    let mut t = tube(400.0, settings);
    t.set_snap([Snap::Stretch(1.2); 3]).unwrap();
    let floor =
        [Collider::half_space(Vec3::new(0.0, -0.5, 0.0), Vec3::new(0.0, 1.0, 0.0)).unwrap()];
    let contacts = Contacts::new(&floor, 0.01, Touch::Particles).unwrap();
    let mut gas = Pressure::new(0.0).unwrap();
    let (start, mut burst) = (t.volume(), None);
    for frame in 0..240 {
        if burst.is_none() {
            gas = Pressure::new(10.0 * frame as f64).unwrap();
        }
        let info = t
            .step_touching_particles(1.0 / 60.0, &mut gas, &contacts)
            .unwrap();
        if info.snapped > 0 && burst.is_none() {
            burst = Some((frame, info.snapped, t.volume()));
            gas.pop();
        }
        assert!(t.positions().iter().all(|p| p.is_finite()));
    }
    let (frame, snapped, at_burst) = burst.expect("it bursts");
    eprintln!(
        "burst at frame {frame} ({snapped} springs) at {at_burst:.3} m³ from {start:.3} m³; then {:.3} m³",
        t.volume()
    );
    assert_eq!(gas.amount(), 0.0);
    assert!(at_burst > start && t.volume().abs() < at_burst);
}

/// Dropped across two rods thinner than its particle spacing (2 cm, under the tube between
/// particles), a torus touching with its drawn surface rests on them, every drawn point
/// clear of the rods by the thickness within 10%; touching with its particles it falls
/// through.
#[test]
fn a_torus_rests_on_rods_its_particles_miss() {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.5,
        ..Settings::default()
    };
    let x = RADIUS * (std::f64::consts::PI / 8.0).cos();
    let rod =
        |x: f64| Collider::capsule(Vec3::new(x, 0.0, -2.0), Vec3::new(x, 0.0, 2.0), 0.02).unwrap();
    let rods = [rod(x), rod(-x)];
    let thickness = 0.01;
    for touch in [
        Touch::Drawn(Smoothing::CatmullRom),
        Touch::Drawn(Smoothing::NaturalSpline),
        Touch::Particles,
    ] {
        let mut t = tube_at(0.5, material(2000.0, 0.5), settings);
        let mut gas = Pressure::at(300.0, t.volume()).unwrap();
        let contacts = Contacts::new(&rods, thickness, touch).unwrap();
        for _ in 0..120 {
            let _ = t.step_touching(1.0 / 60.0, &mut gas, &contacts).unwrap();
        }
        let centre = t.positions().iter().map(|p| p.y).sum::<f64>() / 64.0;
        let Touch::Drawn(smoothing) = touch else {
            eprintln!("{touch:?}: centre at {centre:.3} m");
            assert!(centre < -1.0, "the particles miss the rods: {centre}");
            continue;
        };
        let tu = SurfaceTable::<f64, 8, 65>::closed(smoothing, 65).unwrap();
        let (mut pos, mut nor) = (
            vec![Vec3::default(); 65 * 65],
            vec![Vec3::default(); 65 * 65],
        );
        let tv = SurfaceTable::<f64, 8, 65>::closed(smoothing, 65).unwrap();
        t.draw(&tu, &tv, &mut pos, &mut nor).unwrap();
        let gap = pos
            .iter()
            .map(|p| {
                rods.iter()
                    .map(|r| r.distance(*p).0)
                    .fold(f64::MAX, f64::min)
            })
            .fold(f64::MAX, f64::min);
        eprintln!("{touch:?}: centre at {centre:.3} m, drawn surface {gap:.4} m from the rods");
        assert!(centre > 0.2, "{touch:?} rests on the rods: {centre}");
        assert!(gap > 0.9 * thickness, "{touch:?}: {gap}");
    }
}
