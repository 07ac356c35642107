//! The game-loop helper: a fixed simulation step fed by whatever the frame took.

use crate::error::invalid;
use crate::{Error, Scalar};

/// Turns variable frame times into a whole number of fixed simulation steps.
///
/// Physics is steadier and reproducible at a fixed step; the renderer runs at whatever rate
/// it gets. Each frame, [`advance`](Self::advance) adds the frame time to an accumulator and
/// says how many fixed steps to run. A hitch (the game paused in a debugger, a 1 s load
/// spike) is clamped to `max_frame`, so the simulation slows down for that frame instead of
/// running hundreds of steps; a NaN, infinite or negative frame time counts as 0.
///
/// ```
/// use dunas::FixedTimestep;
/// let mut clock = FixedTimestep::new(1.0 / 60.0, 0.1)?;
/// assert_eq!(clock.advance(1.0 / 30.0), 2); // a 30 fps frame: two 60 Hz steps
/// assert_eq!(clock.advance(1.0), 6); // a 1 s hitch: clamped to 0.1 s
/// assert_eq!(clock.advance(f32::NAN), 0);
/// # Ok::<(), dunas::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedTimestep<S> {
    step: S,
    max_frame: S,
    /// `ceil(max_frame / step)`: the most steps one frame returns.
    max_steps: u32,
    accumulator: S,
}

/// The most fixed steps one frame may ask for: a clock whose `max_frame / step` is larger is
/// refused, which also keeps `accumulator - step` from rounding back to the accumulator (a
/// loop that would never end) in every format.
pub const MAX_STEPS_PER_FRAME: u32 = 4096;

impl<S: Scalar> FixedTimestep<S> {
    /// A clock with the given step (seconds) and longest frame it will catch up on.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless `0 < step <= max_frame`, both finite, and
    /// `max_frame / step <= MAX_STEPS_PER_FRAME`.
    pub fn new(step: S, max_frame: S) -> Result<Self, Error> {
        if !(step > S::ZERO && step <= max_frame && max_frame.is_finite()) {
            return Err(invalid("step", "> 0 and at most the finite max_frame"));
        }
        let max_steps = (max_frame / step).ceil_usize(usize::MAX);
        if max_steps > MAX_STEPS_PER_FRAME as usize {
            return Err(invalid(
                "max_frame",
                "at most 4 096 steps (MAX_STEPS_PER_FRAME)",
            ));
        }
        Ok(FixedTimestep {
            step,
            max_frame,
            max_steps: max_steps as u32,
            accumulator: S::ZERO,
        })
    }

    /// The most steps one [`advance`](Self::advance) returns: `ceil(max_frame / step)`.
    pub fn max_steps(&self) -> u32 {
        self.max_steps
    }

    /// The fixed step (seconds).
    pub fn step(&self) -> S {
        self.step
    }

    /// Adds a frame's duration and returns how many fixed steps to run now: at most
    /// [`max_steps`](Self::max_steps), even when rounding has left more time in the
    /// accumulator (the excess is kept for later frames).
    pub fn advance(&mut self, frame: S) -> u32 {
        let frame = if frame > S::ZERO && frame.is_finite() {
            frame.min(self.max_frame)
        } else {
            S::ZERO
        };
        self.accumulator += frame;
        let mut steps = 0;
        // Bounded even if rounding ever stopped the accumulator from shrinking.
        while self.accumulator >= self.step && steps < self.max_steps {
            self.accumulator -= self.step;
            steps += 1;
        }
        steps
    }

    /// How far the accumulator is into the next step, in `[0, 1]`: blend the last two
    /// physics states by this to draw between steps. It is 1 only while the clock holds a
    /// whole step or more that [`advance`](Self::advance) kept for later (rounding on a
    /// frame of [`max_steps`](Self::max_steps) steps).
    pub fn alpha(&self) -> S {
        (self.accumulator / self.step).max(S::ZERO).min(S::ONE)
    }
}
