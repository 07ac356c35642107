//! The particle systems: [`MassSpring`](crate::MassSpring), its layouts, springs, forces,
//! settings and integrators, the substeps a frame takes and the fixed time step. Uses
//! numbers, geometry and curves; knows nothing of contacts or of the game objects.

pub mod body;
pub mod force;
pub(crate) mod grid_springs;
pub mod hash;
pub mod integrator;
pub(crate) mod pressure;
pub(crate) mod settings;
pub mod shape;
pub mod sleep;
pub mod spring;
pub(crate) mod substeps;
pub mod system;
pub mod timestep;
