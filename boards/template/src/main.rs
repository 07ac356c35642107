//! A dunas game's frame loop on a Cortex-M0, to copy and build on: an 8-particle rope in
//! Q16.16 held at one end by a hand that swings it, stepped and drawn (a Catmull-Rom curve of
//! 29 points) 60 times a second for 15 s, each frame metered. It prints the rope's end, the costliest
//! and the mean frame, and exits (under QEMU; on a board, the loop would run forever and
//! draw the points to a screen).
//!
//! `cargo run --release` (from this directory) builds it for the micro:bit and runs it on an
//! emulated one.
#![no_std]
#![no_main]

mod meter;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use dunas::prelude::*;
use dunas::{Q16, Sleep};

use meter::Meter;

/// A frame at 60 Hz.
const DT: Q16 = Q16::ratio(1, 60);
/// Frames to run: 15 s.
const FRAMES: u32 = 900;

/// The rope: 8 particles, 7 units long, mass 1, hanging from the origin, its top held.
fn rope() -> Result<Rope<Vec2<Q16>, 8>, Error> {
    let q = Q16::from_int;
    let settings = Settings {
        gravity: Vec2::new(q(0), Q16::ratio(-981, 100)),
        damping: Q16::from_int(2),
        ..Settings::default()
    };
    let material = Material {
        stiffness: q(400),
        damping: q(1),
    };
    let mut rope = Rope::new(
        Vec2::new(q(0), q(0)),
        Vec2::new(q(7), q(0)),
        q(1),
        material,
        settings,
    )?;
    // At rest it stops costing its step.
    rope.set_sleep(Some(Sleep::default()))?;
    Ok(rope)
}

/// Where the hand is at `frame`: 2 units right over the first 2 s, back over the next 2,
/// then still (the rope swings, settles and falls asleep).
fn hand(frame: u32) -> Vec2<Q16> {
    let f = frame.min(240) as i32;
    let x = if f <= 120 { f } else { 240 - f };
    Vec2::new(Q16::ratio(x, 60), Q16::from_int(0))
}

#[entry]
fn main() -> ! {
    let Some(peripherals) = cortex_m::Peripherals::take() else {
        stop(false)
    };
    let mut meter = Meter::new(peripherals.SYST);
    let Ok(mut rope) = rope() else { stop(false) };
    let mut curve = [Vec2::default(); 29];
    let (mut worst, mut total, mut asleep) = (0u32, 0u32, 0u32);
    for frame in 1..=FRAMES {
        // The step (`count_long`: a step of a stiffer scene may pass the counter's 2²⁴ ticks).
        let (stepped, step) = meter.count_long(|| {
            rope.move_pinned(0, hand(frame), DT)?;
            rope.step(DT)
        });
        // The drawing: the curve through the particles, 29 points.
        let (drawn, draw) = meter.count(|| rope.sample(Smoothing::CatmullRom, &mut curve));
        let (Ok(info), Ok(points)) = (stepped, drawn) else {
            stop(false)
        };
        // Here a game draws `curve[..points]` (asleep, it may keep the last frame's picture).
        let _ = &curve[..points];
        asleep += u32::from(info.asleep);
        worst = worst.max(step + draw);
        total = total.saturating_add(step + draw);
    }
    let end = rope.positions()[7];
    hprintln!(
        "rope end: ({}, {}) (Q16.16 bits)",
        end.x.to_bits(),
        end.y.to_bits()
    );
    hprintln!("frames asleep: {} of {}", asleep, FRAMES);
    hprintln!(
        "frame instructions: worst {}, mean {}",
        worst,
        total / FRAMES
    );
    stop(true)
}

/// Ends the run (under QEMU: exits with success or failure).
fn stop(ok: bool) -> ! {
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    // Not reached under QEMU; on a board, wait for the next reset.
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    stop(false)
}
