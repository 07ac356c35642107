//! What a first program needs, in one import: `use dunas::prelude::*;`.
//!
//! The rope and cloth types, their settings and materials, the number formats, the points,
//! the smoothing choice, colliders and contacts, the game-loop clock and the traits whose
//! methods those types use.

#[cfg(feature = "fixed")]
pub use crate::Q16;
pub use crate::collider::Collider;
pub use crate::contact::{Contacts, Touch};
pub use crate::integrator::Integrator;
pub use crate::point::{Point, Vec2, Vec3};
pub use crate::{
    Accuracy, Bezier, Cloth, Error, FixedTimestep, Material, Rope, Scalar, Settings, Smoothing,
};
