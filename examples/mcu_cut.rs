//! A rope that breaks, on a microcontroller: the `mcu_rope` catapult rope with a bob hung on
//! its end (`hang`) and a snapping limit on every spring (`Snap::Tension`, checked each
//! step), drawn each frame piece by piece (`draw`), and cut at frame 200 by a scripted swipe
//! across the drawn curve (`cut`): the lower piece and the bob fall away. 600 steps at 60 Hz,
//! in Q16.16 on a Cortex-M0 and in f32 on a Cortex-M4F.
//!
//! It prints what `mcu_rope` prints, plus `cut_frame=` (the frame the swipe cut, 0 for
//! none) and, on the device, `other_frame_instructions=` (the costliest frame but the
//! swipe's, the falling pieces included); the checksum covers every particle after the
//! last step, so equal checksums on the host and the device mean the cut and the fall ran
//! bit-identically:
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_cut` (Q16.16, micro:bit)
//! `cargo run --release --example mcu_cut` (Q16.16 on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::breaking::Piece;
use dunas::prelude::*;
use dunas::spring::Snap;

/// The frame the swipe comes.
const CUT_AT: u32 = 200;

/// The swinging rope with its bob, its limit, its drawing and the swipe.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let px = |v: i16| S::from_i16(v);
    let mut rope = device::catapult_rope::<S>()?;
    rope.hang(7, px(2))?;
    // Well above what the swing pulls (a few hundred units): checked every step.
    rope.set_snap(Snap::Tension(px(5000)))?;
    let dt = S::ratio(1, 60);
    let mut scene = (
        rope,
        [Vec2::new(S::ZERO, S::ZERO); device::CURVE],
        [Piece::EMPTY; 8],
        0usize,
        0u32,
    );
    // Across the rope, from above its swing's left to below its right.
    let swipe = (Vec2::new(px(-60), px(-20)), Vec2::new(px(60), px(-40)));
    let mut cut_frame = 0;
    let costs = device::meter_frames(
        meter,
        &mut scene,
        |(rope, points, pieces, drawn, frame)| {
            *frame += 1;
            if *frame == CUT_AT
                && rope
                    .cut(points, &pieces[..*drawn], swipe.0, swipe.1)?
                    .is_some()
            {
                cut_frame = *frame;
            }
            rope.step(dt)
        },
        |(rope, points, pieces, drawn, _)| {
            *drawn = rope.draw(Smoothing::CatmullRom, points, pieces)?;
            Ok(())
        },
    )?;
    let (rope, points, pieces, drawn, _) = scene;
    let view = dunas::ascii::View::new(Vec2::new(px(-60), px(6)), px(3), px(6))?;
    let frame = device::ascii_frame(|canvas| {
        canvas.line(view.cell(swipe.0), view.cell(swipe.1), b'/');
        for piece in &pieces[..drawn] {
            canvas.polyline(&view, &points[piece.points.clone()], b'#');
        }
        canvas.points(&view, rope.positions(), b'o');
    })?;
    let coordinates = rope.positions().iter().flat_map(|p| [p.x, p.y]);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    report.cut_frame = Some(cut_frame);
    report.other_frame_instructions = Some(costs.costliest_but(CUT_AT));
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
