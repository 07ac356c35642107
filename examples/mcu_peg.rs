//! The rope game loop on a microcontroller with one peg: the `mcu_rope` catapult rope (8
//! particles 10 pixels apart) swinging against a peg of radius 2 beside the line it hangs
//! on, with contacts on the drawn Catmull-Rom curve (the particles alone would pass it), 600
//! steps at 60 Hz, in Q16.16 on a Cortex-M0 and in f32 on a Cortex-M4F.
//!
//! It prints what `mcu_rope` prints, plus `touching_frames=` (frames in which the peg pushed
//! the rope); the checksum covers the contacts, so equal checksums on the host and the
//! device mean the contacts ran bit-identically:
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_peg` (Q16.16, micro:bit)
//! `cargo run --release --target thumbv7em-none-eabihf --example mcu_peg` (f32, MPS2-AN386)
//! `cargo run --release --example mcu_peg` (Q16.16 on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::contact::Push;
use dunas::prelude::*;

/// The catapult rope swinging against a peg, with a rope 2 pixels thick (so the step takes
/// the substeps that keep every drawn point within 2 pixels a substep).
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let mut rope = device::catapult_rope::<S>()?;
    let dt = S::ratio(1, 60);
    let centre = Vec2::new(S::from_i16(-6), S::from_i16(-28));
    let peg = [Collider::ball(centre, S::from_i16(2))?];
    let mut touching = 0;
    let mut report = device::run_frames(
        meter,
        bits,
        &mut rope,
        |r| {
            let mut push = [Push::default()];
            let contacts =
                Contacts::new(&peg, S::from_i16(2), Touch::Drawn(Smoothing::CatmullRom))?
                    .with_pushes(&mut push);
            let info = r.step_touching(dt, (), &contacts);
            touching += u32::from(push[0].impulse != Vec2::new(S::ZERO, S::ZERO));
            info
        },
        |canvas, view| canvas.points(view, &[centre], b'@'),
    )?;
    report.touching_frames = Some(touching);
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
