//! Rollback netplay: a snapshot (a clone) and a replay give the same state checksums frame
//! by frame, in the style of GGRS's sync test, and the scripted scene's checksums are the
//! golden values every platform reproduces (`tests/golden.txt`).

use dunas::prelude::*;

use crate::golden::{self, Scene};

/// Frames a sync test rolls back and replays (GGRS's check distance).
const CHECK_DISTANCE: u32 = 8;

/// The golden value of `format` in `tests/golden.txt` (`q16=…` and `f32=…`, hexadecimal).
fn golden(format: &str) -> u64 {
    golden::expected(format).expect("a golden line in hexadecimal")
}

/// At every frame of the scripted scene's 600 (a moving hand, contacts on the drawn curve,
/// a reel in and out, a cut, a reel after it): save, advance `CHECK_DISTANCE` frames
/// recording the checksums, load, replay them and compare frame by frame; the run goes on
/// from the replay's first frame, as a game that confirmed it. The checksums also equal
/// those of a run that never rolled back.
fn sync_test<S: Scalar>() {
    let mut straight = Scene::<S>::new().unwrap();
    let mut expected = Vec::new();
    while straight.frame < golden::FRAMES + CHECK_DISTANCE {
        straight.advance().unwrap();
        expected.push(straight.rope.state_hash());
    }
    let mut scene = Scene::<S>::new().unwrap();
    while scene.frame < golden::FRAMES {
        let saved = scene.clone();
        let first: Vec<u64> = (0..CHECK_DISTANCE)
            .map(|_| {
                scene.advance().unwrap();
                scene.rope.state_hash()
            })
            .collect();
        scene = saved;
        let start = scene.frame as usize;
        let mut confirmed = None;
        for (k, &hash) in first.iter().enumerate() {
            scene.advance().unwrap();
            assert_eq!(
                scene.rope.state_hash(),
                hash,
                "replayed frame {}",
                start + k
            );
            assert_eq!(hash, expected[start + k], "frame {}", start + k);
            confirmed.get_or_insert_with(|| scene.clone());
        }
        scene = confirmed.unwrap();
    }
    assert_eq!(scene.frame, golden::FRAMES);
}

#[test]
fn a_replay_after_a_rollback_hashes_as_the_first_run() {
    sync_test::<f32>();
    sync_test::<f64>();
    #[cfg(feature = "fixed")]
    sync_test::<Q16>();
}

/// The scripted scene's checksums are the golden values (the Cortex-M0 and M4F and a
/// `.wasm` under node reproduce them in CI).
#[test]
fn the_scripted_scene_hashes_to_its_golden_values() {
    assert_eq!(golden::hashes::<f32>().unwrap(), golden("f32"), "f32");
    #[cfg(feature = "fixed")]
    assert_eq!(golden::hashes::<Q16>().unwrap(), golden("q16"), "q16");
}

/// The checksum sees every part of the state: a position's last bit, a velocity, an
/// inverse mass, a step (the clock and the motion), a cut spring.
#[test]
fn the_state_hash_sees_every_part_of_the_state() {
    let scene = Scene::<f32>::new().unwrap();
    let base = scene.rope.state_hash();
    let bump = |x: f32| f32::from_bits(x.to_bits() + 1);
    let mut changes: Vec<Rope<Vec2<f32>, 8>> = Vec::new();
    let mut moved = scene.rope.clone();
    let p = moved.positions()[3];
    moved.set_position(3, Vec2::new(bump(p.x), p.y)).unwrap();
    changes.push(moved);
    let mut pushed = scene.rope.clone();
    pushed.set_velocity(5, Vec2::new(0.0, 1e-6)).unwrap();
    changes.push(pushed);
    let mut heavier = scene.rope.clone();
    heavier.set_inv_mass(4, 0.5).unwrap();
    changes.push(heavier);
    let mut stepped = scene.rope.clone();
    let _ = stepped.step(1.0 / 60.0).unwrap();
    changes.push(stepped);
    let mut cut = scene.rope.clone();
    let (mut points, mut pieces) = (
        [Vec2::new(0.0, 0.0); 33],
        [dunas::breaking::Piece::EMPTY; 8],
    );
    let drawn = cut
        .draw(Smoothing::CatmullRom, &mut points, &mut pieces)
        .unwrap();
    let swipe = (Vec2::new(-60.0, -20.0), Vec2::new(60.0, -40.0));
    let hit = cut
        .cut(&points, &pieces[..drawn], swipe.0, swipe.1)
        .unwrap();
    assert!(hit.is_some());
    changes.push(cut);
    for (i, changed) in changes.iter().enumerate() {
        assert_ne!(changed.state_hash(), base, "change {i}");
    }
    assert_eq!(scene.rope.clone().state_hash(), base);
}

/// A snapshot is the object itself: at most the sizes `MassSpring::state_hash`'s docs give.
#[test]
fn snapshots_are_as_small_as_the_docs_say() {
    use core::mem::size_of;
    use dunas::integrator::DirectSprings;
    let sizes = [
        (size_of::<Rope<Vec2<f32>, 8>>(), 368),
        (size_of::<Rope<Vec3<f32>, 16>>(), 788),
        (size_of::<Cloth<Vec3<f32>, 8, 8>>(), 1984),
        (size_of::<Cloth<Vec3<f32>, 8, 8, DirectSprings>>(), 7016),
    ];
    for (size, most) in sizes {
        assert!(size <= most, "{size} bytes");
    }
    #[cfg(feature = "fixed")]
    assert!(size_of::<Rope<Vec2<Q16>, 8>>() <= 368);
}

/// The spline rope rolls back too: implicit steps (BDF2 keeps its last step) replayed from a
/// clone hash as the first run, and a force applied for the next step changes the checksum.
#[test]
fn a_spline_rope_replays_after_a_rollback() {
    use dunas::spline_rope::{Bdf2, SplineRope};
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        ..Settings::default()
    }
    .with_integrator(Bdf2::default());
    let material = Material {
        stiffness: 2000.0,
        damping: 1.0,
    };
    let mut rope: SplineRope<Vec2<f64>, 8, Bdf2> = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        1.0,
        material,
        settings,
    )
    .unwrap();
    for _ in 0..10 {
        let _ = rope.step(1.0 / 60.0).unwrap();
    }
    let saved = rope.clone();
    let first: Vec<u64> = (0..CHECK_DISTANCE)
        .map(|_| {
            let _ = rope.step(1.0 / 60.0).unwrap();
            rope.state_hash()
        })
        .collect();
    rope = saved.clone();
    for &hash in &first {
        let _ = rope.step(1.0 / 60.0).unwrap();
        assert_eq!(rope.state_hash(), hash);
    }
    let mut pushed = saved.clone();
    pushed.apply_force(0.5, Vec2::new(0.0, 1.0)).unwrap();
    assert_ne!(pushed.state_hash(), saved.state_hash());
}
