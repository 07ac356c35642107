//! Contacts on a rope's drawn curve: each span's deepest point in every collider, pushed out
//! through the particles' weights in it, then the curve off itself when self-contact is on.

use super::drawn::{DrawnSpans, Weights, ball_clears_span, point_inv_mass, point_of, spread};
use super::{Contacts, PairMemory, Timing, Touch};
use crate::curves::curve::point_at;
use crate::curves::smooth::{Smoothed, Smoothing};
use crate::{Aabb, Point, Scalar};

impl<P: Point> Contacts<'_, P> {
    /// Pushes the drawn curve of a row of particles out of every collider (see the module
    /// docs); particle contacts when [`Touch::Particles`]. `joined[i]` says whether particle
    /// `i` is still joined to particle `i + 1` (`joined[K - 1]`: the last to the first, a
    /// loop's closing spring). A row that came apart is tested piece by piece, each piece's
    /// own curve as [`Rope::draw`](crate::Rope::draw) draws it (a lone particle as a point),
    /// so no curve bridges a cut. `memory` serves the whole row's self-contact (see
    /// [`PairMemory`]), kept by the caller from one substep to the next.
    pub(crate) fn resolve_curve<const K: usize>(
        &self,
        (pos, vel, inv_mass): (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
        timing: Timing<'_, P>,
        joined: &[bool; K],
        memory: Option<&mut PairMemory<P, K>>,
    ) {
        if self.colliders.is_empty() && self.self_friction.is_none() {
            return;
        }
        // Colliders on the drawn curve, or at the particles and self-contact (if on) on the
        // segments between them.
        let (smoothing, closed, on_curve) = match self.touch {
            Touch::Drawn(s) => (s, false, true),
            Touch::DrawnLoop(s) if s != Smoothing::Bezier && K >= 3 => (s, true, true),
            touch => {
                if self.self_friction.is_none() {
                    return self.resolve_particles(pos, vel, inv_mass, timing);
                }
                let closed = matches!(touch, Touch::DrawnLoop(_)) && K >= 3;
                (Smoothing::Polyline, closed, false)
            }
        };
        let resolve = |(pos, vel, w): (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
                       timing: Timing<'_, P>,
                       drawn: &mut Smoothed<P, K>,
                       memory: Option<&mut PairMemory<P, K>>| {
            if on_curve {
                self.resolve_spans((pos, vel, w), timing, drawn, memory);
            } else {
                self.resolve_segments((pos, vel, w), timing, drawn, memory);
            }
        };
        let whole = joined[..K - 1].iter().all(|&j| j);
        if whole && (!closed || joined[K - 1]) {
            let curve = if closed {
                Smoothed::ring(smoothing, pos)
            } else {
                Smoothed::open(smoothing, pos)
            };
            if let Ok(mut drawn) = curve {
                resolve((pos, vel, inv_mass), timing, &mut drawn, memory);
            }
            return;
        }
        let mut start = 0;
        while start < K {
            let mut end = start + 1;
            while end < K && joined[end - 1] {
                end += 1;
            }
            let (run, m) = (start..end, end - start);
            start = end;
            // The piece's motion since the contacts last ran, padded as the piece.
            let mut slid = [P::default(); K];
            if let Some(moved) = timing.slid() {
                slid[..m].copy_from_slice(&moved[run.clone()]);
            }
            if m == 1 {
                let (p, v, w) = (&mut pos[run.clone()], &mut vel[run.clone()], &inv_mass[run]);
                self.resolve_particles(p, v, w, timing.for_run(&slid[..1]));
                continue;
            }
            // The piece, padded with its last particle (weight 0, held: nothing moves it).
            let mut piece = ([pos[end - 1]; K], [P::default(); K], [P::Scalar::ZERO; K]);
            piece.0[..m].copy_from_slice(&pos[run.clone()]);
            piece.1[..m].copy_from_slice(&vel[run.clone()]);
            piece.2[..m].copy_from_slice(&inv_mass[run.clone()]);
            let Ok(mut drawn) = Smoothed::open_first(smoothing, &piece.0, m) else {
                continue;
            };
            let parts = (&mut piece.0, &mut piece.1, &piece.2);
            resolve(parts, timing.for_run(&slid), &mut drawn, None);
            pos[run.clone()].copy_from_slice(&piece.0[..m]);
            vel[run].copy_from_slice(&piece.1[..m]);
        }
    }

    /// Pushes a curve of spans drawn through `pos` out of every collider (see the module
    /// docs), redrawing the spans each correction moved, then off itself if self-contact is
    /// on ([`resolve_with_self`](Self::resolve_with_self)), `lag` seconds before the step's
    /// end.
    pub(crate) fn resolve_spans<const K: usize>(
        &self,
        parts: (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
        timing: Timing<'_, P>,
        curve: &mut impl DrawnSpans<P, K>,
        memory: Option<&mut PairMemory<P, K>>,
    ) {
        let colliders =
            |parts: (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
             curve: &mut _,
             timing: Timing<'_, P>,
             drawn: bool| { self.resolve_colliders(parts, timing, curve, drawn) };
        self.resolve_with_self(parts, timing, curve, memory, colliders);
    }

    /// Pushes the particles of a polyline out of every collider, then its segments off each
    /// other if self-contact is on ([`resolve_with_self`](Self::resolve_with_self)).
    fn resolve_segments<const K: usize>(
        &self,
        parts: (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
        timing: Timing<'_, P>,
        polyline: &mut Smoothed<P, K>,
        memory: Option<&mut PairMemory<P, K>>,
    ) {
        let colliders = |(pos, vel, w): (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
                         polyline: &mut Smoothed<P, K>,
                         timing: Timing<'_, P>,
                         drawn: bool| {
            self.resolve_particles(pos, vel, w, timing);
            !drawn || polyline.rebuild(pos, (0, K - 1)).is_some()
        };
        self.resolve_with_self(parts, timing, polyline, memory, colliders);
    }

    /// Pushes a curve of spans drawn through `pos` out of every collider. A correction
    /// leaves the spans its particles weigh in (7 of a cubic spline's) to draw again when
    /// next read, each once however many pushes moved it (all of a natural spline's or one
    /// Bézier's are drawn again at once), and a span's box, taken once for all the
    /// colliders, grown by what the pushes since can have moved it; `drawn`: all are drawn
    /// again before it returns, for a caller that reads the curve after. `false` when it
    /// left the range (the step's guard undoes it).
    fn resolve_colliders<const K: usize>(
        &self,
        (pos, vel, inv_mass): (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
        timing: Timing<'_, P>,
        curve: &mut impl DrawnSpans<P, K>,
        drawn: bool,
    ) -> bool {
        let n = curve.span_count().min(K);
        // Spans a push moved since they were drawn, and a box that holds each span as drawn
        // (`None`: not taken yet), taken once for all the colliders: with `slack` then (the
        // most, on each axis, that pushes have moved a control point since this began), it
        // holds the span as it is now when grown by what `slack` has gained since, and a
        // span moved is drawn again only when a collider comes within that.
        let mut outdated = [false; K];
        let mut boxes: [Option<(Aabb<P>, P)>; K] = [None; K];
        let mut slack = P::default();
        // The most a control point moves for a particle move of 1 (a sum of weight sizes).
        let spill = match self.bulges() {
            true => P::Scalar::ratio(4, 3),
            false => P::Scalar::ONE,
        };
        let reread = self.colliders.len() > 1;
        let mut weights = Weights::none();
        for (k, collider) in self.colliders.iter().enumerate() {
            let shift = self.offset(k, collider, timing.lag);
            let reach = collider.bounds().moved(-shift).grown(self.thickness);
            for span in 0..n {
                let hull = match boxes[span] {
                    Some((hull, at)) if !hull.swept(slack - at).overlaps(&reach) => continue,
                    Some((hull, _)) if !outdated[span] => hull,
                    _ => {
                        if core::mem::take(&mut outdated[span]) {
                            curve.redraw_spans(pos, (span, 1));
                        }
                        let hull = curve.span_bounds(span);
                        if reread {
                            boxes[span] = Some((hull, slack));
                        }
                        if !hull.overlaps(&reach) {
                            continue;
                        }
                        hull
                    }
                };
                let Some(scale) = self.near(collider, hull, shift) else {
                    continue;
                };
                let clear =
                    |b: [P; 4]| ball_clears_span(collider, b.map(|p| p + shift), self.thickness);
                let cubic = curve.cubic(span);
                if cubic.is_some_and(clear) {
                    continue;
                }
                // In closed form in a half-space; by Newton steps to a ball's centre in
                // floats; else by the halving search (shifts and additions in `Q16`).
                let t = match (collider.outward(), collider.centre()) {
                    (Some(normal), _) => curve.lowest(span, normal),
                    (None, Some(c)) if !P::Scalar::FIXED_POINT => curve.nearest(span, c - shift),
                    _ => curve.deepest(span, |x| collider.search_key(x + shift, scale)),
                };
                // A point clear of the collider takes no push: no weights to take. A cubic
                // span's point from the control points at hand.
                let at = cubic.map_or_else(|| curve.point(span, t), |b| point_at(&b, t));
                let Some(touch) = self.touching(collider, at + shift) else {
                    continue;
                };
                weights.take(&*curve, span, t);
                let v = point_of(vel, weights.entries());
                let Some(w) = point_inv_mass(inv_mass, weights.entries()) else {
                    continue;
                };
                let body = self.body(k, collider);
                let braking = || timing.braking(weights.entries(), body.0);
                let (dx, dv, shifted) = self.response(collider, body, (touch, v, w), braking);
                if let Some(given) = spread(pos, vel, inv_mass, weights.entries(), (dx, dv)) {
                    self.report(k, given, shifted);
                    let Some((first, count)) = curve.outdated(pos, weights.ends()) else {
                        return false;
                    };
                    if count == 0 {
                        // Every span drawn again at once.
                        (outdated, boxes) = ([false; K], [None; K]);
                    } else if reread {
                        // Particle i moved by dx · w_i / (m_i · w). With one collider, each
                        // box is read where it is taken.
                        let most = weights.entries().fold(P::Scalar::ZERO, |most, (i, x)| {
                            most.max(x.abs() * inv_mass[i])
                        });
                        let moved = dx * (most / w * spill);
                        slack += moved.max_coords(-moved);
                    }
                    // Round a loop without a division a span.
                    let mut span = first.checked_rem(n).unwrap_or(0);
                    for _ in 0..count.min(n) {
                        outdated[span] = true;
                        span = if span + 1 == n { 0 } else { span + 1 };
                    }
                }
            }
        }
        if drawn {
            for span in (0..n).filter(|&span| outdated[span]) {
                curve.redraw_spans(pos, (span, 1));
            }
        }
        true
    }
}
