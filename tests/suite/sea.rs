//! The sea (`water::Sea`, a grid of water columns) against closed forms: standing waves'
//! periods as the discrete grid's, the energy of undamped waves, Archimedes for a floating
//! hull, the volume kept, the waves a dropped hull makes, and bad input.
#![cfg(any(feature = "std", feature = "libm"))]

use dunas::surface::SurfaceTable;
use dunas::water::{Hull, Sea};
use dunas::{Error, Point, Smoothing, Vec3};
use std::f64::consts::PI;

const U: usize = 32;
const V: usize = 24;
/// Spacing (m) and the waves' speed (m/s).
const S: f64 = 0.2;
const C: f64 = 2.0;

/// A 6.4 × 4.8 m basin, 1 m deep, its surface in standing mode `(m, n)`.
fn basin(m: usize, n: usize, amplitude: f64) -> Sea<f64, U, V> {
    let mut sea = Sea::<f64, U, V>::new((0.0, 0.0), S, 1.0, C, 1000.0).unwrap();
    for j in 0..V {
        for i in 0..U {
            let x = (PI * m as f64 * (i as f64 + 0.5) / U as f64).cos();
            let z = (PI * n as f64 * (j as f64 + 0.5) / V as f64).cos();
            sea.set_height(i, j, 1.0 + amplitude * x * z).unwrap();
        }
    }
    sea
}

/// The period of the basin's corner column, from 6 crossings of the still level.
fn period(sea: &mut Sea<f64, U, V>) -> f64 {
    let (dt, mut t, mut last, mut crossings) = (1.0 / 240.0, 0.0, 0.01, Vec::new());
    while crossings.len() < 7 {
        let _ = sea.step(dt, 9.81, &mut []).unwrap();
        t += dt;
        let now = sea.heights()[0][0] - 1.0;
        if (last > 0.0) != (now > 0.0) {
            crossings.push(t - dt * now / (now - last));
        }
        last = now;
    }
    (crossings[6] - crossings[0]) / 3.0
}

/// A standing wave swings with the discrete grid's period, `2π / ω`,
/// `ω = (2c / s) · √(sin²(πm / 2U) + sin²(πn / 2V))`: the long wave along a row (its speed
/// within 2% of the discrete chain's; it is within 0.01%) and a diagonal one.
#[test]
fn standing_waves_keep_the_discrete_grids_period() {
    for (m, n) in [(1, 0), (1, 1)] {
        let mut sea = basin(m, n, 0.01);
        let sin2 = |k: usize, count: usize| (PI * k as f64 / (2.0 * count as f64)).sin().powi(2);
        let omega = 2.0 * C / S * (sin2(m, U) + sin2(n, V)).sqrt();
        let expected = 2.0 * PI / omega;
        let got = period(&mut sea);
        eprintln!("mode ({m}, {n}): period {got:.5} s against {expected:.5} s");
        assert!(
            (got - expected).abs() <= 1e-4 * expected,
            "{got} against {expected}"
        );
    }
}

/// Undamped, the waves' energy stays bounded over 60 s: the long wave within 1% (the bound
/// of symplectic Euler's swing, `ω·h / 2`), a splash that excites every wave within 35%.
#[test]
fn undamped_sea_waves_keep_their_energy() {
    let mut splash = Sea::<f64, U, V>::new((0.0, 0.0), S, 1.0, C, 1000.0).unwrap();
    splash.set_height(10, 7, 1.05).unwrap();
    for (mut sea, bound) in [(basin(1, 0, 0.02), 0.01), (splash, 0.35)] {
        let start = sea.energy();
        let mut worst = 0.0f64;
        for _ in 0..3600 {
            let _ = sea.step(1.0 / 60.0, 9.81, &mut []).unwrap();
            worst = worst.max((sea.energy() / start - 1.0).abs());
        }
        eprintln!("energy within {:.3}%", worst * 100.0);
        assert!(worst <= bound, "{worst}");
    }
}

/// A hull floats as deep below the surface under it as Archimedes says, within 1%, for a
/// light and a heavy hull; the sea keeps its volume.
#[test]
fn a_floating_hull_rests_at_archimedes_depth() {
    for mass in [40.0, 150.0] {
        let mut sea = Sea::<f64, U, V>::new((0.0, 0.0), S, 1.0, C, 1000.0)
            .unwrap()
            .with_damping(2.0)
            .unwrap();
        let volume: f64 = sea.heights().iter().flatten().sum();
        let mut hull = [Hull::new((3.1, 2.3), 1.1, (0.6, 1.0, 0.8), mass).unwrap()];
        for _ in 0..1800 {
            let _ = sea.step(1.0 / 60.0, 9.81, &mut hull).unwrap();
        }
        let depth = sea.surface_under((3.1, 2.3), (0.6, 1.0)) - hull[0].bottom;
        let archimedes = mass / (1000.0 * 0.6 * 1.0);
        eprintln!("{mass} kg: {depth:.5} m deep against {archimedes:.5} m");
        assert!((depth - archimedes).abs() <= 0.01 * archimedes);
        let after: f64 = sea.heights().iter().flatten().sum();
        assert!(
            (after - volume).abs() < 1e-9 * volume,
            "{after} against {volume}"
        );
    }
}

/// A hull dropped into still water makes waves that reach the far corner; the surface draws
/// through every column with normals pointing up.
#[test]
fn a_dropped_hull_makes_waves() {
    let mut sea = Sea::<f64, U, V>::new((0.0, 0.0), S, 1.0, C, 1000.0).unwrap();
    let mut hull = [Hull::new((1.0, 1.0), 1.3, (0.4, 0.4, 0.5), 40.0).unwrap()];
    let mut highest = 0.0f64;
    for _ in 0..240 {
        let _ = sea.step(1.0 / 60.0, 9.81, &mut hull).unwrap();
        highest = highest.max((sea.heights()[V - 1][U - 1] - 1.0).abs());
    }
    assert!(highest > 1e-3, "the far corner saw a wave: {highest}");
    let tu = SurfaceTable::<f64, U, 63>::new(Smoothing::CatmullRom, 63).unwrap();
    let tv = SurfaceTable::<f64, V, 47>::new(Smoothing::CatmullRom, 47).unwrap();
    let mut points = vec![Vec3::new(0.0, 0.0, 0.0); 63 * 47];
    let mut normals = points.clone();
    assert_eq!(sea.draw(&tu, &tv, &mut points, &mut normals), Ok(63 * 47));
    // Catmull-Rom passes through the columns: every other drawn point is a column's top.
    assert_eq!(points[0].y, sea.heights()[0][0]);
    assert_eq!(points[2 * 63 + 4].y, sea.heights()[1][2]);
    assert!(
        normals
            .iter()
            .all(|n| n.y > 0.5 && (n.length() - 1.0).abs() < 1e-9)
    );
}

/// Bad input is an `Err` and changes nothing; a frame past 64 stable substeps is slow
/// motion, not a blow-up.
#[test]
fn bad_seas_and_hulls_are_refused() {
    assert!(Sea::<f64, 8, 8>::new((0.0, 0.0), 0.0, 1.0, 2.0, 1000.0).is_err());
    assert!(Sea::<f64, 8, 8>::new((0.0, f64::NAN), 0.1, 1.0, 2.0, 1000.0).is_err());
    assert!(Sea::<f64, 8, 8>::new((0.0, 0.0), 0.1, 1.0, 2.0, -1.0).is_err());
    assert!(Sea::<f64, 8, 1>::new((0.0, 0.0), 0.1, 1.0, 2.0, 1000.0).is_err());
    assert!(
        Sea::<f64, 8, 8>::new((0.0, 0.0), 0.1, 1.0, 2.0, 1000.0)
            .unwrap()
            .with_damping(-1.0)
            .is_err()
    );
    assert!(Hull::new((0.0, 0.0), 1.0, (0.5, -1.0, 0.5), 10.0).is_err());
    assert!(Hull::new((0.0, 0.0), 1.0, (0.5, 0.5, 0.5), f64::NAN).is_err());
    let mut sea = Sea::<f64, 8, 8>::new((0.0, 0.0), 0.1, 1.0, 2.0, 1000.0).unwrap();
    assert!(matches!(
        sea.set_height(8, 0, 1.0),
        Err(Error::IndexOutOfRange { .. })
    ));
    assert!(sea.set_height(0, 0, f64::INFINITY).is_err());
    let before = sea.clone();
    // Heavier than the water its box can displace: it would sink through the sea.
    let mut stone = [Hull::new((0.4, 0.4), 1.0, (0.2, 0.2, 0.2), 10.0).unwrap()];
    assert!(matches!(
        sea.step(1.0 / 60.0, 9.81, &mut stone),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(sea.step(f64::NAN, 9.81, &mut []).is_err());
    assert!(sea.step(1.0 / 60.0, -9.81, &mut []).is_err());
    assert_eq!(sea, before);
    assert_eq!(stone[0].bottom, 1.0);
    let mut long = Sea::<f64, 8, 8>::new((0.0, 0.0), 0.1, 1.0, 2.0, 1000.0).unwrap();
    long.set_height(3, 4, 1.1).unwrap();
    let info = long.step(10.0, 9.81, &mut []).unwrap();
    assert!(info.slow_motion && info.substeps == 64 && info.simulated < 10.0);
    assert!(
        long.heights()
            .iter()
            .flatten()
            .all(|h| h.is_finite() && (h - 1.0).abs() < 0.2)
    );
}

/// The same hull in `Q16`: Archimedes' depth within 1%.
#[cfg(feature = "fixed")]
#[test]
fn a_q16_hull_floats_at_archimedes_depth() {
    use dunas::{Q16, Scalar};
    let q = Q16::from_f64;
    let mut sea = Sea::<Q16, 16, 12>::new((q(0.0), q(0.0)), q(0.4), q(1.0), q(2.0), q(1000.0))
        .unwrap()
        .with_damping(q(2.0))
        .unwrap();
    let mut hull =
        [Hull::new((q(3.1), q(2.3)), q(1.1), (q(0.6), q(1.0), q(0.8)), q(150.0)).unwrap()];
    for _ in 0..1800 {
        let _ = sea.step(Q16::ratio(1, 60), q(9.81), &mut hull).unwrap();
    }
    let depth = (sea.surface_under((q(3.1), q(2.3)), (q(0.6), q(1.0))) - hull[0].bottom).to_f64();
    let archimedes = 150.0 / (1000.0 * 0.6);
    eprintln!("Q16: {depth:.5} m deep against {archimedes:.5} m");
    assert!((depth - archimedes).abs() <= 0.01 * archimedes);
}
