//! Ropes, cables, sails and cloth for the game loop of a low-spec device.
//!
//! `dunas` simulates a few particles and treats them as the **control points of a Bézier
//! curve or surface**; de Casteljau smoothing then draws as many points as the screen needs.
//! A rope of 8 particles looks like one of 30, a sail of 8×8 like one of 20×20.
//!
//! The core is `#![no_std]` and never allocates: sizes are const generics, and every
//! sampler and mesh builder writes into a buffer the caller owns and returns how much it
//! wrote. The same code runs in `f32`, `f64` and Q16.16 fixed point ([`Q16`]), and nothing
//! in it panics or lets a NaN out: bad input is an [`Error`].
//!
//! # A rope in a game loop
//!
//! Make a rope, step it at a fixed rate, hold its end with the player's hand, and draw it:
//!
//! ```
//! use dunas::prelude::*;
//!
//! // 8 particles, 70 units long, 7 mass units, pinned at its first particle.
//! let settings = Settings { gravity: Vec2::new(0.0, -200.0), damping: 0.1, ..Settings::default() };
//! let material = Material { stiffness: 3000.0, damping: 1.0 }; // per spring
//! let mut rope: Rope<Vec2<f32>, 8> =
//!     Rope::new(Vec2::new(0.0, 0.0), Vec2::new(70.0, 0.0), 7.0, material, settings)?;
//! let mut clock = FixedTimestep::new(1.0 / 60.0, 0.25)?; // a long hitch runs 0.25 s, no more
//! let mut screen = [Vec2::default(); 64]; // the points the renderer draws
//!
//! for (frame, frame_time) in [0.016, 0.017, 0.5, 0.016].into_iter().enumerate() {
//!     let hand = Vec2::new(10.0 * frame as f32, 0.0); // where the player holds the rope
//!     for _ in 0..clock.advance(frame_time) {
//!         rope.set_position(0, hand)?;
//!         let info = rope.step(clock.step())?; // substeps chosen from the stiffness
//!         assert!(!info.slow_motion); // true when too stiff for the substep cap: time slows
//!     }
//!     let n = rope.sample(Smoothing::BSpline, &mut screen)?; // draw screen[..n]
//!     assert_eq!(screen[0], hand);
//!     assert_eq!(n, 64);
//! }
//! # Ok::<(), dunas::Error>(())
//! ```
//!
//! Every call returns a [`Result`]: a NaN hand, a step that would blow up or a buffer too
//! small is an [`Error`], and a refused call leaves the rope as it was.
//!
//! # Recipes
//!
//! **A ball the rope hits, both ways, drawn with embedded-graphics.** The ball is a collider
//! with its own mass; the step reports what the rope did to it ([`contact::Push`]), and the
//! game moves the ball by that. Both preludes import together.
//!
//! ```
//! use dunas::contact::Push;
//! use dunas::prelude::*;
//! # #[cfg(feature = "embedded-graphics")]
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor, prelude::*};
//! # #[cfg(feature = "embedded-graphics")]
//! use embedded_graphics::primitives::{Circle, PrimitiveStyle};
//!
//! let settings = Settings { gravity: Vec2::new(0.0, -9.81), damping: 0.1, ..Settings::default() };
//! let material = Material { stiffness: 500.0, damping: 1.0 };
//! let mut rope: Rope<Vec2<f32>, 8> =
//!     Rope::new(Vec2::new(-1.5, 0.5), Vec2::new(1.5, 0.5), 0.5, material, settings)?;
//! rope.set_inv_mass(7, 0.0)?; // both ends held: a rope bridge
//! let (radius, mass) = (0.3, 1.5); // the ball: three times the rope
//! let (mut ball, mut velocity) = (Vec2::new(0.2, 2.0), Vec2::new(0.0, 0.0));
//! let mut pushes = [Push::default(); 1];
//! let mut points = [Vec2::default(); 36];
//! for _ in 0..120 {
//!     velocity += Vec2::new(0.0, -9.81) / 60.0; // gravity first (semi-implicit Euler)
//!     ball += velocity / 60.0; // where the ball will be at the end of the frame
//!     let colliders = [Collider::ball(ball, radius)?.moving(velocity)?.with_mass(mass)?];
//!     let contacts = Contacts::new(&colliders, 0.02, Touch::Drawn(Smoothing::BSpline))?
//!         .with_pushes(&mut pushes);
//!     let info = rope.step_touching(1.0 / 60.0, (), &contacts)?;
//!     assert!(!info.slow_motion);
//!     ball += pushes[0].shift;
//!     velocity += pushes[0].impulse / mass;
//!     let n = rope.sample(Smoothing::BSpline, &mut points)?;
//!     # #[cfg(feature = "embedded-graphics")]
//!     # {
//!     let view = View::new(Vec2::new(-2.0, 2.5), 0.0625, 0.0625)?; // 16 pixels a metre
//!     let mut display = MockDisplay::new();
//!     display.set_allow_overdraw(true);
//!     dunas::graphics::Curve::new(&points[..n], view)
//!         .into_styled(PrimitiveStyle::with_stroke(BinaryColor::On, 2))
//!         .draw(&mut display)
//!         .unwrap();
//!     let (x, y) = view.cell(ball);
//!     Circle::with_center(Point::new(x, y), 10) // embedded-graphics's Point
//!         .into_styled(PrimitiveStyle::with_stroke(BinaryColor::On, 1))
//!         .draw(&mut display)
//!         .unwrap();
//!     # }
//! }
//! assert!(ball.y > 0.0 && ball.y < 2.5); // caught by the rope, and no higher than it fell
//! # Ok::<(), dunas::Error>(())
//! ```
//!
//! **A cut rope on a floor, drawn by pieces.** [`Rope::draw`] draws each piece as its own
//! curve and [`Rope::cut`] cuts where the player swiped across what was drawn; the contacts
//! touch each piece's curve, so nothing sinks through the floor.
//!
//! ```
//! use dunas::breaking::Piece;
//! use dunas::prelude::*;
//!
//! let settings = Settings { gravity: Vec2::new(0.0, -9.81), damping: 0.2, ..Settings::default() };
//! let material = Material { stiffness: 500.0, damping: 1.0 };
//! let mut rope: Rope<Vec2<f32>, 8> =
//!     Rope::new(Vec2::new(0.0, 0.5), Vec2::new(2.3, 0.5), 0.5, material, settings)?;
//! let floor = [Collider::half_space(Vec2::new(0.0, -1.0), Vec2::new(0.0, 1.0))?];
//! let contacts = Contacts::new(&floor, 0.02, Touch::Drawn(Smoothing::BSpline))?;
//! let (mut points, mut pieces) = ([Vec2::default(); 64], [Piece::EMPTY; 8]);
//! let mut drawn = rope.draw(Smoothing::BSpline, &mut points, &mut pieces)?;
//! for frame in 0..240 {
//!     if frame == 60 {
//!         // The player's swipe, across the middle of what the last frame drew.
//!         let middle = points[pieces[0].points.end / 2];
//!         let (from, to) = (middle + Vec2::new(-1.0, 0.1), middle + Vec2::new(1.0, -0.1));
//!         assert!(rope.cut(&points, &pieces[..drawn], from, to)?.is_some());
//!     }
//!     let _ = rope.step_touching(1.0 / 60.0, (), &contacts)?;
//!     drawn = rope.draw(Smoothing::BSpline, &mut points, &mut pieces)?; // draw pieces[..drawn]
//!     for piece in &pieces[..drawn] {
//!         assert!(points[piece.points.clone()].iter().all(|p| p.y > -1.01));
//!     }
//! }
//! assert_eq!(drawn, 2); // the held piece and the one on the floor
//! assert!(rope.sample(Smoothing::BSpline, &mut points).is_err()); // one curve would bridge the cut
//! # Ok::<(), dunas::Error>(())
//! ```
//!
//! **The same rope in Q16.16 on a chip without an FPU.** Constants are `const`, nothing
//! allocates, and the frame function is what a `#![no_std]` game calls 60 times a second.
//!
//! ```
//! use dunas::prelude::*;
//!
//! const DT: Q16 = Q16::ratio(1, 60);
//! const GRAVITY: Q16 = Q16::ratio(-981, 100);
//!
//! fn new_rope(hand: Vec2<Q16>) -> Result<Rope<Vec2<Q16>, 8>, Error> {
//!     let settings = Settings { gravity: Vec2::new(Q16::ZERO, GRAVITY), damping: Q16::ratio(1, 10), ..Settings::default() };
//!     let material = Material { stiffness: Q16::from_int(500), damping: Q16::ONE };
//!     Rope::new(hand, hand + Vec2::new(Q16::ZERO, Q16::ratio(-23, 10)), Q16::ratio(1, 2), material, settings)
//! }
//!
//! /// One frame: the hand moves, the rope steps, the curve is drawn into `points` (the
//! /// count returned: in Q16 the default sampler halves each span, 4 segments here).
//! fn frame(rope: &mut Rope<Vec2<Q16>, 8>, hand: Vec2<Q16>, points: &mut [Vec2<Q16>; 36]) -> Result<usize, Error> {
//!     rope.move_pinned(0, hand, DT)?;
//!     let info = rope.step(DT)?;
//!     if info.saturated || info.slow_motion {
//!         // Past the format's limits: the step says so (and a saturated rope comes back).
//!     }
//!     rope.sample(Smoothing::BSpline, points)
//! }
//!
//! let hand = Vec2::new(Q16::ZERO, Q16::ratio(1, 2));
//! let mut rope = new_rope(hand)?;
//! let mut points = [Vec2::new(Q16::ZERO, Q16::ZERO); 36];
//! for _ in 0..60 {
//!     assert_eq!(frame(&mut rope, hand, &mut points)?, 29); // 7 spans of 4, and the end
//! }
//! assert_eq!(points[0], hand);
//! # Ok::<(), dunas::Error>(())
//! ```
//!
//! # Modules
//!
//! - [`prelude`]: everything the example above uses, in one import.
//! - [`system`]: the [`MassSpring`] system that [`Rope`], [`Cloth`] and [`Torus`] are made of;
//!   [`Settings`] and [`Accuracy`] configure it.
//! - [`integrator`]: eight time integrators, one type each, behind the [`Integrator`] trait.
//! - [`spring`]: [`Material`]s and the topologies that lay springs out.
//! - [`force`]: wind, anchor springs, the gas in a closed body and the
//!   [`ForceField`](force::ForceField) trait.
//! - [`smooth`]: a row of particles as one Bézier, a B-spline or a Catmull-Rom spline.
//! - [`curve`], [`patch`], [`sampler`], [`lod`]: Bézier curves and patches, the samplers
//!   that draw them, and Wang's formula for how many points to draw.
//! - [`scalar`], [`point`]: the [`Scalar`] trait over `f32`, `f64` and [`Q16`]; [`Vec2`],
//!   [`Vec3`] and the [`Point`] trait.
//! - [`ascii`]: a `no_std` text canvas for quick looks and device demos; [`View`] maps the
//!   world to its cells, or to a display's pixels (`graphics`).
//!
//! # Feature flags
//!
//! | feature | default | what it does |
//! |---|---|---|
//! | `std` | yes | float math from `std`, `std::error::Error` for [`Error`] |
//! | `libm` | no | float math without `std` (exact square roots from `libm`) |
//! | `fixed` | yes | the [`Q16`] Q16.16 format, for chips without an FPU |
//! | `micromath` | no | fast approximate `f32` roots behind [`Scalar::approx_sqrt`] and [`Scalar::approx_inv_sqrt`] (at most 6.1% and 3.5% off, measured) |
//! | `mint` | no | conversions between [`Vec2`]/[`Vec3`] and `mint`'s vectors and points (glam, nalgebra, cgmath) |
//! | `xml` | no | loading the thesis's scene and physics XML files (`xml` module; needs `std`) |
//! | `embedded-graphics` | no | drawing curves and patch wireframes into any `DrawTarget` (`graphics` module) |
//!
//! `f32` and `f64` need `std` or `libm`; a hosted build with neither and without `fixed`
//! stops with a `compile_error!`. On bare-metal targets (`target_os = "none"`) float math
//! always comes from `libm`, so the default features build for a microcontroller too.
#![no_std]
// One FPU instruction (`math.rs`, the Cortex-M4F's square root) is the only unsafe code.
#![deny(unsafe_code)]
#![deny(missing_docs)]
// Numeric kernels index several arrays in step, as the formulas they implement do.
#![allow(clippy::needless_range_loop)]

#[cfg(any(dunas_std, test))]
extern crate std;

// `dunas_floats` (set by build.rs): std math on a hosted target, or libm.
#[cfg(not(any(dunas_floats, feature = "fixed")))]
compile_error!(
    "dunas needs a number format: enable `std` (default) or `libm` for f32/f64, \
     or `fixed` for Q16.16 (e.g. `--no-default-features --features libm`)"
);

// The layers, from the bottom up; each uses only the ones before it (ARCHITECTURE.md).

/// 1. Number formats.
mod number;

/// 2. Points, boxes, segments, the catenary.
mod geometry;

/// 3. Curves and surfaces, their samplers and level of detail.
mod curves;

/// 4. Particle systems, springs, forces and integrators.
mod physics;

// 5. Colliders and contacts (public: `dunas::contact`).
pub mod contact;

/// 6. The game objects: ropes, cloth, spline ropes, breaking.
mod objects;

/// 7. Drawing and loading.
mod io;

mod error;
pub mod prelude;

// The module paths a game uses: each layer's public modules at the crate root.
pub use contact::collider;
pub use curves::{curve, flatten, lod, patch, sampler, smooth, surface};
pub use geometry::point;
pub use io::ascii;
#[cfg(feature = "embedded-graphics")]
pub use io::graphics;
#[cfg(all(feature = "xml", dunas_std))]
pub use io::xml;
pub use number::scalar;
pub use objects::{breaking, spline_rope, water};
pub use physics::{body, force, integrator, shape, sleep, spring, system, timestep};

pub use curves::curve::{Bezier, Cubic, Quadratic};
pub use curves::patch::{Bicubic, Patch};
pub use curves::smooth::Smoothing;
pub use error::Error;
pub use geometry::aabb::Aabb;
pub use geometry::point::{Point, Vec2, Vec3};
pub use io::view::View;
#[cfg(feature = "fixed")]
pub use number::q16::Q16;
pub use number::scalar::Scalar;
pub use objects::cloth::Cloth;
pub use objects::rope::Rope;
pub use objects::torus::Torus;
pub use physics::hash::StateHash;
pub use physics::integrator::Integrator;
pub use physics::settings::{Accuracy, Settings};
pub use physics::sleep::Sleep;
pub use physics::spring::Material;
pub use physics::system::MassSpring;
pub use physics::timestep::FixedTimestep;

/// The README's code blocks, run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The guide's code blocks, run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/guide.md")]
pub struct GuideDoctests;
