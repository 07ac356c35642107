//! The device harness shared by the microcontroller examples: an instruction meter (SysTick
//! under QEMU's `-icount`), semihosting output of `key=value` lines, the stack's high-water
//! mark, and the same report on the host. An example defines
//! `simulate<S: Scalar>(&mut impl Meter, fn(S) -> u32) -> Result<Report, Error>` at its root.
#![allow(dead_code)]

use dunas::prelude::*;

/// Frames each example runs.
pub const STEPS: usize = 600;
/// The ASCII frame a run ends with.
pub const W: usize = 40;
pub const H: usize = 14;

/// Counts the instructions `f` takes (0 where nothing can count them).
pub trait Meter {
    fn count<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32);
    /// As [`count`](Self::count), for a call past the counter's 2²⁴ ticks (about a million
    /// instructions; a dozen more for each wrap counted).
    fn count_long<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
        self.count(f)
    }
    /// The end of a frame [`meter_frames_checked`] metered (what a browser's meter reports
    /// frame by frame).
    fn frame_done(&mut self) {}
}

/// What a run reports.
pub struct Report {
    pub checksum: u32,
    /// The step and the drawing of the costliest frame, in instructions (0 on the host).
    pub step_instructions: u32,
    pub sample_instructions: u32,
    pub substeps: u16,
    /// Frames in which a collider pushed the rope, where the scene has colliders.
    pub touching_frames: Option<u32>,
    /// How far a sail's middle stands downwind of its mast (millimetres), for a sail.
    pub belly_mm: Option<i32>,
    /// The frame a scripted swipe cut the rope, where the scene cuts (0: it missed).
    pub cut_frame: Option<u32>,
    /// What one pin change cost, in instructions, where the example meters it.
    pub pin_instructions: Option<u32>,
    /// A frame that reels the rope against the same frame that does not, in thousandths,
    /// where the example meters it.
    pub reel_permille: Option<u32>,
    /// The costliest frame but one the example singles out (the cut's), where it does.
    pub other_frame_instructions: Option<u32>,
    /// The rope's largest stretch over the run, in thousandths, where the example measures it.
    pub stretch_permille: Option<u32>,
    /// A soft body's area at the end, in thousandths of its area at the start.
    pub area_permille: Option<u32>,
    /// The closest two parts of a rope's drawn curve that are not neighbours, over the run,
    /// in thousandths of its diameter, where the example measures it.
    pub closest_permille: Option<u32>,
    /// The deepest a drawn point went inside a collider over the run, in thousandths of
    /// the rope's thickness, where the example measures it.
    pub inside_permille: Option<u32>,
    /// Frames whose step reported it did not keep its method's promise
    /// (`StepInfo::converged` false), where the example counts them.
    pub unconverged_frames: Option<u32>,
    /// The scripted scene's folded state checksums (`common/golden.rs`), where the example
    /// runs it.
    pub golden: Option<u64>,
    /// The mean of the frames' instruction counts (step and drawing).
    pub mean_frame_instructions: u32,
    pub frame: [u8; W * H],
}

/// FNV-1a over the raw bits of every coordinate: equal only for bit-identical states.
pub fn checksum<S: Scalar>(
    coordinates: impl IntoIterator<Item = S>,
    bits: impl Fn(S) -> u32,
) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    for c in coordinates {
        for b in bits(c).to_le_bytes() {
            h ^= b as u32;
            h = h.wrapping_mul(0x0100_0193);
        }
    }
    h
}

/// The catapult rope both device scenes swing: pinned at the origin, a weight on its end,
/// released 40° from hanging, in pixel units (y up; 70 long, particles 10 apart). Everything
/// else is the library's defaults; constants come from integers and ratios, so no f64
/// conversion code reaches the device.
pub fn catapult_rope<S: Scalar>() -> Result<Rope<Vec2<S>, 8>, Error> {
    let px = |v: i16| S::from_i16(v);
    let frac = |n: u32, d: u32| S::ratio(n, d);
    // The default integrator, symplectic Euler, is a type: no other integrator is linked.
    let settings = Settings {
        gravity: Vec2::new(px(0), px(-200)),
        damping: frac(1, 10),
        ..Settings::default()
    };
    let material = Material {
        stiffness: px(300),
        damping: frac(1, 2),
    };
    let mut rope = Rope::new(
        Vec2::new(px(0), px(0)),
        Vec2::new(px(45), -frac(536, 10)),
        px(7),
        material,
        settings,
    )?;
    rope.set_inv_mass(7, frac(1, 4))?;
    Ok(rope)
}

/// Room for the curve: Catmull-Rom over 7 spans, each halved twice, is 29 points.
pub const CURVE: usize = 33;

/// The instruction counts of [`STEPS`] metered frames.
pub struct Costs {
    /// The step and the drawing of the costliest frame.
    pub step: u32,
    pub sample: u32,
    /// The mean frame (step and drawing).
    pub mean: u32,
    /// Substeps of the last step.
    pub substeps: u16,
    /// Which frame was the costliest (from 1), and the costliest of all the others.
    pub costliest_at: u32,
    pub runner_up: u32,
}

impl Costs {
    /// The costliest frame but frame `skip` (from 1).
    pub fn costliest_but(&self, skip: u32) -> u32 {
        if self.costliest_at == skip {
            self.runner_up
        } else {
            self.step + self.sample
        }
    }
}

/// Runs [`STEPS`] frames of `step` (1/60 s of the scene) then `sample` (what the frame
/// draws), metering each.
pub fn meter_frames<T, S: Scalar>(
    meter: &mut impl Meter,
    scene: &mut T,
    step: impl FnMut(&mut T) -> Result<dunas::system::StepInfo<S>, Error>,
    sample: impl FnMut(&mut T) -> Result<(), Error>,
) -> Result<Costs, Error> {
    meter_frames_checked(meter, scene, (step, sample, |_| {}), false)
}

/// As [`meter_frames`], with `check` run after each frame and not metered (what the example
/// measures of the scene, not what a game would run); each step metered with
/// [`Meter::count_long`] when `long` (steps past the counter's million instructions).
pub fn meter_frames_checked<T, S: Scalar>(
    meter: &mut impl Meter,
    scene: &mut T,
    (mut step, mut sample, mut check): (
        impl FnMut(&mut T) -> Result<dunas::system::StepInfo<S>, Error>,
        impl FnMut(&mut T) -> Result<(), Error>,
        impl FnMut(&mut T),
    ),
    long: bool,
) -> Result<Costs, Error> {
    let mut costs = Costs {
        step: 0,
        sample: 0,
        mean: 0,
        substeps: 0,
        costliest_at: 0,
        runner_up: 0,
    };
    // In 32 bits (a 64-bit division would cost the M0 1.3 KB of flash): exact while the
    // frames average under 7 million instructions.
    let mut total: u32 = 0;
    for frame in 1..=STEPS as u32 {
        let (stepped, n) = if long {
            meter.count_long(|| step(scene))
        } else {
            meter.count(|| step(scene))
        };
        let (sampled, m) = meter.count(|| sample(scene));
        costs.substeps = stepped?.substeps;
        sampled?;
        meter.frame_done();
        check(scene);
        total = total.saturating_add(n + m);
        let costliest = costs.step + costs.sample;
        if n + m > costliest {
            costs.runner_up = costliest;
            (costs.step, costs.sample, costs.costliest_at) = (n, m, frame);
        } else {
            costs.runner_up = costs.runner_up.max(n + m);
        }
    }
    costs.mean = total / STEPS as u32;
    Ok(costs)
}

/// Runs [`STEPS`] frames of `step` (which advances the rope by 1/60 s) and a Catmull-Rom
/// curve of the rope, metering each; returns the report of the last frame's state, the ASCII
/// frame drawn with `decorate` (what else the scene shows).
pub fn run_frames<S: Scalar>(
    meter: &mut impl Meter,
    bits: impl Fn(S) -> u32,
    rope: &mut Rope<Vec2<S>, 8>,
    mut step: impl FnMut(&mut Rope<Vec2<S>, 8>) -> Result<dunas::system::StepInfo<S>, Error>,
    decorate: impl FnOnce(&mut dunas::ascii::Canvas, &dunas::ascii::View<Vec2<S>>),
) -> Result<Report, Error> {
    let mut scene = (rope, [Vec2::new(S::ZERO, S::ZERO); CURVE]);
    let costs = meter_frames(
        meter,
        &mut scene,
        |(rope, _)| step(rope),
        |(rope, curve)| rope.sample(Smoothing::CatmullRom, curve).map(drop),
    )?;
    let (rope, curve) = scene;
    let view = dunas::ascii::View::new(
        Vec2::new(S::from_i16(-60), S::from_i16(6)),
        S::from_i16(3),
        S::from_i16(6),
    )?;
    let frame = ascii_frame(|canvas| {
        decorate(canvas, &view);
        canvas.polyline(&view, &curve, b'#');
        canvas.points(&view, rope.positions(), b'o');
    })?;
    let coordinates = rope.positions().iter().flat_map(|p| [p.x, p.y]);
    Ok(report(checksum(coordinates, bits), &costs, frame))
}

/// The final ASCII frame, as `draw` paints it on a blank canvas.
pub fn ascii_frame(draw: impl FnOnce(&mut dunas::ascii::Canvas)) -> Result<[u8; W * H], Error> {
    let mut frame = [b' '; W * H];
    draw(&mut dunas::ascii::Canvas::new(&mut frame, W, H)?);
    Ok(frame)
}

/// A floating body's box seen from the side: centred on `x`, `width` wide, from `bottom`
/// up `height`, drawn with `#`.
pub fn draw_box<S: Scalar>(
    canvas: &mut dunas::ascii::Canvas,
    view: &dunas::View<Vec2<S>>,
    (x, width): (S, S),
    (bottom, height): (S, S),
) {
    let (l, r) = (x - width * S::ratio(1, 2), x + width * S::ratio(1, 2));
    let t = bottom + height;
    let outline = [
        Vec2::new(l, bottom),
        Vec2::new(r, bottom),
        Vec2::new(r, t),
        Vec2::new(l, t),
        Vec2::new(l, bottom),
    ];
    canvas.polyline(view, &outline, b'#');
}

/// The report of a run: its checksum, its costs and its final frame.
pub fn report(checksum: u32, costs: &Costs, frame: [u8; W * H]) -> Report {
    Report {
        checksum,
        step_instructions: costs.step,
        sample_instructions: costs.sample,
        substeps: costs.substeps,
        touching_frames: None,
        belly_mm: None,
        cut_frame: None,
        pin_instructions: None,
        reel_permille: None,
        other_frame_instructions: None,
        stretch_permille: None,
        area_permille: None,
        closest_permille: None,
        inside_permille: None,
        unconverged_frames: None,
        golden: None,
        mean_frame_instructions: costs.mean,
        frame,
    }
}

pub fn q16_bits(x: Q16) -> u32 {
    x.to_bits() as u32
}

pub fn f32_bits(x: f32) -> u32 {
    x.to_bits()
}

/// The template firmware crate's SysTick meter (`boards/template`), which the Arm boards use.
#[cfg(all(target_os = "none", target_arch = "arm"))]
#[path = "../../boards/template/src/meter.rs"]
mod meter;

#[cfg(target_os = "none")]
mod board {
    use core::panic::PanicInfo;

    use super::*;
    use arch::{Counter, exit, put};

    /// A Cortex-M: SysTick counts (the template firmware crate's meter), semihosting prints
    /// (`-semihosting-config` in the runner).
    #[cfg(target_arch = "arm")]
    mod arch {
        use cortex_m_rt::entry;
        use cortex_m_semihosting::{debug, hio};

        use super::{Meter, fail};

        pub use super::super::meter::Meter as Counter;

        impl Meter for Counter {
            fn count<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
                Counter::count(self, f)
            }

            fn count_long<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
                Counter::count_long(self, f)
            }
        }

        /// Writes to the host's standard output.
        pub fn put(bytes: &[u8]) {
            if let Ok(mut out) = hio::hstdout() {
                let _ = out.write_all(bytes);
            }
        }

        pub fn exit(ok: bool) -> ! {
            debug::exit(if ok {
                debug::EXIT_SUCCESS
            } else {
                debug::EXIT_FAILURE
            });
            loop {}
        }

        pub fn stack_pointer() -> usize {
            cortex_m::register::msp::read() as usize
        }

        #[entry]
        fn main() -> ! {
            let Some(peripherals) = cortex_m::Peripherals::take() else {
                fail(b"peripherals")
            };
            super::main(Counter::new(peripherals.SYST))
        }
    }

    /// A RISC-V core in machine mode: `minstret` counts (exact under `-icount`), semihosting
    /// prints (QEMU's `-semihosting-config`).
    #[cfg(target_arch = "riscv32")]
    mod arch {
        use core::arch::asm;
        use core::sync::atomic::{AtomicUsize, Ordering};

        use super::Meter;

        /// Instruction counts from `minstret`.
        pub struct Counter {
            /// Counts of the measurement itself (two back-to-back reads).
            overhead: u32,
            /// Counts per 1000 instructions (see [`calibrate`]): 1000 under QEMU.
            pub per_1000: u32,
        }

        /// `minstret` and `minstreth`, read so that they agree.
        fn retired() -> u64 {
            loop {
                let (hi, lo, again): (u32, u32, u32);
                unsafe {
                    asm!(
                        "csrr {0}, minstreth",
                        "csrr {1}, minstret",
                        "csrr {2}, minstreth",
                        out(reg) hi, out(reg) lo, out(reg) again,
                        options(nomem, nostack)
                    )
                };
                if hi == again {
                    return (u64::from(hi) << 32) | u64::from(lo);
                }
            }
        }

        impl Counter {
            fn retired_during(&mut self, f: impl FnOnce()) -> u64 {
                let start = retired();
                f();
                retired() - start
            }

            fn new() -> Counter {
                let mut s = Counter {
                    overhead: 0,
                    per_1000: 1,
                };
                s.overhead = s.retired_during(|| {}) as u32;
                s.per_1000 = calibrate(|turns| s.retired_during(|| countdown(turns)) as u32);
                s
            }
        }

        /// Ticks per 1000 instructions, from `ticks(turns)`, the ticks of `turns` turns of a
        /// 4-instruction loop: two calls alike but for 25 000 more turns in one, whose difference
        /// is 100 000 instructions from a dozen bytes of code. (As the Arm meter does.)
        fn calibrate(mut ticks: impl FnMut(u32) -> u32) -> u32 {
            let long = ticks(50_000);
            let short = ticks(25_000);
            (long.saturating_sub(short) / 100).max(1)
        }

        /// Instructions in `ticks`, the meter's own `overhead` taken out, rounded; in 32-bit
        /// arithmetic (a 64-bit division would cost the M0 1.3 KB of flash), exact up to 2³²
        /// ticks, some 200 million instructions.
        fn instructions(ticks: u64, overhead: u32, per_1000: u32) -> u32 {
            let t = u32::try_from(ticks.saturating_sub(u64::from(overhead))).unwrap_or(u32::MAX);
            (t / per_1000) * 1000 + ((t % per_1000) * 1000 + per_1000 / 2) / per_1000
        }

        /// `turns` turns of a loop of exactly 4 instructions (`addi`, two `nop`s, `bnez`).
        #[inline(never)]
        pub fn countdown(turns: u32) {
            unsafe {
                asm!(
                    "2:",
                    "addi {0}, {0}, -1",
                    "nop",
                    "nop",
                    "bnez {0}, 2b",
                    inout(reg) turns => _,
                    options(nomem, nostack)
                )
            }
        }

        impl Meter for Counter {
            fn count<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
                let mut out = None;
                let n = self.retired_during(|| out = Some(f()));
                match out {
                    Some(r) => (r, instructions(n, self.overhead, self.per_1000)),
                    None => super::fail(b"meter"),
                }
            }
        }

        /// A semihosting call (`op`, `arg`), in the uncompressed sequence the RISC-V
        /// semihosting spec asks for; what it returns.
        fn semihost(op: usize, arg: usize) -> usize {
            let out: usize;
            unsafe {
                asm!(
                    ".option push",
                    ".option norvc",
                    ".balign 16",
                    "slli x0, x0, 0x1f",
                    "ebreak",
                    "srai x0, x0, 7",
                    ".option pop",
                    inout("a0") op => out,
                    in("a1") arg,
                    options(nostack)
                )
            };
            out
        }

        /// The host's standard output once opened (`usize::MAX` before).
        static STDOUT: AtomicUsize = AtomicUsize::new(usize::MAX);

        /// Writes to the host's standard output (`SYS_OPEN` of `:tt` for writing, once, then
        /// `SYS_WRITE`; `SYS_WRITEC` would go to QEMU's console, its standard error).
        pub fn put(bytes: &[u8]) {
            let mut handle = STDOUT.load(Ordering::Relaxed);
            if handle == usize::MAX {
                let name = b":tt\0";
                handle = semihost(0x01, [name.as_ptr() as usize, 4, 3].as_ptr() as usize);
                STDOUT.store(handle, Ordering::Relaxed);
            }
            semihost(
                0x05,
                [handle, bytes.as_ptr() as usize, bytes.len()].as_ptr() as usize,
            );
        }

        /// `SYS_EXIT` with the application's exit (0) or a run-time error (1).
        pub fn exit(ok: bool) -> ! {
            semihost(0x18, if ok { 0x2_0026 } else { 0x2_0023 });
            loop {}
        }

        pub fn stack_pointer() -> usize {
            let sp: usize;
            unsafe { asm!("mv {0}, sp", out(reg) sp, options(nomem, nostack)) };
            sp
        }

        #[riscv_rt::entry]
        fn main() -> ! {
            super::main(Counter::new())
        }
    }

    // Integers are written by hand, so that `core::fmt` (20-30 KiB with its float code)
    // stays out of flash.

    /// `key=value` in decimal, or in hex (8 digits) with `hex`.
    fn put_number(key: &[u8], value: u32, hex: bool) {
        put_line(key, b"", value, hex);
    }

    /// `key=value` in decimal, with a `-` for a negative value.
    fn put_signed(key: &[u8], value: i32) {
        let sign: &[u8] = if value < 0 { b"-" } else { b"" };
        put_line(key, sign, value.unsigned_abs(), false);
    }

    /// `key=` then `sign` then the digits of `value`, and a newline.
    fn put_line(key: &[u8], sign: &[u8], value: u32, hex: bool) {
        let base = if hex { 16 } else { 10 };
        let mut digits = [0u8; 10];
        let (mut v, mut n) = (value, 0);
        loop {
            let d = (v % base) as u8;
            digits[n] = if d < 10 { b'0' + d } else { b'a' + d - 10 };
            n += 1;
            v /= base;
            if v == 0 && (!hex || n >= 8) {
                break;
            }
        }
        put(key);
        put(b"=");
        put(sign);
        digits[..n].reverse();
        put(&digits[..n]);
        put(b"\n");
    }

    /// `key=value` in hex, 16 digits.
    fn put_hex64(key: &[u8], value: u64) {
        let mut digits = [0u8; 16];
        for (i, d) in digits.iter_mut().enumerate() {
            let nibble = ((value >> (60 - 4 * i)) & 0xf) as u8;
            *d = if nibble < 10 {
                b'0' + nibble
            } else {
                b'a' + nibble - 10
            };
        }
        put(key);
        put(b"=");
        put(&digits);
        put(b"\n");
    }

    fn fail(what: &[u8]) -> ! {
        put(b"error=");
        put(what);
        put(b"\n");
        exit(false)
    }

    const PAINT: u32 = 0xdead_beef;

    unsafe extern "C" {
        static mut __sheap: u32;
        static _stack_start: u32;
    }

    /// Fills the free RAM between the end of .bss and the current stack with a pattern.
    fn paint_stack() {
        unsafe {
            let mut p = core::ptr::addr_of_mut!(__sheap);
            let sp = arch::stack_pointer() as *mut u32;
            while p < sp.sub(16) {
                p.write_volatile(PAINT);
                p = p.add(1);
            }
        }
    }

    /// The deepest the stack reached: from the top of RAM down to the first overwritten word.
    fn stack_high_water() -> u32 {
        unsafe {
            let mut p = core::ptr::addr_of!(__sheap);
            while p.read_volatile() == PAINT {
                p = p.add(1);
            }
            core::ptr::addr_of!(_stack_start) as u32 - p as u32
        }
    }

    #[cfg(target_abi = "eabihf")]
    fn run(meter: &mut Counter) -> Result<Report, Error> {
        put(b"format=f32\n");
        crate::simulate::<f32>(meter, f32_bits)
    }

    #[cfg(not(target_abi = "eabihf"))]
    fn run(meter: &mut Counter) -> Result<Report, Error> {
        put(b"format=q16\n");
        crate::simulate::<Q16>(meter, q16_bits)
    }

    /// Runs the example with `meter` and prints its report.
    fn main(mut meter: Counter) -> ! {
        paint_stack();
        match run(&mut meter) {
            Ok(r) => {
                for row in r.frame.chunks(W) {
                    put(b"|");
                    put(row);
                    put(b"|\n");
                }
                put_number(b"steps", STEPS as u32, false);
                put_number(b"substeps", r.substeps as u32, false);
                put_number(b"checksum", r.checksum, true);
                if let Some(n) = r.touching_frames {
                    put_number(b"touching_frames", n, false);
                }
                if let Some(mm) = r.belly_mm {
                    put_signed(b"belly_mm", mm);
                }
                if let Some(n) = r.cut_frame {
                    put_number(b"cut_frame", n, false);
                }
                if let Some(n) = r.pin_instructions {
                    put_number(b"pin_instructions", n, false);
                }
                if let Some(n) = r.reel_permille {
                    put_number(b"reel_permille", n, false);
                }
                if let Some(n) = r.stretch_permille {
                    put_number(b"stretch_permille", n, false);
                }
                if let Some(n) = r.area_permille {
                    put_number(b"area_permille", n, false);
                }
                if let Some(n) = r.closest_permille {
                    put_number(b"closest_permille", n, false);
                }
                if let Some(n) = r.inside_permille {
                    put_number(b"inside_permille", n, false);
                }
                if let Some(n) = r.unconverged_frames {
                    put_number(b"unconverged_frames", n, false);
                }
                if let Some(n) = r.golden {
                    put_hex64(b"golden", n);
                }
                put_number(b"step_instructions", r.step_instructions, false);
                put_number(b"sample_instructions", r.sample_instructions, false);
                put_number(
                    b"frame_instructions",
                    r.step_instructions + r.sample_instructions,
                    false,
                );
                if let Some(n) = r.other_frame_instructions {
                    put_number(b"other_frame_instructions", n, false);
                }
                put_number(b"mean_frame_instructions", r.mean_frame_instructions, false);
                put_number(b"ticks_per_1000_instructions", meter.per_1000, false);
                put_number(b"stack_bytes", stack_high_water(), false);
                exit(true)
            }
            Err(Error::Diverged) => fail(b"diverged"),
            Err(_) => fail(b"setup"),
        }
    }

    #[panic_handler]
    fn panic(_: &PanicInfo) -> ! {
        fail(b"panic")
    }
}

#[cfg(not(target_os = "none"))]
pub struct NoMeter;

#[cfg(not(target_os = "none"))]
impl Meter for NoMeter {
    fn count<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
        (f(), 0)
    }
}

/// In a browser (wasm32): frames timed by the page's clock, `performance.now()` through the
/// imports `web/devices.mjs` gives (`meter.now`, in milliseconds), each frame's time handed
/// to the page (`meter.frame`) as it ends; `run(format)` (0 Q16.16, 1 f32) plays the
/// example and returns its checksum, or -1 when the simulation failed.
#[cfg(target_arch = "wasm32")]
mod browser {
    use super::*;

    #[link(wasm_import_module = "meter")]
    unsafe extern "C" {
        /// `performance.now()`: milliseconds.
        fn now() -> f64;
        /// A metered frame's time, in milliseconds.
        fn frame(ms: f64);
    }

    /// The time of the counts since the last frame ended (ms); counts are in nanoseconds.
    struct Clock(f64);

    impl Meter for Clock {
        fn count<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
            // SAFETY: imports without arguments or memory access; the page provides them.
            let start = unsafe { now() };
            let result = f();
            let ms = unsafe { now() } - start;
            self.0 += ms;
            (result, (ms * 1e6) as u32)
        }

        fn frame_done(&mut self) {
            // SAFETY: as above; the page records the value.
            unsafe { frame(self.0) };
            self.0 = 0.0;
        }
    }

    #[unsafe(no_mangle)]
    extern "C" fn run(format: u32) -> i64 {
        let report = match format {
            0 => crate::simulate::<Q16>(&mut Clock(0.0), q16_bits),
            _ => crate::simulate::<f32>(&mut Clock(0.0), f32_bits),
        };
        report.map_or(-1, |r| i64::from(r.checksum))
    }
}

/// An example's `simulate` in one format, on the host.
#[cfg(not(target_os = "none"))]
pub type Simulation<S> = fn(&mut NoMeter, fn(S) -> u32) -> Result<Report, Error>;

/// The host's run: the simulation named by the first argument (`q16`, the default, or `f32`),
/// printed as the device prints it (without instruction counts).
#[cfg(not(target_os = "none"))]
pub fn host_main(q16: Simulation<Q16>, f32: Simulation<f32>) {
    let name = env!("CARGO_CRATE_NAME");
    let format = std::env::args().nth(1).unwrap_or_else(|| "q16".into());
    let report = match format.as_str() {
        "q16" => q16(&mut NoMeter, q16_bits),
        "f32" => f32(&mut NoMeter, f32_bits),
        other => {
            eprintln!("{name}: unknown format {other} (q16 or f32)");
            std::process::exit(2);
        }
    };
    match report {
        Ok(r) => {
            for row in r.frame.chunks(W) {
                println!("|{}|", String::from_utf8_lossy(row));
            }
            println!("format={format}");
            println!("steps={STEPS}");
            println!("substeps={}", r.substeps);
            println!("checksum={:08x}", r.checksum);
            if let Some(n) = r.touching_frames {
                println!("touching_frames={n}");
            }
            if let Some(mm) = r.belly_mm {
                println!("belly_mm={mm}");
            }
            if let Some(n) = r.cut_frame {
                println!("cut_frame={n}");
            }
            if let Some(n) = r.stretch_permille {
                println!("stretch_permille={n}");
            }
            if let Some(n) = r.area_permille {
                println!("area_permille={n}");
            }
            if let Some(n) = r.closest_permille {
                println!("closest_permille={n}");
            }
            if let Some(n) = r.inside_permille {
                println!("inside_permille={n}");
            }
            if let Some(n) = r.unconverged_frames {
                println!("unconverged_frames={n}");
            }
            if let Some(n) = r.golden {
                println!("golden={n:016x}");
            }
        }
        Err(e) => {
            eprintln!("{name}: {e}");
            std::process::exit(1);
        }
    }
}
