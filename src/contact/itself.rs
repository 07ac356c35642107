//! Self-contact: a rope's drawn curve kept off itself ([`Contacts::with_self_contact`]).

use super::Contacts;
use super::drawn::{DrawnSpans, point_of, spread};
use crate::{Aabb, Point, Scalar};

impl<P: Point> Contacts<'_, P> {
    /// Keeps every two spans of `curve` that are not neighbours (`closed`: counted round the
    /// loop) at least twice the thickness apart, when self-contact is on. Broad phase: each
    /// span's control-point box (it holds the span) grown by the thickness, sorted along the
    /// first axis and swept, so only spans whose boxes overlap are compared. Narrow phase:
    /// the nearest points of the two spans ([`nearest`]); the pair is pushed apart along the line between them, through both spans'
    /// particle weights (a particle both spans share moves by the difference), with its
    /// approach stopped and its sliding braked by Coulomb friction. Returns the deepest
    /// overlap it found, or `None` when the redrawn curve left the range (the step's guard
    /// undoes it).
    pub(super) fn resolve_self<const K: usize>(
        &self,
        pos: &mut [P; K],
        vel: &mut [P; K],
        inv_mass: &[P::Scalar; K],
        h: P::Scalar,
        curve: &mut impl DrawnSpans<P, K>,
    ) -> Option<P::Scalar> {
        let zero = P::Scalar::ZERO;
        let Some(friction) = self.self_friction else {
            return Some(zero);
        };
        let n = curve.span_count().min(K);
        let mut boxes = [Aabb::point(P::default()); K];
        let mut order = [0usize; K];
        for (span, (b, o)) in boxes.iter_mut().zip(order.iter_mut()).take(n).enumerate() {
            *b = curve.span_bounds(span).grown(self.thickness);
            *o = span;
        }
        let low = |b: &Aabb<P>| b.min.coord(0);
        // Insertion sort: few spans, and a rope's spans in their own order are often nearly
        // sorted along x already.
        for i in 1..n {
            let mut j = i;
            while j > 0 && low(&boxes[order[j - 1]]) > low(&boxes[order[j]]) {
                order.swap(j - 1, j);
                j -= 1;
            }
        }
        let closed = curve.is_closed();
        let mut deepest = zero;
        for i in 0..n {
            let a = order[i];
            for &b in &order[i + 1..n] {
                if low(&boxes[b]) > boxes[a].max.coord(0) {
                    break;
                }
                let apart = a.abs_diff(b);
                let apart = if closed { apart.min(n - apart) } else { apart };
                if apart < 2 || !boxes[a].overlaps(&boxes[b]) {
                    continue;
                }
                deepest = deepest.max(self.push_apart(
                    pos,
                    vel,
                    inv_mass,
                    (h, friction),
                    curve,
                    (a, b),
                )?);
            }
        }
        Some(deepest)
    }

    /// Pushes spans `a` and `b` of `curve` apart where they are nearer than twice the
    /// thickness; returns by how much they were (0 when apart), or `None` when the redrawn
    /// curve left the range.
    fn push_apart<const K: usize>(
        &self,
        pos: &mut [P; K],
        vel: &mut [P; K],
        inv_mass: &[P::Scalar; K],
        (h, friction): (P::Scalar, P::Scalar),
        curve: &mut impl DrawnSpans<P, K>,
        (a, b): (usize, usize),
    ) -> Option<P::Scalar> {
        let zero = P::Scalar::ZERO;
        let gap = self.thickness + self.thickness;
        let between = |u, v| curve.point(a, u) - curve.point(b, v);
        let Some((u, v)) = nearest(|u| curve.point(a, u), |v| curve.point(b, v), gap) else {
            return Some(zero);
        };
        let d = between(u, v);
        let dist = d.length();
        // Two spans that cross exactly give no direction to part them: the next substep will.
        if !(dist < gap && dist > gap * P::Scalar::ratio(1, 1024)) {
            return Some(zero);
        }
        let normal = d * (P::Scalar::ONE / dist);
        let (mut wa, mut wb) = ([zero; K], [zero; K]);
        curve.weights(a, u, &mut wa);
        curve.weights(b, v, &mut wb);
        let g = |i: usize| wa[i] - wb[i];
        let relative = point_of(vel, g);
        let vn = relative.dot(normal);
        let mut dx = normal * (gap - dist);
        let mut dv = P::default();
        if vn < zero {
            let push = -vn;
            let slide = relative - normal * vn;
            let speed = slide.length();
            let brake = if speed <= friction * push {
                slide
            } else {
                slide * (friction * push / speed)
            };
            (dx, dv) = (dx - brake * h, normal * push - brake);
        }
        // `None`: no free particle moves the pair (both spans held), nothing to undo.
        if spread(pos, vel, inv_mass, g, (dx, dv)).is_none() {
            return Some(zero);
        }
        curve.rebuild(pos).then_some(gap - dist)
    }
}

/// The parameters `(u, v)` in `[0, 1]²` of the nearest points of two spans, `a(u)` and
/// `b(v)`. Each span is cut into [`CHORDS`] chords; the [`SEEDS`] chord pairs nearest each
/// other (measured exactly, segment to segment: two spans that cross have chords that nearly
/// cross) seed [`NEWTON_STEPS`] Gauss-Newton steps, then a pattern search in 8 directions
/// from a step of 1/64 down to 1/4096 of a span (at most [`SEARCH_ROUNDS`] rounds); the
/// nearest result wins. `None`, without the search, when no chord pair comes within `gap`
/// plus half the longest chord: the spans are apart.
fn nearest<P: Point>(
    a: impl Fn(P::Scalar) -> P,
    b: impl Fn(P::Scalar) -> P,
    gap: P::Scalar,
) -> Option<(P::Scalar, P::Scalar)> {
    let at = |k: usize| P::Scalar::ratio(k as u32, CHORDS as u32);
    let pa: [P; CHORDS + 1] = core::array::from_fn(|k| a(at(k)));
    let pb: [P; CHORDS + 1] = core::array::from_fn(|k| b(at(k)));
    let longest = pa
        .windows(2)
        .chain(pb.windows(2))
        .map(|c| (c[1] - c[0]).length())
        .fold(P::Scalar::ZERO, P::Scalar::max);
    // The nearest chord pairs, nearest first: (distance, u, v).
    let mut seeds: [Option<Near<P::Scalar>>; SEEDS] = [None; SEEDS];
    for i in 0..CHORDS {
        for j in 0..CHORDS {
            let (s, t, d) = segments_nearest((pa[i], pa[i + 1]), (pb[j], pb[j + 1]));
            if d >= gap + longest / P::Scalar::from_i16(2) {
                continue;
            }
            let mut seed = Some((d, at(i) + s * at(1), at(j) + t * at(1)));
            for slot in &mut seeds {
                if slot.is_none_or(|kept| seed.is_some_and(|new| new.0 < kept.0)) {
                    core::mem::swap(slot, &mut seed);
                }
            }
        }
    }
    let distance = |u, v| (a(u) - b(v)).length();
    let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
    let clamp = |x: P::Scalar| x.max(zero).min(one);
    let mut found: Option<Near<P::Scalar>> = None;
    for (_, u0, v0) in seeds.into_iter().flatten() {
        let mut best = (distance(u0, v0), u0, v0);
        // Gauss-Newton on `a(u) - b(v)`, with the spans' tangents from central differences.
        let e = P::Scalar::ratio(1, 64);
        let tangent = |f: &dyn Fn(P::Scalar) -> P, t: P::Scalar| {
            let (lo, hi) = (clamp(t - e), clamp(t + e));
            (f(hi) - f(lo)) * (one / (hi - lo))
        };
        let (mut u, mut v) = (u0, v0);
        for _ in 0..NEWTON_STEPS {
            let f = a(u) - b(v);
            let (ta, tb) = (tangent(&a, u), tangent(&b, v));
            let (aa, bb, ab) = (ta.dot(ta), tb.dot(tb), ta.dot(tb));
            let det = aa * bb - ab * ab;
            // Spans side by side have no one nearest pair: the pattern search walks along.
            if det <= aa * bb * P::Scalar::ratio(1, 1024) {
                break;
            }
            let (r1, r2) = (-ta.dot(f), tb.dot(f));
            (u, v) = (
                clamp(u + (r1 * bb + ab * r2) / det),
                clamp(v + (aa * r2 + ab * r1) / det),
            );
            let d = distance(u, v);
            if d < best.0 {
                best = (d, u, v);
            }
        }
        // A pattern search finishes it: the step halves only when no direction improves, so
        // it can walk along a valley.
        let mut step = P::Scalar::ratio(1, 64);
        for _ in 0..SEARCH_ROUNDS {
            let (d0, u, v) = best;
            for (du, dv) in DIRECTIONS {
                let (nu, nv) = (
                    clamp(u + step * P::Scalar::from_i16(du)),
                    clamp(v + step * P::Scalar::from_i16(dv)),
                );
                let d = distance(nu, nv);
                if d < best.0 {
                    best = (d, nu, nv);
                }
            }
            if best.0 >= d0 {
                step = step * P::Scalar::ratio(1, 2);
                if step < P::Scalar::ratio(1, 4096) {
                    break;
                }
            }
        }
        if found.is_none_or(|f| best.0 < f.0) {
            found = Some(best);
        }
    }
    found.map(|(_, u, v)| (u, v))
}

/// A distance between two spans and the parameters `(u, v)` where they are that far apart.
type Near<S> = (S, S, S);

/// Chords a span is sampled into to seed the search.
const CHORDS: usize = 8;
/// The nearest chord pairs the search starts from.
const SEEDS: usize = 2;
/// Gauss-Newton steps from each seed at most.
const NEWTON_STEPS: usize = 4;
/// Rounds of the pattern search at most: 9 halvings and the moves between them.
const SEARCH_ROUNDS: usize = 12;
/// The pattern search's directions: the axes and the diagonals (which follow the valley of
/// two spans lying side by side).
const DIRECTIONS: [(i16, i16); 8] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (-1, -1),
    (1, -1),
    (-1, 1),
];

/// The nearest points of segments `p` and `q`: their parameters in `[0, 1]` and the distance
/// (the clamped closest points of the two lines, then each end against the other segment).
fn segments_nearest<P: Point>(
    (p0, p1): (P, P),
    (q0, q1): (P, P),
) -> (P::Scalar, P::Scalar, P::Scalar) {
    let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
    let clamp = |x: P::Scalar| x.max(zero).min(one);
    // The parameter on segment `a + t (b - a)` nearest `x`.
    let onto = |x: P, a: P, ab: P| {
        let len2 = ab.dot(ab);
        if len2 > zero {
            clamp((x - a).dot(ab) / len2)
        } else {
            zero
        }
    };
    let (d1, d2) = (p1 - p0, q1 - q0);
    let at = |s: P::Scalar, t: P::Scalar| (s, t, (p0 + d1 * s - (q0 + d2 * t)).length());
    let mut best = at(zero, onto(p0, q0, d2));
    for candidate in [
        at(one, onto(p1, q0, d2)),
        at(onto(q0, p0, d1), zero),
        at(onto(q1, p0, d1), one),
    ] {
        if candidate.2 < best.2 {
            best = candidate;
        }
    }
    let r = p0 - q0;
    let (a, b, e) = (d1.dot(d1), d1.dot(d2), d2.dot(d2));
    let (c, f) = (d1.dot(r), d2.dot(r));
    let denom = a * e - b * b;
    if denom > zero && e > zero {
        let s = clamp((b * f - c * e) / denom);
        let t = clamp((b * s + f) / e);
        let inner = at(s, t);
        if inner.2 < best.2 {
            best = inner;
        }
    }
    best
}
