//! A rope with a heavy load wrapping a box, on a microcontroller: a 10 m, 2 kg rope of 12
//! particles held at one end, a 70 kg player hung on the other (`hang`), let go level above
//! a box 3 particle spacings wide, so that it falls on the box, wraps its corners and swings
//! under it. Its links are solved together by [`DirectChain`] with the catapult's setting
//! (one solve of up to 2 Newton iterations a frame, halved where a link ends more than 0.1%
//! off), its drawn Catmull-Rom curve touches the box, 600 steps at 60 Hz, in Q16.16 on a
//! Cortex-M0 and in f32 on a Cortex-M4F.
//!
//! It prints what `mcu_rope` prints, plus `touching_frames=` (frames in which the box
//! pushed the rope), `stretch_permille=` (the rope's largest stretch over the run) and
//! `inside_permille=` (the deepest a drawn point went inside the box, in thousandths of
//! the rope's thickness), the last two measured after each frame, outside the metered
//! step and curve, and `unconverged_frames=` (frames whose step reported
//! `converged: false`: the contacts and the links, which take turns after each solve, did
//! not agree within their rounds, or left a link beyond 0.1%). Frames that wrap a corner
//! take several rounds, past the counter's million instructions on the M0: each step is
//! metered with the long counter.
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_wrap` (Q16.16, micro:bit)
//! `cargo run --release --example mcu_wrap` (Q16.16 on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::contact::Push;
use dunas::integrator::DirectChain;
use dunas::prelude::*;

/// The rope, its player, the box, the drawn curve, the largest stretch and depth so far,
/// and the frames touching and unconverged.
type Scene<S> = (
    Rope<Vec2<S>, 12, 12, DirectChain>,
    [Vec2<S>; device::CURVE],
    (S, S),
    (u32, u32),
);

/// The rope falling onto the box and swinging under it.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let m = |v: i16| S::from_i16(v);
    let frac = |n: u32, d: u32| S::ratio(n, d);
    let solver = DirectChain {
        iterations: 2,
        inextensible: true,
        substeps: 1,
        halvings: 6,
    };
    let settings = Settings {
        gravity: Vec2::new(m(0), -frac(981, 100)),
        damping: frac(1, 10),
        ..Settings::default()
    }
    .with_integrator(solver);
    let material = Material {
        stiffness: m(2000),
        damping: m(1),
    };
    let (start, end) = (Vec2::new(m(0), m(0)), Vec2::new(m(10), m(0)));
    let mut rope: Rope<Vec2<S>, 12, 12, DirectChain> =
        Rope::new(start, end, m(2), material, settings)?;
    rope.hang(11, m(70))?;
    // 3 spacings (30/11 m) wide, its top 2 m below the hand, its left side 2.5 m out.
    let (low, high) = (
        Vec2::new(frac(5, 2), -frac(7, 2)),
        Vec2::new(frac(5, 2) + frac(30, 11), m(-2)),
    );
    let block = [Collider::aabb(low, high)?];
    let thickness = frac(1, 20);
    let length = m(10);
    let mut scene: Scene<S> = (
        rope,
        [Vec2::new(S::ZERO, S::ZERO); device::CURVE],
        (S::ZERO, S::ZERO),
        (0, 0),
    );
    let dt = S::ratio(1, 60);
    let costs = device::meter_frames_checked(
        meter,
        &mut scene,
        (
            |(rope, _, _, (touching, unconverged))| {
                let mut push = [Push::default()];
                let contacts =
                    Contacts::new(&block, thickness, Touch::Drawn(Smoothing::CatmullRom))?
                        .with_pushes(&mut push);
                let info = rope.step_touching(dt, (), &contacts);
                *touching += u32::from(push[0].impulse != Vec2::new(S::ZERO, S::ZERO));
                *unconverged += u32::from(info.as_ref().is_ok_and(|i| !i.converged));
                info
            },
            |(rope, curve, _, _)| rope.sample(Smoothing::CatmullRom, curve).map(drop),
            |(rope, curve, (stretch, inside), _)| {
                let chain = rope
                    .positions()
                    .windows(2)
                    .fold(S::ZERO, |sum, pair| sum + (pair[1] - pair[0]).length());
                *stretch = (*stretch).max(chain / length - S::ONE);
                for &p in curve.iter() {
                    *inside = (*inside).max(-block[0].gap(p));
                }
            },
        ),
        true,
    )?;
    let (rope, curve, (stretch, inside), (touching, unconverged)) = scene;
    let view = dunas::ascii::View::new(Vec2::new(m(-11), m(1)), frac(11, 20), frac(6, 7))?;
    let frame = device::ascii_frame(|canvas| {
        canvas.polyline(&view, &curve, b'#');
        canvas.points(&view, rope.positions(), b'o');
        canvas.points(
            &view,
            &[
                low,
                high,
                Vec2::new(low.x, high.y),
                Vec2::new(high.x, low.y),
            ],
            b'@',
        );
    })?;
    let coordinates = rope.positions().iter().flat_map(|p| [p.x, p.y]);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    report.touching_frames = Some(touching);
    report.stretch_permille = Some((stretch * m(1000)).floor_i32().max(0) as u32);
    report.inside_permille = Some((inside / thickness * m(1000)).floor_i32().max(0) as u32);
    report.unconverged_frames = Some(unconverged);
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
