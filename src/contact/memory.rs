//! What self-contact remembers from one round and substep to the next within a step: which
//! pairs of spans were found apart or near each other, and how far each span may have moved
//! since.

use super::drawn::DrawnSpans;
use crate::{Point, Scalar};

/// Pairs of spans searched before in this step, and what they were found to be. A span's
/// points move no farther than its Bézier control points (each point is a convex combination
/// of them), so two spans found `d` apart stay more than the gap apart while the moves of
/// their control points add up to less than `d` less the gap. Two spans found near each
/// other about one or two places, and at least `e` apart everywhere else, touch nowhere else
/// while their moves add up to less than `e` less the gap, and come nearest about those
/// places while they add up to less than half of `e` less their distance: Newton steps from
/// those places find their nearest points then; measured there `c` farther apart than the
/// gap, they stay so while their moves add up to less than `c`, and take no Newton step
/// meanwhile. Each span's moves are added up whenever a
/// pair reads it (the largest of its four control points' moves since it was last read),
/// whatever moved it: the integrator, a collider, a push. It also keeps which pairs the
/// last pass of self-contact pushed apart, and where ([`pushes`](Self::pushes)). Lives on
/// the stack for one step:
/// `K` spans' control points and [`WAYS`] pairs a span, shared: a pair `(a, b)` is kept in
/// one of the `2·WAYS` places of rows `(a + b) mod K` and the next, so that the few spans a
/// pile heaps near many others do not each fill a row of their own.
pub(crate) struct PairMemory<P: Point, const K: usize> {
    /// Each span's control points when it was last read (`None`: not yet).
    anchors: [Option<[P; 4]>; K],
    /// How far each span's control points may have moved since the step began, at most.
    travel: [P::Scalar; K],
    /// Pairs of spans `a < b`, each in row `(a + b) mod K` or the next: what holds while
    /// `travel[a] + travel[b]` stays under `until`.
    pairs: [[Option<Pair<P::Scalar>>; WAYS]; K],
    /// Each span's `travel` when self-contact last ran.
    checked: [P::Scalar; K],
    /// Pairs of spans `a < b` that self-contact's last pass pushed apart, in row `a`, with
    /// the parameters of the points it pushed.
    pushed: [[Option<Pushed<P::Scalar>>; WAYS]; K],
}

/// A pair of spans `(a, b)` pushed apart at parameters `(u, v)`.
type Pushed<S> = ((u16, u16), (S, S));

/// Whether self-contact runs in a substep ([`PairMemory::due`]).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Due {
    /// Not: what the last pass pushed apart is held apart.
    Not,
    /// A step's first substep, whose pass finds what to hold apart until the next: a
    /// pass of a few rounds (the step's last settles what it leaves).
    First,
    /// A pass that settles the overlaps.
    Full,
}

/// What holds for a pair of spans while they have not moved `until`, and that they are
/// farther apart than the gap while they have not moved `clear`.
#[derive(Clone, Copy)]
struct Pair<S> {
    spans: (u16, u16),
    until: S,
    clear: S,
    /// The parameters of their nearest points, and of a second place where they come near,
    /// last found (`None`: apart).
    near: Option<Places<S>>,
}

/// The parameters `(u, v)` of the nearest points of two spans, and of a second place where
/// they come near.
pub(crate) type Places<S> = ((S, S), Option<(S, S)>);

/// What a pair of spans is known to be.
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Recall<S> {
    /// Nothing: search them.
    Unknown,
    /// Farther apart than the gap: nothing to do.
    Apart,
    /// Near each other only about these places: their nearest points are found from there.
    Near(Places<S>),
}

/// Substeps that must follow a step's first for self-contact to run in it too: fewer would
/// hold too little of the step apart to repay the pass (callgrind on the test's settled
/// 16-particle piles: under XPBD's 3 substeps 2% more instructions with 2; under symplectic
/// Euler's 7, 18% fewer).
const HELD: i16 = 3;

/// Pairs remembered a span, on average.
const WAYS: usize = 4;

impl<P: Point, const K: usize> PairMemory<P, K> {
    /// Nothing remembered.
    pub(crate) fn new() -> Self {
        PairMemory {
            anchors: [None; K],
            travel: [P::Scalar::ZERO; K],
            pairs: [[None; WAYS]; K],
            checked: [P::Scalar::ZERO; K],
            pushed: [[None; WAYS]; K],
        }
    }

    /// Whether self-contact is due now, at the end of a substep of `h` seconds `lag` seconds
    /// before the step's end, and how: [`Due::Full`] in the last substep and whenever a span
    /// of `curve` has moved an eighth of `gap` since self-contact last ran (two spans then
    /// cannot have closed more than a quarter of it, let alone passed through each other);
    /// else [`Due::First`] in the first when [`HELD`] substeps or more follow (nothing read
    /// yet: its pushes are held apart until the next pass, [`pushes`](Self::pushes)). Reads
    /// every span; a span that is neither a cubic nor straight makes it due.
    pub(crate) fn due(
        &mut self,
        curve: &impl DrawnSpans<P, K>,
        gap: P::Scalar,
        (h, lag): (P::Scalar, P::Scalar),
    ) -> Due {
        let first = self.anchors.iter().all(Option::is_none);
        let mut due = lag <= P::Scalar::ZERO;
        for span in 0..curve.span_count().min(K) {
            let Some(now) = controls(curve, span) else {
                return Due::Full;
            };
            self.read(span, now);
            due |= (self.travel[span] - self.checked[span]) * P::Scalar::from_i16(8) >= gap;
        }
        // Half a substep short of `HELD`: a substep count's time rounds either way.
        let held = h * (P::Scalar::from_i16(HELD) - P::Scalar::ratio(1, 2));
        match (due, first && lag >= held) {
            (true, _) => Due::Full,
            (false, true) => Due::First,
            (false, false) => Due::Not,
        }
    }

    /// Notes that self-contact has just run on `curve` (reads every span).
    pub(crate) fn checked(&mut self, curve: &impl DrawnSpans<P, K>) {
        for span in 0..curve.span_count().min(K) {
            if let Some(now) = controls(curve, span) {
                self.read(span, now);
            }
            self.checked[span] = self.travel[span];
        }
    }

    /// Adds up how far span `span` moved since it was last read, given its control points
    /// now.
    fn read(&mut self, span: usize, now: [P; 4]) {
        let Some(anchor) = self.anchors.get_mut(span) else {
            return;
        };
        if let Some(then) = anchor {
            let moved = then
                .iter()
                .zip(&now)
                .map(|(&a, &b)| (b - a).dot(b - a))
                .fold(P::Scalar::ZERO, P::Scalar::max);
            self.travel[span] += moved.sqrt();
        }
        *anchor = Some(now);
    }

    /// What is known of spans `a < b`, given their control points now (`None`: not a cubic,
    /// nothing known); reads both.
    pub(crate) fn recall(
        &mut self,
        (a, b): (usize, usize),
        cubics: (Option<[P; 4]>, Option<[P; 4]>),
    ) -> Recall<P::Scalar> {
        let (Some(ca), Some(cb)) = cubics else {
            return Recall::Unknown;
        };
        self.read(a, ca);
        self.read(b, cb);
        let (Some(moved), Some((row, k))) = (self.moved((a, b)), self.find((a, b))) else {
            return Recall::Unknown;
        };
        match self.pairs[row][k] {
            Some(p) if moved < p.clear => Recall::Apart,
            Some(p) if moved < p.until => p.near.map_or(Recall::Apart, Recall::Near),
            _ => Recall::Unknown,
        }
    }

    /// How far spans `a` and `b` have moved since the step began, together (`None` past the
    /// `K` spans).
    fn moved(&self, (a, b): (usize, usize)) -> Option<P::Scalar> {
        Some(*self.travel.get(a)? + *self.travel.get(b)?)
    }

    /// Where pair `(a, b)` is kept (its row and place), if it is.
    fn find(&self, (a, b): (usize, usize)) -> Option<(usize, usize)> {
        if a >= K || b >= K {
            return None;
        }
        let key = (u16::try_from(a).ok()?, u16::try_from(b).ok()?);
        self.rows((a, b)).into_iter().find_map(|row| {
            let k = self.pairs[row]
                .iter()
                .position(|p| p.is_some_and(|p| p.spans == key))?;
            Some((row, k))
        })
    }

    /// The two rows pair `(a, b)` may be kept in (both spans below `K`).
    fn rows(&self, (a, b): (usize, usize)) -> [usize; 2] {
        let row = (a + b) % K;
        [row, (row + 1) % K]
    }

    /// Remembers of spans `a < b` (both just read) that, `margin` over the gap they must
    /// keep, they are apart (`near` is `None`) or touch nowhere but about `near`'s places,
    /// where they are its clearance farther apart than the gap; nothing when `margin` is not
    /// positive (the pair is searched again next time). Replaces the pair's old entry, else
    /// a free one, else the one that expires first.
    pub(crate) fn remember(
        &mut self,
        (a, b): (usize, usize),
        margin: P::Scalar,
        near: Option<(Places<P::Scalar>, P::Scalar)>,
    ) {
        let (slot, moved) = (self.find((a, b)), self.moved((a, b)));
        let (Ok(first), Ok(second), Some(moved)) = (u16::try_from(a), u16::try_from(b), moved)
        else {
            return;
        };
        if margin <= P::Scalar::ZERO {
            if let Some((row, k)) = slot {
                self.pairs[row][k] = None;
            }
            return;
        }
        let until = moved + margin;
        let rows = self.rows((a, b));
        let places = || {
            rows.into_iter()
                .flat_map(|row| (0..WAYS).map(move |k| (row, k)))
        };
        let soonest = |(row, k): (usize, usize)| {
            self.pairs[row][k].map_or(P::Scalar::ZERO, |p: Pair<P::Scalar>| p.until)
        };
        let free = places().find(|&(row, k)| self.pairs[row][k].is_none());
        let (row, k) = slot.or(free).unwrap_or_else(|| {
            places().fold((rows[0], 0), |best, p| {
                if soonest(p) < soonest(best) { p } else { best }
            })
        });
        // Found apart, they stay so while their moves add up to less than the margin; found
        // near, less than their clearance.
        self.pairs[row][k] = Some(Pair {
            spans: (first, second),
            until,
            clear: near.map_or(until, |(_, clearance)| moved + clearance),
            near: near.map(|(places, _)| places),
        });
    }

    /// Forgets the pushes of self-contact's last pass (a new one begins).
    pub(crate) fn forget_pushes(&mut self) {
        self.pushed = [[None; WAYS]; K];
    }

    /// Notes that self-contact pushed spans `a < b` apart at parameters `at` (in their
    /// order): in place of the pair's last push, else in a free place of row `a`, else not
    /// at all.
    pub(crate) fn pushed_at(&mut self, (a, b): (usize, usize), at: (P::Scalar, P::Scalar)) {
        let (Some(row), Ok(first), Ok(second)) =
            (self.pushed.get_mut(a), u16::try_from(a), u16::try_from(b))
        else {
            return;
        };
        let key = (first, second);
        let slot = row
            .iter()
            .position(|p| p.is_some_and(|(spans, _)| spans == key))
            .or_else(|| row.iter().position(Option::is_none));
        if let Some(k) = slot {
            row[k] = Some((key, at));
        }
    }

    /// Whether self-contact's last pass pushed two spans apart: the step then runs its
    /// contacts at every substep, to hold them apart ([`pushes`](Self::pushes)).
    pub(crate) fn holds(&self) -> bool {
        self.pushes().next().is_some()
    }

    /// The pairs of spans `a < b` that self-contact's last pass pushed apart, each with the
    /// parameters of the points it pushed.
    pub(crate) fn pushes(&self) -> impl Iterator<Item = ((usize, usize), (P::Scalar, P::Scalar))> {
        self.pushed
            .iter()
            .flatten()
            .flatten()
            .map(|&((a, b), at)| ((usize::from(a), usize::from(b)), at))
    }

    /// Keeps the nearest points of spans `a < b` (both just read), found again from what
    /// [`recall`] gave, where they are `clearance` farther apart than the gap: nothing to
    /// search while their moves add up to less.
    ///
    /// [`recall`]: Self::recall
    pub(crate) fn moved_to(
        &mut self,
        (a, b): (usize, usize),
        (near, clearance): (Places<P::Scalar>, P::Scalar),
    ) {
        if let (Some(moved), Some((row, k))) = (self.moved((a, b)), self.find((a, b)))
            && let Some(p) = &mut self.pairs[row][k]
        {
            p.near = Some(near);
            p.clear = moved + clearance;
        }
    }
}

/// Points that span `span` of `curve` is a convex combination of: a cubic's control points, a
/// straight segment's ends (`None` for one Bézier through every particle).
fn controls<P: Point, const K: usize>(
    curve: &impl DrawnSpans<P, K>,
    span: usize,
) -> Option<[P; 4]> {
    if curve.is_straight() {
        let (a, b) = (
            curve.point(span, P::Scalar::ZERO),
            curve.point(span, P::Scalar::ONE),
        );
        return Some([a, b, b, b]);
    }
    curve.cubic(span)
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;

    fn span(x: f64) -> Option<[Vec2<f64>; 4]> {
        Some(core::array::from_fn(|k| Vec2::new(x + k as f64, 0.0)))
    }

    /// A pair held apart stays so until its spans' moves add up to its margin; a pair near
    /// but clear of the gap is held apart until they add up to its clearance, then
    /// followed; the ninth pair kept in the same two rows takes the place of the one that
    /// expires first; a margin that is not positive forgets the pair; a span that is no
    /// cubic is never known.
    #[test]
    fn pairs_are_held_until_their_spans_have_moved_their_margin() {
        let mut memory = PairMemory::<Vec2<f64>, 64>::new();
        // Pairs (a, 40 - a): all kept in rows 40 and 41.
        let pair = |a: usize| (a, 40 - a);
        let recall = |memory: &mut PairMemory<Vec2<f64>, 64>, a: usize, x: f64| {
            let (a, b) = pair(a);
            memory.recall((a, b), (span(x), span(b as f64)))
        };
        for a in 0..9 {
            let _ = recall(&mut memory, a, a as f64);
            memory.remember(pair(a), 0.1 * (a + 1) as f64, None);
        }
        // The pair (0, 40), which expired first, gave its place to (8, 32).
        assert!(recall(&mut memory, 0, 0.0) == Recall::Unknown);
        for a in 1..9 {
            assert!(recall(&mut memory, a, a as f64) == Recall::Apart);
        }
        // Span 2 moves 0.35 in two moves: the pairs with margins of 0.4 and over stay apart.
        let _ = recall(&mut memory, 2, 2.2);
        assert!(recall(&mut memory, 2, 2.35) == Recall::Unknown);
        assert!(recall(&mut memory, 3, 3.35) == Recall::Apart);
        memory.remember(pair(3), 0.0, None);
        assert!(recall(&mut memory, 3, 3.35) == Recall::Unknown);
        assert!(memory.recall((4, 36), (None, span(36.0))) == Recall::Unknown);
        // Near about a place, 0.2 clear of the gap, valid for moves of 0.5.
        let places = ((0.5, 0.5), None);
        let _ = recall(&mut memory, 5, 5.0);
        memory.remember(pair(5), 0.5, Some((places, 0.2)));
        assert!(recall(&mut memory, 5, 5.15) == Recall::Apart);
        assert!(recall(&mut memory, 5, 5.25) == Recall::Near(places));
        assert!(recall(&mut memory, 5, 5.55) == Recall::Unknown);
    }
}
