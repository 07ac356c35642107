//! A sea on a microcontroller: a 4 m square of 8 × 8 water columns (`water::Sea`, waves at
//! 3 m/s, calmed a little), a splash in one corner and a boat's hull that floats by buoyancy
//! and makes waves, stepped at 60 Hz for 600 frames and drawn every frame as a Catmull-Rom
//! surface of 15 × 15 points with their normals (tables built once), in Q16.16 on a
//! Cortex-M0 (the same code runs in f32).
//!
//! It prints what `mcu_rope` prints (the final frame: the sea seen from the side, `~` its
//! drawn points, `#` the hull), plus `belly_mm=` (here: how deep the hull floats below the
//! surface under it, in millimetres; Archimedes says 200); the checksum covers every column,
//! the hull and every drawn point and normal of the last frame, so equal checksums on the
//! host and the device mean that the waves, the buoyancy and the surface ran bit-identically:
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_sea` (Q16.16, micro:bit)
//! `cargo run --release --example mcu_sea` (the same on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::prelude::*;
use dunas::surface::SurfaceTable;
use dunas::water::{Hull, Sea};

/// Columns a side, and drawn points a side (through every column).
const SIDE: usize = 8;
const DRAWN: usize = SIDE;

/// The sea, its hull, its table and what it draws.
struct Harbour<S: Scalar> {
    sea: Sea<S, SIDE, SIDE>,
    hull: [Hull<S>; 1],
    table: SurfaceTable<S, SIDE, DRAWN>,
    points: [Vec3<S>; DRAWN * DRAWN],
    normals: [Vec3<S>; DRAWN * DRAWN],
}

/// A sea 1 m deep, 1000 kg/m³, its columns 0.5 m apart, waves at 3 m/s, a corner column
/// raised 0.3 m; a 1 m × 1.5 m hull of 300 kg let go with its bottom at the surface.
/// Constants come from integers and ratios, so no f64 code reaches the device.
fn harbour<S: Scalar>() -> Result<Harbour<S>, Error> {
    let m = |v: i16| S::from_i16(v);
    let frac = |n: u32, d: u32| S::ratio(n, d);
    let mut sea =
        Sea::new((m(0), m(0)), frac(1, 2), m(1), m(3), m(1000))?.with_damping(frac(1, 2))?;
    sea.set_height(SIDE - 1, SIDE - 1, frac(13, 10))?;
    let hull = [Hull::new(
        (frac(3, 2), frac(7, 4)),
        m(1),
        (m(1), frac(3, 2), frac(3, 5)),
        m(300),
    )?];
    let zero = Vec3::new(m(0), m(0), m(0));
    Ok(Harbour {
        sea,
        hull,
        table: SurfaceTable::new(Smoothing::CatmullRom, DRAWN)?,
        points: [zero; DRAWN * DRAWN],
        normals: [zero; DRAWN * DRAWN],
    })
}

/// The sea and its hull, the surface drawn every frame.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let mut scene = harbour::<S>()?;
    let (dt, g) = (S::ratio(1, 60), S::ratio(981, 100));
    let costs = device::meter_frames(
        meter,
        &mut scene,
        |h| h.sea.step(dt, g, &mut h.hull),
        |h| {
            h.sea
                .draw(&h.table, &h.table, &mut h.points, &mut h.normals)
                .map(drop)
        },
    )?;
    // From the side: x across, y up, every drawn point.
    let view = dunas::ascii::View::new(
        Vec2::new(-S::ratio(1, 4), S::ratio(7, 5)),
        S::ratio(1, 9),
        S::ratio(1, 20),
    )?;
    let c = scene.hull[0];
    let frame = device::ascii_frame(|canvas| {
        for p in &scene.points {
            let (col, row) = view.cell(Vec2::new(p.x, p.y));
            canvas.plot(col, row, b'~');
        }
        device::draw_box(canvas, &view, (c.x, c.width), (c.bottom, c.height));
    })?;
    let heights = scene.sea.heights().iter().flatten().copied();
    let drawn = scene
        .points
        .iter()
        .chain(&scene.normals)
        .flat_map(|p| [p.x, p.y, p.z]);
    let coordinates = heights.chain([c.bottom, c.speed]).chain(drawn);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    let depth = scene.sea.surface_under((c.x, c.z), (c.width, c.length)) - c.bottom;
    report.belly_mm = Some((depth * S::from_i16(1000)).floor_i32());
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
