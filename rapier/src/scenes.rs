//! Two scenes a game would have, each stepped at 60 Hz for 10 s and measured:
//! - [`crane`]: a trolley carries a 200 kg crate on a 5 m cable 6 m along and stops; the
//!   crate swings above the ground.
//! - [`wrecking_ball`]: a 400 kg ball on a 7 m rope, let go 70° from the vertical, swings
//!   into a wall of 15 boxes; every restitution 0.

use std::time::Instant;

use dunas::integrator::DirectChain;
use dunas::prelude::*;
use rapier2d::prelude::{
    ColliderBuilder, PhysicsWorld, RigidBodyBuilder, RigidBodyHandle, RopeJointBuilder, Vector,
};

use crate::Hanging;

/// The frame step (s), and the frames a scene runs.
pub const STEP: f32 = 1.0 / 60.0;
pub const FRAMES: usize = 600;

/// What a scene measured.
#[derive(Clone, Copy, Debug, Default)]
pub struct Measured {
    /// The largest gap between the rope's chain (its particles' distances summed) and its
    /// length, over every frame (0.01 is 1%).
    pub largest_off: f32,
    /// The most the total energy (the bodies' motion and height, the rope's) rose above its
    /// value at the start, over the drop's energy (0.01 is 1%); the wrecking ball only.
    pub energy_rise: f32,
    /// The deepest any body went into the ground or into another body (m).
    pub deepest: f32,
    /// The lowest the hanging body's bottom went (m; the ground is at 0).
    pub lowest: f32,
    /// How far the hanging body ended from where it started, along x (m): the crane's
    /// crate carried along, or the ball swung through.
    pub carried: f32,
    /// The wall's boxes that ended more than 0.25 m from where they stood.
    pub knocked: usize,
}

/// Ground: a fixed slab whose top is y = 0.
fn ground(world: &mut PhysicsWorld) {
    world.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5)),
        ColliderBuilder::cuboid(40.0, 0.5).restitution(0.0),
    );
}

/// The chain's gap to the rope's length.
fn off<const N: usize>(hanging: &Hanging<N>) -> f32 {
    let p = hanging.rope.positions();
    let chain: f32 = p.windows(2).map(|w| w[0].distance(w[1])).sum();
    (chain / hanging.rope.length() - 1.0).abs()
}

/// How deep the world's contacts go (m): the largest penetration of any contact point.
fn deepest(world: &PhysicsWorld) -> f32 {
    let mut deepest = 0.0f32;
    for pair in world.narrow_phase.contact_pairs() {
        for manifold in pair.manifolds() {
            for point in &manifold.points {
                deepest = deepest.max(-point.dist);
            }
        }
    }
    deepest
}

/// The crane: its trolley's path, the crate and its cable.
pub struct Crane {
    pub world: PhysicsWorld,
    pub cable: Hanging<10>,
    pub crate_body: RigidBodyHandle,
    /// Frames whose cable step said a link ended beyond its tolerance.
    pub unconverged: u32,
    frame: usize,
}

impl Crane {
    pub fn new() -> Crane {
        let mut world = PhysicsWorld::new();
        ground(&mut world);
        let (crate_body, _) = world.insert(
            RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 2.5)),
            ColliderBuilder::cuboid(0.5, 0.5)
                .mass(200.0)
                .restitution(0.0),
        );
        let material = Material {
            stiffness: 2e5,
            damping: 10.0,
        };
        let cable = Hanging::new(
            &world,
            Vec2::new(0.0, 8.0),
            (crate_body, Vector::new(0.0, 0.5)),
            (5.0, material),
            DirectChain::default(),
        )
        .expect("a valid cable");
        Crane {
            world,
            cable,
            crate_body,
            unconverged: 0,
            frame: 0,
        }
    }

    /// The trolley's x (m) at frame `k`: still for half a second, 6 m along in 3 s
    /// (smoothly), then still.
    fn trolley(k: usize) -> f32 {
        let t = ((k as f32 * STEP - 0.5) / 3.0).clamp(0.0, 1.0);
        6.0 * t * t * (3.0 - 2.0 * t)
    }

    /// One frame: the trolley moves, the cable steps and pulls, rapier steps.
    pub fn step(&mut self) {
        self.frame += 1;
        let to = Vec2::new(Self::trolley(self.frame), 8.0);
        self.cable.move_top(to, STEP).expect("the trolley in range");
        let info = self.cable.step(&mut self.world, STEP);
        self.unconverged += u32::from(!info.expect("the cable steps").converged);
        self.world.step();
    }
}

impl Default for Crane {
    fn default() -> Self {
        Crane::new()
    }
}

/// The crane scene, measured.
pub fn crane() -> Measured {
    let mut crane = Crane::new();
    let start = crane.world.bodies[crane.crate_body].translation();
    let mut measured = Measured {
        lowest: f32::MAX,
        ..Measured::default()
    };
    for _ in 0..FRAMES {
        crane.step();
        measured.largest_off = measured.largest_off.max(off(&crane.cable));
        measured.deepest = measured.deepest.max(deepest(&crane.world));
        let y = crane.world.bodies[crane.crate_body].translation().y;
        measured.lowest = measured.lowest.min(y - 0.5);
    }
    measured.carried = crane.world.bodies[crane.crate_body].translation().x - start.x;
    measured
}

/// The wrecking ball: the wall of boxes, the ball and its rope (dunas's, or rapier's own
/// rope joint for the cost against rapier alone).
pub struct WreckingBall {
    pub world: PhysicsWorld,
    pub rope: Option<Hanging<10>>,
    pub ball: RigidBodyHandle,
    pub boxes: Vec<RigidBodyHandle>,
    /// Frames whose rope step said a link ended beyond its tolerance.
    pub unconverged: u32,
}

/// The wrecking ball's top, rope length, radius and mass, and its start angle.
const TOP: Vector = Vector::new(0.0, 10.0);
const LENGTH: f32 = 7.0;
const RADIUS: f32 = 0.6;
const BALL: f32 = 400.0;
const ANGLE: f32 = 70.0;

impl WreckingBall {
    /// The scene with dunas's rope (`dunas_rope`) or rapier's rope joint.
    pub fn new(dunas_rope: bool) -> WreckingBall {
        let mut world = PhysicsWorld::new();
        ground(&mut world);
        let mut boxes = Vec::new();
        for column in 0..3 {
            for row in 0..5 {
                let at = Vector::new(0.95 + 0.5 * column as f32, 0.25 + 0.5 * row as f32);
                let (body, _) = world.insert(
                    RigidBodyBuilder::dynamic().translation(at),
                    ColliderBuilder::cuboid(0.25, 0.25)
                        .mass(15.0)
                        .restitution(0.0),
                );
                boxes.push(body);
            }
        }
        let angle = ANGLE.to_radians();
        let centre = TOP + Vector::new(-angle.sin(), -angle.cos()) * (LENGTH + RADIUS);
        let (ball, _) = world.insert(
            RigidBodyBuilder::dynamic()
                .translation(centre)
                .rotation(-angle)
                .ccd_enabled(true),
            ColliderBuilder::ball(RADIUS).mass(BALL).restitution(0.0),
        );
        let anchor = Vector::new(0.0, RADIUS);
        let rope = if dunas_rope {
            let material = Material {
                stiffness: 2e5,
                damping: 10.0,
            };
            let top = Vec2::new(TOP.x, TOP.y);
            let rope = Hanging::new(
                &world,
                top,
                (ball, anchor),
                (20.0, material),
                DirectChain::default(),
            );
            Some(rope.expect("a valid rope"))
        } else {
            let top = world.insert_body(RigidBodyBuilder::fixed().translation(TOP));
            world.insert_impulse_joint(
                top,
                ball,
                RopeJointBuilder::new(LENGTH).local_anchor2(anchor),
            );
            None
        };
        WreckingBall {
            world,
            rope,
            ball,
            boxes,
            unconverged: 0,
        }
    }

    /// One frame: the rope steps and pulls, rapier steps.
    pub fn step(&mut self) {
        if let Some(rope) = &mut self.rope {
            let info = rope.step(&mut self.world, STEP);
            self.unconverged += u32::from(!info.expect("the rope steps").converged);
        }
        self.world.step();
    }

    /// The bodies' energy (motion and height) and the rope's (J).
    pub fn energy(&self) -> f32 {
        let g = -self.world.gravity.y;
        let bodies: f32 = (self.world.bodies.iter())
            .filter(|(_, b)| b.is_dynamic())
            .map(|(_, b)| b.kinetic_energy() + b.mass() * g * b.translation().y)
            .sum();
        bodies + self.rope.as_ref().map_or(0.0, Hanging::energy)
    }
}

/// The wrecking-ball scene with dunas's rope (`dunas_rope`) or rapier's rope joint,
/// measured (the rope's chain with dunas's only).
pub fn wrecking_ball(dunas_rope: bool) -> Measured {
    let mut scene = WreckingBall::new(dunas_rope);
    let start = scene.energy();
    let (ball_start, stood): (Vector, Vec<Vector>) = (
        scene.world.bodies[scene.ball].translation(),
        (scene.boxes.iter())
            .map(|&b| scene.world.bodies[b].translation())
            .collect(),
    );
    // The drop: from where the ball starts to the bottom of its swing.
    let drop = BALL * 9.81 * (LENGTH + RADIUS) * (1.0 - ANGLE.to_radians().cos());
    let mut measured = Measured {
        lowest: f32::MAX,
        ..Measured::default()
    };
    for _ in 0..FRAMES {
        scene.step();
        if let Some(rope) = &scene.rope {
            measured.largest_off = measured.largest_off.max(off(rope));
        }
        measured.energy_rise = measured.energy_rise.max((scene.energy() - start) / drop);
        measured.deepest = measured.deepest.max(deepest(&scene.world));
        let y = scene.world.bodies[scene.ball].translation().y;
        measured.lowest = measured.lowest.min(y - RADIUS);
    }
    measured.carried = scene.world.bodies[scene.ball].translation().x - ball_start.x;
    measured.knocked = (scene.boxes.iter().zip(&stood))
        .filter(|(b, at)| scene.world.bodies[**b].translation().distance(**at) > 0.25)
        .count();
    measured
}

/// A wrecking-ball frame's cost (ns) with dunas's rope and with rapier's rope joint alone:
/// `rounds` rounds of the whole scene each; the fastest round's mean frame and the median
/// round's, for each.
pub fn wrecking_ball_cost(rounds: usize) -> [(f64, f64); 2] {
    [true, false].map(|dunas_rope| {
        let mut means: Vec<f64> = (0..rounds)
            .map(|_| {
                let mut scene = WreckingBall::new(dunas_rope);
                let t = Instant::now();
                for _ in 0..FRAMES {
                    scene.step();
                }
                t.elapsed().as_nanos() as f64 / FRAMES as f64
            })
            .collect();
        means.sort_by(f64::total_cmp);
        (means[0], means[rounds / 2])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The crane carries its crate along on a cable that keeps its length within 0.5% at
    /// every frame, and the crate stays above the ground.
    #[test]
    fn the_crane_carries_its_crate_on_a_cable_of_its_length() {
        let m = crane();
        assert!(m.carried > 5.0, "{m:?}");
        assert!(m.largest_off <= 5e-3, "{m:?}");
        assert!(m.lowest >= 0.0, "{m:?}");
    }

    /// A refused step (a bad `dt`) is an `InvalidParameter` and leaves the rope and the
    /// body as they were.
    #[test]
    fn a_refused_step_changes_nothing() {
        let mut scene = WreckingBall::new(true);
        for _ in 0..30 {
            scene.step();
        }
        let rope = scene.rope.as_mut().expect("dunas's rope");
        let (positions, velocities) = (
            rope.rope.positions().to_vec(),
            rope.rope.velocities().to_vec(),
        );
        let ball = (
            scene.world.bodies[scene.ball].translation(),
            scene.world.bodies[scene.ball].linvel(),
        );
        for dt in [f32::NAN, -STEP, f32::INFINITY] {
            let refused = rope.step(&mut scene.world, dt);
            assert!(
                matches!(refused, Err(dunas::Error::InvalidParameter { .. })),
                "{refused:?}"
            );
            assert_eq!(rope.rope.positions(), &positions[..]);
            assert_eq!(rope.rope.velocities(), &velocities[..]);
            let body = &scene.world.bodies[scene.ball];
            assert_eq!((body.translation(), body.linvel()), ball);
        }
    }

    /// The wrecking ball knocks the wall down; with restitution 0 the total energy never
    /// rises above the start's by more than 1% of the drop's, the rope keeps its length
    /// within 0.5%, the ball stays above the ground and no body goes half a box deep into
    /// another (rapier's contacts).
    #[test]
    fn the_wrecking_ball_knocks_the_wall_down_and_gains_no_energy() {
        let m = wrecking_ball(true);
        assert!(m.knocked >= 5, "{m:?}");
        assert!(m.energy_rise <= 0.01, "{m:?}");
        assert!(m.largest_off <= 5e-3, "{m:?}");
        assert!(m.lowest >= 0.0, "{m:?}");
        assert!(m.deepest <= 0.25, "{m:?}");
    }
}
