//! The game objects: [`Rope`](crate::Rope), [`Cloth`](crate::Cloth), the closed cloth
//! [`Torus`](crate::Torus), the
//! [`SplineRope`](crate::objects::spline_rope::SplineRope), and how ropes snap and are cut. Uses every
//! layer below (physics, contacts, curves).

pub mod breaking;
pub(crate) mod cloth;
mod reel;
pub(crate) mod rope;
pub mod spline_rope;
pub(crate) mod torus;
pub mod water;
