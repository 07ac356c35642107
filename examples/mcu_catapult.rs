//! A rope that does not stretch under its bob, on a microcontroller: the `mcu_rope` rope
//! (8 particles, 70 pixel units, mass 7) with a bob of 7 times its mass hung on its end
//! (`hang`, as the catapult's penguin), released 40° from hanging and swinging, its links
//! solved together each frame by [`DirectChain`] (one solve of up to 2 tridiagonal Newton
//! iterations, the second only where the first leaves a link off its length, halved where
//! a link ends more than 0.1% off; one substep a frame at any stiffness). 600 steps at
//! 60 Hz, in Q16.16 on a Cortex-M0 (at most 28 597 instructions a frame: its target of
//! 25 000 is missed by the check that every link ends within 0.1%) and in f32 on a
//! Cortex-M4F.
//!
//! It prints what `mcu_rope` prints, plus `stretch_permille=`, the rope's largest stretch
//! over the run in thousandths (measured after each frame, outside the metered step and
//! curve):
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_catapult` (Q16.16, micro:bit)
//! `cargo run --release --example mcu_catapult` (Q16.16 on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::integrator::DirectChain;
use dunas::prelude::*;

/// The rope with its bob, swinging; its largest stretch is measured after every frame.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let px = |v: i16| S::from_i16(v);
    let frac = |n: u32, d: u32| S::ratio(n, d);
    let solver = DirectChain {
        iterations: 2,
        inextensible: true,
        substeps: 1,
        halvings: 6,
    };
    let settings = Settings {
        gravity: Vec2::new(px(0), px(-200)),
        damping: frac(1, 10),
        ..Settings::default()
    }
    .with_integrator(solver);
    let material = Material {
        stiffness: px(300),
        damping: frac(1, 2),
    };
    let (start, end) = (Vec2::new(px(0), px(0)), Vec2::new(px(45), -frac(536, 10)));
    let mut rope: Rope<Vec2<S>, 8, 8, DirectChain> =
        Rope::new(start, end, px(7), material, settings)?;
    rope.hang(7, px(49))?;
    let length = px(70);
    let mut scene = (rope, [Vec2::new(S::ZERO, S::ZERO); device::CURVE], S::ZERO);
    let dt = S::ratio(1, 60);
    let costs = device::meter_frames_checked(
        meter,
        &mut scene,
        (
            |(rope, _, _)| rope.step(dt),
            |(rope, curve, _)| rope.sample(Smoothing::CatmullRom, curve).map(drop),
            |(rope, _, largest)| {
                let chain = rope
                    .positions()
                    .windows(2)
                    .fold(S::ZERO, |sum, pair| sum + (pair[1] - pair[0]).length());
                *largest = (*largest).max(chain / length - S::ONE);
            },
        ),
        false,
    )?;
    let (rope, curve, largest) = scene;
    let view = dunas::ascii::View::new(Vec2::new(px(-60), px(6)), px(3), px(6))?;
    let frame = device::ascii_frame(|canvas| {
        canvas.polyline(&view, &curve, b'#');
        canvas.points(&view, rope.positions(), b'o');
    })?;
    let coordinates = rope.positions().iter().flat_map(|p| [p.x, p.y]);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    report.stretch_permille = Some((largest * px(1000)).floor_i32().max(0) as u32);
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
