//! Water on a microcontroller: a 4 m pool of 16 columns (`water::Water`, waves at 3 m/s,
//! calmed a little) and a crate dropped into it that floats by buoyancy and makes waves,
//! stepped at 60 Hz for 600 frames and drawn every frame as a Catmull-Rom curve of 61 points
//! through the columns, in Q16.16 on a Cortex-M0 (the same code runs in f32).
//!
//! It prints what `mcu_rope` prints (the final frame: `~` the surface, `#` the crate), plus
//! `belly_mm=` (here: how deep the crate floats below the surface under it, in millimetres;
//! Archimedes says 200); the checksum covers every column, the crate and every drawn point
//! of the last frame, so equal checksums on the host and the device mean that the waves,
//! the buoyancy and the curve ran bit-identically:
//!
//! `cargo run --release --target thumbv6m-none-eabi --example mcu_water` (Q16.16, micro:bit)
//! `cargo run --release --example mcu_water` (the same on the host) or `... -- f32`.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[path = "common/device.rs"]
mod device;

use device::{Meter, Report};
use dunas::prelude::*;
use dunas::water::{Floater, Water};

const COLUMNS: usize = 16;
const DRAWN: usize = 4 * (COLUMNS - 1) + 1;

/// The pool, its crate and what it draws.
struct Pool<S: Scalar> {
    water: Water<S, COLUMNS>,
    crate_: [Floater<S>; 1],
    curve: [Vec2<S>; DRAWN],
}

/// A pool 1 m deep, 1000 kg/m², waves at 3 m/s, and a 0.5 m × 0.6 m crate of 100 kg held 0.2 m
/// above it.
/// Constants come from integers and ratios, so no f64 code reaches the device.
fn pool<S: Scalar>() -> Result<Pool<S>, Error> {
    let m = |v: i16| S::from_i16(v);
    let frac = |n: u32, d: u32| S::ratio(n, d);
    let water = Water::new(m(0), frac(1, 4), m(1), m(3), m(1000))?.with_damping(m(1))?;
    let crate_ = [Floater::new(
        m(2),
        frac(6, 5),
        frac(1, 2),
        frac(3, 5),
        m(100),
    )?];
    Ok(Pool {
        water,
        crate_,
        curve: [Vec2::new(m(0), m(0)); DRAWN],
    })
}

/// The crate dropped into the pool, the surface drawn every frame.
pub fn simulate<S: Scalar>(meter: &mut impl Meter, bits: fn(S) -> u32) -> Result<Report, Error> {
    let mut scene = pool::<S>()?;
    let (dt, g) = (S::ratio(1, 60), S::ratio(981, 100));
    let costs = device::meter_frames(
        meter,
        &mut scene,
        |p| p.water.step(dt, g, &mut p.crate_),
        |p| p.water.draw(Smoothing::CatmullRom, &mut p.curve).map(drop),
    )?;
    let view = dunas::ascii::View::new(
        Vec2::new(S::ZERO, S::ratio(3, 2)),
        S::ratio(1, 10),
        S::ratio(1, 10),
    )?;
    let c = scene.crate_[0];
    let frame = device::ascii_frame(|canvas| {
        canvas.polyline(&view, &scene.curve, b'~');
        device::draw_box(canvas, &view, (c.x, c.width), (c.bottom, c.height));
    })?;
    let heights = scene.water.heights().iter().copied();
    let drawn = scene.curve.iter().flat_map(|p| [p.x, p.y]);
    let coordinates = heights.chain([c.bottom, c.speed]).chain(drawn);
    let mut report = device::report(device::checksum(coordinates, bits), &costs, frame);
    let depth = scene.water.surface_under(c.x, c.width) - c.bottom;
    report.belly_mm = Some((depth * S::from_i16(1000)).floor_i32());
    Ok(report)
}

#[cfg(not(target_os = "none"))]
fn main() {
    device::host_main(simulate::<Q16>, simulate::<f32>);
}
