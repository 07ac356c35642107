//! Reeling a rope in and paying it out (`Rope::length`, `set_length`, `reel`): the rope
//! follows its new length in every integrator and format, an inextensible chain holds every
//! link at it while it reels, and what is refused leaves the rope as it was.

use dunas::integrator::{DirectChain, DirectSprings, ImplicitEuler, SymplecticEuler, Verlet, Xpbd};
use dunas::prelude::*;

/// A rope of 12 particles, 10 units long and of mass 2, hanging from the origin with a bob
/// of 20 on its end, reeled in to 5 at 2 units a second, then paid out to 8, then left to
/// settle: the bob's depth (units) at the end, and the largest link stretch a `DirectChain`
/// step reported while reeling.
fn reeled<S: Scalar, I: Integrator>(solver: I) -> (f64, f64) {
    let f = |x: f64| S::from_f64(x);
    let settings = Settings {
        gravity: Vec2::new(f(0.0), f(-9.81)),
        damping: f(1.0),
        ..Settings::default()
    }
    .with_integrator(solver);
    // `Q16` holds stiffness up to 32 767 (an inextensible chain ignores it).
    let k = if S::FIXED_POINT { 2e4 } else { 1e5 };
    let material = Material {
        stiffness: f(k),
        damping: f(20.0),
    };
    let (top, bottom) = (Vec2::new(f(0.0), f(0.0)), Vec2::new(f(0.0), f(-10.0)));
    let mut rope: Rope<Vec2<S>, 12, 12, I> =
        Rope::new(top, bottom, f(2.0), material, settings).unwrap();
    rope.hang(11, f(20.0)).unwrap();
    let dt = S::ratio(1, 60);
    let mut stretch = 0.0f64;
    for (target, frames) in [(5.0, 240), (8.0, 240), (8.0, 600)] {
        for _ in 0..frames {
            rope.reel(f(target), f(2.0), dt).unwrap();
            let info = rope.step(dt).unwrap();
            stretch = stretch.max(info.stretch.to_f64());
        }
        assert!(
            (rope.length().to_f64() - target).abs() <= 1e-3 * target,
            "{:?}",
            rope.length()
        );
    }
    (-rope.positions()[11].y.to_f64(), stretch)
}

/// The bob hangs at the rope's new length (8) plus what its springs stretch under the
/// weights below them (statics: 0.3% here), within 1%, in every integrator, in
/// `f32`, `f64` and `Q16`; an inextensible `DirectChain` keeps every link within 0.1% of
/// its changing length at the end of every step.
#[test]
fn a_reeled_rope_hangs_at_its_new_length_in_every_integrator() {
    let check = |name: &str, (depth, stretch): (f64, f64), holds: bool| {
        eprintln!(
            "{name}: the bob {depth:.4} deep, links within {:.4}%",
            stretch * 100.0
        );
        assert!((depth - 8.0).abs() <= 0.01 * 8.0, "{name}: {depth}");
        if holds {
            assert!(stretch <= 1e-3, "{name}: {stretch}");
        }
    };
    check("symplectic Euler", reeled::<f64, _>(SymplecticEuler), false);
    check("Verlet", reeled::<f64, _>(Verlet), false);
    check(
        "backward Euler",
        reeled::<f64, _>(ImplicitEuler::default()),
        false,
    );
    check(
        "XPBD, 16 substeps",
        reeled::<f64, _>(Xpbd { substeps: 16 }),
        false,
    );
    check(
        "DirectSprings",
        reeled::<f32, _>(DirectSprings::default()),
        false,
    );
    check(
        "DirectChain",
        reeled::<f32, _>(DirectChain::default()),
        true,
    );
    check(
        "DirectChain, f64",
        reeled::<f64, _>(DirectChain::default()),
        true,
    );
    #[cfg(feature = "fixed")]
    check(
        "DirectChain, Q16",
        reeled::<Q16, _>(DirectChain::default()),
        true,
    );
}

/// What `set_length` and `reel` refuse (a length of 0, negative, NaN, beyond the limits; a
/// negative speed or `dt`) is an `InvalidParameter`, and the rope is as it was (its
/// checksum unchanged); the limits are the documented ones.
#[test]
fn a_refused_length_leaves_the_rope_as_it_was() {
    let settings = Settings::default();
    let material = Material {
        stiffness: 400.0,
        damping: 0.5,
    };
    let mut rope: Rope<Vec2<f32>, 8> = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(7.0, 0.0),
        1.0,
        material,
        settings,
    )
    .unwrap();
    let before = rope.state_hash();
    let (shortest, longest) = Rope::<Vec2<f32>, 8>::length_limits();
    assert_eq!(shortest, 7.0 * 1024.0 * f32::EPSILON);
    assert_eq!(longest, f32::SAFE_RANGE);
    for length in [
        0.0,
        -1.0,
        f32::NAN,
        f32::INFINITY,
        0.5 * shortest,
        2.0 * longest,
    ] {
        assert!(
            matches!(rope.set_length(length), Err(Error::InvalidParameter { .. })),
            "{length}"
        );
        assert!(rope.reel(length, 1.0, 0.1).is_err(), "{length}");
    }
    for (speed, dt) in [
        (-1.0, 0.1),
        (1.0, -0.1),
        (f32::NAN, 0.1),
        (1.0, f32::INFINITY),
    ] {
        assert!(rope.reel(3.0, speed, dt).is_err(), "{speed} {dt}");
    }
    assert_eq!(rope.state_hash(), before);
    assert_eq!(rope.length(), 7.0);
    // At the limits themselves: taken.
    rope.set_length(shortest).unwrap();
    rope.set_length(7.0).unwrap();
    assert!((rope.length() - 7.0).abs() < 1e-5);
}

/// The grappling hook: a 12-particle, 10 m, 2 kg rope with a 70 kg player on its end,
/// swinging from level under `solver`, reeled in to 2 m at 4 m/s (2 s) over its first 150
/// frames: each frame's chain (the particles' distances summed), the rope's
/// length, and what its step reported (converged, the largest stretch); and the sharpest
/// corner of its drawn Catmull-Rom curves (64 points).
fn grapple(solver: DirectChain) -> (Vec<(f64, f64, bool, f64)>, f64) {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        ..Settings::default()
    }
    .with_integrator(solver);
    let material = Material {
        stiffness: 2000.0,
        damping: 1.0,
    };
    let (hook, player) = (Vec2::new(0.0, 0.0), Vec2::new(-10.0, 0.0));
    let mut rope: Rope<Vec2<f32>, 12, 12, DirectChain> =
        Rope::new(hook, player, 2.0, material, settings).unwrap();
    rope.set_inv_mass(0, 0.0).unwrap();
    rope.hang(11, 70.0).unwrap();
    let (mut frames, mut corner) = (Vec::new(), 0.0f64);
    let mut drawn = [Vec2::default(); 64];
    for _ in 0..150 {
        rope.reel(2.0, 4.0, 1.0 / 60.0).unwrap();
        let info = rope.step(1.0 / 60.0).unwrap();
        let chain: f64 = (rope.positions().windows(2))
            .map(|w| f64::from(w[0].distance(w[1])))
            .sum();
        let length = f64::from(rope.length());
        frames.push((chain, length, info.converged, f64::from(info.stretch)));
        let n = rope.sample(Smoothing::CatmullRom, &mut drawn).unwrap();
        let line: Vec<Vec2<f64>> = drawn[..n]
            .iter()
            .map(|p| Vec2::new(f64::from(p.x), f64::from(p.y)))
            .collect();
        corner = corner.max(crate::common::sharpest_corner(&line));
    }
    (frames, corner)
}

/// Reeled from 10 m to 2 m in 2 s under a 70 kg player (35 times the rope's mass) while it
/// swings, an inextensible `DirectChain` of 8 iterations a solve holds the chain within
/// 0.5% of the rope's length at every frame, and its drawn curve has no corner sharper than
/// the smooth rope's at rest (4.4°). At the default 4 iterations some frames end further
/// off (1.5% at worst): each of those says so (`converged` false, its `stretch` at least
/// the chain's).
#[test]
fn a_grappling_hook_reels_its_player_in_at_its_length() {
    let eight = DirectChain {
        iterations: 8,
        ..DirectChain::default()
    };
    let (reeled, corner) = grapple(eight);
    for (frame, &(chain, length, _, _)) in reeled.iter().enumerate() {
        assert!(
            (chain - length).abs() <= 5e-3 * length,
            "frame {frame}: the chain {chain} m, the rope {length} m"
        );
    }
    assert!((reeled[reeled.len() - 1].1 - 2.0).abs() < 1e-4);
    // The 8-particle Catmull-Rom rope's sharpest drawn corner at rest, 64 points
    // (`docs/summary.md`, section (c)): the smooth rope's look.
    assert!(corner <= 4.4, "{corner}° reeled");
    let (defaults, _) = grapple(DirectChain::default());
    for (frame, &(chain, length, converged, stretch)) in defaults.iter().enumerate() {
        let off = (chain - length).abs() / length;
        if off > 1e-3 {
            assert!(
                !converged && stretch >= off,
                "frame {frame}: {off} off, {stretch} reported"
            );
        }
    }
}
