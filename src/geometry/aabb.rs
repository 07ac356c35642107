//! Axis-aligned bounding boxes: the cheap half of the convex hull property.

use crate::Point;

/// An axis-aligned box `min..=max`, used as a first-pass overlap test.
///
/// A Bézier curve or patch lies inside the box of its control points (convex hull
/// property), so two boxes that do not overlap prove the shapes do not touch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb<P> {
    /// Corner with the smallest coordinates.
    pub min: P,
    /// Corner with the largest coordinates.
    pub max: P,
}

impl<P: Point> Aabb<P> {
    /// The box of a single point.
    #[inline]
    pub fn point(p: P) -> Self {
        Aabb { min: p, max: p }
    }

    /// The smallest box around `points`, or `None` when the slice is empty. Cost: one
    /// compare per coordinate per point.
    pub fn from_points(points: &[P]) -> Option<Self> {
        let (first, rest) = points.split_first()?;
        Some(
            rest.iter()
                .fold(Aabb::point(*first), |b, &p| b.including(p)),
        )
    }

    /// This box grown to contain `p`.
    #[inline]
    pub fn including(self, p: P) -> Self {
        Aabb {
            min: self.min.min_coords(p),
            max: self.max.max_coords(p),
        }
    }

    /// The smallest box containing both.
    #[inline]
    pub fn union(self, other: Self) -> Self {
        Aabb {
            min: self.min.min_coords(other.min),
            max: self.max.max_coords(other.max),
        }
    }

    /// This box grown by `r` on every side.
    #[inline]
    pub(crate) fn grown(self, r: P::Scalar) -> Self {
        Aabb {
            min: self.min - P::splat(r),
            max: self.max + P::splat(r),
        }
    }

    /// This box grown on each axis by `by`'s size along it: it holds the box moved by
    /// any multiple of `by` from -1 to 1.
    #[inline]
    pub(crate) fn swept(self, by: P) -> Self {
        let size = by.max_coords(-by);
        Aabb {
            min: self.min - size,
            max: self.max + size,
        }
    }

    /// This box moved by `offset`.
    #[inline]
    pub(crate) fn moved(self, offset: P) -> Self {
        Aabb {
            min: self.min + offset,
            max: self.max + offset,
        }
    }

    /// `true` when `p` is inside or on the boundary.
    pub fn contains(&self, p: P) -> bool {
        (0..P::DIM).all(|d| self.min.coord(d) <= p.coord(d) && p.coord(d) <= self.max.coord(d))
    }

    /// `true` when the boxes share at least one point.
    pub fn overlaps(&self, other: &Self) -> bool {
        (0..P::DIM).all(|d| {
            self.min.coord(d) <= other.max.coord(d) && other.min.coord(d) <= self.max.coord(d)
        })
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec2;

    #[test]
    fn from_points_contains_and_overlaps() {
        let b = Aabb::from_points(&[Vec2::new(1.0f32, 5.0), Vec2::new(-2.0, 3.0)]).unwrap();
        assert_eq!(b.min, Vec2::new(-2.0, 3.0));
        assert_eq!(b.max, Vec2::new(1.0, 5.0));
        assert!(b.contains(Vec2::new(0.0, 4.0)));
        assert!(!b.contains(Vec2::new(0.0, 6.0)));
        let far = Aabb::point(Vec2::new(10.0f32, 10.0));
        assert!(!b.overlaps(&far));
        assert!(b.union(far).contains(Vec2::new(5.0, 5.0)));
        assert_eq!(Aabb::<Vec2<f32>>::from_points(&[]), None);
    }
}
