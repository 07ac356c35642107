//! Rollback netplay's determinism on a microcontroller: the scripted scene of
//! `common/golden.rs` (the catapult rope held by a moving hand, swinging against a ball
//! with contacts on its drawn curve, cut at frame 300 and reeled), its 600 frames' state checksums
//! ([`MassSpring::state_hash`](dunas::MassSpring::state_hash)) folded into one and printed
//! as `golden=`, which must equal `tests/golden.txt`'s for the format: in Q16.16 on a
//! Cortex-M0, in f32 on a Cortex-M4F, as on the host and in a `.wasm` under node.
//! `frame_instructions=` is the mean frame of the scene, checksum included.
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
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
