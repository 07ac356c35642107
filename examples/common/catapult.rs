//! The catapult game's scene, shared by `examples/catapult.rs` and its test: a hand whirls a
//! rope with a penguin on its end, lets go at the click, and the penguin flies a ballistic
//! arc to the snow. Metres, seconds, kilograms; y up.
#![allow(dead_code)]

use dunas::ascii::{Canvas, View};
use dunas::body::Body;
use dunas::integrator::DirectChain;
use dunas::prelude::*;

/// The frame step.
pub const STEP: f32 = 1.0 / 60.0;
/// Where the snow is.
pub const GROUND: f32 = -3.0;
/// The penguin's mass (kg); the rope weighs 0.4 kg.
pub const PENGUIN: f32 = 3.0;
/// The rope's length (m).
const ROPE_LENGTH: f32 = 1.6;
/// The hand whirls on a circle of this radius (m) round the origin (an inextensible rope
/// stores nothing to fling the penguin with, so the hand does the work)...
const HAND_RADIUS: f32 = 0.8;
/// ...at this many turns a second (counter-clockwise), after a second of spin-up.
const TURNS: f32 = 1.0;
/// The player clicks once the penguin has whirled this long and heads up and forward.
const CLICK_AFTER: f32 = 3.0;

/// Where the penguin is: on the rope, in the air, or landed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Penguin {
    Swinging,
    Flying(Body<Vec2<f32>>),
    /// Landed at this x (m), after flying from `from` with velocity `launch`.
    Landed {
        x: f32,
        from: Vec2<f32>,
        launch: Vec2<f32>,
    },
}

pub struct Catapult {
    /// The rope's links solved together each frame ([`DirectChain`]): it does not stretch
    /// under the penguin.
    pub rope: Rope<Vec2<f32>, 8, 8, DirectChain>,
    pub penguin: Penguin,
    /// Where and how fast the penguin left the rope.
    pub released: Option<(Vec2<f32>, Vec2<f32>)>,
    trail: Vec<Vec2<f32>>,
    time: f32,
    /// Frames whose step hit the substep cap and simulated less than the frame.
    pub slow_frames: u32,
    /// The largest stretch of the rope (its particles' chain) while the penguin hangs on it
    /// (0.01 is 1%).
    pub largest_stretch: f32,
}

impl Catapult {
    pub fn new() -> Catapult {
        let settings = Settings {
            gravity: Vec2::new(0.0, -9.81),
            damping: 0.05,
            ..Settings::default()
        }
        .with_integrator(DirectChain {
            iterations: 6,
            inextensible: true,
            substeps: 6,
        });
        let material = Material {
            stiffness: 4000.0,
            damping: 4.0,
        };
        let mut rope = Rope::new(
            Vec2::new(HAND_RADIUS, 0.0),
            Vec2::new(HAND_RADIUS, -ROPE_LENGTH),
            0.4,
            material,
            settings,
        )
        .expect("a valid rope");
        rope.hang(7, PENGUIN).expect("the end is free");
        Catapult {
            rope,
            penguin: Penguin::Swinging,
            released: None,
            trail: Vec::new(),
            time: 0.0,
            slow_frames: 0,
            largest_stretch: 0.0,
        }
    }

    pub fn time(&self) -> f32 {
        self.time
    }

    /// Where the hand is at time `t`: it speeds up over the first second.
    fn hand(t: f32) -> Vec2<f32> {
        let ramp = (t.min(1.0) * t.min(1.0) * 0.5 + (t - 1.0).max(0.0)) * TURNS;
        let a = std::f32::consts::TAU * ramp;
        Vec2::new(HAND_RADIUS * a.cos(), HAND_RADIUS * a.sin())
    }

    /// One frame: the hand moves, the rope steps, the penguin flies; the click comes once
    /// the penguin heads up and forward at 30° to 60°.
    pub fn step(&mut self) {
        self.time += STEP;
        self.rope
            .move_pinned(0, Self::hand(self.time), STEP)
            .expect("the hand stays in range");
        let info = self.rope.step(STEP).expect("the rope stays stable");
        self.slow_frames += u32::from(info.slow_motion);
        if self.penguin == Penguin::Swinging {
            let length: f32 = self
                .rope
                .positions()
                .windows(2)
                .map(|pair| pair[0].distance(pair[1]))
                .sum();
            self.largest_stretch = self.largest_stretch.max(length / ROPE_LENGTH - 1.0);
        }
        match self.penguin {
            Penguin::Swinging => {
                let v = self.rope.velocities()[7];
                let heading = v.y.atan2(v.x).to_degrees();
                if self.time > CLICK_AFTER && (30.0..60.0).contains(&heading) {
                    let body = self
                        .rope
                        .release(7, PENGUIN)
                        .expect("the penguin hangs there");
                    self.released = Some((body.position, body.velocity));
                    self.penguin = Penguin::Flying(body);
                }
            }
            Penguin::Flying(mut body) => {
                let before = body.position;
                body.fly(STEP, self.rope.settings().gravity);
                self.trail.push(body.position);
                self.penguin = if body.position.y <= GROUND {
                    // The frame crossed the snow: where along its chord.
                    let (from, launch) = self.released.unwrap_or_default();
                    let t = (before.y - GROUND) / (before.y - body.position.y);
                    let x = before.x + (body.position.x - before.x) * t;
                    Penguin::Landed { x, from, launch }
                } else {
                    Penguin::Flying(body)
                };
            }
            Penguin::Landed { .. } => {}
        }
    }

    /// The scene as text, `w × h` characters: the snow, the hand, the rope, the penguin and
    /// its trail.
    pub fn render(&self, w: usize, h: usize) -> Vec<String> {
        let mut cells = vec![b' '; w * h];
        let mut canvas = Canvas::new(&mut cells, w, h).expect("a valid canvas");
        let view =
            View::new(Vec2::new(-3.0, 2.5), 24.0 / w as f32, 6.0 / h as f32).expect("a valid view");
        let (_, snow) = view.cell(Vec2::new(0.0, GROUND));
        canvas.line((0, snow), (w as i32 - 1, snow), b'=');
        let (mut points, mut pieces) = ([Vec2::default(); 40], [dunas::breaking::Piece::EMPTY; 8]);
        if let Ok(n) = self
            .rope
            .draw(Smoothing::CatmullRom, &mut points, &mut pieces)
        {
            for piece in &pieces[..n] {
                canvas.polyline(&view, &points[piece.points.clone()], b'#');
            }
        }
        canvas.points(&view, &self.trail, b'.');
        canvas.points(&view, &self.rope.positions()[..1], b'H');
        let penguin = match self.penguin {
            Penguin::Swinging => self.rope.positions()[7],
            Penguin::Flying(body) => body.position,
            Penguin::Landed { x, .. } => Vec2::new(x, GROUND),
        };
        canvas.points(&view, &[penguin], b'@');
        canvas
            .rows()
            .map(|r| String::from_utf8_lossy(r).into_owned())
            .collect()
    }
}

/// Where a body leaving `from` at `launch` under gravity `g` (negative, along y) meets the
/// snow: the closed-form root of `y(t) = GROUND`.
pub fn landing_x(from: Vec2<f32>, launch: Vec2<f32>, g: f32) -> f32 {
    let (y0, vy, g) = (from.y as f64 - GROUND as f64, launch.y as f64, -g as f64);
    let t = (vy + (vy * vy + 2.0 * g * y0).sqrt()) / g;
    (from.x as f64 + launch.x as f64 * t) as f32
}
