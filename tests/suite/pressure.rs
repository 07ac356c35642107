//! The gas in a closed loop (`force::Pressure`) against closed forms: a pressurised ring at
//! rest where its springs balance its gas, a rolling jelly that keeps its area, and bad input.
#![cfg(any(feature = "std", feature = "libm"))]

use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::force::Pressure;
use dunas::smooth::Smoothed;
use dunas::spring::{Material, Springs, Topology};
use dunas::{Error, Point, Rope, Settings, Smoothing, Vec2};

const N: usize = 16;

/// A ring of `N` particles of `radius` around `centre`, 1 kg in all, its loop springs of `k`
/// relaxed at that radius.
fn ring(
    centre: Vec2<f64>,
    radius: f64,
    k: f64,
    settings: Settings<Vec2<f64>>,
) -> Rope<Vec2<f64>, N> {
    let points: [Vec2<f64>; N] = core::array::from_fn(|i| {
        let a = std::f64::consts::TAU * i as f64 / N as f64;
        centre + Vec2::new(radius * a.cos(), radius * a.sin())
    });
    let springs = Springs::closed_loop(
        &points,
        Material {
            stiffness: k,
            damping: 0.5,
        },
    )
    .unwrap();
    Rope::from_parts(points, [N as f64; N], springs, settings).unwrap()
}

/// The radius at which a regular `N`-gon of springs `k` (rest side `rest`) balances the gas
/// `amount`: the edges' push `p·s·cos(π/N)` against the springs' pull `2·k·(s − rest)·sin(π/N)`,
/// `s = 2r·sin(π/N)`, `p = amount / area`, `area = (N/2)·r²·sin(2π/N)`; by bisection.
fn balanced_radius(amount: f64, k: f64, rest: f64) -> f64 {
    let t = std::f64::consts::PI / N as f64;
    let net = |r: f64| {
        let s = 2.0 * r * t.sin();
        let area = N as f64 / 2.0 * r * r * (2.0 * t).sin();
        amount / area * s * t.cos() - 2.0 * k * (s - rest) * t.sin()
    };
    let (mut lo, mut hi) = (rest / (2.0 * t.sin()), 100.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if net(mid) > 0.0 { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// Mean distance of the particles from their centroid.
fn mean_radius(x: &[Vec2<f64>]) -> f64 {
    let c = x.iter().fold(Vec2::new(0.0, 0.0), |s, &p| s + p) * (1.0 / x.len() as f64);
    x.iter().map(|p| p.distance(c)).sum::<f64>() / x.len() as f64
}

/// The ring comes to rest within 1% of the radius where its springs balance its gas.
#[test]
fn a_pressurised_ring_rests_at_its_closed_form_radius() {
    let settings = Settings {
        damping: 2.0,
        ..Settings::default()
    };
    let k = 200.0;
    let rest = 2.0 * (std::f64::consts::PI / N as f64).sin();
    for amount in [2.0, 10.0, 40.0] {
        let mut jelly = ring(Vec2::new(0.0, 0.0), 1.0, k, settings);
        let mut gas = Pressure::new(amount).unwrap();
        for _ in 0..900 {
            let _ = jelly.step_with(1.0 / 60.0, &mut gas).unwrap();
        }
        let (got, want) = (
            mean_radius(jelly.positions()),
            balanced_radius(amount, k, rest),
        );
        eprintln!("amount {amount}: radius {got:.5} m against {want:.5} m");
        assert!(
            (got - want).abs() <= 0.01 * want,
            "{amount}: {got} against {want}"
        );
    }
}

/// A jelly dropped on a floor and rolled along it keeps its area within 2% of the area it
/// rests at, touching the floor with its particles (which then stay above it) and with its
/// drawn closed curve (which then stays above it; a B-spline's particles lie outside its
/// curve, so they may dip below).
#[test]
fn a_rolling_jelly_keeps_its_area() {
    for touch in [Touch::Particles, Touch::DrawnLoop(Smoothing::BSpline)] {
        let settings = Settings {
            gravity: Vec2::new(0.0, -9.81),
            damping: 0.1,
            ..Settings::default()
        };
        let mut jelly = ring(Vec2::new(0.0, 0.55), 0.5, 3000.0, settings);
        let mut gas = Pressure::at(200.0, Pressure::area(jelly.positions())).unwrap();
        let floor = [
            Collider::half_space(Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0))
                .unwrap()
                .with_friction(0.8, 0.6)
                .unwrap(),
        ];
        let contacts = Contacts::new(&floor, 0.0, touch).unwrap();
        let mut drawn = [Vec2::new(0.0, 0.0); 4 * N + 1];
        let mut step = |jelly: &mut Rope<Vec2<f64>, N>| {
            let _ = jelly
                .step_touching(1.0 / 60.0, &mut gas, &contacts)
                .unwrap();
            let n = Smoothed::closed(Smoothing::BSpline, jelly.position_array())
                .unwrap()
                .sample(&mut drawn)
                .unwrap();
            drawn[..n].iter().map(|p| p.y).fold(f64::INFINITY, f64::min)
        };
        for _ in 0..120 {
            step(&mut jelly);
        }
        let resting = Pressure::area(jelly.positions());
        for i in 0..N {
            jelly.set_velocity(i, Vec2::new(2.0, 0.0)).unwrap();
        }
        let (mut least, mut most, start) = (resting, resting, mean_x(&jelly));
        let mut lowest = f64::INFINITY;
        for _ in 0..180 {
            lowest = lowest.min(step(&mut jelly));
            let area = Pressure::area(jelly.positions());
            (least, most) = (least.min(area), most.max(area));
            if touch == Touch::Particles {
                assert!(jelly.positions().iter().all(|p| p.y >= -1e-9));
            }
        }
        let travelled = mean_x(&jelly) - start;
        eprintln!(
            "{touch:?}: rolled {travelled:.2} m, area {least:.4}..{most:.4} m² around \
             {resting:.4} m², drawn curve down to {lowest:.2e} m"
        );
        assert!(travelled > 1.0, "it rolled: {travelled}");
        assert!(least >= 0.98 * resting && most <= 1.02 * resting);
        if touch != Touch::Particles {
            assert!(
                lowest >= -1e-6,
                "the drawn curve stays above the floor: {lowest}"
            );
        }
    }
}

/// Squashed on a floor by its weight, a jelly rests where its springs, its gas and its
/// weight balance by the virial identity (each particle at rest: `Σ x · F = 0` over springs,
/// gas, gravity and the floor's push at the contact height), `Σ k (l − r) l = 2 · amount −
/// W (ȳ − t)`, within 1% of `2 · amount`, for weights from 5 to 80 N: the heavier, the
/// smaller its area and the harder its gas pushes (`p = amount / area`).
#[test]
fn a_jelly_squashed_by_its_weight_balances_by_the_gas_law() {
    let (amount, thickness, mass) = (20.0, 0.01, 1.0);
    let mut last_area = f64::INFINITY;
    for g in [5.0, 20.0, 80.0] {
        let settings = Settings {
            gravity: Vec2::new(0.0, -g),
            damping: 3.0,
            ..Settings::default()
        };
        let mut jelly = ring(Vec2::new(0.0, 0.6), 0.5, 400.0, settings);
        let mut gas = Pressure::new(amount).unwrap();
        let floor = [Collider::half_space(Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0)).unwrap()];
        let contacts = Contacts::new(&floor, thickness, Touch::Particles).unwrap();
        for _ in 0..1200 {
            let _ = jelly
                .step_touching(1.0 / 60.0, &mut gas, &contacts)
                .unwrap();
        }
        let x = jelly.positions();
        let mut springs = 0.0;
        jelly.topology().for_each_spring(|a, b, rest, m| {
            let l = x[a].distance(x[b]);
            springs += m.stiffness * (l - rest) * l;
        });
        let (weight, height) = (mass * g, x.iter().map(|p| p.y).sum::<f64>() / N as f64);
        let balance = 2.0 * amount - weight * (height - thickness);
        let area = Pressure::area(x);
        let speed = jelly
            .velocities()
            .iter()
            .map(|v| v.length())
            .fold(0.0, f64::max);
        eprintln!(
            "{weight} N: area {area:.4} m², pressure {:.2} N/m; Σk(l−r)l {springs:.4} against \
             {balance:.4}; fastest particle {speed:.1e} m/s",
            amount / area
        );
        assert!(speed < 1e-3, "at rest: {speed}");
        assert!(
            (springs - balance).abs() <= 0.01 * 2.0 * amount,
            "{springs} against {balance}"
        );
        assert!(
            area < last_area,
            "squashed smaller: {area} after {last_area}"
        );
        last_area = area;
    }
}

fn mean_x(rope: &Rope<Vec2<f64>, N>) -> f64 {
    rope.positions().iter().map(|p| p.x).sum::<f64>() / N as f64
}

/// Bad gas is an `Err`; a loop with no area gets no push, never a NaN.
#[test]
fn bad_gas_is_refused_and_a_flat_loop_gets_no_push() {
    assert!(matches!(
        Pressure::new(f64::NAN),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        Pressure::new(-1.0),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        Pressure::at(1.0, f64::INFINITY),
        Err(Error::InvalidParameter { .. })
    ));
    // A loop folded flat along a line: area 0.
    let points: [Vec2<f64>; 4] = [
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(2.0, 0.0),
        Vec2::new(1.0, 0.0),
    ];
    assert_eq!(Pressure::area(&points), 0.0);
    let springs = Springs::<f64, 4>::chain(
        &points,
        Material {
            stiffness: 10.0,
            damping: 0.0,
        },
    )
    .unwrap();
    let mut flat = Rope::from_parts(points, [1.0; 4], springs, Settings::default()).unwrap();
    let mut gas = Pressure::new(5.0).unwrap();
    let _ = flat.step_with(1.0 / 60.0, &mut gas).unwrap();
    assert!(flat.positions().iter().all(|p| p.is_finite()));
    assert_eq!(flat.positions()[1], Vec2::new(1.0, 0.0), "no push");
}

/// Held by one particle, swung and let go, a jelly's centre of mass flies the closed-form
/// ballistic arc from its speed at the release (the gas's pushes sum to zero), within 1% of
/// its fall; over-blown, its loop tears and `pop` lets it go limp.
#[test]
fn a_jelly_is_thrown_and_pops() {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        ..Settings::default()
    };
    let mut jelly = ring(Vec2::new(0.0, 0.0), 0.3, 2000.0, settings);
    let mut gas = Pressure::at(100.0, Pressure::area(jelly.positions())).unwrap();
    jelly.set_inv_mass(0, 0.0).unwrap();
    for frame in 1..=30 {
        let t = frame as f64 / 60.0;
        let hand = Vec2::new(0.3 * t * t * 60.0 / 30.0, 0.0);
        jelly.move_pinned(0, hand, 1.0 / 60.0).unwrap();
        let _ = jelly.step_with(1.0 / 60.0, &mut gas).unwrap();
    }
    jelly.set_inv_mass(0, N as f64).unwrap();
    let com = |r: &Rope<Vec2<f64>, N>| {
        r.positions()
            .iter()
            .fold(Vec2::new(0.0, 0.0), |s, &p| s + p)
            * (1.0 / N as f64)
    };
    let momentum = |r: &Rope<Vec2<f64>, N>| {
        r.velocities()
            .iter()
            .fold(Vec2::new(0.0, 0.0), |s, &v| s + v)
            * (1.0 / N as f64)
    };
    let (start, speed) = (com(&jelly), momentum(&jelly));
    for _ in 0..60 {
        let _ = jelly.step_with(1.0 / 60.0, &mut gas).unwrap();
    }
    let arc = start + speed * 1.0 + Vec2::new(0.0, -9.81 / 2.0);
    let off = com(&jelly).distance(arc);
    eprintln!(
        "thrown: centre {:?} against the arc's {arc:?} ({off:.4} m off)",
        com(&jelly)
    );
    assert!(off <= 0.01 * 4.905, "{off}");
    // Blown up past what its springs hold: a spring tears, the game lets the gas out.
    let mut balloon = ring(
        Vec2::new(0.0, 0.0),
        0.3,
        200.0,
        Settings {
            damping: 1.0,
            ..Settings::default()
        },
    );
    balloon.set_snap(dunas::spring::Snap::Stretch(1.3)).unwrap();
    let mut gas = Pressure::at(2000.0, Pressure::area(balloon.positions())).unwrap();
    let mut popped = false;
    for _ in 0..120 {
        let info = balloon.step_with(1.0 / 60.0, &mut gas).unwrap();
        if info.snapped > 0 && !popped {
            gas.pop();
            popped = true;
        }
    }
    assert!(popped && gas.amount() == 0.0);
    assert!(balloon.positions().iter().all(|p| p.is_finite()));
}

/// A `Q16` loop too large for its area to fit the format gets no push and the step says
/// `saturated`; nothing leaves the range.
#[cfg(feature = "fixed")]
#[test]
fn a_q16_loop_too_large_for_its_area_is_reported() {
    use dunas::{Q16, Scalar};
    let q = Q16::from_f64;
    let points: [Vec2<Q16>; 4] = [
        Vec2::new(q(-150.0), q(-150.0)),
        Vec2::new(q(150.0), q(-150.0)),
        Vec2::new(q(150.0), q(150.0)),
        Vec2::new(q(-150.0), q(150.0)),
    ];
    assert!(!Pressure::signed_area(&points).is_finite()); // 90 000 square units
    let springs = Springs::<Q16, 4>::closed_loop(
        &points,
        Material {
            stiffness: q(1.0),
            damping: q(0.0),
        },
    )
    .unwrap();
    let mut square = Rope::from_parts(points, [Q16::ONE; 4], springs, Settings::default()).unwrap();
    let mut gas = Pressure::new(q(10.0)).unwrap();
    let info = square.step_with(Q16::ratio(1, 60), &mut gas).unwrap();
    assert!(info.saturated);
    assert_eq!(square.positions(), &points);
}
