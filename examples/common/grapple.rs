//! The grappling-hook game, shared by `examples/grapple.rs` and the browser page (`web/`): a
//! climber swings on a rope from a hook in a cave's roof, reels itself in to climb, and
//! throws the rope to the next hook to swing on, hook after hook to the last. The rope is
//! 8 particles solved together each frame (`DirectChain`, inextensible) with the 70 kg
//! climber hung on its end, reeled with `Rope::reel`. Metres, seconds, kilograms; y up.
#![allow(dead_code)]
// `.ok().expect(..)` rather than `.expect(..)`: the message is the same, and `Error`'s
// `Debug` (with the float formatting it brings, 40 KB) stays out of the browser's .wasm.
#![allow(clippy::ok_expect)]

use dunas::ascii::{Canvas, View};
use dunas::breaking::Piece;
use dunas::integrator::DirectChain;
use dunas::prelude::*;

/// The frame step (s).
pub const STEP: f32 = 1.0 / 60.0;
/// The hooks in the roof, left to right (m).
pub const HOOKS: [Vec2<f32>; 8] = [
    Vec2::new(0.0, 10.0),
    Vec2::new(7.0, 11.0),
    Vec2::new(14.0, 9.5),
    Vec2::new(21.0, 11.5),
    Vec2::new(28.0, 10.0),
    Vec2::new(35.0, 12.0),
    Vec2::new(42.0, 10.5),
    Vec2::new(49.0, 11.0),
];
/// The cave's floor (m): the climber slides on it.
pub const FLOOR: f32 = 0.0;
/// The longest rope a throw reaches, and the shortest the reel winds it to (m).
pub const REACH: f32 = 11.0;
pub const SHORTEST: f32 = 1.5;
/// The reel's speed (m/s).
pub const REEL_SPEED: f32 = 4.0;
/// The climber's mass and the rope's (kg), and the climber's radius (m).
pub const CLIMBER: f32 = 70.0;
const ROPE_MASS: f32 = 2.0;
pub const CLIMBER_RADIUS: f32 = 0.35;
/// Particles in the rope (as the catapult's: the page holds one rope solver), and points in
/// its drawn curve (5 a span and the end).
pub const PARTICLES: usize = 8;
pub const DRAWN: usize = 36;

type HookRope = Rope<Vec2<f32>, PARTICLES, PARTICLES, DirectChain>;

pub struct Grapple {
    pub rope: HookRope,
    /// The hook the rope hangs from (an index into [`HOOKS`]).
    pub hook: usize,
    /// Whether the reel winds the rope in this frame.
    pub reeling: bool,
    time: f32,
    floor: [Collider<Vec2<f32>>; 1],
    /// Frames whose step said a solve on the way left a link more than 0.1% off
    /// (`StepInfo::converged`), and frames that hit the substep cap (slow motion).
    pub unconverged_frames: u32,
    pub slow_frames: u32,
    /// The largest gap between the rope's chain (its particles' distances summed) and its
    /// length, over every frame so far (0.01 is 1%).
    pub largest_off: f32,
}

impl Grapple {
    /// The climber on an 8 m rope from the first hook, let go at 45° behind it.
    pub fn new() -> Grapple {
        let hook = HOOKS[0];
        let climber = hook + Vec2::new(-1.0, -1.0) * (8.0 / 2f32.sqrt());
        Grapple {
            rope: rope_to(hook, climber, Vec2::default()),
            hook: 0,
            reeling: false,
            time: 0.0,
            floor: [
                Collider::half_space(Vec2::new(0.0, FLOOR), Vec2::new(0.0, 1.0))
                    .and_then(|c| c.with_friction(0.6, 0.5))
                    .ok()
                    .expect("a valid floor"),
            ],
            unconverged_frames: 0,
            slow_frames: 0,
            largest_off: 0.0,
        }
    }

    pub fn time(&self) -> f32 {
        self.time
    }

    /// Where the climber is (m).
    pub fn climber(&self) -> Vec2<f32> {
        self.rope.positions()[PARTICLES - 1]
    }

    /// Whether the climber has reached the last hook: on it, reeled in within 2 m.
    pub fn won(&self) -> bool {
        self.hook + 1 == HOOKS.len() && self.rope.length() <= 2.0
    }

    /// Throws the rope to hook `i`: a new rope from it to the climber, who keeps their
    /// velocity (the rope's particles take theirs in proportion along it); returns whether
    /// it caught (the hook is another, and within [`REACH`] and beyond [`SHORTEST`]).
    pub fn throw(&mut self, i: usize) -> bool {
        let Some(&hook) = HOOKS.get(i) else {
            return false;
        };
        let climber = self.climber();
        let distance = hook.distance(climber);
        if i == self.hook || !(SHORTEST..=REACH).contains(&distance) {
            return false;
        }
        let velocity = self.rope.velocities()[PARTICLES - 1];
        self.rope = rope_to(hook, climber, velocity);
        self.hook = i;
        true
    }

    /// One frame: the reel winds while [`reeling`](Self::reeling), the rope steps on the
    /// floor's contacts with its particles.
    pub fn step(&mut self) {
        self.time += STEP;
        if self.reeling {
            self.rope
                .reel(SHORTEST, REEL_SPEED, STEP)
                .ok()
                .expect("the reel's target is within the rope's limits");
        }
        let floor = Contacts::new(&self.floor, 0.05, Touch::Particles)
            .ok()
            .expect("a valid floor");
        let info = self
            .rope
            .step_touching_particles(STEP, (), &floor)
            .ok()
            .expect("the rope stays stable");
        self.unconverged_frames += u32::from(!info.converged);
        self.slow_frames += u32::from(info.slow_motion);
        let chain: f32 = (self.rope.positions().windows(2))
            .map(|w| w[0].distance(w[1]))
            .sum();
        let length = self.rope.length();
        self.largest_off = self.largest_off.max((chain - length).abs() / length);
    }

    /// The computer's play, for the demo: reel in down to 4 m; swinging forward past the
    /// hook, throw to the next one if it is in reach.
    pub fn auto(&mut self) {
        let (climber, hook) = (self.climber(), HOOKS[self.hook]);
        let last = self.hook + 1 == HOOKS.len();
        self.reeling = self.rope.length() > if last { SHORTEST } else { 4.0 };
        let v = self.rope.velocities()[PARTICLES - 1];
        if !last && v.x > 1.0 && v.y > 0.0 && climber.x > hook.x + 1.0 {
            self.throw(self.hook + 1);
        }
    }

    /// The rope drawn as the player sees it: a Catmull-Rom curve through its particles
    /// (drawn as the catapult's is, so that the page holds one drawing code); how many
    /// points it drew.
    pub fn drawn(&self, points: &mut [Vec2<f32>; DRAWN]) -> usize {
        let mut pieces = [Piece::EMPTY; 1];
        match self.rope.draw(Smoothing::CatmullRom, points, &mut pieces) {
            Ok(1) => pieces[0].points.end,
            _ => 0,
        }
    }

    /// The scene as text, `w × h` characters, 24 m wide round the climber: the floor, the
    /// hooks, the rope and the climber.
    pub fn render(&self, w: usize, h: usize) -> Vec<String> {
        let mut cells = vec![b' '; w * h];
        let mut canvas = Canvas::new(&mut cells, w, h).ok().expect("a valid canvas");
        let left = (self.climber().x - 12.0).clamp(-6.0, HOOKS[HOOKS.len() - 1].x - 18.0);
        let view = View::new(Vec2::new(left, 13.0), 24.0 / w as f32, 14.0 / h as f32)
            .ok()
            .expect("a valid view");
        let (_, floor) = view.cell(Vec2::new(0.0, FLOOR));
        canvas.line((0, floor), (w as i32 - 1, floor), b'=');
        canvas.points(&view, &HOOKS, b'o');
        let mut points = [Vec2::default(); DRAWN];
        let n = self.drawn(&mut points);
        canvas.polyline(&view, &points[..n], b'#');
        canvas.points(&view, &[self.climber()], b'@');
        canvas
            .rows()
            .map(|r| String::from_utf8_lossy(r).into_owned())
            .collect()
    }
}

/// A rope from `hook` (held) to the climber at `climber` moving at `velocity`, its
/// particles moving in proportion along it.
fn rope_to(hook: Vec2<f32>, climber: Vec2<f32>, velocity: Vec2<f32>) -> HookRope {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping: 0.02,
        ..Settings::default()
    }
    .with_integrator(DirectChain {
        iterations: 8,
        ..DirectChain::default()
    });
    let material = Material {
        stiffness: 2000.0,
        damping: 1.0,
    };
    let mut rope = Rope::new(hook, climber, ROPE_MASS, material, settings)
        .ok()
        .expect("the hook and the climber apart");
    rope.set_inv_mass(0, 0.0).ok().expect("a particle");
    rope.hang(PARTICLES - 1, CLIMBER)
        .ok()
        .expect("the end is free");
    for i in 1..PARTICLES {
        let share = i as f32 / (PARTICLES - 1) as f32;
        rope.set_velocity(i, velocity * share)
            .ok()
            .expect("a finite velocity");
    }
    rope
}
