//! The catapult game's scene, shared by `examples/catapult.rs`, the browser page (`web/`)
//! and their tests: a hand whirls a rope with a penguin on its end, lets go at the click, and
//! the penguin flies a ballistic arc to the snow; a swipe across the drawn rope cuts it.
//! Metres, seconds, kilograms; y up.
#![allow(dead_code)]
// `.ok().expect(..)` rather than `.expect(..)`: the message is the same, and `Error`'s
// `Debug` (with the float formatting it brings, 40 KB) stays out of the browser's .wasm.
#![allow(clippy::ok_expect)]

use dunas::ascii::{Canvas, View};
use dunas::body::Body;
use dunas::breaking::Piece;
use dunas::integrator::DirectChain;
use dunas::prelude::*;

/// The frame step.
pub const STEP: f32 = 1.0 / 60.0;
/// Where the snow is.
pub const GROUND: f32 = -3.0;
/// The penguin's mass (kg); the rope weighs 0.4 kg.
pub const PENGUIN: f32 = 3.0;
/// The rope's length (m).
pub const ROPE_LENGTH: f32 = 1.6;
/// The hand whirls on a circle of this radius (m) round the origin (an inextensible rope
/// stores nothing to fling the penguin with, so the hand does the work)...
pub const HAND_RADIUS: f32 = 0.8;
/// ...at this many turns a second (counter-clockwise), after a second of spin-up.
const TURNS: f32 = 1.0;
/// The game clicks by itself once the penguin has whirled this long and heads up and forward
/// (unless the player clicks: [`Catapult::played`]).
const CLICK_AFTER: f32 = 3.0;
/// The rope's radius (m): a cut piece lies on the snow.
const THICKNESS: f32 = 0.03;
/// Points the drawn rope has: 5 a span (it is drawn one curve a piece once cut).
pub const DRAWN: usize = 36;

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
    /// Whether the game clicks by itself (`false`: the player clicks with [`Catapult::let_go`]).
    auto_click: bool,
    /// The player's click, carried out at the next frame's end.
    clicked: bool,
    /// The snow, which a cut piece of rope falls on.
    snow: [Collider<Vec2<f32>>; 1],
    /// Frames whose step hit the substep cap and simulated less than the frame.
    pub slow_frames: u32,
    /// Frames whose step said it left a link more than 0.1% off (`StepInfo::converged`).
    pub unconverged_frames: u32,
    /// The largest stretch of the rope (its particles' chain) while the penguin hangs on it
    /// (0.01 is 1%).
    pub largest_stretch: f32,
}

impl Catapult {
    /// The game that clicks by itself, 3 s in, when the penguin heads up and forward.
    pub fn new() -> Catapult {
        Catapult {
            auto_click: true,
            ..Catapult::played()
        }
    }

    /// The game the player clicks ([`let_go`](Catapult::let_go)).
    pub fn played() -> Catapult {
        let settings = Settings {
            gravity: Vec2::new(0.0, -9.81),
            damping: 0.05,
            ..Settings::default()
        }
        .with_integrator(DirectChain {
            iterations: 6,
            inextensible: true,
            substeps: 6,
            halvings: 6,
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
        .ok()
        .expect("a valid rope");
        rope.hang(7, PENGUIN).ok().expect("the end is free");
        Catapult {
            rope,
            penguin: Penguin::Swinging,
            released: None,
            trail: Vec::new(),
            time: 0.0,
            auto_click: false,
            clicked: false,
            snow: [
                Collider::half_space(Vec2::new(0.0, GROUND), Vec2::new(0.0, 1.0))
                    .and_then(|c| c.with_friction(0.5, 0.4))
                    .ok()
                    .expect("a valid floor"),
            ],
            slow_frames: 0,
            unconverged_frames: 0,
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
            .ok()
            .expect("the hand stays in range");
        // The whirled rope cannot reach the snow; a cut piece falls on it (the contacts' extra
        // substeps are paid only then). The snow is wide: its particles touch it, and the
        // browser page links no curve contacts.
        let info = if self.pieces() > 1 {
            let snow = Contacts::new(&self.snow, THICKNESS, Touch::Particles)
                .ok()
                .expect("valid");
            self.rope.step_touching_particles(STEP, (), &snow)
        } else {
            self.rope.step(STEP)
        }
        .ok()
        .expect("the rope stays stable");
        self.slow_frames += u32::from(info.slow_motion);
        self.unconverged_frames += u32::from(!info.converged);
        if self.penguin == Penguin::Swinging && self.pieces() == 1 {
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
                let auto = self.auto_click && self.time > CLICK_AFTER;
                if self.clicked || (auto && (30.0..60.0).contains(&heading)) {
                    let body = self
                        .rope
                        .release(7, PENGUIN)
                        .ok()
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
        self.clicked = false;
    }

    /// The player's click: the hand lets go of the penguin at the end of the next frame
    /// (nothing once it has left the rope).
    pub fn let_go(&mut self) {
        self.clicked = true;
    }

    /// The rope drawn as the player sees it: a Catmull-Rom curve through its particles, one
    /// a piece; returns how many pieces `pieces[..n]` says are in `points`.
    pub fn drawn(&self, points: &mut [Vec2<f32>; DRAWN], pieces: &mut [Piece; 8]) -> usize {
        self.rope
            .draw(Smoothing::CatmullRom, points, pieces)
            .unwrap_or(0)
    }

    /// How many pieces the rope is in (1 until it is cut).
    pub fn pieces(&self) -> usize {
        self.rope.pieces().count()
    }

    /// A swipe from `from` to `to` (m) cuts the rope where it crosses its drawn curve first;
    /// returns whether it cut. The penguin stays on its piece.
    pub fn cut(&mut self, from: Vec2<f32>, to: Vec2<f32>) -> bool {
        let (mut points, mut pieces) = ([Vec2::default(); DRAWN], [Piece::EMPTY; 8]);
        let n = self.drawn(&mut points, &mut pieces);
        matches!(self.rope.cut(&points, &pieces[..n], from, to), Ok(Some(_)))
    }

    /// The penguin's trail since it left the rope (m).
    pub fn trail(&self) -> &[Vec2<f32>] {
        &self.trail
    }

    /// Where the penguin is (m).
    pub fn penguin_at(&self) -> Vec2<f32> {
        match self.penguin {
            Penguin::Swinging => self.rope.positions()[7],
            Penguin::Flying(body) => body.position,
            Penguin::Landed { x, .. } => Vec2::new(x, GROUND),
        }
    }

    /// The scene as text, `w × h` characters: the snow, the hand, the rope, the penguin and
    /// its trail.
    pub fn render(&self, w: usize, h: usize) -> Vec<String> {
        let mut cells = vec![b' '; w * h];
        let mut canvas = Canvas::new(&mut cells, w, h).ok().expect("a valid canvas");
        let view = View::new(Vec2::new(-3.0, 2.5), 24.0 / w as f32, 6.0 / h as f32)
            .ok()
            .expect("a valid view");
        let (_, snow) = view.cell(Vec2::new(0.0, GROUND));
        canvas.line((0, snow), (w as i32 - 1, snow), b'=');
        let (mut points, mut pieces) = ([Vec2::default(); DRAWN], [Piece::EMPTY; 8]);
        let n = self.drawn(&mut points, &mut pieces);
        for piece in &pieces[..n] {
            canvas.polyline(&view, &points[piece.points.clone()], b'#');
        }
        canvas.points(&view, &self.trail, b'.');
        canvas.points(&view, &self.rope.positions()[..1], b'H');
        canvas.points(&view, &[self.penguin_at()], b'@');
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
