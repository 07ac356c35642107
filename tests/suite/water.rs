//! The water row (`water::Water`) against closed forms: a standing wave's period as the
//! discrete chain's, the energy of undamped waves, Archimedes for a floating box, the waves a
//! dropped box makes, and bad input.
#![cfg(any(feature = "std", feature = "libm"))]

use dunas::water::{Floater, Water};
use dunas::{Error, Smoothing, Vec2};

const N: usize = 64;

/// A 6.4 m basin of 64 columns, 1 m deep, waves at 2 m/s, its surface in its first mode.
fn basin(amplitude: f64) -> Water<f64, N> {
    let mut water = Water::<f64, N>::new(0.0, 0.1, 1.0, 2.0, 1000.0).unwrap();
    for i in 0..N {
        let x = std::f64::consts::PI * (i as f64 + 0.5) / N as f64;
        water.set_height(i, 1.0 + amplitude * x.cos()).unwrap();
    }
    water
}

/// The first standing wave of a basin with walls swings with the discrete chain's period,
/// `2π / ω`, `ω = (2c / spacing) · sin(π / 2N)`: its long-wave speed within 2% (it is within
/// 0.1%).
#[test]
fn a_standing_wave_keeps_the_discrete_chains_period() {
    let mut water = basin(0.01);
    let omega = 2.0 * 2.0 / 0.1 * (std::f64::consts::PI / (2.0 * N as f64)).sin();
    let expected = std::f64::consts::TAU / omega;
    let (dt, mut t, mut last, mut crossings) = (1.0 / 240.0, 0.0, 0.01, Vec::new());
    while crossings.len() < 7 {
        let _ = water.step(dt, 9.81, &mut []).unwrap();
        t += dt;
        let now = water.heights()[0] - 1.0;
        if (last > 0.0) != (now > 0.0) {
            crossings.push(t - dt * now / (now - last));
        }
        last = now;
    }
    let period = (crossings[6] - crossings[0]) / 3.0;
    eprintln!("period {period:.5} s against {expected:.5} s");
    assert!(
        (period - expected).abs() <= 0.001 * expected,
        "{period} against {expected}"
    );
}

/// Undamped, the waves' energy stays bounded over 60 s (symplectic Euler's swing, no drift):
/// the first mode within 1%, a splash that excites every mode within 35% (its shortest
/// waves swing at `ω·h` up to 0.67 a step; the documented bounds of `Water`).
#[test]
fn undamped_waves_keep_their_energy() {
    let mut splash = Water::<f64, N>::new(0.0, 0.1, 1.0, 2.0, 1000.0).unwrap();
    splash.set_height(20, 1.05).unwrap();
    for (mut water, bound) in [(basin(0.02), 0.01), (splash, 0.35)] {
        let start = water.energy();
        let (mut worst, mut late) = (0.0f64, 0.0f64);
        for frame in 0..3600 {
            let _ = water.step(1.0 / 60.0, 9.81, &mut []).unwrap();
            let off = (water.energy() / start - 1.0).abs();
            worst = worst.max(off);
            if frame >= 3000 {
                late = late.max(off);
            }
        }
        eprintln!(
            "energy within {:.3}% (last 10 s: {:.3}%)",
            worst * 100.0,
            late * 100.0
        );
        assert!(worst <= bound, "{worst}");
    }
}

/// A box floats as deep below the surface under it as Archimedes says, within 1%, for a
/// light and a heavy box; the water keeps its volume.
#[test]
fn a_floating_box_rests_at_archimedes_depth() {
    for mass in [40.0, 150.0] {
        let mut water = Water::<f64, 32>::new(0.0, 0.25, 1.0, 2.0, 1000.0)
            .unwrap()
            .with_damping(2.0)
            .unwrap();
        let volume: f64 = water.heights().iter().sum();
        let mut boat = [Floater::new(4.0, 1.1, 0.6, 0.5, mass).unwrap()];
        for _ in 0..1800 {
            let _ = water.step(1.0 / 60.0, 9.81, &mut boat).unwrap();
        }
        let depth = water.surface_under(4.0, 0.6) - boat[0].bottom;
        let archimedes = mass / (1000.0 * 0.6);
        eprintln!("{mass} kg: {depth:.5} m deep against {archimedes:.5} m");
        assert!((depth - archimedes).abs() <= 0.01 * archimedes);
        let after: f64 = water.heights().iter().sum();
        assert!(
            (after - volume).abs() < 1e-9 * volume,
            "{after} against {volume}"
        );
    }
}

/// A box dropped into still water makes waves that reach the far wall; its surface draws as
/// a smooth curve.
#[test]
fn a_dropped_box_makes_waves() {
    let mut water = Water::<f64, N>::new(0.0, 0.1, 1.0, 2.0, 1000.0).unwrap();
    let mut boat = [Floater::new(1.0, 1.3, 0.4, 0.5, 60.0).unwrap()];
    let mut highest = 1.0f64;
    for _ in 0..180 {
        let _ = water.step(1.0 / 60.0, 9.81, &mut boat).unwrap();
        highest = highest.max((water.heights()[N - 1] - 1.0).abs() + 1.0);
    }
    assert!(highest > 1.001, "the far wall saw a wave: {highest}");
    let mut curve = [Vec2::new(0.0, 0.0); 4 * (N - 1) + 1];
    assert_eq!(
        water.draw(Smoothing::CatmullRom, &mut curve),
        Ok(curve.len())
    );
    assert_eq!(curve[0].y, water.heights()[0]);
}

/// Bad input is an `Err` and changes nothing.
#[test]
fn bad_water_and_bodies_are_refused() {
    assert!(Water::<f64, 8>::new(0.0, 0.0, 1.0, 2.0, 1000.0).is_err());
    assert!(Water::<f64, 8>::new(0.0, 0.1, f64::NAN, 2.0, 1000.0).is_err());
    assert!(Water::<f64, 1>::new(0.0, 0.1, 1.0, 2.0, 1000.0).is_err());
    assert!(Floater::new(0.0, 1.0, -1.0, 0.5, 10.0).is_err());
    let mut water = Water::<f64, 8>::new(0.0, 0.1, 1.0, 2.0, 1000.0).unwrap();
    let before = water.heights().to_owned();
    // Heavier than the water its box can displace: it would sink through the row.
    let mut stone = [Floater::new(0.4, 1.0, 0.2, 0.2, 50.0).unwrap()];
    assert!(matches!(
        water.step(1.0 / 60.0, 9.81, &mut stone),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(water.step(f64::NAN, 9.81, &mut []).is_err());
    // A frame longer than 64 stable substeps: slow motion, never a blow-up.
    let mut long = Water::<f64, 8>::new(0.0, 0.1, 1.0, 2.0, 1000.0).unwrap();
    long.set_height(3, 1.1).unwrap();
    let info = long.step(10.0, 9.81, &mut []).unwrap();
    assert!(info.slow_motion && info.substeps == 64 && info.simulated < 10.0);
    assert!(
        long.heights()
            .iter()
            .all(|h| h.is_finite() && (h - 1.0).abs() < 0.2)
    );
    assert_eq!(water.heights().to_owned(), before);
    assert_eq!(stone[0].bottom, 1.0);
}

/// The same box in `Q16`: Archimedes' depth within 1%.
#[cfg(feature = "fixed")]
#[test]
fn a_q16_box_floats_at_archimedes_depth() {
    use dunas::{Q16, Scalar};
    let q = Q16::from_f64;
    let mut water = Water::<Q16, 32>::new(q(0.0), q(0.25), q(1.0), q(2.0), q(1000.0))
        .unwrap()
        .with_damping(q(2.0))
        .unwrap();
    let mut boat = [Floater::new(q(4.0), q(1.1), q(0.6), q(0.5), q(150.0)).unwrap()];
    for _ in 0..1800 {
        let _ = water.step(Q16::ratio(1, 60), q(9.81), &mut boat).unwrap();
    }
    let depth = (water.surface_under(q(4.0), q(0.6)) - boat[0].bottom).to_f64();
    let archimedes = 150.0 / (1000.0 * 0.6);
    eprintln!("Q16: {depth:.5} m deep against {archimedes:.5} m");
    assert!((depth - archimedes).abs() <= 0.01 * archimedes);
}
