//! Rollback netplay's determinism on a microcontroller: the scripted scene of
//! `common/golden.rs` (the catapult rope held by a moving hand, swinging against a ball
//! with contacts on its drawn curve, cut at frame 300 and reeled), its 600 frames' state checksums
//! ([`MassSpring::state_hash`](dunas::MassSpring::state_hash)) folded into one and printed
//! as `golden=`, which must equal `tests/golden.txt`'s for the format: in Q16.16 on a
//! Cortex-M0, in f32 on a Cortex-M4F, as on the host and in a `.wasm` under node.
//! `frame_instructions=` is the mean frame of the scene, checksum included. On the device it
//! also prints `reel_permille=`: a frame of the scene's rope (8 particles, symplectic Euler,
//! its hand moving, its drawn curve on the ball) that reels it in, against the same frame
//! from the same state that does not, in thousandths, over the scene's first reel (frames 30
//! to 160; each frame both ways from a copy, the reeled one carried on).
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_golden` (Q16.16, micro:bit)
//! `cargo run --release --example mcu_golden` (Q16.16 on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;
#[path = "common/golden.rs"]
mod golden;

use device::{Costs, Meter, Report};
use dunas::prelude::*;

/// The scripted scene's frames 30 to 160, where it reels in, each played from the same
/// state with and without its reel: the reeling frames' instructions over the others', in
/// thousandths (1 000 where the meter counts nothing, as on the host).
fn reel_permille<S: Scalar>(meter: &mut impl Meter) -> Result<u32, Error> {
    let mut scene = golden::Scene::<S>::new()?;
    while scene.frame < 30 {
        scene.advance()?;
    }
    let (mut reeled, mut plain) = (0u32, 0u32);
    while scene.frame <= 160 {
        let mut still = scene.clone();
        let input = golden::input(scene.frame);
        let (done, n) = meter.count(|| still.advance_plain(input));
        done?;
        plain += n;
        let (done, n) = meter.count(|| scene.advance_with(input));
        done?;
        reeled += n;
    }
    Ok(if plain == 0 {
        1000
    } else {
        (u64::from(reeled) * 1000 / u64::from(plain)) as u32
    })
}

/// The scripted scene, metered as one call.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, _: fn(S) -> u32) -> Result<Report, Error> {
    let (hashes, instructions) = meter.count_long(golden::hashes::<S>);
    let hashes = hashes?;
    let per_frame = instructions / golden::FRAMES;
    let costs = Costs {
        step: per_frame,
        sample: 0,
        mean: per_frame,
        substeps: 1,
        costliest_at: 0,
        runner_up: 0,
    };
    let frame = device::ascii_frame(|_| {})?;
    let mut report = device::report((hashes ^ (hashes >> 32)) as u32, &costs, frame);
    report.golden = Some(hashes);
    report.reel_permille = Some(reel_permille::<S>(meter)?);
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
