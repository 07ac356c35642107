//! Points and shapes in the plane and in space: [`Vec2`](crate::Vec2), [`Vec3`](crate::Vec3),
//! boxes, segment crossings and the catenary. Uses the number formats.

pub(crate) mod aabb;
pub(crate) mod catenary;
pub mod point;
pub(crate) mod segment;
