//! When a frame's contacts run, and what friction takes back of the sliding since they last
//! ran. A frame within reach resolves its contacts before a point can close on a collider
//! by more than the thickness ([`Contacts::due`]) and at the step's end: a rope that the
//! springs split into 8 substeps but that moves slowly meets its colliders once a frame,
//! not 8 times.

use super::Contacts;
use super::drawn::point_of;
use crate::{Point, Scalar};

/// A call of the contacts at the end of a substep.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Timing<'a, P: Point> {
    /// The substep's length (s); 0 for a round with no time passing.
    pub(crate) h: P::Scalar,
    /// Seconds from the substep's end to the step's (a kinematic collider is that far
    /// behind its pose).
    pub(crate) lag: P::Scalar,
    /// The substeps since the contacts last ran, and how far each particle moved since
    /// then; `None` when they ran at the end of the substep before (or no time passes).
    waited: Option<(u16, &'a [P])>,
}

impl<'a, P: Point> Timing<'a, P> {
    /// The contacts of a substep of `h` ending `lag` seconds before the step's end, right
    /// after the last.
    pub(crate) fn substep((h, lag): (P::Scalar, P::Scalar)) -> Self {
        Timing {
            h,
            lag,
            waited: None,
        }
    }

    /// The contacts of the same substep after `count` substeps (more than one) without
    /// them, each particle having moved by `slid` since.
    pub(crate) fn waited(self, count: u16, slid: &'a [P]) -> Self {
        Timing {
            waited: Some((count, slid)),
            ..self
        }
    }

    /// The same substep's contacts in a round after the first: what slid since the
    /// contacts last ran was taken back once, by the first.
    pub(crate) fn again(self) -> Self {
        Timing {
            waited: None,
            ..self
        }
    }

    /// The same timing for a run of particles whose motion since the contacts last ran is
    /// `slid` (a cut rope's piece), when one was waited for.
    pub(crate) fn for_run<'b>(&self, slid: &'b [P]) -> Timing<'b, P> {
        Timing {
            h: self.h,
            lag: self.lag,
            waited: self.waited.map(|(count, _)| (count, slid)),
        }
    }

    /// How far the particles moved since the contacts last ran, when more than a substep
    /// ago.
    pub(crate) fn slid(&self) -> Option<&'a [P]> {
        self.waited.map(|(_, slid)| slid)
    }

    /// What friction takes back at a point with particle weights `w` touching a body that
    /// moves at `body_velocity`.
    #[inline]
    pub(super) fn braking(
        &self,
        w: impl IntoIterator<Item = (usize, P::Scalar)>,
        body_velocity: P,
    ) -> Braking<P> {
        match self.waited {
            None => Braking {
                time: self.h,
                slid: None,
            },
            Some((count, slid)) => self.after_waiting(count, point_of(slid, w), body_velocity),
        }
    }

    /// [`braking`](Self::braking) after `count` substeps without contacts, in which the
    /// point moved by `slid`.
    #[cold]
    #[inline(never)]
    fn after_waiting(&self, count: u16, slid: P, body_velocity: P) -> Braking<P> {
        let time = self.h * P::Scalar::ratio(u32::from(count), 1);
        Braking {
            time: self.h * P::Scalar::ratio(u32::from(count) + 1, 2),
            slid: Some(slid - body_velocity * time),
        }
    }
}

/// What friction takes back of a contact's sliding, in position: the braking times `time`,
/// or, when it holds the point still and the contacts waited substeps, all the point
/// `slid` along the collider since they last ran.
#[derive(Clone, Copy, Debug)]
pub(super) struct Braking<P: Point> {
    /// Over `n` substeps of `h` since the contacts last ran, `h (n + 1) / 2`: what friction
    /// at the end of each would have taken back of a steady slide, in all.
    time: P::Scalar,
    /// How far the point moved against the collider since the contacts last ran.
    slid: Option<P>,
}

impl<P: Point> Braking<P> {
    /// The position change that takes back the sliding that `brake` stops of `slide` (the
    /// point's velocity across `normal`), the friction's limits `(static, kinetic)` (m/s of
    /// braking): static friction (`brake == slide`) takes back all the point slid across
    /// `normal` since the contacts last ran, when that is no more than the static limit
    /// times the time (a point that slid at a steady rate within the limit: a rope on a
    /// slope stays put); a point that slid farther, although it slides slowly now (a
    /// solve's links pulled it across the floor), as far as the kinetic limit times the time
    /// along it. Kinetic friction, and every contact of a substep right after the last, the
    /// braking times the time.
    #[inline]
    pub(super) fn take_back(
        &self,
        (slide, brake): (P, P),
        normal: P,
        (stick, kinetic): (P::Scalar, P::Scalar),
    ) -> P {
        match self.slid {
            Some(slid) if brake == slide => {
                let across = slid - normal * slid.dot(normal);
                if across.shorter_than(stick * self.time) {
                    return across;
                }
                let length = across.length();
                match length > P::Scalar::ZERO {
                    true => across * (kinetic * self.time / length),
                    false => P::default(),
                }
            }
            _ => brake * self.time,
        }
    }
}

/// The substeps since a frame's contacts last ran.
#[derive(Clone, Copy, Default)]
pub(super) struct Waited<S> {
    /// Their time (s).
    pub(super) time: S,
    /// Their count.
    pub(super) count: u16,
}

impl<P: Point> Contacts<'_, P> {
    /// Whether contacts that [`may_wait`](Self::may_wait) are due at the end of a substep
    /// of `h` ending `lag` seconds before the step's end (`waited`: the substeps since they
    /// last ran, this one counted), for particles now moving at `v`, in a frame where a
    /// point closes on a collider at `closing` at most for particle speeds up to `speed`,
    /// by `allowance` at most between runs ([`rate`](Self::rate)): at the step's end; when
    /// a point could close by more than the allowance by the end of another substep since
    /// they last ran; when a particle moves as fast as `speed` or faster (the bound holds no
    /// longer). Costs a pass over the velocities (their squares, no root) when nothing else
    /// makes them due.
    pub(super) fn due(
        &self,
        (h, lag): (P::Scalar, P::Scalar),
        waited: &Waited<P::Scalar>,
        (closing, speed, allowance): (P::Scalar, P::Scalar, P::Scalar),
        v: &[P],
    ) -> bool {
        lag <= P::Scalar::ZERO
            || (waited.time + h) * closing > allowance
            || v.iter().any(|v| !v.shorter_than(speed))
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;

    /// Static friction after waited substeps takes back all the point slid across the
    /// normal, up to its limit times `h (n + 1) / 2` (beyond, the kinetic limit times that
    /// along it); kinetic friction the braking times `h (n + 1) / 2`; right after the last
    /// contacts, the braking times `h`.
    #[test]
    fn friction_takes_back_what_it_stops() {
        let slid = [Vec2::new(0.3f64, -0.2), Vec2::new(0.1, 0.0)];
        let normal = Vec2::new(0.0, 1.0);
        let waited = Timing {
            h: 0.01,
            lag: 0.02,
            waited: Some((3, &slid[..])),
        };
        let braking = waited.braking([(0, 0.5), (1, 0.5)], Vec2::new(0.1, 0.0));
        // The point slid (0.2, -0.1); the body moved 0.1 · 0.03 along x.
        let slide = Vec2::new(2.0, 0.0);
        // Within the static limit (12 m/s over 0.02 s: 0.24 m), all of it.
        let stuck = braking.take_back((slide, slide), normal, (12.0, 6.0));
        assert!(
            (stuck - Vec2::new(0.2 - 0.003, 0.0)).length() < 1e-15,
            "{stuck:?}"
        );
        // Slid farther than the static limit allows (2 m/s over 0.02 s): the kinetic limit
        // (1 m/s) times the time along it.
        let far = braking.take_back((slide, slide), normal, (2.0, 1.0));
        assert!((far - Vec2::new(0.02, 0.0)).length() < 1e-15, "{far:?}");
        let braked = Vec2::new(1.0, 0.0);
        let sliding = braking.take_back((slide, braked), normal, (1.0, 1.0));
        assert!(
            (sliding - Vec2::new(0.02, 0.0)).length() < 1e-15,
            "{sliding:?}"
        );
        let next = Timing::substep((0.01, 0.0)).braking([(0, 1.0)], Vec2::default());
        let back = next.take_back((slide, slide), normal, (12.0, 6.0));
        assert_eq!(back, Vec2::new(0.02, 0.0));
    }
}
