//! Self-contact: a rope's drawn curve and a cloth's drawn surface kept off themselves
//! ([`Contacts::with_self_contact`]).

use super::Contacts;
use super::drawn::{DrawnSpans, SurfacePoint, point_of, spread};
use crate::curves::smooth::{Smoothed, Smoothing};
use crate::{Aabb, Point, Scalar};

impl<P: Point> Contacts<'_, P> {
    /// Keeps every two spans of `curve` that are not neighbours (`closed`: counted round the
    /// loop) at least twice the thickness apart, when self-contact is on. Broad phase: each
    /// span's control-point box (it holds the span) grown by the thickness, sorted along the
    /// first axis and swept, so only spans whose boxes overlap are compared. Narrow phase:
    /// the nearest points of the two spans ([`nearest`]; exactly, for the straight segments
    /// between the particles); the pair is pushed apart along the line between them, through both spans'
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
        let closed = curve.is_closed();
        let mut deepest = zero;
        sweep(&boxes[..n], &mut order[..n], |a, b| {
            let apart = a.abs_diff(b);
            let apart = if closed { apart.min(n - apart) } else { apart };
            if apart >= 2 {
                let depth = self.push_apart(pos, vel, inv_mass, (h, friction), curve, (a, b))?;
                deepest = deepest.max(depth);
            }
            Some(())
        })?;
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
        let found = if curve.is_straight() {
            // Two segments: their nearest points exactly.
            let ends = |span| (curve.point(span, zero), curve.point(span, P::Scalar::ONE));
            let (u, v, _) = segments_nearest(ends(a), ends(b));
            Some((u, v))
        } else {
            nearest(|u| curve.point(a, u), |v| curve.point(b, v), gap)
        };
        let Some((u, v)) = found else {
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
        let parted = parting(normal, gap - dist, point_of(vel, g), (friction, h));
        // `None`: no free particle moves the pair (both spans held), nothing to undo.
        if spread(pos, vel, inv_mass, g, parted).is_none() {
            return Some(zero);
        }
        curve.rebuild(pos).then_some(gap - dist)
    }

    /// Keeps every two cells of the surface drawn through a `U × V` grid (`pos`, row by row)
    /// that are not neighbours (sharing no particle row and column both) at least twice the
    /// thickness apart, when self-contact is on. `smoothing` draws it (`Polyline`: the flat
    /// quadrilaterals between the particles); `controls` is a natural spline's control net,
    /// kept up to date. Broad phase: the boxes of the cells' Bézier control points
    /// ([`cell_boxes`]) grown by the thickness, swept along x. Narrow phase: the nearest points
    /// of the two cells ([`nearest_on_cells`]), pushed apart through both points' particle
    /// weights, their approach stopped and their sliding braked. Returns the deepest overlap
    /// it found.
    pub(super) fn resolve_self_surface<const U: usize, const V: usize>(
        &self,
        (pos, vel, inv_mass): (&mut [P], &mut [P], &[P::Scalar]),
        h: P::Scalar,
        smoothing: Smoothing,
        controls: &mut Option<[[P; U]; V]>,
    ) -> P::Scalar {
        let zero = P::Scalar::ZERO;
        let Some(friction) = self.self_friction else {
            return zero;
        };
        let (columns, cells) = (U - 1, (U - 1) * (V - 1));
        let cell_at = |c: usize| (c % columns, c / columns);
        let mut boxes = [[Aabb::point(P::default()); U]; V];
        let mut order = [[0usize; U]; V];
        let (boxes, order) = (boxes.as_flattened_mut(), order.as_flattened_mut());
        if cell_boxes::<P, U, V>(smoothing, pos, boxes).is_none() {
            // Out of range: the step's guard undoes it.
            return zero;
        }
        for (c, (b, o)) in boxes
            .iter_mut()
            .zip(order.iter_mut())
            .take(cells)
            .enumerate()
        {
            *b = b.grown(self.thickness);
            *o = c;
        }
        let mut at_a = SurfacePoint::<P::Scalar, U, V>::new(smoothing, false);
        let mut at_b = SurfacePoint::<P::Scalar, U, V>::new(smoothing, false);
        let gap = self.thickness + self.thickness;
        let mut deepest = zero;
        let _ = sweep(&boxes[..cells], &mut order[..cells], |a, b| {
            let ((ua, va), (ub, vb)) = (cell_at(a), cell_at(b));
            if ua.abs_diff(ub) < 2 && va.abs_diff(vb) < 2 {
                return Some(());
            }
            let found = nearest_on_cells(
                |u, v| {
                    at_a.at((ua, va), (u, v));
                    at_a.point(pos)
                },
                |u, v| {
                    at_b.at((ub, vb), (u, v));
                    at_b.point(pos)
                },
                gap,
            );
            let Some([sa, ta, sb, tb]) = found else {
                return Some(());
            };
            at_a.at((ua, va), (sa, ta));
            at_b.at((ub, vb), (sb, tb));
            let d = at_a.point(pos) - at_b.point(pos);
            let dist = d.length();
            // Cells that cross exactly give no direction to part them: the next substep will.
            if !(dist < gap && dist > gap * P::Scalar::ratio(1, 1024)) {
                return Some(());
            }
            let g = |i: usize| at_a.wu[i % U] * at_a.wv[i / U] - at_b.wu[i % U] * at_b.wv[i / U];
            let normal = d * (P::Scalar::ONE / dist);
            let parted = parting(normal, gap - dist, point_of(vel, g), (friction, h));
            if spread(pos, vel, inv_mass, g, parted).is_some() {
                deepest = deepest.max(gap - dist);
            }
            Some(())
        });
        if let Some(net) = controls.as_mut().filter(|_| deepest > zero) {
            let grid = pos.as_chunks::<U>().0;
            *net = core::array::from_fn(|j| grid[j]);
            crate::curves::surface::natural_grid(net);
        }
        deepest
    }
}

/// Writes into `boxes[cv · (U − 1) + cu]` a box that holds cell `(cu, cv)` of the surface
/// `smoothing` draws through the `U × V` grid `pos`: the box of the cell's Bézier control
/// points (each row's span through the cell, every row drawn once, then each of those
/// control points' columns along `v`), which hold the cell (the convex hull property); one
/// Bézier's cells all get the whole net's box. Stack: `4·U·V` points. `None` when a row or
/// column is out of range.
fn cell_boxes<P: Point, const U: usize, const V: usize>(
    smoothing: Smoothing,
    pos: &[P],
    boxes: &mut [Aabb<P>],
) -> Option<()> {
    let rows = pos.as_chunks::<U>().0;
    if smoothing == Smoothing::Bezier {
        boxes.fill(Aabb::from_points(pos)?);
        return Some(());
    }
    // Each row's spans' control points, every row drawn once: `spans[j][cu]`.
    let mut spans = [[[P::default(); 4]; U]; V];
    let mut controls = 0;
    for (row, spans) in rows.iter().zip(spans.iter_mut()) {
        let curve = Smoothed::open(smoothing, row).ok()?;
        for (cu, span) in spans.iter_mut().enumerate().take(U - 1) {
            let points = curve.span_points(cu);
            controls = points.len().min(4);
            span[..controls].copy_from_slice(&points[..controls]);
        }
    }
    for cu in 0..U - 1 {
        for k in 0..controls {
            let column: [P; V] = core::array::from_fn(|j| spans[j][cu][k]);
            let curve = Smoothed::open(smoothing, &column).ok()?;
            for cv in 0..V - 1 {
                let b = Aabb::from_points(curve.span_points(cv))?;
                let cell = &mut boxes[cv * (U - 1) + cu];
                *cell = if k == 0 { b } else { cell.union(b) };
            }
        }
    }
    Some(())
}

/// Calls `visit(a, b)` once for every two items whose `boxes` overlap: `order` (the items'
/// indices) insertion-sorted by the boxes' low x (few items, and often nearly sorted
/// already), then swept. Stops at the first `None` from `visit` and returns it.
fn sweep<P: Point>(
    boxes: &[Aabb<P>],
    order: &mut [usize],
    mut visit: impl FnMut(usize, usize) -> Option<()>,
) -> Option<()> {
    let low = |b: &Aabb<P>| b.min.coord(0);
    for i in 1..order.len() {
        let mut j = i;
        while j > 0 && low(&boxes[order[j - 1]]) > low(&boxes[order[j]]) {
            order.swap(j - 1, j);
            j -= 1;
        }
    }
    for (i, &a) in order.iter().enumerate() {
        for &b in &order[i + 1..] {
            if low(&boxes[b]) > boxes[a].max.coord(0) {
                break;
            }
            if boxes[a].overlaps(&boxes[b]) {
                visit(a, b)?;
            }
        }
    }
    Some(())
}

/// The position and velocity changes that part two points `depth` too near along `normal`
/// (from the second to the first), moving at `relative` (the first's velocity less the
/// second's): pushed apart by `depth`, their approach stopped, their sliding braked by
/// Coulomb `friction` and that braking taken back from this substep of `h`'s move.
fn parting<P: Point>(
    normal: P,
    depth: P::Scalar,
    relative: P,
    (friction, h): (P::Scalar, P::Scalar),
) -> (P, P) {
    let vn = relative.dot(normal);
    let dx = normal * depth;
    if vn >= P::Scalar::ZERO {
        return (dx, P::default());
    }
    let push = -vn;
    let slide = relative - normal * vn;
    let speed = slide.length();
    let brake = if speed <= friction * push {
        slide
    } else {
        slide * (friction * push / speed)
    };
    (dx - brake * h, normal * push - brake)
}

/// The parameters `[u_a, v_a, u_b, v_b]` in `[0, 1]⁴` of the nearest points of two surface
/// cells `a(u, v)` and `b(u, v)`: the [`SEEDS`] nearest pairs of their 3×3 samples, each
/// finished by a pattern search along the four parameters from a step of 1/4 down to
/// 1/1024 of a cell (at most [`CELL_ROUNDS`] rounds), each trial moving one point only;
/// the nearest result wins. `None`, without the search, when no sample pair comes within
/// `gap` plus the longest distance between neighbouring samples: the cells are apart.
fn nearest_on_cells<P: Point>(
    mut a: impl FnMut(P::Scalar, P::Scalar) -> P,
    mut b: impl FnMut(P::Scalar, P::Scalar) -> P,
    gap: P::Scalar,
) -> Option<[P::Scalar; 4]> {
    let at = |k: usize| {
        (
            P::Scalar::ratio(k as u32 % 3, 2),
            P::Scalar::ratio(k as u32 / 3, 2),
        )
    };
    let pa: [P; 9] = core::array::from_fn(|k| a(at(k).0, at(k).1));
    let pb: [P; 9] = core::array::from_fn(|k| b(at(k).0, at(k).1));
    // The longest step between neighbouring samples (right and above) of either cell.
    let mut spacing = P::Scalar::ZERO;
    for k in 0..9 {
        for next in [k + 1, k + 3] {
            if next < 9 && (next == k + 3 || k % 3 < 2) {
                spacing = spacing
                    .max((pa[next] - pa[k]).length())
                    .max((pb[next] - pb[k]).length());
            }
        }
    }
    let mut seeds: [Option<(P::Scalar, usize, usize)>; SEEDS] = [None; SEEDS];
    for (i, &x) in pa.iter().enumerate() {
        for (j, &y) in pb.iter().enumerate() {
            let d = (x - y).length();
            if d >= gap + spacing {
                continue;
            }
            let mut seed = Some((d, i, j));
            for slot in &mut seeds {
                if slot.is_none_or(|kept| seed.is_some_and(|new| new.0 < kept.0)) {
                    core::mem::swap(slot, &mut seed);
                }
            }
        }
    }
    let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
    let clamp = |x: P::Scalar| x.max(zero).min(one);
    let mut found: Option<(P::Scalar, [P::Scalar; 4])> = None;
    for (d, i, j) in seeds.into_iter().flatten() {
        let mut params = [at(i).0, at(i).1, at(j).0, at(j).1];
        let (mut xa, mut xb, mut best) = (pa[i], pb[j], d);
        let mut step = P::Scalar::ratio(1, 4);
        for _ in 0..CELL_ROUNDS {
            let before = best;
            for k in 0..8 {
                let (axis, sign) = (k / 2, if k % 2 == 0 { step } else { -step });
                let mut trial = params;
                trial[axis] = clamp(trial[axis] + sign);
                if trial[axis] == params[axis] {
                    continue;
                }
                let (ta, tb) = if axis < 2 {
                    (a(trial[0], trial[1]), xb)
                } else {
                    (xa, b(trial[2], trial[3]))
                };
                let d = (ta - tb).length();
                if d < best {
                    (params, xa, xb, best) = (trial, ta, tb, d);
                }
            }
            if best >= before {
                step = step * P::Scalar::ratio(1, 2);
                if step < P::Scalar::ratio(1, 1024) {
                    break;
                }
            }
        }
        if found.is_none_or(|f| best < f.0) {
            found = Some((best, params));
        }
    }
    found.map(|(_, params)| params)
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
/// Rounds of the pattern search on two surface cells at most: 8 halvings and the moves
/// between them.
const CELL_ROUNDS: usize = 16;
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
/// Always inlined: it is the inner loop of [`nearest`]'s 64 chord pairs.
#[inline(always)]
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
