//! The crate's tests, built as one binary (one link, one compile of the shared helpers):
//! each file is a module named for what it tests. `cargo test` runs them all;
//! `cargo test physics::` runs one file's. The soak's length is `DUNAS_SOAK_STEPS` (20 000
//! steps unless set).

#[path = "../common/mod.rs"]
mod common;

#[path = "../../examples/common/catapult.rs"]
mod catapult;
#[path = "../../examples/common/golden.rs"]
mod golden;
#[path = "../../examples/common/raster.rs"]
mod raster;
#[path = "../../examples/common/rope_scene.rs"]
mod rope_scene;

mod breaking;
mod contacts;
mod converge;
mod evaluation;
mod flatten;
mod fuzz;
mod fuzz_torus;
mod layers;
mod physics;
mod ppm;
mod pressure;
mod promises;
mod properties;
mod reel;
mod regressions;
mod rollback;
mod rope;
mod samplers;
mod sea;
mod sleep;
mod snapshots;
mod soak;
mod spline_rope;
mod torus;
mod water;
mod xml;
