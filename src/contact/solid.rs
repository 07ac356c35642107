//! The solid shapes of [`Collider`](super::collider::Collider)s: their boxes, and the signed
//! distance and outward normal of a point from each.

use super::collider::MAX_VERTICES;
use crate::{Aabb, Point, Scalar};

/// The solid shape of a collider.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Solid<P: Point> {
    Ball {
        center: P,
        radius: P::Scalar,
    },
    Capsule {
        a: P,
        /// Unit direction from `a` to the other end.
        dir: P,
        length: P::Scalar,
        radius: P::Scalar,
    },
    HalfSpace {
        point: P,
        normal: P,
    },
    Box(Aabb<P>),
    /// Counter-clockwise corners and their edges' outward unit normals (2D only).
    Polygon {
        corners: [P; MAX_VERTICES],
        normals: [P; MAX_VERTICES],
        count: u8,
    },
}

impl<P: Point> Solid<P> {
    /// A box holding the solid (see [`Collider::bounds`]).
    pub(super) fn bounds(&self) -> Aabb<P> {
        match self {
            Solid::Ball { center, radius } => Aabb::point(*center).grown(*radius),
            Solid::Capsule {
                a,
                dir,
                length,
                radius,
            } => Aabb::point(*a)
                .including(*a + *dir * *length)
                .grown(*radius),
            Solid::HalfSpace { .. } => Aabb {
                min: P::splat(-P::Scalar::SAFE_RANGE),
                max: P::splat(P::Scalar::SAFE_RANGE),
            },
            Solid::Box(b) => *b,
            Solid::Polygon { corners, count, .. } => {
                Aabb::from_points(&corners[..usize::from(*count)])
                    .unwrap_or(Aabb::point(P::default()))
            }
        }
    }
}

/// `|v|` and `v / |v|` from one square root (`None` when `v` is too short to have a
/// direction in the format).
#[inline]
pub(super) fn length_and_unit<P: Point>(v: P) -> (P::Scalar, Option<P>) {
    let len = v.length();
    let dir =
        (len > P::Scalar::EPSILON * P::Scalar::from_i16(16)).then(|| v * (P::Scalar::ONE / len));
    (len, dir)
}

/// The first axis, the normal used where a point sits exactly on a ball's centre.
pub(super) fn first_axis<P: Point>() -> P {
    let mut up = P::default();
    up.set_coord(1, P::Scalar::ONE);
    up
}

/// Signed distance from a ball of `radius` around `centre`.
#[inline]
pub(super) fn from_centre<P: Point>(p: P, centre: P, radius: P::Scalar) -> (P::Scalar, P) {
    match length_and_unit(p - centre) {
        (len, Some(n)) => (len - radius, n),
        (_, None) => (-radius, first_axis()),
    }
}

/// How deep `p`, inside `b`, is: its distance to the nearest face.
pub(super) fn inside_box<P: Point>(b: &Aabb<P>, p: P) -> P::Scalar {
    (0..P::DIM).fold(P::Scalar::SAFE_RANGE, |least, d| {
        least
            .min(p.coord(d) - b.min.coord(d))
            .min(b.max.coord(d) - p.coord(d))
    })
}

/// Signed distance from box `b` (negative inside) and the outward normal.
pub(super) fn box_distance<P: Point>(b: &Aabb<P>, p: P) -> (P::Scalar, P) {
    let clamped = p.max_coords(b.min).min_coords(b.max);
    if let (len, Some(n)) = length_and_unit(p - clamped) {
        return (len, n);
    }
    // Inside (or on the surface): out through the nearest face.
    let mut best = (P::Scalar::SAFE_RANGE, first_axis::<P>());
    for d in 0..P::DIM {
        for (gap, sign) in [
            (p.coord(d) - b.min.coord(d), -P::Scalar::ONE),
            (b.max.coord(d) - p.coord(d), P::Scalar::ONE),
        ] {
            if gap < best.0 {
                let mut n = P::default();
                n.set_coord(d, sign);
                best = (gap, n);
            }
        }
    }
    (-best.0, best.1)
}

/// Signed distance from the convex polygon of `corners` and their edges' outward unit
/// `normals` (negative inside), and the outward normal.
pub(super) fn polygon_distance<P: Point>(corners: &[P], normals: &[P], p: P) -> (P::Scalar, P) {
    let count = corners.len();
    // Inside when every edge has `p` behind it: the least-deep edge is the way out.
    let mut deepest = (-P::Scalar::SAFE_RANGE, first_axis::<P>());
    for (c, n) in corners.iter().zip(normals) {
        let s = (p - *c).dot(*n);
        if s > deepest.0 {
            deepest = (s, *n);
        }
    }
    if deepest.0 <= P::Scalar::ZERO {
        return deepest;
    }
    // Outside: the nearest point of the boundary.
    let mut nearest = (P::Scalar::SAFE_RANGE, first_axis::<P>());
    for i in 0..count {
        let (a, b) = (corners[i], corners[(i + 1) % count]);
        let q = match length_and_unit(b - a) {
            (len, Some(dir)) => a + dir * (p - a).dot(dir).max(P::Scalar::ZERO).min(len),
            (_, None) => a,
        };
        let (d, dir) = length_and_unit(p - q);
        if d < nearest.0 {
            nearest = (d, dir.unwrap_or(normals[i]));
        }
    }
    nearest
}
