//! A rope that folds onto itself on the floor without passing through itself, on a
//! microcontroller: 10 particles (1.8 m, 0.5 kg, 2 cm thick) let fall end first onto a floor
//! with friction, its particles kept off the floor and the segments between them off each
//! other (`Contacts::with_self_contact` with `Touch::Particles`: exact segment distances, the
//! cheap form for a small core), stepped at 60 Hz for 600 frames and drawn every frame as a
//! Catmull-Rom curve (37 points), in Q16.16 on a Cortex-M0 (the same code runs in f32).
//!
//! It prints what `mcu_rope` prints (the final frame: `o` the particles, `#` the drawn curve,
//! `=` the floor), plus `closest_permille=`: the closest two points of segments that are not
//! neighbours over the run (4 points a segment), in thousandths of the rope's diameter,
//! measured after each frame outside the metered step and curve. The checksum covers every
//! particle and drawn point of the last frame, so equal checksums on the host and the device
//! mean that the contacts, the self-contact, the step and the curve ran bit-identically:
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_coil` (Q16.16, micro:bit)
//! `cargo run --release --example mcu_coil` (the same on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::prelude::*;

/// Particles, and drawn points (4 a span, and the last).
const N: usize = 10;
const DRAWN: usize = 4 * (N - 1) + 1;

/// The rope falling end first onto the floor, what it draws, and the closest its
/// non-neighbouring spans came.
struct Coil<S: Scalar> {
    rope: Rope<Vec2<S>, N>,
    curve: [Vec2<S>; DRAWN],
    closest: S,
}

/// The rope heaping on the floor, drawn every frame.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let frac = |n: u32, d: u32| S::ratio(n, d);
    let settings = Settings {
        gravity: Vec2::new(S::ZERO, -frac(981, 100)),
        damping: frac(1, 2),
        ..Settings::default()
    };
    let material = Material {
        stiffness: S::from_i16(2000),
        damping: S::ONE,
    };
    // Nearly upright, its lower end 10 cm above the floor: it falls end first and buckles.
    let rope = Rope::new(
        Vec2::new(S::ZERO, frac(1, 10)),
        Vec2::new(frac(1, 20), frac(19, 10)),
        frac(1, 2),
        material,
        settings,
    )?;
    let floor = [
        Collider::half_space(Vec2::new(S::ZERO, S::ZERO), Vec2::new(S::ZERO, S::ONE))?
            .with_friction(frac(1, 2), frac(2, 5))?,
    ];
    let radius = frac(1, 100);
    let contacts =
        Contacts::new(&floor, radius, Touch::Particles)?.with_self_contact(frac(3, 10))?;
    let mut scene = Coil {
        rope,
        curve: [Vec2::new(S::ZERO, S::ZERO); DRAWN],
        closest: S::from_i16(100),
    };
    let dt = S::ratio(1, 60);
    let costs = device::meter_frames_checked(
        meter,
        &mut scene,
        (
            |c| c.rope.step_touching(dt, (), &contacts),
            |c| c.rope.sample(Smoothing::CatmullRom, &mut c.curve).map(drop),
            |c| {
                // The segments between the particles, where self-contact keeps the rope off
                // itself, at 4 points each: points of segments two or more apart.
                let x = c.rope.positions();
                let line: [Vec2<S>; DRAWN] = core::array::from_fn(|k| {
                    let (i, t) = (
                        (k / 4).min(N - 2),
                        S::ratio((k - 4 * (k / 4).min(N - 2)) as u32, 4),
                    );
                    x[i] + (x[i + 1] - x[i]) * t
                });
                for (a, &p) in line.iter().enumerate() {
                    for (b, &q) in line.iter().enumerate().skip(a + 1) {
                        if b / 4 >= a / 4 + 2 {
                            c.closest = c.closest.min((p - q).length());
                        }
                    }
                }
            },
        ),
        true,
    )?;
    let view = dunas::ascii::View::new(
        Vec2::new(-frac(2, 10), frac(26, 100)),
        frac(1, 20),
        frac(1, 50),
    )?;
    let frame = device::ascii_frame(|canvas| {
        canvas.polyline(
            &view,
            &[
                Vec2::new(-S::ONE, -frac(1, 100)),
                Vec2::new(S::from_i16(3), -frac(1, 100)),
            ],
            b'=',
        );
        canvas.polyline(&view, &scene.curve, b'#');
        canvas.points(&view, scene.rope.positions(), b'o');
    })?;
    let points = scene.rope.positions().iter().chain(&scene.curve);
    let coordinates = points.flat_map(|p| [p.x, p.y]);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    let diameter = radius + radius;
    let permille = scene.closest * S::from_i16(1000) / diameter;
    report.closest_permille = Some(permille.floor_i32().max(0) as u32);
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
