//! Contacts: ropes and sails pushed out of colliders, with restitution and Coulomb friction,
//! at their particles or on the curve the game draws.
//!
//! [`Contacts`] names the colliders, the rope's thickness (its radius) and where to test
//! ([`Touch`]). Stepping with it ([`MassSpring::step_touching`](crate::MassSpring::step_touching),
//! [`Rope::step_touching`](crate::Rope::step_touching)) resolves the contacts after every
//! substep, whatever the integrator: a point closer to a collider than the thickness is moved
//! out along the collider's normal, and its velocity relative to the collider loses its
//! inward part (times `1 + restitution`) and, by Coulomb's law, its sliding part: all of it
//! while that stays within static friction times the normal change, else kinetic friction
//! times it. Every integrator keeps positions and velocities, so the same projection and
//! impulse serve them all.
//!
//! - [`Touch::Particles`] tests the particles only: cheap (one distance per particle and
//!   collider), and enough when colliders are wider than the particle spacing.
//! - [`Touch::Curve`] tests the drawn curve: each span's control-point box first (the convex
//!   hull property) against the collider's box and its distance from the box's centre,
//!   then the deepest point of the span, found by 9 samples and 12 rounds
//!   of golden-section search around the deepest (to a bracket under 1/1000 of the span). The
//!   correction `d` found at a point with particle weights `w` (see
//!   [`Smoothed::weights`](crate::smooth::Smoothed::weights)) moves particle `i` by
//!   `(w_i / m_i) · d / Σ_j w_j² / m_j`: the smallest mass-weighted change that moves the drawn
//!   point by exactly `d` (with equal masses, `w_i · d / Σ w_j²`). Friction and restitution
//!   go the same way. This catches pegs far thinner than the particle spacing.
//!
//! **No tunnelling.** With a thickness `r > 0`, a step takes enough substeps that no particle
//! moves more than `r` against a collider in one substep, judged from the speeds at the start
//! of the frame plus what gravity adds during it (Catmull-Rom's drawn points move up to 5/4 as
//! fast as its particles, which the count allows for), within [`MAX_SUBSTEPS`]. A point that
//! moves less than `r` a substep cannot cross a collider unseen. Past the cap the frame still
//! simulates its whole `dt` (contacts never slow time), and a point faster than
//! `r · MAX_SUBSTEPS / dt` may cross a collider thinner than its step. A thickness of 0 gives
//! no such guarantee.
//!
//! [`MAX_SUBSTEPS`]: crate::system::MAX_SUBSTEPS

use crate::collider::Collider;
use crate::error::check_non_negative;
use crate::smooth::{Smoothed, Smoothing};
use crate::{Error, Point, Scalar};

/// Where contacts are tested.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Touch {
    /// At the particles only.
    #[default]
    Particles,
    /// On the curve this smoothing draws through the particles (ropes); other systems test
    /// their particles.
    Curve(Smoothing),
}

/// The colliders a step resolves contacts against, the thickness of what touches them, and
/// where it touches.
#[derive(Clone, Copy, Debug)]
pub struct Contacts<'a, P: Point> {
    colliders: &'a [Collider<P>],
    thickness: P::Scalar,
    touch: Touch,
}

impl<'a, P: Point> Contacts<'a, P> {
    /// Contacts of a rope or cloth of radius `thickness` with `colliders`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite thickness, or one beyond
    /// [`Scalar::SAFE_RANGE`].
    pub fn new(
        colliders: &'a [Collider<P>],
        thickness: P::Scalar,
        touch: Touch,
    ) -> Result<Self, Error> {
        if check_non_negative(thickness)? > P::Scalar::SAFE_RANGE {
            return Err(Error::InvalidParameter);
        }
        Ok(Contacts {
            colliders,
            thickness,
            touch,
        })
    }

    /// Where the contacts are tested.
    #[inline]
    pub fn touch(&self) -> Touch {
        self.touch
    }

    /// Substeps per second that keep every point within the thickness of its previous place
    /// against every collider, for speeds up to `speed` (0 when the thickness is 0).
    pub(crate) fn rate(&self, speed: P::Scalar) -> P::Scalar {
        if self.thickness <= P::Scalar::ZERO {
            return P::Scalar::ZERO;
        }
        let collider = self
            .colliders
            .iter()
            .map(|c| c.velocity().length())
            .fold(P::Scalar::ZERO, P::Scalar::max);
        let reach = match self.touch {
            Touch::Curve(Smoothing::CatmullRom) => speed + speed * P::Scalar::ratio(1, 4),
            _ => speed,
        };
        (reach + collider) / self.thickness
    }

    /// Pushes every particle with a mass out of every collider. `lag`: seconds from this
    /// substep to the end of the frame (a kinematic collider is that far behind its pose).
    pub(crate) fn resolve_particles(
        &self,
        pos: &mut [P],
        vel: &mut [P],
        inv_mass: &[P::Scalar],
        (h, lag): (P::Scalar, P::Scalar),
    ) {
        for collider in self.colliders {
            for ((x, v), &w) in pos.iter_mut().zip(vel.iter_mut()).zip(inv_mass) {
                if w > P::Scalar::ZERO
                    && let Some((dx, dv)) = self.response(collider, *x, *v, (h, lag))
                {
                    *x += dx;
                    *v += dv;
                }
            }
        }
    }

    /// Pushes the drawn curve of a row of particles out of every collider (see the module
    /// docs); particle contacts when [`Touch::Particles`].
    pub(crate) fn resolve_curve<const K: usize>(
        &self,
        pos: &mut [P; K],
        vel: &mut [P; K],
        inv_mass: &[P::Scalar; K],
        (h, lag): (P::Scalar, P::Scalar),
    ) {
        let Touch::Curve(smoothing) = self.touch else {
            return self.resolve_particles(pos, vel, inv_mass, (h, lag));
        };
        let mut weights = [P::Scalar::ZERO; K];
        let Ok(mut curve) = Smoothed::open(smoothing, pos) else {
            return;
        };
        for collider in self.colliders {
            let reach = grown_by(collider.bounds(), collider.velocity() * lag, self.thickness);
            let shift = collider.velocity() * lag;
            for span in 0..curve.span_count() {
                let hull = curve.span_bounds(span);
                if !hull.overlaps(&reach) {
                    continue;
                }
                // The distance changes no faster than the point moves: every point of the
                // box is at least d(centre) - half its diagonal from the collider.
                let centre = hull.min.midpoint(hull.max);
                let half_diagonal = (hull.max - centre).length();
                if collider.distance(centre + shift).0 - half_diagonal >= self.thickness {
                    continue;
                }
                let t = self.deepest(&curve, span, collider, lag);
                let x = curve.point(span, t);
                curve.weights(span, t, &mut weights);
                let v = point_of(vel, &weights);
                let Some((dx, dv)) = self.response(collider, x, v, (h, lag)) else {
                    continue;
                };
                let mut norm = P::Scalar::ZERO;
                for (&w, &m) in weights.iter().zip(inv_mass) {
                    norm += w * w * m;
                }
                if norm <= P::Scalar::ZERO {
                    continue; // every particle that moves this point is pinned
                }
                let share = P::Scalar::ONE / norm;
                for i in 0..K {
                    let k = weights[i] * inv_mass[i] * share;
                    pos[i] += dx * k;
                    vel[i] += dv * k;
                }
                match Smoothed::open(smoothing, pos) {
                    Ok(c) => curve = c,
                    Err(_) => return, // left the range: the step's guard undoes it
                }
            }
        }
    }

    /// The parameter of span `span` deepest into `collider`: the best of 9 samples, then
    /// golden-section search on the bracket around it.
    fn deepest<const K: usize>(
        &self,
        curve: &Smoothed<P, K>,
        span: usize,
        collider: &Collider<P>,
        lag: P::Scalar,
    ) -> P::Scalar {
        let shift = collider.velocity() * lag;
        let depth = |t: P::Scalar| collider.distance(curve.point(span, t) + shift).0;
        let at = |k: u32| P::Scalar::ratio(k, 8);
        let mut best = (0u32, depth(at(0)));
        for k in 1..=8 {
            let d = depth(at(k));
            if d < best.1 {
                best = (k, d);
            }
        }
        let (mut lo, mut hi) = (at(best.0.saturating_sub(1)), at((best.0 + 1).min(8)));
        let golden = P::Scalar::ratio(382, 1000);
        let (mut a, mut b) = (lo + (hi - lo) * golden, hi - (hi - lo) * golden);
        let (mut da, mut db) = (depth(a), depth(b));
        for _ in 0..12 {
            if da <= db {
                hi = b;
                (b, db) = (a, da);
                a = lo + (hi - lo) * golden;
                da = depth(a);
            } else {
                lo = a;
                (a, da) = (b, db);
                b = hi - (hi - lo) * golden;
                db = depth(b);
            }
        }
        let found = if da <= db { (a, da) } else { (b, db) };
        if found.1 < best.1 {
            found.0
        } else {
            at(best.0)
        }
    }

    /// The position and velocity change for a point at `x` moving at `v` at the end of a
    /// substep of `h`, or `None` when it is clear of `collider`. Friction also takes back the
    /// sliding it stops from this substep's move (`brake · h`), so a sticking contact does
    /// not creep.
    fn response(
        &self,
        collider: &Collider<P>,
        x: P,
        v: P,
        (h, lag): (P::Scalar, P::Scalar),
    ) -> Option<(P, P)> {
        let zero = P::Scalar::ZERO;
        let (d, n) = collider.distance(x + collider.velocity() * lag);
        if d >= self.thickness || !d.is_finite() {
            return None;
        }
        let dx = n * (self.thickness - d);
        let relative = v - collider.velocity();
        let vn = relative.dot(n);
        if vn >= zero {
            return Some((dx, P::default()));
        }
        let push = -vn * (P::Scalar::ONE + collider.restitution());
        let slide = relative - n * vn;
        let speed = slide.length();
        let (stick, kinetic) = collider.friction();
        let brake = if speed <= stick * push {
            slide
        } else {
            slide * (kinetic * push / speed)
        };
        Some((dx - brake * h, n * push - brake))
    }
}

/// `Σ w_i · p_i`.
fn point_of<P: Point>(points: &[P], weights: &[P::Scalar]) -> P {
    points
        .iter()
        .zip(weights)
        .fold(P::default(), |acc, (&p, &w)| acc + p * w)
}

/// `b` moved back by `behind` and grown by `r` on every side.
fn grown_by<P: Point>(b: crate::Aabb<P>, behind: P, r: P::Scalar) -> crate::Aabb<P> {
    crate::Aabb {
        min: b.min - behind - P::splat(r),
        max: b.max - behind + P::splat(r),
    }
}
