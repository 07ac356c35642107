//! What a first program needs, in one import: `use dunas::prelude::*;`.
//!
//! The rope and cloth types, their settings and materials, the number formats, the points,
//! the smoothing choice, colliders and contacts, the game-loop clock and the traits whose
//! methods those types use. The [`Point`](crate::Point) trait comes in unnamed (`as _`): its
//! methods work, and the name stays free for `embedded_graphics::prelude::Point`, so both
//! preludes can be imported together. Generic code names it as `dunas::Point`.
//!
//! ```
//! use dunas::prelude::*;
//! # #[cfg(feature = "embedded-graphics")]
//! use embedded_graphics::prelude::*;
//!
//! let a = Vec2::new(3.0f32, 4.0);
//! assert_eq!(a.length(), 5.0); // a `dunas::Point` method
//! # #[cfg(feature = "embedded-graphics")]
//! let pixel = Point::new(3, 4); // embedded-graphics's Point
//! # Ok::<(), dunas::Error>(())
//! ```

#[cfg(feature = "fixed")]
pub use crate::Q16;
pub use crate::collider::Collider;
pub use crate::contact::{Contacts, Touch};
pub use crate::geometry::point::Point as _;
pub use crate::geometry::point::{Vec2, Vec3};
pub use crate::physics::integrator::Integrator;
pub use crate::{
    Accuracy, Bezier, Cloth, Error, FixedTimestep, Material, Rope, Scalar, Settings, Sleep,
    Smoothing, View,
};
