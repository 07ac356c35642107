//! A boat's sail on a microcontroller: an 8×8 gaff-rigged sail (3 m on the boom, 4 m on the
//! mast, 2 kg) filled by a gusty 5 m/s wind (`SailWind`), stepped at 60 Hz for 600 frames by
//! one solve of its springs a frame (`DirectSprings`, its factor kept between frames) and
//! drawn every frame as a 16×16 natural-spline surface with normals (tables built once), in
//! f32 on a Cortex-M4F; the same code runs in Q16.16.
//!
//! It prints what `mcu_rope` prints (the final frame is the drawn sail seen obliquely, `o` its
//! particles, `.` its drawn points), plus `belly_mm=` (how far the sail's middle stands
//! downwind of its luff) and, on the device, `other_frame_instructions=` (the costliest frame
//! but the first, which factors); the checksum covers every particle and every drawn point and normal
//! of the last frame, so equal checksums on the host and the device mean that the wind, the
//! step and the surface ran bit-identically:
//!
//! `cargo run --release --target thumbv7em-none-eabihf --example mcu_sail` (f32, MPS2-AN386)
//! `cargo run --release --example mcu_sail -- f32` (f32 on the host) or `...` (Q16.16).
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::force::{SailWind, Wind};
use dunas::integrator::DirectSprings;
use dunas::prelude::*;
use dunas::surface::SurfaceTable;

/// Particles a side, and drawn points a side.
const GRID: usize = 8;
const DRAWN: usize = 16;

/// The sail, its wind, its two tables and what it draws.
struct Boat<S: Scalar> {
    sail: Cloth<Vec3<S>, GRID, GRID, DirectSprings>,
    wind: SailWind<S>,
    table: SurfaceTable<S, GRID, DRAWN>,
    positions: [Vec3<S>; DRAWN * DRAWN],
    normals: [Vec3<S>; DRAWN * DRAWN],
}

/// The boat scene's sail (`examples/cloth.rs`): its luff on the mast, its head on the gaff,
/// its foot on the boom, its leech free; a gust of 4 m/s for 1.5 s every 3 s. Constants come
/// from integers and ratios, so no f64 code reaches the device.
fn boat<S: Scalar>() -> Result<Boat<S>, Error> {
    let m = |v: i16| S::from_i16(v);
    let frac = |n: u32, d: u32| S::ratio(n, d);
    let settings = Settings {
        gravity: Vec3::new(m(0), -frac(981, 100), m(0)),
        damping: frac(3, 10),
        ..Settings::default()
    }
    // One iteration a solve, unmeasured: the frame's budget (measured, the solve would
    // report how far it ended, at about a third more a frame; see `DirectSprings::measure`).
    .with_integrator(DirectSprings {
        iterations: 1,
        measure: false,
        ..DirectSprings::default()
    });
    let materials = [(900, (3, 5)), (300, (1, 5)), (60, (1, 20))].map(|(k, (n, d))| Material {
        stiffness: m(k),
        damping: frac(n, d),
    });
    let mut sail = Cloth::rectangle(
        Vec3::new(m(0), frac(9, 2), m(0)),
        Vec3::new(m(3), m(0), m(0)),
        Vec3::new(m(0), m(-4), m(0)),
        m(2),
        materials,
        settings,
    )?;
    sail.pin_column(0)?;
    sail.pin_row(0)?;
    sail.pin_row(GRID - 1)?;
    let mut air = Wind::still(frac(1, 50));
    air.velocity = Vec3::new(m(0), m(0), m(5));
    air.gust = Vec3::new(m(0), m(0), m(4));
    air.gust_start = frac(1, 2);
    air.gust_length = frac(3, 2);
    air.gust_every = m(3);
    let zero = Vec3::new(m(0), m(0), m(0));
    Ok(Boat {
        sail,
        wind: SailWind::new(air, frac(7, 10))?,
        table: SurfaceTable::new(Smoothing::NaturalSpline, DRAWN)?,
        positions: [zero; DRAWN * DRAWN],
        normals: [zero; DRAWN * DRAWN],
    })
}

/// The sail in its wind, drawn every frame.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let mut boat = boat::<S>()?;
    let dt = S::ratio(1, 60);
    let costs = device::meter_frames(
        meter,
        &mut boat,
        |b| b.sail.step_with(dt, &mut b.wind),
        |b| {
            b.sail
                .draw(&b.table, &b.table, &mut b.positions, &mut b.normals)
                .map(drop)
        },
    )?;
    // Seen from abeam and a little ahead: downwind (z) goes right and up the page.
    let oblique = |p: Vec3<S>| Vec2::new(p.x + p.z * S::ratio(3, 5), p.y + p.z * S::ratio(1, 5));
    let view = dunas::ascii::View::new(
        Vec2::new(-S::ratio(1, 2), S::from_i16(5)),
        S::ratio(1, 8),
        S::ratio(3, 8),
    )?;
    let frame = device::ascii_frame(|canvas| {
        for &p in &boat.positions {
            let (col, row) = view.cell(oblique(p));
            canvas.plot(col, row, b'.');
        }
        for &p in boat.sail.positions() {
            let (col, row) = view.cell(oblique(p));
            canvas.plot(col, row, b'o');
        }
    })?;
    let points = boat
        .sail
        .positions()
        .iter()
        .chain(&boat.positions)
        .chain(&boat.normals);
    let coordinates = points.flat_map(|p| [p.x, p.y, p.z]);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    // The first frame factors the springs' matrix; the others reuse the factor.
    report.other_frame_instructions = Some(costs.costliest_but(1));
    // The middle particle's distance downwind of the mast, in millimetres.
    let middle = boat.sail.positions()[GRID * (GRID / 2) + GRID / 2];
    report.belly_mm = Some((middle.z * S::from_i16(1000)).floor_i32());
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
