//! Self-contact: a rope's drawn curve and a cloth's drawn surface kept off themselves
//! ([`Contacts::with_self_contact`]), in rounds with the colliders, and held apart between
//! its passes.

use super::Contacts;
use super::collider::coulomb;
use super::drawn::{DrawnSpans, SurfacePoint, Weights, point_of, spread};
use super::memory::{Due, PairMemory, Recall};
use super::span_pairs::{Near, Samples, segments_nearest};
use super::timing::{Braking, Timing};
use crate::curves::smooth::{Smoothed, Smoothing};
use crate::{Aabb, Point, Scalar};

/// Rounds of collider and self contacts a substep when self-contact is on.
pub(super) const SELF_ROUNDS: usize = 12;
/// Rounds of the pass in a step's first substep that finds what the substeps until the next
/// hold apart ([`Due::First`]): the step's last pass settles what it leaves. (With one, a
/// pile came 2.65% of the diameter short at the closest, 1.20% with two; a whipped rope's
/// frame took 15% fewer instructions with two than with three.)
const FIRST_ROUNDS: usize = 2;

/// The share of its inverse mass that a particle a collider pushed moves by in
/// self-contact, in the same substep's rounds: a rope resting on a floor is held by it, so a
/// span landing on it moves it less (mass scaling, as in shock propagation), and a round no
/// longer pushes the bottom of a heap into the floor for the next to push it out again:
/// fewer rounds settle a pile (`docs/summary.md`, section (g)).
const RESTING_SHARE: (u32, u32) = (3, 10);

/// The particles a collider pushed in a substep's rounds so far.
struct Resting<const K: usize>([bool; K]);

impl<const K: usize> Resting<K> {
    /// Adds the particles that moved from `before` to `now` (the colliders' round).
    fn note<P: Point>(&mut self, before: &[P; K], now: &[P; K]) -> &Self {
        for ((rests, a), b) in self.0.iter_mut().zip(before).zip(now) {
            *rests |= a != b;
        }
        self
    }

    /// The inverse masses self-contact moves the particles by: [`RESTING_SHARE`] of
    /// `inv_mass` for those resting on a collider.
    fn masses<S: Scalar>(&self, inv_mass: &[S; K]) -> [S; K] {
        let share = S::ratio(RESTING_SHARE.0, RESTING_SHARE.1);
        core::array::from_fn(|i| match self.0[i] {
            true => inv_mass[i] * share,
            false => inv_mass[i],
        })
    }
}

impl<P: Point> Contacts<'_, P> {
    /// `colliders` (what touches them pushed out of every collider at a timing; `drawn`:
    /// `curve` drawn again after, for a reader; `false` when it left the range), then, when
    /// self-contact is on and due ([`PairMemory::due`]; every substep without a memory),
    /// rounds of the colliders and self-contact ([`rounds`](Self::rounds)) with the
    /// colliders' last word; friction takes back what slid since the contacts last ran in
    /// the first round only ([`Timing::again`]). Between two such passes, what the last
    /// pushed apart is held apart ([`hold_apart`](Self::hold_apart)).
    pub(super) fn resolve_with_self<const K: usize, C: DrawnSpans<P, K>>(
        &self,
        (pos, vel, inv_mass): (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
        timing: Timing<'_, P>,
        curve: &mut C,
        mut memory: Option<&mut PairMemory<P, K>>,
        colliders: impl Fn(
            (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
            &mut C,
            Timing<'_, P>,
            bool,
        ) -> bool,
    ) {
        let gap = self.thickness + self.thickness;
        let due = match memory.as_deref_mut() {
            _ if self.self_friction.is_none() => Due::Not,
            Some(m) => m.due(curve, gap, (timing.h, timing.lag)),
            None => Due::Full,
        };
        if due == Due::Not {
            let before = *pos;
            colliders((pos, vel, inv_mass), curve, timing, false);
            if let Some(memory) = memory {
                let moved_by = Resting([false; K]).note(&before, pos).masses(inv_mass);
                self.hold_apart((pos, vel, &moved_by), timing, curve, memory);
            }
            return;
        }
        if let Some(memory) = memory.as_deref_mut() {
            memory.forget_pushes();
        }
        let most = match due {
            Due::First => FIRST_ROUNDS,
            _ => SELF_ROUNDS,
        };
        let mut resting = Resting([false; K]);
        let mut round = timing;
        let last = self.rounds(most, || {
            let before = *pos;
            if !colliders((&mut *pos, &mut *vel, inv_mass), curve, round, true) {
                return None;
            }
            let moved_by = resting.note(&before, pos).masses(inv_mass);
            let memory = memory.as_deref_mut();
            let parts = (&mut *pos, &mut *vel, &moved_by);
            let deepest = self.resolve_self(parts, round, curve, memory);
            round = timing.again();
            deepest
        });
        // Self-contact's last pushes may reach into a collider: the colliders have the last
        // word (a floor is never passed; two spans may stay within the rounds' tolerance).
        if last {
            colliders(
                (pos, vel, inv_mass),
                curve,
                timing.again(),
                memory.is_some(),
            );
        }
        if let Some(memory) = memory {
            memory.checked(curve);
        }
    }

    /// Runs `round` (the colliders, then self-contact: the deepest overlap it met, or `None`
    /// to stop) until no two parts overlapped by more than 1/100 of the gap between them
    /// (the tolerance of the self-contact guarantee), at most `most` times
    /// ([`SELF_ROUNDS`], or [`FIRST_ROUNDS`]): with self-contact a pile is a stack of
    /// contacts on contacts, each push undoing part of its neighbours'. Without
    /// self-contact, one round. Returns whether the last round pushed two parts apart.
    pub(super) fn rounds(&self, most: usize, mut round: impl FnMut() -> Option<P::Scalar>) -> bool {
        let settled = (self.thickness + self.thickness) * P::Scalar::ratio(1, 100);
        let mut last = None;
        for _ in 0..most {
            last = round();
            if last.is_none_or(|deepest| deepest <= settled) {
                break;
            }
        }
        last.is_some_and(|deepest| deepest > P::Scalar::ZERO)
    }

    /// Keeps every two spans of `curve` that are not neighbours (`closed`: counted round the
    /// loop) at least twice the thickness apart, when self-contact is on. Broad phase: each
    /// span's control-point box (it holds the span) grown by the thickness, sorted along the
    /// first axis and swept, so only spans whose boxes overlap are compared. Narrow phase:
    /// the nearest points of the two spans ([`nearest`], from [`SAMPLES`] + 1 points of each
    /// span taken once for all its pairs; exactly, for the straight segments between the
    /// particles, and a pair of them no nearer than twice the thickness left there, by
    /// [`Point::shorter_than`], with no root and no weights), found on the curve as the
    /// pass began; the pair is measured where the
    /// particles are now (each point a weighted sum of them) and pushed apart along the line
    /// between them, through both spans' particle weights (a particle both spans share moves
    /// by the difference), with its approach stopped and its sliding braked by Coulomb
    /// friction. A curve of cubic spans has the spans each push moved redrawn after it (those
    /// the two points' particles weigh in), and their samples taken again when next needed;
    /// straight segments are redrawn once, after the pass. `memory` ([`PairMemory`]) spares
    /// the search of two cubic spans it holds apart, follows two it found near each other
    /// from where they were by Newton steps alone, and keeps the pairs pushed apart for
    /// [`hold_apart`](Self::hold_apart). Returns the deepest overlap it
    /// found, or `None` when the redrawn curve left the range (the step's guard undoes it).
    pub(super) fn resolve_self<const K: usize>(
        &self,
        (pos, vel, inv_mass): (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
        timing: Timing<'_, P>,
        curve: &mut impl DrawnSpans<P, K>,
        mut memory: Option<&mut PairMemory<P, K>>,
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
        // Straight segments are measured from the particles: no samples.
        let straight = curve.is_straight();
        let mut samples = (!straight).then(Samples::new);
        let mut deepest = zero;
        sweep(&boxes[..n], &mut order[..n], |a, b| {
            let apart = a.abs_diff(b);
            let apart = if closed { apart.min(n - apart) } else { apart };
            if apart >= 2 {
                let parts = (&mut *pos, &mut *vel, inv_mass);
                let known = (samples.as_mut(), memory.as_deref_mut());
                let (depth, moved) =
                    self.push_apart(parts, (timing, friction), &*curve, (a, b), known);
                // A curved span's search reads the curve: the spans each point's particles
                // weigh in are redrawn after each push. Straight spans are read from the
                // particles, and the curve redrawn once at the end.
                if depth > zero {
                    deepest = deepest.max(depth);
                    if !straight {
                        // Two points near each other along the curve redraw one run.
                        let [(a0, a1), (b0, b1)] = moved;
                        let runs = if a0.max(b0) <= a1.min(b1) + 4 {
                            [Some((a0.min(b0), a1.max(b1))), None]
                        } else {
                            [Some((a0, a1)), Some((b0, b1))]
                        };
                        for ends in runs.into_iter().flatten() {
                            let spans = curve.rebuild(pos, ends)?;
                            if let Some(samples) = samples.as_mut() {
                                samples.forget(spans, n);
                            }
                        }
                    }
                }
            }
            Some(())
        })?;
        (!straight || deepest == zero || curve.rebuild(pos, (0, K - 1)).is_some())
            .then_some(deepest)
    }

    /// Pushes spans `a` and `b` of `curve` apart where they are nearer than twice the
    /// thickness ([`Samples::nearest`]: searched, or followed from where `memory` last found
    /// them near, and what was found kept there; without samples, exactly between the
    /// straight segments of a polyline); returns by how much they were (0 when apart or
    /// both spans are held) and the first and last particle that weigh in each of the two
    /// points.
    fn push_apart<const K: usize>(
        &self,
        (pos, vel, inv_mass): (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
        (timing, friction): (Timing<'_, P>, P::Scalar),
        curve: &impl DrawnSpans<P, K>,
        (a, b): (usize, usize),
        (samples, mut memory): (Option<&mut Samples<P, K>>, Option<&mut PairMemory<P, K>>),
    ) -> (P::Scalar, [(usize, usize); 2]) {
        let zero = (P::Scalar::ZERO, [(1, 0); 2]);
        let gap = self.thickness + self.thickness;
        let pair = (a.min(b), a.max(b));
        // The memory keeps a pair's parameters in the order of its spans.
        let ordered = |(u, v)| if a < b { (u, v) } else { (v, u) };
        // Where the pair comes nearest, and whether it was searched afresh.
        let (near, fresh) = if let Some(samples) = samples {
            let places = match memory
                .as_deref_mut()
                .map(|m| m.recall(pair, (curve.cubic(pair.0), curve.cubic(pair.1))))
            {
                Some(Recall::Apart) => return zero,
                Some(Recall::Near((at, also))) => Some((ordered(at), also.map(ordered))),
                _ => None,
            };
            match samples.nearest(curve, (a, b), places, gap) {
                Ok(found) => found,
                Err(clear) => {
                    if let Some(memory) = memory {
                        memory.remember(pair, clear - gap, None);
                    }
                    return zero;
                }
            }
        } else {
            // Two segments between the particles: their nearest points exactly.
            let ends = |span: usize| (pos[span], pos[(span + 1) % K]);
            let (u, v, apart) = segments_nearest(ends(a), ends(b));
            // Apart: no weights to take, no root.
            if !apart.shorter_than(gap) {
                return zero;
            }
            (Near::only((u, v)), false)
        };
        let (u, v) = near.at;
        let (wa, wb) = (weights(curve, a, u), weights(curve, b, v));
        let g = wa.minus(&wb);
        let d = point_of(pos, g.entries());
        let dist = d.length();
        // Straight segments are measured afresh each time: only their pushes are kept.
        if let Some(memory) = memory.as_deref_mut().filter(|_| !curve.is_straight()) {
            let places = (ordered(near.at), near.also.map(ordered));
            if fresh {
                // Nowhere else nearer than `elsewhere`: while the spans move less than the
                // margin, they touch nowhere else, or the nearest points stay about these
                // places; at most a gap.
                let margin = near.elsewhere.map_or(gap, |e| {
                    (e - gap).max((e - dist) * P::Scalar::ratio(1, 2)).min(gap)
                });
                memory.remember(pair, margin, Some((places, dist - gap)));
            } else {
                memory.moved_to(pair, (places, dist - gap));
            }
        }
        match part(
            (pos, vel, inv_mass),
            (timing, friction),
            g.entries(),
            (d, dist),
            gap,
        ) {
            true => {
                if let Some(memory) = memory {
                    memory.pushed_at(pair, ordered(near.at));
                }
                (gap - dist, [wa.ends(), wb.ends()])
            }
            false => zero,
        }
    }

    /// Between two passes of self-contact ([`resolve_self`](Self::resolve_self)), parts
    /// again, where they came nearer than twice the thickness, the points that the last pass
    /// pushed apart ([`PairMemory::pushes`], at the same parameters: no search, no redraw).
    /// Two points of spans that are not neighbours may never be nearer than that, so such a
    /// push is never wrong; it keeps a heap's upper turns from sinking into the lower ones
    /// under their weight until the next pass, which then finds less to undo (with the first
    /// substep's pass, callgrind on the test's settled 16-particle piles: 18% fewer
    /// instructions a frame under symplectic Euler, 11% under Verlet). Costs two weights, a
    /// root and a push a pair.
    pub(super) fn hold_apart<const K: usize>(
        &self,
        (pos, vel, inv_mass): (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
        timing: Timing<'_, P>,
        curve: &impl DrawnSpans<P, K>,
        memory: &PairMemory<P, K>,
    ) {
        let Some(friction) = self.self_friction else {
            return;
        };
        let gap = self.thickness + self.thickness;
        let n = curve.span_count().min(K);
        for ((a, b), (u, v)) in memory.pushes().filter(|((_, b), _)| *b < n) {
            let g = weights(curve, a, u).minus(&weights(curve, b, v));
            let d = point_of(pos, g.entries());
            let parts = (&mut pos[..], &mut vel[..], &inv_mass[..]);
            part(parts, (timing, friction), g.entries(), (d, d.length()), gap);
        }
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
        timing: Timing<'_, P>,
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
            let g = |i: usize| at_a.wu[i % U] * at_a.wv[i / U] - at_b.wu[i % U] * at_b.wv[i / U];
            let g = (0..U * V).map(|i| (i, g(i)));
            let parts = (&mut pos[..], &mut vel[..], inv_mass);
            if part(parts, (timing, friction), g, (d, dist), gap) {
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

/// The particle weights of the point at parameter `t` of span `span` of `curve`.
fn weights<P: Point, const K: usize>(
    curve: &impl DrawnSpans<P, K>,
    span: usize,
    t: P::Scalar,
) -> Weights<P::Scalar, K> {
    match curve.is_straight() {
        true => Weights::on_segment(span, t),
        false => Weights::of(curve, span, t),
    }
}

/// Parts two points `dist` apart, `d` the first less the second, nearer than `gap`, through
/// the particle weights `g` (`(i, w_i)`) of the first less the second's: their approach
/// stopped, their sliding braked. Whether it pushed (not when they are apart, when they
/// cross exactly and give no direction to part them, or when no free particle moves them).
fn part<P: Point>(
    (pos, vel, inv_mass): (&mut [P], &mut [P], &[P::Scalar]),
    (timing, friction): (Timing<'_, P>, P::Scalar),
    g: impl IntoIterator<Item = (usize, P::Scalar)> + Clone,
    (d, dist): (P, P::Scalar),
    gap: P::Scalar,
) -> bool {
    // Two parts that cross exactly: the next substep parts them.
    if !(dist < gap && dist > gap * P::Scalar::ratio(1, 1024)) {
        return false;
    }
    let normal = d * (P::Scalar::ONE / dist);
    let braking = || timing.braking(g.clone(), P::default());
    let parted = parting(
        normal,
        gap - dist,
        point_of(vel, g.clone()),
        (friction, braking),
    );
    spread(pos, vel, inv_mass, g, parted).is_some()
}

/// The position and velocity changes that part two points `depth` too near along `normal`
/// (from the second to the first), moving at `relative` (the first's velocity less the
/// second's): pushed apart by `depth`, their approach stopped, their sliding braked by
/// Coulomb `friction` and that braking taken back from their move ([`Braking`]).
fn parting<P: Point>(
    normal: P,
    depth: P::Scalar,
    relative: P,
    (friction, braking): (P::Scalar, impl FnOnce() -> Braking<P>),
) -> (P, P) {
    let vn = relative.dot(normal);
    let dx = normal * depth;
    if vn >= P::Scalar::ZERO {
        return (dx, P::default());
    }
    let push = -vn;
    let slide = relative - normal * vn;
    let limits = (friction * push, friction * push);
    let brake = coulomb(slide, limits);
    (
        dx - braking().take_back((slide, brake), normal, limits),
        normal * push - brake,
    )
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

/// The nearest cell-sample pairs the surface search starts from.
const SEEDS: usize = 2;
/// Rounds of the pattern search on two surface cells at most: 8 halvings and the moves
/// between them.
const CELL_ROUNDS: usize = 16;
