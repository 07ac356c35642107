//! An inner tube on a microcontroller: a closed cloth of 8×5 particles wrapped into a torus
//! (`Torus`, 0.3 m round its ring, 0.1 m round its tube, 0.8 kg) blown up by the gas inside
//! it (`force::Pressure`), dropped on a floor with friction, squashing and bouncing,
//! stepped at 60 Hz for 600 frames and drawn every frame as a closed Catmull-Rom surface of
//! 17×11 points with normals, in Q16.16 on a Cortex-M0 (the same code runs in f32).
//!
//! It prints what `mcu_rope` prints (the final frame seen from the side: `o` the particles,
//! `#` the drawn surface, `=` the floor), plus `area_permille=` (here the tube's volume at
//! the end over its volume blown up at the start, in thousandths); the checksum covers every
//! particle and every drawn point and normal of the last frame, so equal checksums on the
//! host and the device mean that the gas, the contacts, the step and the surface ran
//! bit-identically:
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_tube` (Q16.16, micro:bit)
//! `cargo run --release --example mcu_tube` (the same on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::Torus;
use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::force::Pressure;
use dunas::prelude::*;
use dunas::surface::SurfaceTable;

/// Particles round the ring and round the tube, and drawn points each way (2 a span, and
/// the closing point).
const U: usize = 6;
const V: usize = 5;
const NU: usize = 13;
const NV: usize = 6;

/// The tube, its gas, its tables and what it draws.
struct Tube<S: Scalar> {
    body: Torus<S, U, V>,
    gas: Pressure<S>,
    tables: (SurfaceTable<S, U, NU>, SurfaceTable<S, V, NV>),
    points: [Vec3<S>; NU * NV],
    normals: [Vec3<S>; NU * NV],
}

/// A torus of 0.3 m and 0.1 m lying flat 0.5 m above the floor, tilted by a push, its
/// springs 300 N/m, its gas at 200 N/m² of pressure.
fn tube<S: Scalar>() -> Result<Tube<S>, Error> {
    let frac = |n: u32, d: u32| S::ratio(n, d);
    let material = |k: i16| Material {
        stiffness: S::from_i16(k),
        damping: frac(1, 5),
    };
    let springs = [material(100), material(40), material(10)];
    let settings = Settings {
        gravity: Vec3::new(S::ZERO, -frac(981, 100), S::ZERO),
        damping: frac(1, 10),
        ..Settings::default()
    };
    let centre = Vec3::new(S::ZERO, frac(6, 10), S::ZERO);
    let mut body = Torus::new(
        centre,
        frac(3, 10),
        frac(1, 10),
        frac(4, 5),
        springs,
        settings,
    )?;
    // A spin about z, so that it lands on one side and rolls over.
    for i in 0..U * V {
        let p = body.positions()[i] - centre;
        body.set_velocity(i, Vec3::new(-p.y, p.x, S::ZERO) * S::from_i16(3))?;
    }
    let gas = Pressure::at(S::from_i16(200), body.volume())?;
    let zero = Vec3::new(S::ZERO, S::ZERO, S::ZERO);
    Ok(Tube {
        body,
        gas,
        tables: (
            SurfaceTable::closed(Smoothing::CatmullRom, NU)?,
            SurfaceTable::closed(Smoothing::CatmullRom, NV)?,
        ),
        points: [zero; NU * NV],
        normals: [zero; NU * NV],
    })
}

/// The tube dropped on the floor, drawn every frame.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let mut scene = tube::<S>()?;
    let start = scene.body.volume();
    let up = Vec3::new(S::ZERO, S::ONE, S::ZERO);
    let floor = [
        Collider::half_space(Vec3::new(S::ZERO, S::ZERO, S::ZERO), up)?
            .with_friction(S::ratio(1, 2), S::ratio(2, 5))?,
    ];
    let contacts = Contacts::new(&floor, S::ratio(1, 50), Touch::Particles)?;
    let dt = S::ratio(1, 60);
    let costs = device::meter_frames(
        meter,
        &mut scene,
        |t| t.body.step_touching_particles(dt, &mut t.gas, &contacts),
        |t| {
            let (tu, tv) = &t.tables;
            t.body.draw(tu, tv, &mut t.points, &mut t.normals).map(drop)
        },
    )?;
    // From the side: x across, y up.
    let view = dunas::ascii::View::new(
        Vec2::new(-S::ratio(4, 5), S::ratio(7, 10)),
        S::ratio(1, 25),
        S::ratio(1, 20),
    )?;
    let side = |p: &Vec3<S>| Vec2::new(p.x, p.y);
    let frame = device::ascii_frame(|canvas| {
        let ground = [Vec2::new(-S::ONE, S::ZERO), Vec2::new(S::ONE, S::ZERO)];
        canvas.polyline(&view, &ground, b'=');
        for p in &scene.points {
            let (col, row) = view.cell(side(p));
            canvas.plot(col, row, b'#');
        }
        for p in scene.body.positions() {
            let (col, row) = view.cell(side(p));
            canvas.plot(col, row, b'o');
        }
    })?;
    let drawn = scene
        .body
        .positions()
        .iter()
        .chain(&scene.points)
        .chain(&scene.normals);
    let coordinates = drawn.flat_map(|p| [p.x, p.y, p.z]);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    let volume = scene.body.volume();
    report.area_permille = Some((volume * S::from_i16(1000) / start).floor_i32().max(0) as u32);
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
