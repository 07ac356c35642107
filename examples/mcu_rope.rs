//! The rope game loop on a microcontroller: 8 particles, 600 steps at 60 Hz, the curve sampled
//! every frame, in Q16.16 on a Cortex-M0 (no FPU) and in f32 on a Cortex-M4F.
//!
//! On the device (under QEMU, see `.cargo/config.toml`) it prints a final ASCII frame and
//! `key=value` lines through semihosting, among them `checksum=` (a hash of every particle
//! position after the last step), `frame_instructions=` (the costliest frame: one step plus
//! one curve, counted exactly with SysTick under `-icount`) and `mean_frame_instructions=`,
//! then exits with success, or failure on any error or panic:
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_rope` (Q16.16, micro:bit)
//! `cargo run --release --target thumbv7em-none-eabihf --example mcu_rope` (f32, MPS2-AN386)
//!
//! On the host the same simulation runs with std and prints the same `checksum=` line:
//! `cargo run --release --example mcu_rope` (Q16.16) or `... -- f32`. `mcu_peg` is the same
//! rope swinging against a peg.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::prelude::*;

/// The catapult rope swinging free.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let mut rope = device::catapult_rope::<S>()?;
    let dt = S::ratio(1, 60);
    device::run_frames(meter, bits, &mut rope, |r| r.step(dt), |_, _| {})
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
