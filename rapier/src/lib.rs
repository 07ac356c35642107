//! A dunas rope holding a rapier2d rigid body, coupled both ways: the recipe in one type.
//!
//! Each frame, before `world.step()`, [`Hanging::step`]:
//! 1. puts the rope's end particle on the body's anchor, moving with the body there
//!    (`velocity_at_point`), with the body's effective mass at that point along the rope's
//!    last link (`1 / (1/m + (r × n)² / I)`: a crate held off its centre turns as it is
//!    pulled);
//! 2. steps the rope (`DirectChain`: its links hold their length under the body);
//! 3. gives the body, at the anchor, the impulse the rope's step gave the end particle
//!    beyond gravity (`m · (v_after − v_before − g·dt)`), so that rapier's step moves it
//!    with the rope's pull (and its own gravity, contacts and joints).
//!
//! The rope sees the body as one particle at its anchor; rapier sees the rope as an impulse
//! a frame. Contacts between the rope and rapier's colliders are not coupled: the rope
//! passes through rapier's bodies (give the rope dunas colliders for the shapes it should
//! touch).
//!
//! `cargo run --release -p dunas-rapier` runs the two scenes ([`scenes`]) and prints what
//! they measure; `cargo test -p dunas-rapier` holds them to their bounds.

pub mod scenes;

use dunas::Error;
use dunas::integrator::DirectChain;
use dunas::prelude::*;
use dunas::system::StepInfo;
use rapier2d::prelude::{PhysicsWorld, RigidBodyHandle, Vector};

/// The rope's points and rapier's: both are 2D `f32` vectors.
fn to_dunas(v: Vector) -> Vec2<f32> {
    Vec2::new(v.x, v.y)
}
fn to_rapier(v: Vec2<f32>) -> Vector {
    Vector::new(v.x, v.y)
}

/// A rope of `N` particles whose first particle is held (by the game's hand, a crane's
/// trolley: [`Hanging::move_top`]) and whose last holds a rapier body at an anchor.
pub struct Hanging<const N: usize> {
    pub rope: Rope<Vec2<f32>, N, N, DirectChain>,
    pub body: RigidBodyHandle,
    /// The anchor in the body's own frame (m).
    pub anchor: Vector,
}

impl<const N: usize> Hanging<N> {
    /// A rope from `top` to `body`'s `anchor` (its length their distance), of `mass` (kg)
    /// and `material`, solved by `solver` under `world`'s gravity.
    ///
    /// # Errors
    /// The rope's ([`Rope::new`]): a zero length, a bad mass or material.
    pub fn new(
        world: &PhysicsWorld,
        top: Vec2<f32>,
        (body, anchor): (RigidBodyHandle, Vector),
        (mass, material): (f32, Material<f32>),
        solver: DirectChain,
    ) -> Result<Self, Error> {
        let settings = Settings {
            gravity: to_dunas(world.gravity),
            ..Settings::default()
        }
        .with_integrator(solver);
        let end = world.bodies[body].position().transform_point(anchor);
        let mut rope = Rope::new(top, to_dunas(end), mass, material, settings)?;
        rope.set_inv_mass(0, 0.0)?;
        Ok(Hanging { rope, body, anchor })
    }

    /// Moves the rope's held top to `to` over the coming frame of `dt` seconds.
    ///
    /// # Errors
    /// [`MassSpring::move_pinned`]'s.
    pub fn move_top(&mut self, to: Vec2<f32>, dt: f32) -> Result<(), Error> {
        self.rope.move_pinned(0, to, dt)
    }

    /// Steps the rope a frame of `dt` and gives the body the rope's impulse at the anchor;
    /// call it before `world.step()` with the same `dt`.
    ///
    /// # Errors
    /// The rope's step's ([`MassSpring::step`]: a negative or non-finite `dt` is
    /// [`Error::InvalidParameter`]); the rope and the body are then left as they were.
    pub fn step(&mut self, world: &mut PhysicsWorld, dt: f32) -> Result<StepInfo<f32>, Error> {
        let before = self.rope.clone();
        let stepped = self.pull(world, dt);
        if stepped.is_err() {
            self.rope = before;
        }
        stepped
    }

    /// [`step`](Self::step), the rope changed even where it fails.
    fn pull(&mut self, world: &mut PhysicsWorld, dt: f32) -> Result<StepInfo<f32>, Error> {
        let end = N - 1;
        let body = &world.bodies[self.body];
        let at = body.position().transform_point(self.anchor);
        let velocity = body.velocity_at_point(at);
        // The body's mass at the anchor along the last link: what the rope pulls on there.
        let props = body.mass_properties();
        let link = to_rapier(self.rope.positions()[end] - self.rope.positions()[end - 1]);
        let along = link.try_normalize().unwrap_or(Vector::Y);
        let arm = (at - props.world_com).perp_dot(along);
        let inverse = props.effective_inv_mass.x.max(props.effective_inv_mass.y)
            + arm * arm * props.effective_world_inv_inertia;
        self.rope.set_position(end, to_dunas(at))?;
        self.rope.set_velocity(end, to_dunas(velocity))?;
        self.rope.set_inv_mass(end, inverse)?;
        let info = self.rope.step(dt)?;
        let pulled = to_rapier(self.rope.velocities()[end]) - velocity - world.gravity * dt;
        if inverse > 0.0 {
            world.bodies[self.body].apply_impulse_at_point(pulled / inverse, at, true);
        }
        Ok(info)
    }

    /// The rope's energy (motion, gravity; an inextensible rope's links store none), its end
    /// particle left out (the body's motion is rapier's to count).
    pub fn energy(&self) -> f32 {
        let (x, v, w) = (
            self.rope.positions(),
            self.rope.velocities(),
            self.rope.inv_masses(),
        );
        let g = self.rope.settings().gravity;
        (1..N - 1)
            .filter(|&i| w[i] > 0.0)
            .map(|i| (0.5 * v[i].dot(v[i]) - g.dot(x[i])) / w[i])
            .sum()
    }
}
