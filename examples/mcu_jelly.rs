//! A jelly on a microcontroller: a ring of 8 particles (0.6 m across, 0.8 kg) blown up by the
//! gas inside it (`force::Pressure`), dropped on a floor with friction, squashing and
//! bouncing, stepped at 60 Hz for 600 frames and drawn every frame as a closed B-spline of 32
//! points, in Q16.16 on a Cortex-M0 (the same code runs in f32).
//!
//! It prints what `mcu_rope` prints (the final frame: `o` the particles, `#` the drawn curve,
//! `=` the floor), plus `area_permille=` (the jelly's area at the end over its area at the
//! start, in thousandths); the checksum covers every particle and drawn point of the last
//! frame, so equal checksums on the host and the device mean that the gas, the contacts, the
//! step and the curve ran bit-identically:
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_jelly` (Q16.16, micro:bit)
//! `cargo run --release --example mcu_jelly` (the same on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::force::Pressure;
use dunas::prelude::*;
use dunas::smooth::Smoothed;
use dunas::spring::Springs;

/// Particles, and drawn points (4 a span, and the closing point).
const N: usize = 8;
const DRAWN: usize = 33;

/// The jelly, its gas and what it draws.
struct Jelly<S: Scalar> {
    body: Rope<Vec2<S>, N>,
    gas: Pressure<S>,
    curve: [Vec2<S>; DRAWN],
}

/// A ring of 8 particles of radius 0.3 m, 0.1 kg each, on loop springs of 200 N/m, its gas
/// at 40 N/m of pressure, its lowest point 0.5 m above the floor. Constants come from
/// integers and ratios, so no f64 code reaches the device.
fn jelly<S: Scalar>() -> Result<Jelly<S>, Error> {
    let frac = |n: u32, d: u32| S::ratio(n, d);
    // cos and sin of the 8 directions, to 4 places.
    let c = frac(7071, 10_000);
    let dirs = [
        (S::ONE, S::ZERO),
        (c, c),
        (S::ZERO, S::ONE),
        (-c, c),
        (-S::ONE, S::ZERO),
        (-c, -c),
        (S::ZERO, -S::ONE),
        (c, -c),
    ];
    let (r, height) = (frac(3, 10), frac(8, 10));
    let points = dirs.map(|(x, y)| Vec2::new(x * r, height + y * r));
    let springs = Springs::closed_loop(
        &points,
        Material {
            stiffness: S::from_i16(200),
            damping: frac(1, 5),
        },
    )?;
    let settings = Settings {
        gravity: Vec2::new(S::ZERO, -frac(981, 100)),
        damping: frac(1, 10),
        ..Settings::default()
    };
    let body = Rope::from_parts(points, [S::from_i16(10); N], springs, settings)?;
    let gas = Pressure::at(S::from_i16(40), Pressure::area(&points))?;
    Ok(Jelly {
        body,
        gas,
        curve: [Vec2::new(S::ZERO, S::ZERO); DRAWN],
    })
}

/// The jelly dropped on the floor, drawn every frame.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let mut scene = jelly::<S>()?;
    let start = Pressure::area(scene.body.positions());
    let floor = [
        Collider::half_space(Vec2::new(S::ZERO, S::ZERO), Vec2::new(S::ZERO, S::ONE))?
            .with_friction(S::ratio(1, 2), S::ratio(2, 5))?,
    ];
    let contacts = Contacts::new(&floor, S::ratio(1, 20), Touch::Particles)?;
    let dt = S::ratio(1, 60);
    let costs = device::meter_frames(
        meter,
        &mut scene,
        |j| j.body.step_touching_particles(dt, &mut j.gas, &contacts),
        |j| {
            Smoothed::closed(Smoothing::BSpline, j.body.position_array())?
                .sample(&mut j.curve)
                .map(drop)
        },
    )?;
    let view = dunas::ascii::View::new(
        Vec2::new(-S::ONE, S::ratio(9, 10)),
        S::ratio(1, 20),
        S::ratio(1, 14),
    )?;
    let frame = device::ascii_frame(|canvas| {
        canvas.polyline(
            &view,
            &[Vec2::new(-S::ONE, S::ZERO), Vec2::new(S::ONE, S::ZERO)],
            b'=',
        );
        canvas.polyline(&view, &scene.curve, b'#');
        canvas.points(&view, scene.body.positions(), b'o');
    })?;
    let points = scene.body.positions().iter().chain(&scene.curve);
    let coordinates = points.flat_map(|p| [p.x, p.y]);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    let area = Pressure::area(scene.body.positions());
    report.area_permille = Some((area * S::from_i16(1000) / start).floor_i32().max(0) as u32);
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
