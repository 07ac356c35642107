//! Self-contact: a rope's drawn curve and a cloth's drawn surface kept off themselves
//! ([`Contacts::with_self_contact`]).

use super::Contacts;
use super::drawn::{DrawnSpans, SurfacePoint, Weights, point_of, spread};
use crate::curves::power::Power;
use crate::curves::smooth::{Smoothed, Smoothing};
use crate::{Aabb, Point, Scalar};

/// What the pair search reads of one span, taken when a pair first needs it and kept until
/// the curve moves: a span's samples serve all its pairs.
#[derive(Clone, Copy)]
struct Sampled<P: Point> {
    /// Its points at [`SAMPLES`] + 1 even steps: the ends of its chords.
    points: [P; SAMPLES + 1],
    /// How far it strays from those chords at most: `3/(4·SAMPLES²)` of its control points'
    /// largest second difference (a cubic's `|p''| / 6`), the bound of linear interpolation.
    bend: P::Scalar,
    /// Half its longest chord.
    half: P::Scalar,
    /// Its second derivative, `p''(t) = second[0] + t·second[1]`.
    second: [P; 2],
    /// In floating point, its cubic in power form.
    power: Option<Power<P>>,
}

/// Every span's [`Sampled`], and whether it is up to date.
struct Samples<P: Point, const K: usize> {
    spans: [Sampled<P>; K],
    fresh: [bool; K],
}

impl<P: Point, const K: usize> Samples<P, K> {
    fn new() -> Self {
        let zero = P::Scalar::ZERO;
        let empty = Sampled {
            points: [P::default(); SAMPLES + 1],
            bend: zero,
            half: zero,
            second: [P::default(); 2],
            power: None,
        };
        Samples {
            spans: [empty; K],
            fresh: [false; K],
        }
    }

    /// Brings span `span` of `curve` up to date. A span that is no cubic (one Bézier through
    /// every particle: a single span, which pairs with none) counts as unbent.
    fn take(&mut self, curve: &impl DrawnSpans<P, K>, span: usize) {
        if self.fresh[span] {
            return;
        }
        let cubic = curve.cubic(span);
        let s = &mut self.spans[span];
        // Fixed point keeps de Casteljau's convex combinations: the power form's
        // coefficients can leave the format's range.
        s.power = cubic.filter(|_| !P::Scalar::FIXED_POINT).map(Power::of);
        for (k, x) in s.points.iter_mut().enumerate() {
            let t = P::Scalar::ratio(k as u32, SAMPLES as u32);
            *x = s.power.map_or_else(|| curve.point(span, t), |c| c.at(t));
        }
        let (d0, d1) = cubic.map_or((P::default(), P::default()), |[p0, p1, p2, p3]| {
            (p2 - p1 - (p1 - p0), p3 - p2 - (p2 - p1))
        });
        let six = P::Scalar::from_i16(6);
        s.second = [d0 * six, (d1 - d0) * six];
        s.bend = d0.length().max(d1.length()) * P::Scalar::ratio(3, (4 * SAMPLES * SAMPLES) as u32);
        let longest = s
            .points
            .windows(2)
            .map(|c| (c[1] - c[0]).dot(c[1] - c[0]))
            .fold(P::Scalar::ZERO, P::Scalar::max);
        s.half = longest.sqrt() * P::Scalar::ratio(1, 2);
        self.fresh[span] = true;
    }

    /// Forgets the samples of `count` spans from `first` on, counted round the `n` (they
    /// were drawn again).
    fn forget(&mut self, (first, count): (usize, usize), n: usize) {
        for j in 0..count.min(n) {
            self.fresh[(first + j) % n] = false;
        }
    }
}

impl<P: Point> Contacts<'_, P> {
    /// Keeps every two spans of `curve` that are not neighbours (`closed`: counted round the
    /// loop) at least twice the thickness apart, when self-contact is on. Broad phase: each
    /// span's control-point box (it holds the span) grown by the thickness, sorted along the
    /// first axis and swept, so only spans whose boxes overlap are compared. Narrow phase:
    /// the nearest points of the two spans ([`nearest`], from [`SAMPLES`] + 1 points of each
    /// span taken once for all its pairs; exactly, for the straight segments between the
    /// particles), found on the curve as the pass began; the pair is measured where the
    /// particles are now (each point a weighted sum of them) and pushed apart along the line
    /// between them, through both spans' particle weights (a particle both spans share moves
    /// by the difference), with its approach stopped and its sliding braked by Coulomb
    /// friction. A curve of cubic spans has the spans each push moved redrawn after it (those
    /// the two points' particles weigh in), and their samples taken again when next needed;
    /// straight segments are redrawn once, after the pass. Returns the deepest overlap it
    /// found, or `None` when the redrawn curve left the range (the step's guard undoes it).
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
        // Straight segments are measured from the particles: no samples.
        let straight = curve.is_straight();
        let mut samples = (!straight).then(Samples::new);
        let mut deepest = zero;
        sweep(&boxes[..n], &mut order[..n], |a, b| {
            let apart = a.abs_diff(b);
            let apart = if closed { apart.min(n - apart) } else { apart };
            if apart >= 2 {
                let parts = (&mut *pos, &mut *vel, inv_mass);
                let (depth, moved) =
                    self.push_apart(parts, (h, friction), &*curve, (a, b), samples.as_mut());
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
    /// thickness ([`nearest`] from `samples`; without them, exactly between the straight
    /// segments of a polyline); returns by how much they were (0 when apart or both spans
    /// are held) and the first and last particle that weigh in each of the two points.
    fn push_apart<const K: usize>(
        &self,
        (pos, vel, inv_mass): (&mut [P; K], &mut [P; K], &[P::Scalar; K]),
        (h, friction): (P::Scalar, P::Scalar),
        curve: &impl DrawnSpans<P, K>,
        (a, b): (usize, usize),
        samples: Option<&mut Samples<P, K>>,
    ) -> (P::Scalar, [(usize, usize); 2]) {
        let zero = (P::Scalar::ZERO, [(1, 0); 2]);
        let gap = self.thickness + self.thickness;
        let found = if let Some(samples) = samples {
            samples.take(curve, a);
            samples.take(curve, b);
            let (sa, sb) = (&samples.spans[a], &samples.spans[b]);
            let point =
                |s: &Sampled<P>, span, t| s.power.map_or_else(|| curve.point(span, t), |c| c.at(t));
            let slope = |s: &Sampled<P>, span, t| {
                s.power
                    .map_or_else(|| curve.tangent(span, t), |c| c.slope(t))
            };
            nearest(
                (sa, |u| point(sa, a, u), |u| slope(sa, a, u)),
                (sb, |v| point(sb, b, v), |v| slope(sb, b, v)),
                gap,
            )
        } else {
            // Two segments between the particles: their nearest points exactly.
            let ends = |span: usize| (pos[span], pos[(span + 1) % K]);
            let (u, v, _) = segments_nearest(ends(a), ends(b));
            Some((u, v))
        };
        let Some((u, v)) = found else {
            return zero;
        };
        let (wa, wb) = (Weights::of(curve, a, u), Weights::of(curve, b, v));
        let g = wa.minus(&wb);
        let d = point_of(pos, g.entries());
        let dist = d.length();
        // Two spans that cross exactly give no direction to part them: the next substep will.
        if !(dist < gap && dist > gap * P::Scalar::ratio(1, 1024)) {
            return zero;
        }
        let normal = d * (P::Scalar::ONE / dist);
        let parted = parting(
            normal,
            gap - dist,
            point_of(vel, g.entries()),
            (friction, h),
        );
        // `None`: no free particle moves the pair (both spans held).
        match spread(pos, vel, inv_mass, g.entries(), parted) {
            Some(_) => (gap - dist, [wa.ends(), wb.ends()]),
            None => zero,
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
            let g = (0..U * V).map(|i| (i, g(i)));
            let parted = parting(normal, gap - dist, point_of(vel, g.clone()), (friction, h));
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
/// `b(v)` with tangents `ta` and `tb`, sampled in `sa` and `sb`. Each span lies within its
/// `bend` of the chords between its samples, so the chords' exact distances (segment to
/// segment; a chord pair whose nearest corners are too far for it to matter is skipped
/// unmeasured) bound the spans' within the two bends. `None`, without more, when no chord
/// pair comes within `gap` plus both bends: the spans are apart. Otherwise the nearest chord
/// pair seeds [`refine`], and so does the nearest pair of chords that are no neighbours of
/// those, when it could still hold a nearer point pair (two arcs near each other in two
/// places); the nearest result wins. Cost: `(SAMPLES + 1)²` squared distances, up to
/// `SAMPLES²` segment distances, and 2 or 4 points and tangents a Newton step.
fn nearest<P: Point>(
    (sa, a, ta): (
        &Sampled<P>,
        impl Fn(P::Scalar) -> P,
        impl Fn(P::Scalar) -> P,
    ),
    (sb, b, tb): (
        &Sampled<P>,
        impl Fn(P::Scalar) -> P,
        impl Fn(P::Scalar) -> P,
    ),
    gap: P::Scalar,
) -> Option<(P::Scalar, P::Scalar)> {
    let d2 = |p: P| p.dot(p);
    let (pa, pb) = (&sa.points, &sb.points);
    let slack = sa.bend + sb.bend;
    let halves = sa.half + sb.half;
    let corner: [[P::Scalar; SAMPLES + 1]; SAMPLES + 1] =
        core::array::from_fn(|k| core::array::from_fn(|l| d2(pa[k] - pb[l])));
    // Each chord pair's squared distance and nearest parameters, once measured.
    let mut chords = [[None; SAMPLES]; SAMPLES];
    let mut best: Option<(P::Scalar, usize, usize)> = None;
    // Chords this far apart hold the spans apart.
    let far = gap + slack;
    // Farther than this, a chord pair neither touches nor beats the nearest by the bends.
    let mut limit = far;
    for i in 0..SAMPLES {
        for j in 0..SAMPLES {
            // Every point of a chord is within half of it from one of its ends.
            let near = corner[i][j]
                .min(corner[i + 1][j])
                .min(corner[i][j + 1])
                .min(corner[i + 1][j + 1]);
            let reach = limit + halves;
            if near >= reach * reach {
                continue;
            }
            let (s, t, d) = segments_nearest((pa[i], pa[i + 1]), (pb[j], pb[j + 1]));
            chords[i][j] = Some((d, s, t));
            if best.is_none_or(|(kept, _, _)| d < kept) {
                best = Some((d, i, j));
                limit = limit.min(d.sqrt() + slack);
            }
        }
    }
    let (d, i, j) = best?;
    if d >= far * far {
        return None;
    }
    let param = |k: usize, s: P::Scalar| {
        (P::Scalar::from_i16(k as i16) + s) / P::Scalar::from_i16(SAMPLES as i16)
    };
    let seed = |k: usize, l: usize| chords[k][l].map(|(_, s, t)| (param(k, s), param(l, t)));
    let (sa2, sb2) = (sa.second, sb.second);
    let a = (&a, &ta, &|u| sa2[0] + sa2[1] * u);
    let b = (&b, &tb, &|v| sb2[0] + sb2[1] * v);
    let (found, mut u, mut v) = refine(a, b, seed(i, j)?);
    // The nearest chord pair that is no neighbour of the first, refined when its bound could
    // beat what the first found.
    let mut other: Option<(P::Scalar, usize, usize)> = None;
    for (k, row) in chords.iter().enumerate() {
        for (l, c) in row.iter().enumerate() {
            if let Some((dc, _, _)) = *c
                && (k.abs_diff(i) >= 2 || l.abs_diff(j) >= 2)
                && other.is_none_or(|(kept, _, _)| dc < kept)
            {
                other = Some((dc, k, l));
            }
        }
    }
    if let Some((dc, k, l)) = other {
        let bound = dc.sqrt() - slack;
        if let Some(start) =
            seed(k, l).filter(|_| bound <= P::Scalar::ZERO || bound * bound < found)
        {
            let (e, nu, nv) = refine(a, b, start);
            if e < found {
                (u, v) = (nu, nv);
            }
        }
    }
    Some((u, v))
}

/// Newton steps from `(u, v)` on half the squared distance between the points of two spans,
/// each given as its point, tangent and second derivative at a parameter: the full Hessian
/// (curvature terms included, so two arcs side by side or bending away converge where
/// Gauss-Newton stalls), its least eigenvalue raised to 1/1024 of the tangents' squared
/// lengths, a parameter held at `[0, 1]`'s bound where the slope or the step pushes out of
/// it, and the step shortened to stay in `[0, 1]²` (a clamped step need not descend). A step that does not bring the points nearer is cut to the least of the
/// parabola through the distance there, at the start and the start's slope (to between
/// 1/10 and 1/2 of it), up to [`CUTS`] times. At most [`NEWTON_STEPS`] steps, stopped once
/// one moves less than 1/4096 of a span. Returns the squared distance and the parameters of
/// the nearest pair met.
fn refine<P: Point>(
    (a, ta, sa): (
        &impl Fn(P::Scalar) -> P,
        &impl Fn(P::Scalar) -> P,
        &impl Fn(P::Scalar) -> P,
    ),
    (b, tb, sb): (
        &impl Fn(P::Scalar) -> P,
        &impl Fn(P::Scalar) -> P,
        &impl Fn(P::Scalar) -> P,
    ),
    (mut u, mut v): (P::Scalar, P::Scalar),
) -> (P::Scalar, P::Scalar, P::Scalar) {
    let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
    let half = P::Scalar::ratio(1, 2);
    let clamp = |x: P::Scalar| x.max(zero).min(one);
    let small = P::Scalar::ratio(1, 4096);
    let mut f = a(u) - b(v);
    let mut e = f.dot(f);
    'steps: for _ in 0..NEWTON_STEPS {
        let (da, db) = (ta(u), tb(v));
        let (aa, bb) = (da.dot(da), db.dot(db));
        let (gu, gv) = (f.dot(da), -f.dot(db));
        let (mut huu, mut hvv, huv) = (aa + f.dot(sa(u)), bb - f.dot(sb(v)), -da.dot(db));
        // Raise the least eigenvalue of [[huu, huv], [huv, hvv]] to a floor: a descent step.
        let spread = (huu - hvv) * half;
        let least = (huu + hvv) * half - (spread * spread + huv * huv).sqrt();
        let raise = ((aa + bb) * P::Scalar::ratio(1, 1024) - least).max(zero);
        (huu, hvv) = (huu + raise, hvv + raise);
        // A parameter at a bound stays there when the slope, or the step, pushes out of it.
        let out = |x: P::Scalar, d: P::Scalar| (x <= zero && d < zero) || (x >= one && d > zero);
        let mut held = (out(u, -gu), out(v, -gv));
        let det = huu * hvv - huv * huv;
        let mut free = None;
        if held == (false, false) && det > zero {
            let (du, dv) = ((huv * gv - hvv * gu) / det, (huv * gu - huu * gv) / det);
            held = (out(u, du), out(v, dv));
            free = Some((du, dv)).filter(|_| held == (false, false));
        }
        let (mut du, mut dv) = match (free, held) {
            (Some(step), _) => step,
            (None, (true, false)) if hvv > zero => (zero, -gv / hvv),
            (None, (false, true)) if huu > zero => (-gu / huu, zero),
            _ => break,
        };
        // Shortened to stay in the box: still a descent direction, as a clamped one is not.
        let mut scale = one;
        for (x, d) in [(u, du), (v, dv)] {
            if x + d > one {
                scale = scale.min((one - x) / d);
            } else if x + d < zero {
                scale = scale.min(x / -d);
            }
        }
        (du, dv) = (du * scale, dv * scale);
        for _ in 0..=CUTS {
            let (nu, nv) = (clamp(u + du), clamp(v + dv));
            let nf = a(nu) - b(nv);
            let ne = nf.dot(nf);
            let (su, sv) = (nu - u, nv - v);
            if ne < e {
                (u, v, f, e) = (nu, nv, nf, ne);
                if su.abs().max(sv.abs()) < small {
                    break 'steps;
                }
                continue 'steps;
            }
            // The squared distance along the step: `e + slope·s + bend·s²`, `s` in [0, 1].
            let slope = (gu * su + gv * sv) * P::Scalar::from_i16(2);
            let bend = ne - e - slope;
            let cut = if slope < zero && bend > zero {
                (-slope / (bend + bend))
                    .max(P::Scalar::ratio(1, 10))
                    .min(half)
            } else {
                half
            };
            (du, dv) = (su * cut, sv * cut);
        }
        break;
    }
    (e, u, v)
}

/// Steps a span is sampled in to seed the search for its nearest points to another.
const SAMPLES: usize = 4;
/// Newton steps from a seed at most.
const NEWTON_STEPS: usize = 8;
/// Times a Newton step that does not bring the points nearer is cut at most.
const CUTS: usize = 4;
/// The nearest cell-sample pairs the surface search starts from.
const SEEDS: usize = 2;
/// Rounds of the pattern search on two surface cells at most: 8 halvings and the moves
/// between them.
const CELL_ROUNDS: usize = 16;

/// The nearest points of segments `p` and `q`: their parameters in `[0, 1]` and the squared
/// distance (the clamped closest points of the two lines, then each end against the other
/// segment; no root).
fn segments_nearest<P: Point>(
    (p0, p1): (P, P),
    (q0, q1): (P, P),
) -> (P::Scalar, P::Scalar, P::Scalar) {
    let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
    let clamp = |x: P::Scalar| x.max(zero).min(one);
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, b, e) = (d1.dot(d1), d1.dot(d2), d2.dot(d2));
    let (c, f) = (d1.dot(r), d2.dot(r));
    // The parameter nearest a point on each segment: its projection over the squared length
    // (one division a segment; a point segment has only its start).
    let (over_a, over_e) = (
        if a > zero { one / a } else { zero },
        if e > zero { one / e } else { zero },
    );
    let at = |s: P::Scalar, t: P::Scalar| {
        let d = p0 + d1 * s - (q0 + d2 * t);
        (s, t, d.dot(d))
    };
    // Each end against the other segment: `(p·d)` of the end less that segment's start.
    let mut best = at(zero, clamp(f * over_e));
    for candidate in [
        at(one, clamp((f + b) * over_e)),
        at(clamp(-c * over_a), zero),
        at(clamp((b - c) * over_a), one),
    ] {
        if candidate.2 < best.2 {
            best = candidate;
        }
    }
    let denom = a * e - b * b;
    if denom > zero && e > zero {
        let s = clamp((b * f - c * e) / denom);
        let t = clamp((b * s + f) * over_e);
        let inner = at(s, t);
        if inner.2 < best.2 {
            best = inner;
        }
    }
    best
}
