//! Curves and surfaces: Bézier curves and patches, the samplers that draw them, the
//! smoothings that turn a row or grid of particles into a curve or a surface, and the level
//! of detail that says how many points to draw. Uses numbers and geometry.

pub mod curve;
pub mod flatten;
pub mod lod;
pub(crate) mod natural;
pub mod patch;
pub(crate) mod power;
pub mod sampler;
pub mod smooth;
mod spans;
pub mod surface;
mod weights;
