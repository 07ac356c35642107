//! Reeling a rope in and paying it out: its length changed at run time (a grappling hook, a
//! winch, a fishing reel, a crane's cable).

use crate::error::{check_positive, invalid};
use crate::objects::rope::Rope;
use crate::physics::integrator::Integrator;
use crate::physics::spring::Topology;
use crate::{Error, Point, Scalar};

impl<P: Point, const N: usize, const CAP: usize, I: Integrator> Rope<P, N, CAP, I> {
    /// The rope's length: the sum of its live links' rest lengths (the springs from particle
    /// `i` to `i + 1`; a cut link no longer counts). A pass over the springs.
    pub fn length(&self) -> P::Scalar {
        let mut length = P::Scalar::ZERO;
        self.topology().for_each_spring(|a, b, rest, _| {
            if a.abs_diff(b) == 1 {
                length += rest;
            }
        });
        length
    }

    /// The shortest and the longest length [`set_length`](Self::set_length) takes for this
    /// rope: `N − 1` links of at least 1 024 units of rounding each (1/64 in `Q16`,
    /// `1.2·10⁻⁴` in `f32`: below it a link's direction is lost to rounding), and at most
    /// [`Scalar::SAFE_RANGE`] in all (so that its ends' difference stays in the format).
    pub fn length_limits() -> (P::Scalar, P::Scalar) {
        let links = P::Scalar::from_i16(N.saturating_sub(1).min(i16::MAX as usize) as i16);
        let shortest_link = P::Scalar::EPSILON * P::Scalar::from_i16(1024);
        (shortest_link * links, P::Scalar::SAFE_RANGE)
    }

    /// Makes the rope `length` long: every spring's rest length (its links' and any other
    /// spring's) is scaled by the same factor, so the particles keep their count and their
    /// even spacing along the rope and the drawn curve stays smooth; the rope is reeled in
    /// or paid out evenly along it rather than through its held end. The particles stay
    /// where they are: the springs (or, with an inextensible
    /// [`DirectChain`](crate::integrator::DirectChain), the links' solve) bring them to the
    /// new length over the next steps. The stiffness of each spring is kept (a shorter rope
    /// is as stiff a link, so its stability and substeps do not change).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a length that is not positive and finite (a rope of
    /// length 0 is refused), or outside [`length_limits`](Self::length_limits), or for a
    /// rope with no live link; nothing changes then.
    pub fn set_length(&mut self, length: P::Scalar) -> Result<(), Error> {
        check_positive(length, "length")?;
        let (shortest, longest) = Self::length_limits();
        if length < shortest || length > longest {
            return Err(invalid(
                "length",
                "within the rope's length limits (Rope::length_limits)",
            ));
        }
        let now = self.length();
        if now <= P::Scalar::ZERO {
            return Err(invalid("length", "a rope with a live link"));
        }
        let factor = length / now;
        self.with_topology(|springs| springs.scale_rest(factor))
    }

    /// Reels the rope toward `target` length at up to `speed` units a second for `dt`
    /// seconds (in or out, whichever way `target` is), and returns its new length: one
    /// call a frame, as a winch turns. See [`set_length`](Self::set_length) for what
    /// changes. Cost: two passes over the springs and the stiffness bound's update.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite `speed` or `dt`, and
    /// [`set_length`](Self::set_length)'s errors for `target`; nothing changes then.
    ///
    /// ```
    /// use dunas::integrator::DirectChain;
    /// use dunas::prelude::*;
    /// // A grappling hook's rope: 10 m, a 70 kg player on its end, reeled in at 2 m/s.
    /// let settings = Settings { gravity: Vec2::new(0.0, -9.81), ..Settings::default() }
    ///     .with_integrator(DirectChain::default());
    /// let material = Material { stiffness: 2000.0, damping: 1.0 };
    /// let mut rope: Rope<Vec2<f32>, 12, 12, DirectChain> =
    ///     Rope::new(Vec2::new(0.0, 0.0), Vec2::new(0.0, -10.0), 2.0, material, settings)?;
    /// rope.hang(11, 70.0)?;
    /// for _ in 0..120 {
    ///     rope.reel(6.0, 2.0, 1.0 / 60.0)?;
    ///     rope.step(1.0 / 60.0)?;
    /// }
    /// assert!((rope.length() - 6.0).abs() < 1e-3);
    /// assert!((rope.positions()[11].y + 6.0).abs() < 0.05, "{:?}", rope.positions()[11]);
    /// # Ok::<(), dunas::Error>(())
    /// ```
    pub fn reel(
        &mut self,
        target: P::Scalar,
        speed: P::Scalar,
        dt: P::Scalar,
    ) -> Result<P::Scalar, Error> {
        for (value, name) in [(speed, "speed"), (dt, "dt")] {
            if !(value >= P::Scalar::ZERO && value.is_finite()) {
                return Err(invalid(name, "finite and >= 0"));
            }
        }
        check_positive(target, "target")?;
        let (shortest, longest) = Self::length_limits();
        if target < shortest || target > longest {
            return Err(invalid(
                "target",
                "within the rope's length limits (Rope::length_limits)",
            ));
        }
        let now = self.length();
        let step = speed * dt;
        let next = if target > now {
            (now + step).min(target)
        } else {
            (now - step).max(target)
        };
        if next != now {
            self.set_length(next)?;
        }
        Ok(next)
    }
}
