//! What a frame can reach: the substeps the colliders and self-contact ask for, which
//! colliders can be touched at all within the frame ([`Contacts`]' broad phase in time),
//! and which boxes of a drawn curve or surface a collider is near.

use super::{Contacts, Touch};
use crate::collider::Collider;
use crate::curves::smooth::Smoothing;
use crate::physics::hash::StateHash;
use crate::{Aabb, Point, Scalar};

/// The most a touched point's velocity weighs in the particles' with `touch` (`surface`:
/// the drawn points are a surface's), the sum of its weights' sizes: a drawn point moves at
/// most this times as fast as the fastest particle. Catmull-Rom's 5/4 on a curve, 25/16 on
/// a surface; the natural spline's 31/20 and 5/2; 1 for the others, whose drawn points lie
/// in their particles' hull.
pub(super) fn weight_sum<S: Scalar>(touch: Touch, surface: bool) -> S {
    match (touch, surface) {
        (Touch::Drawn(Smoothing::CatmullRom) | Touch::DrawnLoop(Smoothing::CatmullRom), false) => {
            S::ratio(5, 4)
        }
        (Touch::Drawn(Smoothing::CatmullRom), true) => S::ratio(25, 16),
        (
            Touch::Drawn(Smoothing::NaturalSpline) | Touch::DrawnLoop(Smoothing::NaturalSpline),
            false,
        ) => S::ratio(31, 20),
        (Touch::Drawn(Smoothing::NaturalSpline), true) => S::ratio(5, 2),
        _ => S::ONE,
    }
}

impl<P: Point> Contacts<'_, P> {
    /// How fast the points touched can move for particle speeds up to `speed` (`surface` as
    /// in [`weight_sum`]).
    fn point_speed(&self, speed: P::Scalar, surface: bool) -> P::Scalar {
        let (curve, sheet) = self.weight_sums;
        speed * if surface { sheet } else { curve }
    }

    /// Whether the drawn points can lie outside their particles' box (a Catmull-Rom or
    /// natural spline's, whose weights can be below 0).
    pub(crate) fn bulges(&self) -> bool {
        self.weight_sums.0 > P::Scalar::ONE
    }

    /// Substeps per second that keep every point, against every collider it can reach this
    /// frame, within the thickness and the collider's [`depth`](Collider::depth) of its
    /// previous place (so that nothing passes through a collider or out of its far side),
    /// and, with self-contact, two parts of a rope within the thickness; for particle speeds
    /// up to `speed` (0 when the thickness is 0); `surface` when the drawn points are a
    /// surface's. `object` holds what is drawn at the frame's start: a collider that is not
    /// [`reachable`](Self::reachable) within the `dt` seconds asks for no substeps. Also the
    /// fastest a point can close on a collider it can reach (its speed and the collider's),
    /// with self-contact at least twice its points' speed (two parts of the rope meeting
    /// head on), and with a thickness of 0 the least [`depth`](Collider::depth) of the
    /// colliders it can reach: contacts that wait no longer than that closing takes to cover the
    /// [`allowance`](Self::allowance) let no point close on a collider or on another part
    /// by more than that.
    pub(crate) fn rate(
        &self,
        (speed, surface): (P::Scalar, bool),
        (object, dt): (Aabb<P>, P::Scalar),
    ) -> (P::Scalar, P::Scalar, P::Scalar) {
        let zero = P::Scalar::ZERO;
        let reach = self.point_speed(speed, surface);
        let (colliders, closing, deepest) =
            self.colliders
                .iter()
                .fold((zero, zero, P::Scalar::SAFE_RANGE), |most, c| {
                    if !self.reachable(c, (object, reach), dt) {
                        return most;
                    }
                    let (closing, depth) = (reach + c.velocity().length(), c.depth());
                    match self.thickness > zero {
                        true => {
                            let rate = closing / (self.thickness + depth);
                            (most.0.max(rate), most.1.max(closing), most.2)
                        }
                        false => (most.0, most.1.max(closing), most.2.min(depth)),
                    }
                });
        // Two parts of a rope can meet head on.
        if self.self_friction.is_some() && self.thickness > zero {
            let apart = reach + reach;
            (
                colliders.max(apart / self.thickness),
                closing.max(apart),
                deepest,
            )
        } else {
            (colliders, closing, deepest)
        }
    }

    /// How far a point may close on a collider between two runs of waiting contacts
    /// ([`due`](Self::due)), when the least [`depth`](Collider::depth) of the colliders it
    /// can reach is `depth` and `shortest` gives the shortest rest length of a spring with a
    /// free end: the thickness (its centre line then never enters a collider); with a
    /// thickness of 0, an eighth of that depth (never so far into a collider that a run
    /// pushes it out of the far side) or a sixty-fourth of that length, the less (0 without
    /// a spring), to be pushed out by the next run, at the latest the step's end.
    pub(super) fn allowance(
        &self,
        depth: P::Scalar,
        shortest: impl FnOnce() -> Option<P::Scalar>,
    ) -> P::Scalar {
        if self.thickness > P::Scalar::ZERO {
            return self.thickness;
        }
        let spacing = shortest().unwrap_or(P::Scalar::ZERO);
        (depth * P::Scalar::ratio(1, 8)).min(spacing * P::Scalar::ratio(1, 64))
    }

    /// Whether the contacts may skip substeps ([`due`](Self::due)). They run at every
    /// substep with self-contact at a thickness of 0, with self-contact unless
    /// `remembering` (a step that
    /// keeps a [`PairMemory`](super::memory::PairMemory), which runs them at every substep
    /// only while it holds two parts apart: a pile's stacked contacts, with a frame's weight
    /// on them, take more rounds than they have), on a natural spline (each
    /// drawn point weighs in every particle, so that a push anywhere moves it all, and a
    /// frame's pushes take more than one pass) and with a body that has a mass (a two-way
    /// contact's pushes are each substep's).
    pub(crate) fn may_wait(&self, remembering: bool) -> bool {
        let natural = matches!(
            self.touch,
            Touch::Drawn(Smoothing::NaturalSpline) | Touch::DrawnLoop(Smoothing::NaturalSpline)
        );
        let apart =
            self.self_friction.is_none() || (remembering && self.thickness > P::Scalar::ZERO);
        !natural
            && apart
            && !self
                .colliders
                .iter()
                .any(|c| c.inv_mass() > P::Scalar::ZERO)
    }

    /// Whether `c` can touch within `dt` seconds what `object` holds, its points moving up
    /// to `reach` a second: its path over the frame (from where its velocity puts it at the
    /// start to its place at the end) comes within the thickness and that reach of it.
    fn reachable(
        &self,
        c: &Collider<P>,
        (object, reach): (Aabb<P>, P::Scalar),
        dt: P::Scalar,
    ) -> bool {
        let end = c.bounds();
        let path = end.union(end.moved(-(c.velocity() * dt)));
        path.overlaps(&object.grown(self.thickness + reach * dt))
    }

    /// Whether anything can touch what `object` holds within `dt` seconds, for particle
    /// speeds up to `speed` (`surface` as in [`rate`](Self::rate)): self-contact is on, or a
    /// collider is [`reachable`](Self::reachable).
    pub(crate) fn can_touch(
        &self,
        (speed, surface): (P::Scalar, bool),
        (object, dt): (Aabb<P>, P::Scalar),
    ) -> bool {
        let reach = self.point_speed(speed, surface);
        self.self_friction.is_some()
            || self
                .colliders
                .iter()
                .any(|c| self.reachable(c, (object, reach), dt))
    }

    /// The [`search_key`](Collider::search_key) scale for `hull`, or `None` when every point
    /// of `hull` is at least the thickness from `collider` moved by `shift`: the distance
    /// changes no faster than the point moves, so every point of the box is at least
    /// d(centre) - half its diagonal away (and at most d(centre) + half of it). A ball by
    /// the box's nearest point to its centre instead (exact, no root), its scale from the
    /// farthest corner's coordinate offsets summed (at least its distance).
    pub(super) fn near(
        &self,
        collider: &Collider<P>,
        hull: Aabb<P>,
        shift: P,
    ) -> Option<P::Scalar> {
        if let Some((c, radius)) = collider.as_ball() {
            let c = c - shift;
            let off = c.min_coords(hull.max).max_coords(hull.min) - c;
            if !off.shorter_than(radius + self.thickness) {
                return None;
            }
            if !P::Scalar::FIXED_POINT {
                return Some(P::Scalar::ONE);
            }
            let (low, high) = (hull.min - c, hull.max - c);
            let far = (0..P::DIM).fold(P::Scalar::ZERO, |sum, d| {
                sum + low.coord(d).abs().max(high.coord(d).abs())
            });
            return Some(collider.key_scale(far - radius));
        }
        let centre = hull.min.midpoint(hull.max);
        let half_diagonal = (hull.max - centre).length();
        let gap = collider.gap(centre + shift);
        (gap - half_diagonal < self.thickness).then(|| collider.key_scale(gap + half_diagonal))
    }

    /// For [`Sleep`](crate::Sleep): a key of the colliders that can touch
    /// `object` (a box of an object at rest) within `dt` seconds, and of the thickness and
    /// touch; `None` when one of them has a velocity or a mass (it moves, or may be pushed).
    /// A test a collider.
    pub(crate) fn still_key(&self, object: Aabb<P>, dt: P::Scalar) -> Option<u64> {
        let mut key = StateHash::new();
        for c in self.colliders {
            if self.reachable(c, (object, P::Scalar::ZERO), dt) {
                if c.velocity() != P::default() || c.inv_mass() > P::Scalar::ZERO {
                    return None;
                }
                c.hash(&mut key);
            }
        }
        key.add_scalar(self.thickness);
        key.add_u32(u32::from(self.self_friction.is_some()));
        Some(key.finish())
    }
}
