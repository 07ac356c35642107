//! Sleep (`MassSpring::set_sleep`): an object at rest falls asleep in every integrator and
//! format, moves nothing while asleep, stays within the documented distance of an awake
//! run, wakes exactly when something can move it, and refuses a bad setting.

use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::force::{AnchorSpring, Wind};
use dunas::integrator::{DirectChain, DirectSprings, ImplicitEuler, SymplecticEuler, Verlet, Xpbd};
use dunas::prelude::*;

const DAMPING: f64 = 2.0;

/// An 8-particle rope of 7 units and mass 1 hanging from the origin, damped at 2/s, with
/// sleep at its defaults (1/100 unit a second for 30 steps).
fn hanging<S: Scalar, I: Integrator>(solver: I) -> Rope<Vec2<S>, 8, 8, I> {
    let f = |x: f64| S::from_f64(x);
    let settings = Settings {
        gravity: Vec2::new(f(0.0), f(-9.81)),
        damping: f(DAMPING),
        ..Settings::default()
    }
    .with_integrator(solver);
    let material = Material {
        stiffness: f(400.0),
        damping: f(1.0),
    };
    let (top, bottom) = (Vec2::new(f(0.0), f(0.0)), Vec2::new(f(3.0), f(-6.0)));
    let mut rope = Rope::new(top, bottom, f(1.0), material, settings).unwrap();
    rope.set_sleep(Some(Sleep::default())).unwrap();
    rope
}

/// Steps until the rope falls asleep (at most 20 s at 60 Hz); the frames it took.
fn until_asleep<S: Scalar, I: Integrator>(rope: &mut Rope<Vec2<S>, 8, 8, I>) -> usize {
    (1..=1200)
        .find(|_| {
            let _ = rope.step(S::ratio(1, 60)).unwrap();
            rope.is_asleep()
        })
        .expect("the rope never fell asleep")
}

fn asleep_everywhere<S: Scalar, I: Integrator>(solver: I, name: &str) {
    let mut rope = hanging::<S, I>(solver);
    let frames = until_asleep(&mut rope);
    eprintln!("{name}: asleep after {frames} frames");
    let (before, time) = (rope.positions().to_vec(), rope.time());
    for _ in 0..60 {
        let info = rope.step(S::ratio(1, 60)).unwrap();
        assert!(info.asleep && info.substeps == 0, "{name}: {info:?}");
    }
    assert_eq!(rope.positions(), &before[..], "{name}");
    let slept = (rope.time() - time).to_f64();
    assert!(
        (slept - 1.0).abs() < 1e-3,
        "{name}: the clock ran {slept} s"
    );
}

/// A damped rope at rest falls asleep in every integrator and in `f32`, `f64` and `Q16`;
/// asleep, its steps report it, take no substep, move nothing, and its clock runs on.
#[test]
fn a_rope_at_rest_falls_asleep_in_every_integrator_and_format() {
    asleep_everywhere::<f32, _>(SymplecticEuler, "symplectic Euler f32");
    asleep_everywhere::<f64, _>(SymplecticEuler, "symplectic Euler f64");
    asleep_everywhere::<Q16, _>(SymplecticEuler, "symplectic Euler Q16");
    asleep_everywhere::<f32, _>(Verlet, "Verlet");
    asleep_everywhere::<f32, _>(ImplicitEuler::default(), "implicit Euler");
    asleep_everywhere::<f32, _>(Xpbd::default(), "XPBD");
    asleep_everywhere::<f32, _>(DirectSprings::default(), "DirectSprings");
    asleep_everywhere::<f32, _>(DirectChain::default(), "DirectChain");
    asleep_everywhere::<Q16, _>(DirectChain::default(), "DirectChain Q16");
}

/// The largest distance between the particles of two ropes.
fn apart(a: &[Vec2<f32>], b: &[Vec2<f32>]) -> f32 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (*p - *q).length())
        .fold(0.0, f32::max)
}

/// A rope that sleeps stays within `2 · speed / damping` (the docs' bound: 1 cm here) of the
/// same rope awake, while it sleeps and after a hand moves both and they settle again.
#[test]
fn a_sleeping_rope_stays_within_the_bound_of_an_awake_one() {
    let mut sleeping = hanging::<f32, _>(SymplecticEuler);
    let mut awake = sleeping.clone();
    awake.set_sleep(None).unwrap();
    let bound = 2.0 * Sleep::<f32>::default().speed / DAMPING as f32;
    let (mut worst, mut slept) = (0.0f32, 0);
    for frame in 0..1800 {
        if frame == 900 {
            for rope in [&mut sleeping, &mut awake] {
                rope.move_pinned(0, Vec2::new(0.3, 0.0), 1.0 / 60.0)
                    .unwrap();
            }
        }
        let info = sleeping.step(1.0 / 60.0).unwrap();
        let _ = awake.step(1.0 / 60.0).unwrap();
        slept += usize::from(info.asleep);
        worst = worst.max(apart(sleeping.positions(), awake.positions()));
    }
    eprintln!(
        "asleep {slept} of 1 800 frames, at most {worst:.5} from the awake rope (bound {bound})"
    );
    assert!(slept > 1000, "{slept}");
    assert!(worst <= bound, "{worst} > {bound}");
}

/// Waking resumes exactly: a rope that slept for 100 frames and is woken steps to the same
/// bits as a copy taken the frame it fell asleep, woken and stepped at once.
#[test]
fn waking_resumes_from_the_state_it_fell_asleep_in() {
    let mut rope = hanging::<f32, _>(DirectSprings::default());
    until_asleep(&mut rope);
    let mut copy = rope.clone();
    for _ in 0..100 {
        let _ = rope.step(1.0 / 60.0).unwrap();
    }
    rope.wake();
    copy.wake();
    for _ in 0..30 {
        assert!(!rope.step(1.0 / 60.0).unwrap().asleep);
        let _ = copy.step(1.0 / 60.0).unwrap();
        assert_eq!(rope.positions(), copy.positions());
        assert_eq!(rope.velocities(), copy.velocities());
    }
}

/// Every way the game can move a sleeping rope wakes it, and its next step steps; a call
/// that changes nothing leaves it asleep.
#[test]
fn what_can_move_a_sleeping_rope_wakes_it() {
    type R = Rope<Vec2<f32>, 8, 8, SymplecticEuler>;
    let asleep = || {
        let mut rope = hanging::<f32, _>(SymplecticEuler);
        until_asleep(&mut rope);
        rope
    };
    let stays = |what: &str, change: &dyn Fn(&mut R)| {
        let mut rope = asleep();
        change(&mut rope);
        assert!(rope.is_asleep(), "{what} woke it");
        assert!(rope.step(1.0 / 60.0).unwrap().asleep, "{what}");
    };
    let wakes = |what: &str, change: &dyn Fn(&mut R)| {
        let mut rope = asleep();
        change(&mut rope);
        assert!(!rope.is_asleep(), "{what} left it asleep");
        assert!(!rope.step(1.0 / 60.0).unwrap().asleep, "{what}");
    };
    stays("the held end set where it is", &|r| {
        let p = r.positions()[0];
        r.set_position(0, p).unwrap();
    });
    stays("the hand still", &|r| {
        let p = r.positions()[0];
        r.move_pinned(0, p, 1.0 / 60.0).unwrap();
    });
    stays("a refused call", &|r| {
        assert!(r.set_position(99, Vec2::new(0.0, 0.0)).is_err());
    });
    wakes("a moved hand", &|r| {
        r.move_pinned(0, Vec2::new(0.1, 0.0), 1.0 / 60.0).unwrap()
    });
    wakes("a teleport", &|r| {
        r.set_position(3, Vec2::new(1.0, -2.0)).unwrap()
    });
    wakes("a velocity", &|r| {
        r.set_velocity(7, Vec2::new(1.0, 0.0)).unwrap()
    });
    wakes("an impulse", &|r| {
        r.apply_impulse(7, Vec2::new(0.1, 0.0)).unwrap()
    });
    wakes("a hung weight", &|r| r.hang(7, 1.0).unwrap());
    wakes("a pin", &|r| r.set_inv_mass(7, 0.0).unwrap());
    wakes("a reel", &|r| r.set_length(6.0).unwrap());
    wakes("gravity", &|r| {
        let s = Settings {
            gravity: Vec2::new(2.0, -9.81),
            ..*r.settings()
        };
        r.set_settings(s).unwrap();
    });
    wakes("wake()", &|r| r.wake());
    wakes("sleep set again", &|r| {
        r.set_sleep(Some(Sleep::default())).unwrap()
    });
}

/// A force field keeps the rope asleep while it stays the same and wakes it when it changes;
/// a gusty wind keeps it awake.
#[test]
fn force_fields_wake_a_rope_when_they_change() {
    let mut rope = hanging::<f32, _>(SymplecticEuler);
    let mut air = Wind::still(0.05);
    air.velocity = Vec2::new(1.0, 0.0);
    let mut hand = AnchorSpring::new(
        7,
        Vec2::new(3.0, -6.0),
        0.0,
        Material {
            stiffness: 5.0,
            damping: 1.0,
        },
    )
    .unwrap();
    let asleep = (0..1200).any(|_| {
        let _ = rope.step_with(1.0 / 60.0, (&mut air, &mut hand)).unwrap();
        rope.is_asleep()
    });
    assert!(asleep, "a steady wind and anchor: the rope never slept");
    assert!(
        rope.step_with(1.0 / 60.0, (&mut air, &mut hand))
            .unwrap()
            .asleep
    );
    // Another anchor: awake.
    hand.set_anchor(Vec2::new(3.5, -6.0)).unwrap();
    assert!(
        !rope
            .step_with(1.0 / 60.0, (&mut air, &mut hand))
            .unwrap()
            .asleep
    );
    // A plain step has other forces (none): awake.
    let mut rope = hanging::<f32, _>(SymplecticEuler);
    until_asleep(&mut rope);
    assert!(!rope.step_with(1.0 / 60.0, &mut air).unwrap().asleep);
    // Gusts never let it sleep.
    air.gust = Vec2::new(0.5, 0.0);
    air.gust_length = 1.0;
    air.gust_every = 3.0;
    let slept = (0..1200).any(|_| rope.step_with(1.0 / 60.0, &mut air).unwrap().asleep);
    assert!(!slept, "a gusty wind let it sleep");
}

/// A rope lying on a floor sleeps with the floor under it; a ball moving far away leaves it
/// asleep, the same ball coming within reach wakes it that frame, a still ball put down
/// beside it wakes it, and a ball with a mass (it may be pushed) keeps it awake.
#[test]
fn colliders_wake_a_rope_when_they_come_within_reach() {
    let settings = Settings {
        gravity: Vec2::new(0.0f32, -9.81),
        damping: 2.0,
        ..Settings::default()
    };
    let material = Material {
        stiffness: 400.0,
        damping: 1.0,
    };
    let mut rope: Rope<Vec2<f32>, 8> = Rope::new(
        Vec2::new(-3.5, 0.2),
        Vec2::new(3.5, 0.2),
        1.0,
        material,
        settings,
    )
    .unwrap();
    rope.set_sleep(Some(Sleep::default())).unwrap();
    let floor = Collider::half_space(Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0)).unwrap();
    let touch = Touch::Drawn(Smoothing::CatmullRom);
    let step = |rope: &mut Rope<Vec2<f32>, 8>, colliders: &[Collider<Vec2<f32>>]| {
        let contacts = Contacts::new(colliders, 0.02, touch).unwrap();
        rope.step_touching(1.0 / 60.0, (), &contacts).unwrap()
    };
    let slept = (0..1200).any(|_| step(&mut rope, &[floor]).asleep);
    assert!(slept, "the rope on the floor never slept");
    // A ball 50 units up, falling at 30 units a second: out of reach for a while.
    let mut ball = Collider::ball(Vec2::new(0.0, 50.0), 0.5)
        .unwrap()
        .moving(Vec2::new(0.0, -30.0))
        .unwrap();
    let mut frames = 0;
    loop {
        ball.advance(1.0 / 60.0).unwrap();
        frames += 1;
        let info = step(&mut rope, &[floor, ball]);
        if !info.asleep {
            break;
        }
        assert!(frames < 200, "the ball never woke the rope");
    }
    let gap = ball.bounds().min.y
        - rope
            .positions()
            .iter()
            .map(|p| p.y)
            .fold(f32::MIN, f32::max);
    eprintln!("woken at frame {frames}, the ball {gap:.3} above the rope (it moves 0.5 a frame)");
    // Within reach: the ball's move over the frame (0.5), the thickness and the bulge
    // allowed the drawn curve (the spacing, 1), and not yet on the rope.
    assert!(
        frames > 60 && gap > 0.0 && gap <= 0.5 + 0.02 + 1.0,
        "{frames}, {gap}"
    );
    // Asleep again on the floor, a still ball set down beside it wakes it.
    let slept = (0..1200).any(|_| step(&mut rope, &[floor]).asleep);
    assert!(slept);
    let stone = Collider::ball(Vec2::new(0.0, 0.6), 0.3).unwrap();
    assert!(!step(&mut rope, &[floor, stone]).asleep);
    // A ball with a mass resting on it keeps it awake.
    let heavy = stone.with_mass(2.0).unwrap();
    let slept = (0..600).any(|_| step(&mut rope, &[floor, heavy]).asleep);
    assert!(!slept, "it slept under a ball it holds up");
}

/// A cloth asleep wakes when it is cut.
#[test]
fn a_cut_wakes_a_sleeping_cloth() {
    let settings = Settings {
        gravity: Vec3::new(0.0f32, -9.81, 0.0),
        damping: 2.0,
        ..Settings::default()
    };
    let m = Material {
        stiffness: 400.0,
        damping: 1.0,
    };
    let mut cloth: Cloth<Vec3<f32>, 6, 6> = Cloth::rectangle(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        0.5,
        [m, m, m],
        settings,
    )
    .unwrap();
    cloth.pin_row(0).unwrap();
    cloth.set_sleep(Some(Sleep::default())).unwrap();
    let slept = (0..1200).any(|_| cloth.step(1.0 / 60.0).unwrap().asleep);
    assert!(slept, "the cloth never slept");
    let torn = cloth
        .cut(Vec2::new(0.5, 1.0), Vec2::new(0.5, -2.0))
        .unwrap();
    assert!(torn > 0 && !cloth.is_asleep());
    assert!(!cloth.step(1.0 / 60.0).unwrap().asleep);
}

/// A bad setting is refused and the old one kept; a sleeping rope refuses a bad `dt` and
/// stays as it was; sleep is in the state checksum only when it is on.
#[test]
fn bad_sleep_settings_are_refused() {
    let mut rope = hanging::<f32, _>(SymplecticEuler);
    for bad in [
        Sleep {
            speed: -1.0,
            frames: 30,
        },
        Sleep {
            speed: f32::NAN,
            frames: 30,
        },
        Sleep {
            speed: 0.1,
            frames: 0,
        },
    ] {
        assert!(rope.set_sleep(Some(bad)).is_err(), "{bad:?}");
        assert_eq!(rope.sleep(), Some(Sleep::default()));
    }
    until_asleep(&mut rope);
    let hash = rope.state_hash();
    assert!(rope.step(-1.0).is_err() && rope.step(f32::NAN).is_err());
    assert!(rope.is_asleep() && rope.state_hash() == hash);
    let mut off = hanging::<f32, _>(SymplecticEuler);
    let plain = off.state_hash();
    off.set_sleep(None).unwrap();
    assert_ne!(plain, off.state_hash());
}

/// A rope woken by a change too small to move it fast (an anchor moved 1 mm) answers it for
/// `frames` steps before it may sleep again: waking counts the still steps afresh.
#[test]
fn a_woken_rope_takes_its_still_steps_again() {
    let mut rope = hanging::<f32, _>(SymplecticEuler);
    let soft = Material {
        stiffness: 5.0,
        damping: 1.0,
    };
    let mut hand = AnchorSpring::new(7, Vec2::new(3.0, -6.0), 0.0, soft).unwrap();
    let asleep = (0..1200).any(|_| rope.step_with(1.0 / 60.0, &mut hand).unwrap().asleep);
    assert!(asleep);
    hand.set_anchor(Vec2::new(3.001, -6.0)).unwrap();
    let frames = usize::from(Sleep::<f32>::default().frames);
    for k in 0..frames {
        let info = rope.step_with(1.0 / 60.0, &mut hand).unwrap();
        assert!(
            !info.asleep,
            "asleep again {k} steps after the anchor moved"
        );
    }
}
