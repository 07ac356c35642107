//! What contacts test and move: a drawn curve's spans and a drawn surface's cells, each point
//! a weighted sum of the particles, and how a correction at a drawn point reaches them.

use super::collider::Collider;
use crate::curves::curve::clamp_unit;
use crate::curves::smooth::{Smoothed, Smoothing};
use crate::{Aabb, Point, Scalar};

/// A curve of spans drawn through `K` control points, as contacts test it: each span lies
/// in the box of its own control points, and each of its points is a weighted sum of the
/// `K` (see [`Smoothed`]).
pub(crate) trait DrawnSpans<P: Point, const K: usize> {
    /// Number of spans.
    fn span_count(&self) -> usize;
    /// A box that holds span `span`.
    fn span_bounds(&self, span: usize) -> Aabb<P>;
    /// The parameter in `[0, 1]` of span `span` where `key` is least.
    fn deepest(&self, span: usize, key: impl Fn(P) -> P::Scalar) -> P::Scalar;
    /// The parameter of `span` where it reaches farthest against `normal`.
    fn lowest(&self, span: usize, normal: P) -> P::Scalar;
    /// The parameter of `span` nearest `c`.
    fn nearest(&self, span: usize, c: P) -> P::Scalar;
    /// The point of span `span` at `t`.
    fn point(&self, span: usize, t: P::Scalar) -> P;
    /// Its derivative `dP/dt` there.
    fn tangent(&self, span: usize, t: P::Scalar) -> P;
    /// Span `span`'s Bézier control points when it is a cubic.
    fn cubic(&self, span: usize) -> Option<[P; 4]>;
    /// The control points' weights in that point.
    fn weights(&self, span: usize, t: P::Scalar, weights: &mut [P::Scalar; K]);
    /// The same weights when only 4 control points can weigh in (an open cubic spline's or
    /// polyline's): the first of them and their weights, with no pass over all `K`.
    fn window(&self, _span: usize, _t: P::Scalar) -> Option<(usize, [P::Scalar; 4])> {
        None
    }
    /// Draws again the spans that the control points `moved` (the first and the last,
    /// inclusive) weigh in, after they moved: the spans drawn again, `(first, count)`
    /// counted round a loop, or `None` when the moved points left the range.
    fn rebuild(&mut self, pos: &[P; K], moved: (usize, usize)) -> Option<(usize, usize)>;
    /// [`rebuild`](Self::rebuild) put off: the spans that the moved control points weigh
    /// in, `(first, count)` round a loop, left for
    /// [`redraw_spans`](Self::redraw_spans) when next read; `(0, 0)` when this drew every
    /// span again at once (one Bézier's, a natural spline's); `None` when they left the
    /// range.
    fn outdated(&mut self, pos: &[P; K], moved: (usize, usize)) -> Option<(usize, usize)>;
    /// Draws spans `first..first + count` (round a loop) again from `pos`.
    fn redraw_spans(&mut self, pos: &[P; K], spans: (usize, usize));
    /// Whether the last span joins the first (a loop).
    fn is_closed(&self) -> bool {
        false
    }
    /// Whether every span is a straight segment (the polyline between the particles).
    fn is_straight(&self) -> bool {
        false
    }
}

impl<P: Point, const K: usize> DrawnSpans<P, K> for Smoothed<P, K> {
    fn span_count(&self) -> usize {
        Smoothed::span_count(self)
    }
    fn span_bounds(&self, span: usize) -> Aabb<P> {
        Smoothed::span_bounds(self, span)
    }
    fn deepest(&self, span: usize, key: impl Fn(P) -> P::Scalar) -> P::Scalar {
        Smoothed::deepest(self, span, key)
    }
    fn lowest(&self, span: usize, normal: P) -> P::Scalar {
        Smoothed::lowest(self, span, normal)
    }
    fn nearest(&self, span: usize, c: P) -> P::Scalar {
        Smoothed::nearest(self, span, c)
    }
    fn point(&self, span: usize, t: P::Scalar) -> P {
        Smoothed::point(self, span, t)
    }
    fn tangent(&self, span: usize, t: P::Scalar) -> P {
        Smoothed::tangent(self, span, t)
    }
    fn cubic(&self, span: usize) -> Option<[P; 4]> {
        self.span_points(span).try_into().ok()
    }
    fn weights(&self, span: usize, t: P::Scalar, weights: &mut [P::Scalar; K]) {
        Smoothed::weights(self, span, t, weights);
    }
    fn window(&self, span: usize, t: P::Scalar) -> Option<(usize, [P::Scalar; 4])> {
        Smoothed::window(self, span, t)
    }
    fn is_closed(&self) -> bool {
        Smoothed::span_count(self) == K
    }
    fn is_straight(&self) -> bool {
        self.method() == Smoothing::Polyline
    }
    fn rebuild(&mut self, pos: &[P; K], moved: (usize, usize)) -> Option<(usize, usize)> {
        self.redraw(pos, moved).ok()
    }
    fn outdated(&mut self, pos: &[P; K], moved: (usize, usize)) -> Option<(usize, usize)> {
        Some(Smoothed::outdated(self, pos, moved).ok()?.unwrap_or((0, 0)))
    }
    fn redraw_spans(&mut self, pos: &[P; K], spans: (usize, usize)) {
        Smoothed::redraw_spans(self, pos, spans);
    }
}

/// A drawn point's particle weights, only those that are not zero (at most 4 for a cubic
/// span's point, 2 for a segment's, all `K` for one Bézier's or a natural spline's), in
/// rising particle order: what reads and moves the point costs that many particles, not `K`.
#[derive(Clone)]
pub(super) struct Weights<S, const K: usize> {
    entries: heapless::Vec<(usize, S), K>,
}

impl<S: Scalar, const K: usize> Weights<S, K> {
    /// The weights of span `span`'s point at `t` on `curve`.
    pub(super) fn of<P: Point<Scalar = S>>(
        curve: &impl DrawnSpans<P, K>,
        span: usize,
        t: S,
    ) -> Self {
        let mut w = Self::none();
        w.take(curve, span, t);
        w
    }

    /// Makes these the weights of span `span`'s point at `t` on `curve`, as
    /// [`of`](Self::of) does, in place: a loop that takes one point's weights after another
    /// fills one buffer and copies none out.
    pub(super) fn take<P: Point<Scalar = S>>(
        &mut self,
        curve: &impl DrawnSpans<P, K>,
        span: usize,
        t: S,
    ) {
        self.entries.clear();
        match curve.window(span, t) {
            Some((first, near)) => {
                for (i, &x) in near.iter().enumerate() {
                    self.push(first + i, x);
                }
            }
            None => {
                let mut dense = [S::ZERO; K];
                curve.weights(span, t, &mut dense);
                for (i, &x) in dense.iter().enumerate() {
                    self.push(i, x);
                }
            }
        }
    }

    /// The weights of the point at `u` (clamped to `[0, 1]`) of the straight segment from
    /// particle `span` to the next (round a loop): what [`of`](Self::of) gives on a
    /// polyline, without its pass over all `K`.
    pub(super) fn on_segment(span: usize, u: S) -> Self {
        let u = clamp_unit(u);
        let (here, next) = ((span, S::ONE - u), ((span + 1) % K, u));
        let (first, second) = if next.0 < here.0 {
            (next, here)
        } else {
            (here, next)
        };
        let mut w = Self::none();
        w.push(first.0, first.1);
        w.push(second.0, second.1);
        w
    }

    /// No particle weighs in.
    pub(super) fn none() -> Self {
        Weights {
            entries: heapless::Vec::new(),
        }
    }

    /// The weights of one point less another's (a particle in both weighs the difference).
    pub(super) fn minus(&self, other: &Self) -> Self {
        let mut w = Self::none();
        let (mut a, mut b) = (self.entries().peekable(), other.entries().peekable());
        loop {
            match (a.peek().copied(), b.peek().copied()) {
                (Some((i, x)), Some((j, y))) if i == j => {
                    w.push(i, x - y);
                    a.next();
                    b.next();
                }
                (Some((i, x)), Some((j, _))) if i < j => {
                    w.push(i, x);
                    a.next();
                }
                (_, Some((j, y))) => {
                    w.push(j, -y);
                    b.next();
                }
                (Some((i, x)), None) => {
                    w.push(i, x);
                    a.next();
                }
                (None, None) => return w,
            }
        }
    }

    /// Appends particle `i` at weight `x` unless it is zero (`i` past the last).
    fn push(&mut self, i: usize, x: S) {
        if x != S::ZERO {
            // At most `K` particles weigh in: a push past them has none to add.
            let _ = self.entries.push((i, x));
        }
    }

    /// The first and the last particle that weigh in the point (`(1, 0)` when none does).
    pub(super) fn ends(&self) -> (usize, usize) {
        match (self.entries.first(), self.entries.last()) {
            (Some(&(first, _)), Some(&(last, _))) => (first, last),
            _ => (1, 0),
        }
    }

    /// `(particle, weight)` for each weight that is not zero.
    pub(super) fn entries(&self) -> impl Iterator<Item = (usize, S)> + Clone + '_ {
        self.entries.iter().copied()
    }
}

/// Whether the cubic span with Bézier control points `b` (in the collider's frame) is
/// clear of `collider` by the `thickness`, judged without a search: the span lies in its
/// control points' convex hull, whose every point is within `ρ` of the chord `b[0]`–`b[3]`
/// (`ρ` the farther of `b[1]` and `b[2]` from it), so a ball that is further than `ρ` and
/// the thickness from the chord (by a 1/1024 of `ρ` and of the chord's longest coordinate,
/// and 4 units in the last place of the coordinates, for the rounding) is clear of the
/// span. One division and one root; `false` for every solid but a ball, and in `Q16`
/// (whose products of a short chord keep few bits, and of a long one saturate; its roots
/// and division are dear on a Cortex-M0), which then take the search.
pub(super) fn ball_clears_span<P: Point>(
    collider: &Collider<P>,
    b: [P; 4],
    thickness: P::Scalar,
) -> bool {
    let Some((centre, radius)) = collider.as_ball().filter(|_| !P::Scalar::FIXED_POINT) else {
        return false;
    };
    let (zero, one) = (P::Scalar::ZERO, P::Scalar::ONE);
    let chord = b[3] - b[0];
    let squared = chord.dot(chord);
    let inverse = if squared > zero { one / squared } else { zero };
    // The chord's nearest point to `p`.
    let nearest = |p: P| b[0] + chord * ((p - b[0]).dot(chord) * inverse).max(zero).min(one);
    let off = |p: P| {
        let d = p - nearest(p);
        d.dot(d)
    };
    let bulge = off(b[1]).max(off(b[2])).sqrt();
    let largest = |v: P| (0..P::DIM).fold(zero, |m, d| m.max(v.coord(d).abs()));
    let rounding = (largest(b[0]) + largest(centre) + one) * P::Scalar::EPSILON;
    let margin =
        (bulge + largest(chord)) * P::Scalar::ratio(1, 1024) + rounding * P::Scalar::from_i16(4);
    // Its gap, `|centre − nearest| − radius`, at least `bulge` more than the thickness.
    !(centre - nearest(centre)).shorter_than(radius + thickness + margin + bulge)
}

/// `Σ w_i · p_i` over `(i, w_i)` in `w`.
pub(super) fn point_of<P: Point>(
    points: &[P],
    w: impl IntoIterator<Item = (usize, P::Scalar)>,
) -> P {
    w.into_iter()
        .fold(P::default(), |acc, (i, x)| acc + points[i] * x)
}

/// The inverse mass of the drawn point with particle weights `w` (`(i, w_i)`), `Σ w_i² / m_i`
/// over the free particles (what a push on that point meets), or `None` when every particle
/// that moves it is pinned.
pub(super) fn point_inv_mass<S: Scalar>(
    inv_mass: &[S],
    w: impl IntoIterator<Item = (usize, S)>,
) -> Option<S> {
    let norm = w
        .into_iter()
        .filter(|&(i, _)| inv_mass[i] > S::ZERO)
        .fold(S::ZERO, |norm, (i, x)| norm + x * x * inv_mass[i]);
    (norm > S::ZERO).then_some(norm)
}

/// Moves the particles so that the drawn point with particle weights `w` (`(i, w_i)`, each
/// particle once) moves by `dx` and its velocity changes by `dv`: the smallest change in the
/// inverse-mass metric. Returns the momentum the particles gained, or `None` when every
/// particle that moves the point is pinned.
pub(super) fn spread<P: Point>(
    pos: &mut [P],
    vel: &mut [P],
    inv_mass: &[P::Scalar],
    w: impl IntoIterator<Item = (usize, P::Scalar)> + Clone,
    (dx, dv): (P, P),
) -> Option<P> {
    let zero = P::Scalar::ZERO;
    let (mut norm, mut sum) = (zero, zero);
    for (i, x) in w.clone() {
        let m = inv_mass[i];
        if m > zero {
            norm += x * x * m;
            sum += x;
        }
    }
    if norm <= zero {
        return None;
    }
    let share = P::Scalar::ONE / norm;
    for (i, x) in w {
        let m = inv_mass[i];
        if m > zero {
            let k = x * m * share;
            pos[i] += dx * k;
            vel[i] += dv * k;
        }
    }
    Some(dv * (sum * share))
}

/// A point of the surface that a smoothing draws through a `U × V` grid: its two directions'
/// particle weights.
pub(super) struct SurfacePoint<S, const U: usize, const V: usize> {
    pub(super) smoothing: Smoothing,
    /// Rows and columns close on themselves (a torus).
    closed: bool,
    pub(super) wu: [S; U],
    pub(super) wv: [S; V],
    /// The columns and rows whose weights are not zero (all of them for one Bézier or a
    /// natural spline, 4 for the local bases): the only ones [`point`](Self::point) reads.
    support: (core::ops::Range<usize>, core::ops::Range<usize>),
}

/// The indices from the first to the last non-zero weight.
fn nonzero<S: Scalar>(w: &[S]) -> core::ops::Range<usize> {
    let first = w.iter().position(|&x| x != S::ZERO).unwrap_or(0);
    let end = w
        .iter()
        .rposition(|&x| x != S::ZERO)
        .map_or(first, |i| i + 1);
    first..end
}

impl<S: Scalar, const U: usize, const V: usize> SurfacePoint<S, U, V> {
    /// A point of the surface `smoothing` draws (`closed`: round a torus's rings both
    /// ways), not yet placed.
    pub(super) fn new(smoothing: Smoothing, closed: bool) -> Self {
        SurfacePoint {
            smoothing,
            closed,
            wu: [S::ZERO; U],
            wv: [S::ZERO; V],
            support: (0..0, 0..0),
        }
    }

    /// Moves to `(u, v)` in `[0, 1]²` of cell `(cu, cv)`, the cell between particles
    /// `(cu, cv)` and `(cu + 1, cv + 1)`.
    pub(super) fn at(&mut self, (cu, cv): (usize, usize), (u, v): (S, S)) {
        let (su, tu) = locate(self.smoothing, cu, u, U);
        let (sv, tv) = locate(self.smoothing, cv, v, V);
        self.smoothing.weights(self.closed, su, tu, &mut self.wu);
        self.smoothing.weights(self.closed, sv, tv, &mut self.wv);
        self.support = (nonzero(&self.wu), nonzero(&self.wv));
    }

    /// `Σ wu_i wv_j · points[j·U + i]`, over the weights that are not zero.
    pub(super) fn point<P: Point<Scalar = S>>(&self, points: &[P]) -> P {
        let (columns, rows) = self.support.clone();
        let wu = &self.wu[columns.clone()];
        let mut sum = P::default();
        for (row, &wv) in points
            .chunks_exact(U)
            .zip(&self.wv)
            .take(rows.end)
            .skip(rows.start)
        {
            sum += point_of(&row[columns.clone()], wu.iter().copied().enumerate()) * wv;
        }
        sum
    }

    /// A box that holds cell `(cu, cv)` of the surface: its supporting particles' box (every
    /// particle for one Bézier), grown about its centre by `overshoot`, the most `Σ|w|` of
    /// the basis reaches. `None` only for an empty grid.
    pub(super) fn cell_bounds<P: Point<Scalar = S>>(
        &self,
        points: &[P],
        (cu, cv): (usize, usize),
        overshoot: S,
    ) -> Option<Aabb<P>> {
        // The particles a cell's points weigh: all for one Bézier, else the cell's corners
        // and one more each side (wrapping round a closed grid).
        let support = |c: usize, n: usize| {
            let (first, end) = match self.smoothing {
                Smoothing::Bezier => (0, n),
                _ if self.closed => (c + n - 1, c + n + 3),
                _ => (c.saturating_sub(1), (c + 3).min(n)),
            };
            (first..end).map(move |i| i % n)
        };
        let mut hull: Option<Aabb<P>> = None;
        for j in support(cv, V) {
            for i in support(cu, U) {
                let p = points[j * U + i];
                hull = Some(hull.map_or(Aabb::point(p), |b| b.including(p)));
            }
        }
        let hull = hull?;
        let centre = hull.min.midpoint(hull.max);
        let half = (hull.max - centre) * overshoot;
        Some(Aabb {
            min: centre - half,
            max: centre + half,
        })
    }
}

/// Span and parameter along one grid direction of `n` particles for cell `cell` at `t`: one
/// Bézier spans the whole direction, the other smoothings have a span per cell.
pub(super) fn locate<S: Scalar>(smoothing: Smoothing, cell: usize, t: S, n: usize) -> (usize, S) {
    match smoothing {
        Smoothing::Bezier => (
            0,
            (S::from_i16(cell as i16) + t) * S::ratio(1, (n - 1) as u32),
        ),
        _ => (cell, t),
    }
}

/// The `(u, v)` in `[0, 1]²` of a cell where `key` (of a point: the point and its search
/// key) is least: the best of 3×3 samples, then 8 rounds of a compass search whose step halves
/// from 1/4 (its last step 1/512 of the cell). `None`, without the search, unless
/// `near(best sample, the longest distance between neighbouring samples)`: every point of a
/// cell lies that close to a sample unless the cell folds between them.
pub(super) fn deepest_in_cell<P: Point>(
    mut key: impl FnMut(P::Scalar, P::Scalar) -> (P, P::Scalar),
    near: impl Fn(P, P::Scalar) -> bool,
) -> Option<(P::Scalar, P::Scalar)> {
    let (zero, half) = (P::Scalar::ZERO, P::Scalar::ratio(1, 2));
    let mut samples = [(P::default(), zero); 9];
    let at = |k: usize| {
        (
            P::Scalar::ratio(k as u32 % 3, 2),
            P::Scalar::ratio(k as u32 / 3, 2),
        )
    };
    for (k, sample) in samples.iter_mut().enumerate() {
        *sample = key(at(k).0, at(k).1);
    }
    let (mut best, mut nearest, mut spacing) = ((zero, zero, samples[0].1), samples[0].0, zero);
    for (k, &(x, d)) in samples.iter().enumerate() {
        if d < best.2 {
            (best, nearest) = ((at(k).0, at(k).1, d), x);
        }
        // The neighbours to the right (same row) and above.
        for next in [k + 1, k + 3] {
            if next < 9 && (next == k + 3 || k % 3 < 2) {
                spacing = spacing.max((samples[next].0 - x).length());
            }
        }
    }
    if !near(nearest, spacing) {
        return None;
    }
    let mut step = P::Scalar::ratio(1, 4);
    for _ in 0..8 {
        let (u, v, _) = best;
        for (du, dv) in [(step, zero), (-step, zero), (zero, step), (zero, -step)] {
            let (nu, nv) = (
                crate::curves::curve::clamp_unit(u + du),
                crate::curves::curve::clamp_unit(v + dv),
            );
            let d = key(nu, nv).1;
            if d < best.2 {
                best = (nu, nv, d);
            }
        }
        step = step * half;
    }
    Some((best.0, best.1))
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::{Bezier, Vec2};

    /// A segment's two weights are those a polyline's point has, open and round a loop, at
    /// its ends and between (the particles' order kept).
    #[test]
    fn a_segments_weights_are_the_polylines() {
        let pos: [Vec2<f64>; 6] = core::array::from_fn(|i| Vec2::new(i as f64, (i * i) as f64));
        let open = Smoothed::open(Smoothing::Polyline, &pos).unwrap();
        let ring = Smoothed::ring(Smoothing::Polyline, &pos).unwrap();
        for curve in [open, ring] {
            for span in 0..curve.span_count() {
                for u in [-0.5, 0.0, 0.3, 1.0, 1.5] {
                    let (direct, general) = (
                        Weights::<f64, 6>::on_segment(span, u),
                        Weights::of(&curve, span, u),
                    );
                    let entries = |w: &Weights<f64, 6>| w.entries().collect::<std::vec::Vec<_>>();
                    assert_eq!(entries(&direct), entries(&general), "{span} {u}");
                }
            }
        }
    }

    /// Random cubic spans and balls at `scale` (control points within `2·scale` of the
    /// origin, centres within `4·scale`), in `f32`: how many the test judged clear, and how
    /// many are; it panics on a span judged clear that comes nearer the ball than its radius
    /// and the thickness (the span sampled at 4 096 points in `f64`, less the sampling's
    /// reach).
    fn judge_spans(scale: f32, seed: u64) -> (usize, usize) {
        let mut next = crate::curves::power::tests::uniform(seed);
        let mut at = |k: f32| k * scale * next() as f32;
        let (mut judged, mut clear) = (0, 0);
        for _ in 0..20_000 {
            let b: [Vec2<f32>; 4] = core::array::from_fn(|_| Vec2::new(at(1.0), at(1.0)));
            let centre = Vec2::new(at(2.0), at(2.0));
            let (radius, thickness) = (at(0.3).abs(), at(0.05).abs());
            let ball = Collider::ball(centre, radius).unwrap();
            let wide = |p: Vec2<f32>| Vec2::new(f64::from(p.x), f64::from(p.y));
            let (curve, c) = (Bezier::new(b.map(wide)).unwrap(), wide(centre));
            let least = (0..=4096)
                .map(|k| (curve.eval(k as f64 / 4096.0) - c).length())
                .fold(f64::INFINITY, f64::min);
            // Consecutive samples are at most |P'| / 4096 apart, |P'| ≤ 3 · the longest leg.
            let legs = b.windows(2).map(|w| (wide(w[1]) - wide(w[0])).length());
            let reach = 3.0 * legs.fold(0.0, f64::max) / 8192.0;
            let clearance = f64::from(radius) + f64::from(thickness);
            if ball_clears_span(&ball, b, thickness) {
                judged += 1;
                let near = least + reach;
                assert!(near >= clearance, "{b:?}, {centre:?}, {radius}: {least}");
            }
            clear += usize::from(least >= clearance);
        }
        (judged, clear)
    }

    /// A ball is judged clear of a cubic span only where it is: on 20 000 random spans and
    /// balls, in `f32`, with spans 4 m and 400 m across, every span judged clear comes no
    /// nearer the ball than its radius and the thickness; and the test is no idle one: it
    /// judges clear more than half the spans that are, and a straight span beside a ball.
    #[test]
    fn a_ball_clear_of_a_span_is_clear_of_every_point() {
        for (scale, seed) in [(1.0, 29), (100.0, 31)] {
            let (judged, clear) = judge_spans(scale, seed);
            assert!(judged * 2 > clear, "{judged} judged clear of {clear} clear");
        }
        let line = [0.0f32, 1.0, 2.0, 3.0].map(|x| Vec2::new(x, 0.0));
        let ball = Collider::ball(Vec2::new(1.5, -0.3), 0.2).unwrap();
        assert!(ball_clears_span(&ball, line, 0.05));
        assert!(!ball_clears_span(&ball, line, 0.15));
    }
}
