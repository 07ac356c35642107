//! Line segments in the plane: where two cross (a swipe across a rope's drawn curve or a
//! cloth's springs).

use crate::{Scalar, Vec2};

/// Where segment `a`–`b` crosses segment `c`–`d`: the fractions along each (`0..=1`), or
/// `None` when they miss or are parallel. Differences are scaled so that the largest is at
/// most 64 before any product, so `Q16` neither saturates nor loses the signs.
pub(crate) fn crossing<S: Scalar>(
    a: Vec2<S>,
    b: Vec2<S>,
    c: Vec2<S>,
    d: Vec2<S>,
) -> Option<(S, S)> {
    // Boxes first: most segments miss a swipe by a mile, and comparisons are cheap where
    // multiplications are not (Q16 on a Cortex-M0).
    let apart = |p: S, q: S, r: S, t: S| p.max(q) < r.min(t) || r.max(t) < p.min(q);
    if apart(a.x, b.x, c.x, d.x) || apart(a.y, b.y, c.y, d.y) {
        return None;
    }
    let (ab, cd, ca, cb) = (b - a, d - c, a - c, b - c);
    let largest = [ab, cd, ca, cb]
        .iter()
        .flat_map(|v| [v.x.abs(), v.y.abs()])
        .fold(S::ZERO, S::max);
    let limit = S::from_i16(64);
    let scale = if largest > limit {
        limit / largest
    } else {
        S::ONE
    };
    let (ab, cd, ca, cb) = (ab * scale, cd * scale, ca * scale, cb * scale);
    // Sides of a and b against the swipe's line, and of c and d against ab's.
    let (side_a, side_b) = (cd.cross(ca), cd.cross(cb));
    let ac = -ca;
    let side_c = ab.cross(ac);
    let side_d = ab.cross(ac + cd);
    let zero = S::ZERO;
    let opposite = |p: S, q: S| (p <= zero && q >= zero) || (p >= zero && q <= zero);
    if !opposite(side_a, side_b) || !opposite(side_c, side_d) || side_a == side_b {
        return None;
    }
    let along = side_a / (side_a - side_b);
    let across = if side_c == side_d {
        zero
    } else {
        side_c / (side_c - side_d)
    };
    Some((along.max(zero).min(S::ONE), across.max(zero).min(S::ONE)))
}
