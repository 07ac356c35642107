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
/// those places find their nearest points then. Each span's moves are added up whenever a
/// pair reads it (the largest of its four control points' moves since it was last read),
/// whatever moved it: the integrator, a collider, a push. Lives on the stack for one step:
/// `K` spans' control points and [`WAYS`] pairs a span.
pub(crate) struct PairMemory<P: Point, const K: usize> {
    /// Each span's control points when it was last read (`None`: not yet).
    anchors: [Option<[P; 4]>; K],
    /// How far each span's control points may have moved since the step began, at most.
    travel: [P::Scalar; K],
    /// For span `a`, pairs with a later span `b`: what holds while `travel[a] + travel[b]`
    /// stays under `until`.
    pairs: [[Option<Pair<P::Scalar>>; WAYS]; K],
    /// Each span's `travel` when self-contact last ran.
    checked: [P::Scalar; K],
}

/// What holds for a pair of spans while they have not moved `until`.
#[derive(Clone, Copy)]
struct Pair<S> {
    other: u16,
    until: S,
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

/// Pairs remembered for each span (with the spans after it).
const WAYS: usize = 4;

impl<P: Point, const K: usize> PairMemory<P, K> {
    /// Nothing remembered.
    pub(crate) fn new() -> Self {
        PairMemory {
            anchors: [None; K],
            travel: [P::Scalar::ZERO; K],
            pairs: [[None; WAYS]; K],
            checked: [P::Scalar::ZERO; K],
        }
    }

    /// Whether self-contact is due now, in a substep of a step (`last`: its last substep):
    /// in the last, and whenever a span of `curve` has moved an eighth of `gap` since
    /// self-contact last ran (two spans then cannot have closed more than a quarter of it,
    /// let alone passed through each other). Reads every span; a span that is neither a
    /// cubic nor straight makes it due.
    pub(crate) fn due(
        &mut self,
        curve: &impl DrawnSpans<P, K>,
        gap: P::Scalar,
        last: bool,
    ) -> bool {
        let mut due = last;
        for span in 0..curve.span_count().min(K) {
            let Some(now) = controls(curve, span) else {
                return true;
            };
            self.read(span, now);
            due |= (self.travel[span] - self.checked[span]) * P::Scalar::from_i16(8) >= gap;
        }
        due
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
        let (Some(moved), Some(k)) = (self.moved((a, b)), self.find((a, b))) else {
            return Recall::Unknown;
        };
        match self.pairs[a][k] {
            Some(p) if moved < p.until => p.near.map_or(Recall::Apart, Recall::Near),
            _ => Recall::Unknown,
        }
    }

    /// How far spans `a` and `b` have moved since the step began, together (`None` past the
    /// `K` spans).
    fn moved(&self, (a, b): (usize, usize)) -> Option<P::Scalar> {
        Some(*self.travel.get(a)? + *self.travel.get(b)?)
    }

    /// Where pair `(a, b)` is kept in span `a`'s row, if it is.
    fn find(&self, (a, b): (usize, usize)) -> Option<usize> {
        let row = self.pairs.get(a)?;
        row.iter()
            .position(|p| p.is_some_and(|p| usize::from(p.other) == b))
    }

    /// Remembers of spans `a < b` (both just read) that, `margin` over the gap they must
    /// keep, they are apart (`near` is `None`) or touch nowhere but about `near`; nothing
    /// when `margin` is not positive (the pair is searched again next time). Replaces the
    /// pair's old entry, else a free one, else the one that expires first.
    pub(crate) fn remember(
        &mut self,
        (a, b): (usize, usize),
        margin: P::Scalar,
        near: Option<Places<P::Scalar>>,
    ) {
        let (slot, moved) = (self.find((a, b)), self.moved((a, b)));
        let (Some(row), Ok(other), Some(moved)) = (self.pairs.get_mut(a), u16::try_from(b), moved)
        else {
            return;
        };
        if margin <= P::Scalar::ZERO {
            if let Some(k) = slot {
                row[k] = None;
            }
            return;
        }
        let until = moved + margin;
        let soonest = |k: usize| row[k].map_or(P::Scalar::ZERO, |p| p.until);
        let k = slot
            .or_else(|| row.iter().position(Option::is_none))
            .unwrap_or_else(|| {
                (1..WAYS).fold(
                    0,
                    |best, k| if soonest(k) < soonest(best) { k } else { best },
                )
            });
        row[k] = Some(Pair { other, until, near });
    }

    /// Keeps the nearest points of spans `a < b`, found again from what [`recall`] gave.
    ///
    /// [`recall`]: Self::recall
    pub(crate) fn moved_to(&mut self, (a, b): (usize, usize), near: Places<P::Scalar>) {
        if let Some(k) = self.find((a, b))
            && let Some(Some(p)) = self.pairs.get_mut(a).map(|row| &mut row[k])
        {
            p.near = Some(near);
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

    /// A pair held apart stays so until its spans' moves add up to its margin; a span's
    /// fifth pair takes the place of the one that expires first; a margin that is not
    /// positive forgets the pair; a span that is no cubic is never known.
    #[test]
    fn pairs_are_held_until_their_spans_have_moved_their_margin() {
        let mut memory = PairMemory::<Vec2<f64>, 8>::new();
        for b in 2..7 {
            let _ = memory.recall((0, b), (span(0.0), span(b as f64)));
            memory.remember((0, b), 0.1 * b as f64, None);
        }
        // The pair (0, 2), which expired first, gave its place to (0, 6).
        assert!(memory.recall((0, 2), (span(0.0), span(2.0))) == Recall::Unknown);
        for b in 3..7 {
            assert!(memory.recall((0, b), (span(0.0), span(b as f64))) == Recall::Apart);
        }
        // Span 0 moves 0.35 in two moves: the pairs with margins of 0.4 and over stay apart.
        let _ = memory.recall((0, 3), (span(0.2), span(3.0)));
        assert!(memory.recall((0, 3), (span(0.35), span(3.0))) == Recall::Unknown);
        assert!(memory.recall((0, 4), (span(0.35), span(4.0))) == Recall::Apart);
        memory.remember((0, 4), 0.0, None);
        assert!(memory.recall((0, 4), (span(0.35), span(4.0))) == Recall::Unknown);
        assert!(memory.recall((0, 5), (None, span(5.0))) == Recall::Unknown);
    }
}
