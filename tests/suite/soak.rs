//! Soak: a rope held by a hand on a random, jerky path through a game loop with 1 s hitches,
//! in `f32` and `Q16`. 20 000 fixed steps by default (CI); set `DUNAS_SOAK_STEPS` for the
//! long run, e.g. `DUNAS_SOAK_STEPS=1000000 cargo test --release --test soak`.
//!
//! Every step must keep the rope finite and inside its bounds; a refused step must leave it
//! as it was; and the rope must still hang from the hand at the end.
#![cfg(all(feature = "std", feature = "fixed"))]

use dunas::prelude::*;

/// A small deterministic generator (xorshift), so a failure repeats.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn steps() -> u64 {
    std::env::var("DUNAS_SOAK_STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_000)
}

fn soak<S: Scalar>(seed: u64) {
    let s = S::from_f64;
    let settings = Settings {
        gravity: Vec2::new(s(0.0), s(-200.0)),
        damping: s(0.1),
        bounds: s(2000.0),
        ..Settings::default()
    };
    let material = Material {
        stiffness: s(3000.0),
        damping: s(1.0),
    };
    let mut rope: Rope<Vec2<S>, 8> = Rope::new(
        Vec2::new(s(0.0), s(0.0)),
        Vec2::new(s(70.0), s(0.0)),
        s(7.0),
        material,
        settings,
    )
    .unwrap();
    let mut clock = FixedTimestep::new(s(1.0 / 60.0), s(0.25)).unwrap();
    let mut rng = Rng(seed);
    let (mut hand, mut done, mut refused, mut saturated) = ((0.0f64, 0.0f64), 0u64, 0u64, 0u64);
    let mut out = [Vec2::new(S::ZERO, S::ZERO); 33];
    while done < steps() {
        // Frames of 16 ms with jitter, a 1 s hitch now and then.
        let frame = if rng.unit() < 0.01 {
            1.0
        } else {
            0.016 + 0.004 * rng.unit()
        };
        // The hand wanders, and sometimes jerks up to 60 units in one frame.
        let jerk = if rng.unit() < 0.05 { 60.0 } else { 4.0 };
        hand.0 = (hand.0 + jerk * (rng.unit() - 0.5)).clamp(-500.0, 500.0);
        hand.1 = (hand.1 + jerk * (rng.unit() - 0.5)).clamp(-500.0, 500.0);
        for _ in 0..clock.advance(s(frame)) {
            rope.set_position(0, Vec2::new(s(hand.0), s(hand.1)))
                .unwrap();
            let before = rope.clone();
            match rope.step(clock.step()) {
                Ok(info) => saturated += info.saturated as u64,
                Err(e) => {
                    assert_eq!(e, Error::Diverged, "step {done}");
                    assert_eq!(rope.positions(), before.positions());
                    assert_eq!(rope.velocities(), before.velocities());
                    refused += 1;
                }
            }
            for p in rope.positions() {
                assert!(p.in_safe_range(), "step {done}: {p:?}");
                assert!(p.x.abs() <= s(2000.0) && p.y.abs() <= s(2000.0));
            }
            done += 1;
        }
        let n = rope.sample(Smoothing::CatmullRom, &mut out).unwrap();
        assert_eq!(out[0], rope.positions()[0]);
        assert_eq!(out[n - 1], rope.positions()[7]);
    }
    // Still a rope, still on the hand: every particle within its stretched length of it.
    let holder = rope.positions()[0];
    for p in rope.positions() {
        assert!((*p - holder).length() <= s(140.0), "{p:?} from {holder:?}");
    }
    eprintln!(
        "{}: {done} steps, {refused} refused, {saturated} saturated",
        core::any::type_name::<S>()
    );
    assert!(
        refused * 1000 <= done,
        "more than one step in 1000 refused: {refused}"
    );
}

#[test]
fn an_f32_rope_survives_a_jerky_hand_and_hitches() {
    soak::<f32>(0x5eed_1234);
}

#[test]
fn a_q16_rope_survives_a_jerky_hand_and_hitches() {
    soak::<Q16>(0x5eed_5678);
}
