//! Rollback netplay with GGRS: the scripted scene of `examples/common/golden.rs` (a rope
//! held by a moving hand against a ball, contacts on its drawn curve, reeled in and out, cut
//! by a swipe, reeled again) played under [`ggrs::SyncTestSession`]. Each frame GGRS saves
//! the scene (a clone: no heap in it), then rolls back 8 frames, loads, replays them with
//! the same inputs and compares every frame's checksum with the first run's
//! ([`MassSpring::state_hash`](dunas::MassSpring::state_hash)); a difference is GGRS's
//! `MismatchedChecksum`.
//!
//! `cargo run --release -p dunas-netplay [q16|f32|f64]` plays the 600 frames and prints the
//! folded checksums, which in Q16.16 and f32 equal `tests/golden.txt`'s (and so the
//! Cortex-M0's, the M4F's and wasm32's); `cargo test -p dunas-netplay` checks all three.

#[path = "../../examples/common/golden.rs"]
mod golden;

use dunas::{Q16, Scalar, StateHash};
use ggrs::{Config, GgrsRequest, SessionBuilder};

use golden::Scene;

/// Frames GGRS rolls back and replays each frame.
const CHECK_DISTANCE: usize = 8;

/// The session's types: the input is the hand's x (the scene's only input), the state the
/// scene itself.
struct Netplay<S>(core::marker::PhantomData<S>);

impl<S: Scalar + Send + Sync + 'static> Config for Netplay<S> {
    type Input = i8;
    type State = Scene<S>;
    type Address = u8;
}

/// Plays the scene's frames under a sync-test session; the folded checksums of the frames
/// as first played (as `golden::hashes` folds them). Fails on the scene's refused step or
/// on GGRS's error (`MismatchedChecksum`: a replay that differed).
fn play<S: Scalar + Send + Sync + 'static>() -> Result<u64, Box<dyn std::error::Error>> {
    let mut session = SessionBuilder::<Netplay<S>>::new()
        .with_num_players(1)
        .with_check_distance(CHECK_DISTANCE)
        .with_max_prediction_window(CHECK_DISTANCE + 1)
        .start_synctest_session()?;
    let mut scene = Scene::<S>::new()?;
    let mut first = Vec::new();
    for frame in 0..golden::FRAMES {
        session.add_local_input(0, golden::input(frame))?;
        for request in session.advance_frame()? {
            match request {
                GgrsRequest::SaveGameState { cell, frame } => {
                    let hash = scene.rope.state_hash();
                    cell.save(frame, Some(scene.clone()), Some(u128::from(hash)));
                }
                GgrsRequest::LoadGameState { cell, .. } => {
                    if let Some(saved) = cell.load() {
                        scene = saved;
                    }
                }
                GgrsRequest::AdvanceFrame { inputs } => {
                    scene.advance_with(inputs[0].0)?;
                    let at = scene.frame as usize;
                    if at > first.len() {
                        first.push(scene.rope.state_hash());
                    }
                }
            }
        }
    }
    let mut all = StateHash::new();
    for hash in first {
        all.add_u64(hash);
    }
    Ok(all.finish())
}

fn main() {
    let format = std::env::args().nth(1).unwrap_or_else(|| "q16".into());
    let played = match format.as_str() {
        "q16" => play::<Q16>(),
        "f32" => play::<f32>(),
        "f64" => play::<f64>(),
        other => {
            eprintln!("unknown format {other}: q16, f32 or f64");
            std::process::exit(2);
        }
    };
    match played {
        Ok(hash) => println!(
            "{format}: {} frames under GGRS's sync test, {CHECK_DISTANCE} rolled back and replayed each frame, every checksum equal; golden={hash:016x}",
            golden::FRAMES
        ),
        Err(failure) => {
            eprintln!("{format}: {failure}");
            std::process::exit(1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The golden value of `format` in `tests/golden.txt`.
    fn golden(format: &str) -> u64 {
        golden::expected(format).expect("a golden line in hexadecimal")
    }

    #[test]
    fn ggrs_sync_test_replays_every_frame_to_the_same_checksum() {
        assert_eq!(play::<Q16>().unwrap(), golden("q16"));
        assert_eq!(play::<f32>().unwrap(), golden("f32"));
        assert_eq!(
            play::<f64>().unwrap(),
            golden::hashes::<f64>().unwrap(),
            "f64 as the scene played without GGRS"
        );
    }
}
