//! Colliders: the solid things of a scene that ropes and sails touch.
//!
//! A [`Collider`] is a ball (a circle in 2D, a sphere in 3D), a capsule, a half-space (a
//! half-plane in 2D, a plane's solid side in 3D), an axis-aligned box or, in 2D, a convex
//! polygon of up to [`MAX_VERTICES`] corners. It is static, or kinematic: the game moves it
//! between frames and gives it a velocity, so a bat or a platform pushes what it touches. Its
//! surface has Coulomb friction (static and kinetic) and a restitution. The game owns its
//! colliders, in a slice or an array; nothing is allocated.
//!
//! Every query is [`Collider::distance`]: the signed distance from the surface (negative
//! inside) and the outward unit normal. Cost: a square root for a ball, capsule or box from
//! outside, none for a half-space, one per edge for a polygon.
//!
//! ```
//! use dunas::{Vec2, collider::Collider};
//! let peg = Collider::ball(Vec2::new(0.0f32, 0.0), 1.0)?;
//! let (d, n) = peg.distance(Vec2::new(3.0, 0.0));
//! assert_eq!((d, n), (2.0, Vec2::new(1.0, 0.0)));
//! assert!(Collider::ball(Vec2::new(0.0f32, 0.0), -1.0).is_err());
//! # Ok::<(), dunas::Error>(())
//! ```

use super::solid::{
    Solid, box_distance, first_axis, from_centre, inside_box, length_and_unit, polygon_distance,
};
use crate::error::{check_non_negative, check_points, check_positive};
use crate::error::{invalid, out_of_range};
use crate::physics::hash::StateHash;
use crate::{Aabb, Error, Point, Scalar, Vec2};

/// Most corners of a [`Collider::polygon`].
pub const MAX_VERTICES: usize = 8;

/// A solid shape with its motion and surface. Build it with [`ball`](Self::ball),
/// [`capsule`](Self::capsule), [`half_space`](Self::half_space), [`aabb`](Self::aabb) or
/// [`polygon`](Self::polygon); every constructor checks its input, so a built collider
/// answers every query with finite values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collider<P: Point> {
    solid: Solid<P>,
    /// The solid's box, kept with it ([`bounds`](Self::bounds)).
    bounds: Aabb<P>,
    velocity: P,
    static_friction: P::Scalar,
    kinetic_friction: P::Scalar,
    restitution: P::Scalar,
    /// 1 / the body's mass; 0 for a kinematic collider (infinitely heavy).
    inv_mass: P::Scalar,
}

/// `v / |v|`, or `None` when `v` is too short to have a direction in the format.
#[inline]
pub(crate) fn unit<P: Point>(v: P) -> Option<P> {
    length_and_unit(v).1
}

/// Checks a radius: finite, not negative, inside the safe range.
fn check_radius<S: Scalar>(r: S) -> Result<S, Error> {
    check_non_negative(r, "radius")?;
    if r > S::SAFE_RANGE {
        return Err(out_of_range::<S>("radius"));
    }
    Ok(r)
}

impl<P: Point> Collider<P> {
    fn new(solid: Solid<P>) -> Self {
        Collider {
            solid,
            bounds: solid.bounds(),
            velocity: P::default(),
            static_friction: P::Scalar::ZERO,
            kinetic_friction: P::Scalar::ZERO,
            restitution: P::Scalar::ZERO,
            inv_mass: P::Scalar::ZERO,
        }
    }

    /// A ball: a circle in 2D, a sphere in 3D.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a bad centre;
    /// [`Error::InvalidParameter`] for a negative, NaN or infinite radius,
    /// [`Error::OutOfRange`] for one beyond [`Scalar::SAFE_RANGE`].
    pub fn ball(center: P, radius: P::Scalar) -> Result<Self, Error> {
        check_points(&[center], "center")?;
        let radius = check_radius(radius)?;
        Ok(Self::new(Solid::Ball { center, radius }))
    }

    /// A capsule: the points within `radius` of the segment `a`–`b` (a ball when `a = b`).
    ///
    /// # Errors
    /// As [`ball`](Self::ball), for both ends.
    pub fn capsule(a: P, b: P, radius: P::Scalar) -> Result<Self, Error> {
        check_points(&[a, b], "a or b")?;
        let radius = check_radius(radius)?;
        let (length, dir) = length_and_unit(b - a);
        let dir = dir.unwrap_or_else(first_axis);
        Ok(Self::new(Solid::Capsule {
            a,
            dir,
            length,
            radius,
        }))
    }

    /// The solid side of the plane through `point` with outward normal `normal` (the side
    /// the normal points away from): the ground, a wall.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a bad point or normal;
    /// [`Error::InvalidParameter`] for a normal too short to have a direction.
    pub fn half_space(point: P, normal: P) -> Result<Self, Error> {
        check_points(&[point, normal], "point or normal")?;
        let normal = unit(normal).ok_or(invalid("normal", "long enough to have a direction"))?;
        Ok(Self::new(Solid::HalfSpace { point, normal }))
    }

    /// An axis-aligned box from `min` to `max` (a crate, a platform).
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a bad corner;
    /// [`Error::InvalidParameter`] when a coordinate of `min` is above that of `max`.
    pub fn aabb(min: P, max: P) -> Result<Self, Error> {
        check_points(&[min, max], "min or max")?;
        if (0..P::DIM).any(|d| min.coord(d) > max.coord(d)) {
            return Err(invalid("min", "at most max in every coordinate"));
        }
        Ok(Self::new(Solid::Box(Aabb { min, max })))
    }

    /// The same collider moving at `velocity` (units per second): the speed at which the game
    /// moves it. Contacts push with it and rub against it; [`advance`](Self::advance) moves it.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a bad velocity.
    pub fn moving(mut self, velocity: P) -> Result<Self, Error> {
        check_points(&[velocity], "velocity")?;
        self.velocity = velocity;
        Ok(self)
    }

    /// The same collider with Coulomb friction coefficients: `static_friction` holds a
    /// contact still while the tangential push stays within it times the normal push,
    /// `kinetic_friction` brakes a sliding one. Both default to 0 (ice).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a negative or non-finite coefficient, or a kinetic one
    /// above the static one.
    pub fn with_friction(
        mut self,
        static_friction: P::Scalar,
        kinetic_friction: P::Scalar,
    ) -> Result<Self, Error> {
        check_non_negative(static_friction, "static friction")?;
        check_non_negative(kinetic_friction, "kinetic friction")?;
        if kinetic_friction > static_friction {
            return Err(invalid("kinetic friction", "at most the static friction"));
        }
        (self.static_friction, self.kinetic_friction) = (static_friction, kinetic_friction);
        Ok(self)
    }

    /// The same collider with a restitution in `0..=1`: the share of the normal speed a hit
    /// gives back (0, the default, stops it; 1 bounces it back at full speed).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] outside `0..=1` or NaN.
    pub fn with_restitution(mut self, restitution: P::Scalar) -> Result<Self, Error> {
        if !(restitution >= P::Scalar::ZERO && restitution <= P::Scalar::ONE) {
            return Err(invalid("restitution", "in 0..=1"));
        }
        self.restitution = restitution;
        Ok(self)
    }

    /// The same collider as a free body of `mass`, for two-way coupling: when its
    /// [`Push`](crate::contact::Push) is reported
    /// ([`Contacts::with_pushes`](crate::contact::Contacts::with_pushes)), each contact is
    /// resolved between the rope or cloth and a body of this mass, which takes its share of
    /// every push at once. Without a report it stays kinematic (infinitely heavy).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a mass that is not finite and positive, or whose
    /// inverse or itself is beyond the safe range (`Q16`: masses from 1/16 383 to 16 383).
    pub fn with_mass(mut self, mass: P::Scalar) -> Result<Self, Error> {
        const EXPECTED: &str = "finite and > 0, it and its inverse within the safe range";
        let inv_mass = P::Scalar::ONE / check_positive(mass, "mass")?;
        if !(mass.in_safe_range() && inv_mass.in_safe_range() && inv_mass > P::Scalar::ZERO) {
            return Err(invalid("mass", EXPECTED));
        }
        self.inv_mass = inv_mass;
        Ok(self)
    }

    /// 1 / the mass given by [`with_mass`](Self::with_mass); 0 for a kinematic collider.
    #[inline]
    pub fn inv_mass(&self) -> P::Scalar {
        self.inv_mass
    }

    /// The velocity given by [`moving`](Self::moving).
    #[inline]
    pub fn velocity(&self) -> P {
        self.velocity
    }

    /// `(static, kinetic)` friction coefficients.
    #[inline]
    pub fn friction(&self) -> (P::Scalar, P::Scalar) {
        (self.static_friction, self.kinetic_friction)
    }

    /// The restitution.
    #[inline]
    pub fn restitution(&self) -> P::Scalar {
        self.restitution
    }

    /// Moves the collider by `offset`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] when the offset or the moved shape leaves
    /// the safe range; the collider is then unchanged.
    pub fn translate(&mut self, offset: P) -> Result<(), Error> {
        check_points(&[offset], "offset")?;
        let mut moved = self.solid;
        match &mut moved {
            Solid::Ball { center: p, .. }
            | Solid::Capsule { a: p, .. }
            | Solid::HalfSpace { point: p, .. } => {
                *p += offset;
                check_points(&[*p], "moved collider")?;
            }
            Solid::Box(b) => {
                (b.min, b.max) = (b.min + offset, b.max + offset);
                check_points(&[b.min, b.max], "min or max")?;
            }
            Solid::Polygon { corners, count, .. } => {
                for c in &mut corners[..usize::from(*count)] {
                    *c += offset;
                }
                check_points(&corners[..usize::from(*count)], "moved corner")?;
            }
        }
        if let Solid::Capsule { a, dir, length, .. } = moved {
            check_points(&[a + dir * length], "moved capsule end")?;
        }
        self.solid = moved;
        self.bounds = moved.bounds();
        Ok(())
    }

    /// Moves the collider by its velocity for `dt` seconds: call it once a frame for a
    /// kinematic collider.
    ///
    /// # Errors
    /// As [`translate`](Self::translate); [`Error::InvalidParameter`] for a negative or
    /// non-finite `dt`.
    pub fn advance(&mut self, dt: P::Scalar) -> Result<(), Error> {
        check_non_negative(dt, "dt")?;
        self.translate(self.velocity * dt)
    }

    /// Signed distance from `p` to the surface (negative inside) and the outward unit normal
    /// at the nearest surface point. Total: finite for every finite `p` in the safe range.
    pub fn distance(&self, p: P) -> (P::Scalar, P) {
        let zero = P::Scalar::ZERO;
        match &self.solid {
            Solid::Ball { center, radius } => from_centre(p, *center, *radius),
            Solid::Capsule {
                a,
                dir,
                length,
                radius,
            } => {
                let along = (p - *a).dot(*dir).max(zero).min(*length);
                from_centre(p, *a + *dir * along, *radius)
            }
            Solid::HalfSpace { point, normal } => ((p - *point).dot(*normal), *normal),
            Solid::Box(b) => box_distance(b, p),
            Solid::Polygon {
                corners,
                normals,
                count,
            } => polygon_distance(
                &corners[..usize::from(*count)],
                &normals[..usize::from(*count)],
                p,
            ),
        }
    }

    /// The signed distance of [`distance`](Self::distance) without the normal: a square root
    /// at most and no division for a ball, a capsule or a half-space (what a search for the
    /// deepest point calls many times).
    pub fn gap(&self, p: P) -> P::Scalar {
        match &self.solid {
            Solid::Ball { center, radius } => (p - *center).length() - *radius,
            Solid::Capsule {
                a,
                dir,
                length,
                radius,
            } => {
                let along = (p - *a).dot(*dir).max(P::Scalar::ZERO).min(*length);
                (p - (*a + *dir * along)).length() - *radius
            }
            Solid::HalfSpace { point, normal } => (p - *point).dot(*normal),
            Solid::Box(_) | Solid::Polygon { .. } => self.distance(p).0,
        }
    }

    /// A ball's centre (its surface's nearest point to any point lies towards it); `None`
    /// for other solids.
    pub(crate) fn centre(&self) -> Option<P> {
        self.as_ball().map(|(centre, _)| centre)
    }

    /// A ball's centre and radius; `None` for other solids.
    pub(crate) fn as_ball(&self) -> Option<(P, P::Scalar)> {
        match &self.solid {
            Solid::Ball { center, radius } => Some((*center, *radius)),
            _ => None,
        }
    }

    /// A half-space's outward unit normal (its gap grows along it); `None` for other solids.
    pub(crate) fn outward(&self) -> Option<P> {
        match &self.solid {
            Solid::HalfSpace { normal, .. } => Some(*normal),
            _ => None,
        }
    }

    /// A number that orders points near the solid as [`gap`](Self::gap) does, with no square
    /// root: the squared distance to a ball's centre or a capsule's axis, times `scale²`; a
    /// box's squared distance times `scale²` outside it and its depth, negated, inside; else
    /// the gap. `scale` (from [`key_scale`](Self::key_scale)) keeps the square inside `Q16`.
    pub(crate) fn search_key(&self, p: P, scale: P::Scalar) -> P::Scalar {
        let off = match &self.solid {
            Solid::Ball { center, .. } => p - *center,
            Solid::Capsule { a, dir, length, .. } => {
                let along = (p - *a).dot(*dir).max(P::Scalar::ZERO).min(*length);
                p - (*a + *dir * along)
            }
            Solid::Box(b) => {
                let off = p - p.max_coords(b.min).min_coords(b.max);
                if off == P::default() {
                    return -inside_box(b, p);
                }
                off
            }
            _ => return self.gap(p),
        };
        let off = if scale == P::Scalar::ONE {
            off
        } else {
            off * scale
        };
        off.dot(off)
    }

    /// The scale for [`search_key`](Self::search_key) over points whose gap is at most
    /// `gap`: 1 in floats; in fixed point a power of two that keeps the scaled distance to
    /// the centre or axis under 128, so that its square does not saturate, and for a box the
    /// largest such power up to 1 024, so that a small distance's square keeps its
    /// resolution.
    pub(crate) fn key_scale(&self, gap: P::Scalar) -> P::Scalar {
        let radius = match &self.solid {
            Solid::Ball { radius, .. } | Solid::Capsule { radius, .. } => *radius,
            Solid::Box(_) => P::Scalar::ZERO,
            _ => return P::Scalar::ONE,
        };
        let (mut reach, mut scale) = (gap.max(P::Scalar::ZERO) + radius, P::Scalar::ONE);
        if P::Scalar::FIXED_POINT {
            let (limit, half) = (P::Scalar::from_i16(128), P::Scalar::ratio(1, 2));
            while reach >= limit {
                (reach, scale) = (reach * half, scale * half);
            }
            if matches!(self.solid, Solid::Box(_)) {
                let (double, most) = (P::Scalar::from_i16(2), P::Scalar::from_i16(1024));
                while reach * double < limit && scale < most {
                    (reach, scale) = (reach * double, scale * double);
                }
            }
        }
        scale
    }

    /// How deep a point can go into the solid and still have the surface it came in by
    /// nearest, at least: a ball's or capsule's radius, a box's least half side, a polygon's
    /// distance from its corners' mean to its nearest edge, the safe range for a half-space
    /// (it has no far side). A point that moves less than this past the surface in a substep
    /// is pushed back out the way it came.
    pub(crate) fn depth(&self) -> P::Scalar {
        let half = P::Scalar::ratio(1, 2);
        match &self.solid {
            Solid::Ball { radius, .. } | Solid::Capsule { radius, .. } => *radius,
            Solid::HalfSpace { .. } => P::Scalar::SAFE_RANGE,
            Solid::Box(b) => (0..P::DIM)
                .map(|d| (b.max.coord(d) - b.min.coord(d)) * half)
                .fold(P::Scalar::SAFE_RANGE, P::Scalar::min),
            Solid::Polygon {
                corners,
                normals,
                count,
            } => {
                let n = usize::from(*count);
                let sum = corners[..n].iter().fold(P::default(), |s, &c| s + c);
                let mean = sum * (P::Scalar::ONE / P::Scalar::from_i16(n as i16));
                corners[..n]
                    .iter()
                    .zip(&normals[..n])
                    .map(|(&c, &normal)| (c - mean).dot(normal).max(P::Scalar::ZERO))
                    .fold(P::Scalar::SAFE_RANGE, P::Scalar::min)
            }
        }
    }

    /// Adds everything that defines it to `key`: its solid, velocity, friction, restitution
    /// and mass.
    pub(crate) fn hash(&self, key: &mut StateHash) {
        let mut points = |points: &[P], scalars: &[P::Scalar]| {
            points.iter().for_each(|&p| key.add_point(p));
            scalars.iter().for_each(|&x| key.add_scalar(x));
        };
        match &self.solid {
            Solid::Ball { center, radius } => points(&[*center], &[*radius]),
            Solid::Capsule {
                a,
                dir,
                length,
                radius,
            } => points(&[*a, *dir], &[*length, *radius]),
            Solid::HalfSpace { point, normal } => points(&[*point, *normal], &[]),
            Solid::Box(b) => points(&[b.min, b.max], &[]),
            Solid::Polygon { corners, count, .. } => points(&corners[..usize::from(*count)], &[]),
        }
        points(
            &[self.velocity],
            &[
                self.static_friction,
                self.kinetic_friction,
                self.restitution,
                self.inv_mass,
            ],
        );
    }

    /// A box holding the solid (the half-space's is the whole safe range): the broad phase.
    /// Kept with the solid: a load.
    #[inline]
    pub fn bounds(&self) -> Aabb<P> {
        self.bounds
    }
}

impl<S: Scalar> Collider<Vec2<S>> {
    /// A convex polygon through 3 to [`MAX_VERTICES`] corners, in either winding.
    ///
    /// ```
    /// use dunas::{Vec2, collider::Collider};
    /// let ramp = Collider::polygon(&[Vec2::new(0.0f32, 0.0), Vec2::new(4.0, 0.0), Vec2::new(0.0, 2.0)])?;
    /// assert!(ramp.distance(Vec2::new(1.0, 0.5)).0 < 0.0);
    /// # Ok::<(), dunas::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] / [`Error::OutOfRange`] for a bad corner;
    /// [`Error::CapacityExceeded`] past [`MAX_VERTICES`]; [`Error::InvalidParameter`] for fewer
    /// than 3 corners, a zero-length edge, or corners that do not turn one way (non-convex,
    /// or all on a line).
    pub fn polygon(corners: &[Vec2<S>]) -> Result<Self, Error> {
        check_points(corners, "corners")?;
        let count = corners.len();
        if count > MAX_VERTICES {
            return Err(Error::CapacityExceeded {
                capacity: MAX_VERTICES,
            });
        }
        if count < 3 {
            return Err(invalid("polygon", "at least 3 distinct corners"));
        }
        let edge = |i: usize| corners[(i + 1) % count] - corners[i % count];
        // Convex: every turn has the sign of the first non-zero one; a line has none.
        let turns = (0..count).map(|i| edge(i).cross(edge(i + 1)));
        let (mut left, mut right) = (false, false);
        for t in turns {
            left |= t > S::ZERO;
            right |= t < S::ZERO;
        }
        if left == right {
            return Err(invalid(
                "polygon",
                "convex, its corners not all on one line",
            ));
        }
        let mut ordered = [Vec2::default(); MAX_VERTICES];
        for (i, o) in ordered.iter_mut().take(count).enumerate() {
            *o = if left {
                corners[i]
            } else {
                corners[count - 1 - i]
            };
        }
        let mut normals = [Vec2::default(); MAX_VERTICES];
        for i in 0..count {
            let e = ordered[(i + 1) % count] - ordered[i];
            normals[i] = unit(Vec2::new(e.y, -e.x))
                .ok_or(invalid("polygon edge", "long enough to have a direction"))?;
        }
        Ok(Self::new(Solid::Polygon {
            corners: ordered,
            normals,
            count: count as u8,
        }))
    }
}

/// What Coulomb friction takes from a sliding velocity `slide`: all of it while its speed is
/// within `stick`, else `kinetic` of it along it (a root only then).
pub(super) fn coulomb<P: Point>(slide: P, (stick, kinetic): (P::Scalar, P::Scalar)) -> P {
    if slide.shorter_than(stick) {
        return slide;
    }
    let speed = slide.length();
    if speed <= stick {
        slide
    } else {
        slide * (kinetic / speed)
    }
}

#[cfg(all(test, dunas_floats))]
mod tests {
    use super::*;
    use crate::Vec3;

    #[test]
    fn every_shape_measures_from_its_surface() {
        let near = |(d, n): (f64, Vec2<f64>), (e, m): (f64, Vec2<f64>)| {
            assert!(
                (d - e).abs() < 1e-12 && (n - m).length() < 1e-12,
                "{d} {n:?}"
            );
        };
        let p = Vec2::new(3.0f64, 4.0);
        let ball = Collider::ball(Vec2::new(0.0, 0.0), 1.0).unwrap();
        near(ball.distance(p), (4.0, Vec2::new(0.6, 0.8)));
        let capsule = Collider::capsule(Vec2::new(-5.0, 0.0), Vec2::new(5.0, 0.0), 1.0).unwrap();
        near(capsule.distance(p), (3.0, Vec2::new(0.0, 1.0)));
        let ground = Collider::half_space(Vec2::new(0.0, 1.0), Vec2::new(0.0, 2.0)).unwrap();
        near(ground.distance(p), (3.0, Vec2::new(0.0, 1.0)));
        let crate_ = Collider::aabb(Vec2::new(0.0, 0.0), Vec2::new(2.0, 1.0)).unwrap();
        near(
            crate_.distance(Vec2::new(1.0, 0.8)),
            (-0.2, Vec2::new(0.0, 1.0)),
        );
        assert_eq!(crate_.distance(Vec2::new(5.0, 5.0)).0, 5.0);
        // Clockwise corners are reordered: the same square either way.
        let square = [
            Vec2::new(0.0, 0.0),
            Vec2::new(0.0, 2.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(2.0, 0.0),
        ];
        let poly = Collider::polygon(&square).unwrap();
        near(
            poly.distance(Vec2::new(1.0, 1.5)),
            (-0.5, Vec2::new(0.0, 1.0)),
        );
        near(
            poly.distance(Vec2::new(5.0, 6.0)),
            (5.0, Vec2::new(0.6, 0.8)),
        );
        let sphere = Collider::ball(Vec3::new(0.0, 0.0, 0.0), 2.0).unwrap();
        assert_eq!(sphere.distance(Vec3::new(0.0, 0.0, 5.0)).0, 3.0);
    }

    #[test]
    fn bad_shapes_are_refused() {
        let o = Vec2::new(0.0f32, 0.0);
        assert!(matches!(
            Collider::ball(o, f32::NAN),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            Collider::ball(o, f32::INFINITY),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            Collider::ball(o, -1.0),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            Collider::ball(Vec2::new(f32::NAN, 0.0), 1.0),
            Err(Error::NonFinite { .. })
        ));
        assert!(matches!(
            Collider::ball(o, 1e30),
            Err(Error::OutOfRange { .. })
        ));
        assert!(matches!(
            Collider::half_space(o, o),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            Collider::aabb(Vec2::new(1.0, 0.0), o),
            Err(Error::InvalidParameter { .. })
        ));
        let line = [o, Vec2::new(1.0, 0.0), Vec2::new(2.0, 0.0)];
        assert!(matches!(
            Collider::polygon(&line),
            Err(Error::InvalidParameter { .. })
        ));
        let dart = [
            o,
            Vec2::new(2.0, 1.0),
            Vec2::new(0.0, 2.0),
            Vec2::new(0.5, 1.0),
        ];
        assert!(matches!(
            Collider::polygon(&dart),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            Collider::polygon(&line[..2]),
            Err(Error::InvalidParameter { .. })
        ));
        assert_eq!(
            Collider::polygon(&[o; 9]),
            Err(Error::CapacityExceeded { capacity: 8 })
        );
        let ball = Collider::ball(o, 1.0).unwrap();
        assert!(matches!(
            ball.with_friction(0.2, 0.5),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            ball.with_restitution(1.5),
            Err(Error::InvalidParameter { .. })
        ));
        let mut moved = ball;
        assert!(matches!(
            moved.translate(Vec2::new(1e30, 0.0)),
            Err(Error::OutOfRange { .. })
        ));
        assert_eq!(moved, ball);
    }

    /// A box's search key orders points as their gap does, inside the box and out, in `f64`
    /// and, scaled, in `Q16`: the search for a span's deepest point in a box takes no root.
    #[test]
    fn a_box_key_orders_points_as_their_gap_does() {
        fn check<S: Scalar>(resolution: f64) {
            let at = |i: i32, j: i32| {
                Vec2::new(S::from_f64(0.1 * i as f64), S::from_f64(0.1 * j as f64))
            };
            let b = Collider::aabb(at(-10, -5), at(10, 5)).unwrap();
            let scale = b.key_scale(S::from_f64(0.8));
            let grid = || (-12..=12).flat_map(|i| (-8..=8).map(move |j| at(i, j)));
            for p in grid() {
                for q in grid() {
                    let (gp, gq) = (b.gap(p).to_f64(), b.gap(q).to_f64());
                    let (kp, kq) = (b.search_key(p, scale), b.search_key(q, scale));
                    if (gp - gq).abs() > resolution {
                        assert_eq!(gp < gq, kp < kq, "{p:?} {q:?}: {gp} {gq}");
                    }
                }
            }
        }
        check::<f64>(1e-12);
        #[cfg(feature = "fixed")]
        check::<crate::Q16>(1e-3);
    }
}
