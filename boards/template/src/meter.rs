//! What a call costs, from the Cortex-M's SysTick timer: clock cycles on a board, and exact
//! instruction counts under QEMU with `-icount` (where the clock advances the same for every
//! instruction). dunas's own device examples count with this file too.

use core::arch::asm;
use core::sync::atomic::{AtomicU32, Ordering};

use cortex_m::peripheral::{SYST, syst::SystClkSource};
use cortex_m_rt::exception;

/// SysTick, free-running over its 24 bits, with its wraps counted for long calls.
pub struct Meter {
    syst: SYST,
    /// Ticks of the measurement itself (two back-to-back reads).
    overhead: u32,
    /// Ticks per 1000 instructions of a plain loop: on a board about 1000 × cycles per
    /// instruction; under QEMU a constant, so counts divide into exact instructions.
    pub per_1000: u32,
}

/// The counter's wraps during [`Meter::count_long`].
static WRAPS: AtomicU32 = AtomicU32::new(0);

#[exception]
fn SysTick() {
    // A load and a store (the Cortex-M0 has no atomic add); nothing else writes it.
    WRAPS.store(
        WRAPS.load(Ordering::Relaxed).wrapping_add(1),
        Ordering::Relaxed,
    );
}

impl Meter {
    /// Starts SysTick on the core clock and calibrates it.
    pub fn new(mut syst: SYST) -> Meter {
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(0x00ff_ffff);
        syst.clear_current();
        syst.enable_counter();
        let mut meter = Meter {
            syst,
            overhead: 0,
            per_1000: 1,
        };
        meter.overhead = meter.ticks(|| {});
        // Two calls alike but for 25 000 more turns of a 4-instruction loop in one: their
        // difference is 100 000 instructions. (QEMU's counter reads are some 100 ticks
        // coarse: a sled of 500 instructions was 0.8% off.)
        let long = meter.ticks(|| countdown(50_000));
        let short = meter.ticks(|| countdown(25_000));
        meter.per_1000 = (long.saturating_sub(short) / 100).max(1);
        meter
    }

    /// The ticks `f` takes, up to the counter's 2²⁴ (a second at 16 MHz).
    fn ticks(&mut self, f: impl FnOnce()) -> u32 {
        let start = SYST::get_current();
        f();
        let end = SYST::get_current();
        start.wrapping_sub(end) & 0x00ff_ffff // the counter counts down
    }

    /// `f`'s result and the instructions it took (under QEMU; on a board, cycles times
    /// 1000 / `per_1000`), for a call under 2²⁴ ticks.
    pub fn count<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
        let mut out = None;
        let t = self.ticks(|| out = Some(f()));
        match out {
            Some(r) => (r, self.instructions(u64::from(t))),
            None => unreachable!("the call ran"),
        }
    }

    /// As [`count`](Self::count), for a call of any length (an interrupt counts the wraps:
    /// a dozen instructions more for each).
    pub fn count_long<R>(&mut self, f: impl FnOnce() -> R) -> (R, u32) {
        WRAPS.store(0, Ordering::Relaxed);
        self.syst.enable_interrupt();
        let start = ticks_with_wraps();
        let out = f();
        let end = ticks_with_wraps();
        self.syst.disable_interrupt();
        (out, self.instructions(end - start))
    }

    /// Instructions in `ticks`, the meter's own taken out, rounded; in 32-bit arithmetic (a
    /// 64-bit division costs a Cortex-M0 1.3 KB of flash), exact up to 2³² ticks.
    fn instructions(&self, ticks: u64) -> u32 {
        let t = u32::try_from(ticks.saturating_sub(u64::from(self.overhead))).unwrap_or(u32::MAX);
        let p = self.per_1000;
        (t / p) * 1000 + ((t % p) * 1000 + p / 2) / p
    }
}

/// Ticks since the count began, from the wraps and the counter read so that they agree.
fn ticks_with_wraps() -> u64 {
    loop {
        let wraps = WRAPS.load(Ordering::Relaxed);
        let current = SYST::get_current();
        if WRAPS.load(Ordering::Relaxed) == wraps {
            return (u64::from(wraps) << 24) + u64::from(0x00ff_ffff - current);
        }
    }
}

/// `turns` turns of a loop of exactly 4 instructions (`subs`, two `nop`s, `bne`).
#[inline(never)]
fn countdown(turns: u32) {
    unsafe {
        asm!(
            "2:",
            "subs r0, #1",
            "nop",
            "nop",
            "bne 2b",
            inout("r0") turns => _,
            options(nomem, nostack)
        )
    }
}
