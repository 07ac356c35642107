//! The spline rope on a microcontroller: the `mcu_rope` catapult rope's length, mass and
//! stiffness, but its state is the 8 control points of its drawn curve (`SplineRope`),
//! released level, 600 steps at 60 Hz and the curve drawn every frame, in Q16.16 on a
//! Cortex-M0 and in f32 on a Cortex-M4F.
//!
//! It prints what `mcu_rope` prints, plus `pin_instructions=`: one `set_pinned`, which
//! factors the mass matrix and finds the substep bound again, in software `f64` on the M0.
//! The checksum covers every control point after the last step, so equal checksums on the
//! host and the device mean the step ran bit-identically:
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_spline` (Q16.16, micro:bit)
//! `cargo run --release --target thumbv7em-none-eabihf --example mcu_spline` (f32, MPS2-AN386)
//! `cargo run --release --example mcu_spline` (Q16.16 on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::prelude::*;
use dunas::spline_rope::SplineRope;

/// A 70 px rope of 7 mass units, pinned at the origin and released level: `EA = 3000` (the
/// catapult rope's 300 a spring over 7 springs of 10 px), strain damping 5, gravity 200 px/s².
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let px = |v: i16| S::from_i16(v);
    let settings = Settings {
        gravity: Vec2::new(px(0), px(-200)),
        damping: S::ratio(1, 10),
        ..Settings::default()
    };
    let stretch = Material {
        stiffness: px(3000),
        damping: px(5),
    };
    let mut rope: SplineRope<Vec2<S>, 8> = SplineRope::new(
        Vec2::new(px(0), px(0)),
        Vec2::new(px(70), px(0)),
        px(7),
        stretch,
        settings,
    )?;
    // A hand takes the free end and lets it go: each change finds the substep bound again.
    let (pinned, pin) = meter.count_long(|| rope.set_pinned(7, true));
    pinned?;
    rope.set_pinned(7, false)?;
    let mut scene = (rope, [Vec2::new(S::ZERO, S::ZERO); device::CURVE]);
    let costs = frames(meter, &mut scene)?;
    let (rope, mut curve) = scene;
    let drawn = rope.sample(&mut curve)?;
    let view = dunas::ascii::View::new(Vec2::new(px(-60), px(6)), px(3), px(6))?;
    let frame = device::ascii_frame(|canvas| {
        canvas.polyline(&view, &curve[..drawn], b'#');
        canvas.points(&view, rope.positions(), b'o');
    })?;
    let coordinates = rope.positions().iter().flat_map(|p| [p.x, p.y]);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    report.pin_instructions = Some(pin);
    Ok(report)
}

/// The metered frames: a step of 1/60 s and the curve drawn. Out of line, so that their
/// locals and the pin change's `f64` work above are not summed on the stack.
#[inline(never)]
fn frames<S: Scalar>(
    meter: &mut impl Meter,
    scene: &mut (SplineRope<Vec2<S>, 8>, [Vec2<S>; device::CURVE]),
) -> Result<device::Costs, Error> {
    let dt = S::ratio(1, 60);
    device::meter_frames(
        meter,
        scene,
        |(rope, _)| rope.step(dt),
        |(rope, curve)| rope.sample(curve).map(drop),
    )
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
