//! The catapult scene of the rope demo, shared with its snapshot test: three ropes of the same
//! length, mass and material swinging from a pin with a weight on the end, hit by a gust,
//! against two thin pegs and a wall. The smoothed rope touches them with its drawn curve; the
//! raw ones with their particles, so pegs thinner than the spacing slip through the raw 8.
#![allow(dead_code)]

use std::time::{Duration, Instant};

use dunas::ascii::{Canvas, View};
use dunas::force::Wind;
use dunas::prelude::*;

/// Panel size in characters.
pub const PANEL_W: usize = 26;
pub const PANEL_H: usize = 22;
/// Points drawn for the smoothed rope.
pub const CURVE_POINTS: usize = 64;

const LENGTH: f32 = 70.0;
const MASS: f32 = 7.0;
/// Whole-rope stiffness: a segment of a rope cut into `n` springs is `n` times stiffer, so
/// every rope stretches alike (about 1 unit under the weight) and the finer one needs more
/// substeps to stay stable.
const ROPE_STIFFNESS: f32 = 1500.0;
const WEIGHT_INV_MASS: f32 = 1.0;

fn rope<const N: usize>() -> Rope<Vec2<f32>, N> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -200.0),
        damping: 0.05,
        ..Settings::default()
    };
    let segments = (N - 1) as f32;
    let material = Material {
        stiffness: ROPE_STIFFNESS * segments,
        damping: 0.5 * segments,
    };
    // Pulled back 35° from hanging, as a catapult is before the release.
    let (sin, cos) = (0.574, 0.819);
    let end = Vec2::new(LENGTH * sin, -LENGTH * cos);
    let mut r = Rope::new(Vec2::new(0.0, 0.0), end, MASS, material, settings).expect("valid rope");
    r.set_inv_mass(N - 1, WEIGHT_INV_MASS)
        .expect("index in range"); // the penguin
    r
}

/// Pegs of radius 1.5 (0.15× the spacing of 8 particles, 0.6× that of 30) the ropes swing
/// against, and a wall on the left.
pub const PEGS: [(f32, f32); 2] = [(-22.0, -50.0), (8.0, -58.0)];
const PEG_RADIUS: f32 = 1.5;
pub const WALL_X: f32 = -50.0;
/// The ropes' radius.
const THICKNESS: f32 = 0.5;

/// The pegs and the wall as colliders, a little slippery.
pub fn colliders() -> [Collider<Vec2<f32>>; 3] {
    let peg = |(x, y)| {
        Collider::ball(Vec2::new(x, y), PEG_RADIUS)
            .and_then(|c| c.with_friction(0.2, 0.1))
            .expect("a valid peg")
    };
    let wall = Collider::half_space(Vec2::new(WALL_X, 0.0), Vec2::new(1.0, 0.0)).expect("a wall");
    [peg(PEGS[0]), peg(PEGS[1]), wall]
}

/// A wind that gusts sideways from 3 s to 5 s.
pub fn gust() -> Wind<Vec2<f32>> {
    let mut w = Wind::still(0.02);
    w.gust = Vec2::new(-120.0, 30.0);
    w.gust_start = 3.0;
    w.gust_length = 2.0;
    w
}

/// A rope's cost per frame: the median of the last 120 frames (a median, so that a cold
/// first frame or a preempted one does not skew it).
#[derive(Default)]
pub struct Cost {
    recent: Vec<u32>,
    next: usize,
}

impl Cost {
    const KEEP: usize = 120;

    fn add(&mut self, d: Duration) {
        let ns = d.as_nanos().min(u32::MAX as u128) as u32;
        if self.recent.len() < Self::KEEP {
            self.recent.push(ns);
        } else {
            self.recent[self.next] = ns;
        }
        self.next = (self.next + 1) % Self::KEEP;
    }

    /// Median nanoseconds per frame over the recent frames.
    pub fn ns(&self) -> f64 {
        let mut v = self.recent.clone();
        v.sort_unstable();
        v.get(v.len() / 2).map_or(0.0, |&m| m as f64)
    }
}

pub struct Scene {
    smooth8: Rope<Vec2<f32>, 8>,
    raw8: Rope<Vec2<f32>, 8>,
    raw30: Rope<Vec2<f32>, 30>,
    curve: [Vec2<f32>; CURVE_POINTS],
    wind: Wind<Vec2<f32>>,
    colliders: [Collider<Vec2<f32>>; 3],
    /// Cost per frame of each rope: physics step plus the points it draws.
    pub costs: [Cost; 3],
    /// Whether each rope's last step ran in slow motion (its substep cap was hit).
    slow: [bool; 3],
    held_at: Vec2<f32>,
}

impl Scene {
    pub fn new() -> Self {
        Scene {
            smooth8: rope(),
            raw8: rope(),
            raw30: rope(),
            curve: [Vec2::default(); CURVE_POINTS],
            wind: gust(),
            colliders: colliders(),
            costs: Default::default(),
            slow: [false; 3],
            held_at: Self::hand(0.0),
        }
    }

    /// Simulated seconds.
    pub fn time(&self) -> f32 {
        self.smooth8.time()
    }

    /// Where the hand holding the ropes is at time `t`: still, then shaking sideways from
    /// 1 s to 3.5 s (which sends waves down the ropes), then still again.
    pub fn hand(t: f32) -> Vec2<f32> {
        if !(1.0..3.5).contains(&t) {
            return Vec2::new(0.0, 0.0);
        }
        Vec2::new(6.0 * (std::f32::consts::TAU * (t - 1.0) / 1.0).sin(), 0.0)
    }

    /// One fixed step of `dt` for every rope, timing each (step + drawing points).
    pub fn step(&mut self, dt: f32) {
        let hand = Self::hand(self.time() + dt);
        self.held_at = hand;
        for pin in [
            &mut self.smooth8.set_position(0, hand),
            &mut self.raw8.set_position(0, hand),
            &mut self.raw30.set_position(0, hand),
        ] {
            pin.as_ref().expect("the hand stays in range");
        }
        let touch = |touch| Contacts::new(&self.colliders, THICKNESS, touch).expect("valid");
        let (curve, particles) = (
            touch(Touch::Drawn(Smoothing::BSpline)),
            touch(Touch::Particles),
        );
        let t = Instant::now();
        let smooth8 = self
            .smooth8
            .step_touching(dt, &mut self.wind, &curve)
            .expect("the rope stays stable");
        self.smooth8
            .sample(Smoothing::BSpline, &mut self.curve)
            .expect("the curve buffer holds 2 points or more");
        self.costs[0].add(t.elapsed());
        let t = Instant::now();
        let raw8 = self
            .raw8
            .step_touching(dt, &mut self.wind, &particles)
            .expect("the rope stays stable");
        self.costs[1].add(t.elapsed());
        let t = Instant::now();
        let raw30 = self
            .raw30
            .step_touching(dt, &mut self.wind, &particles)
            .expect("the rope stays stable");
        self.costs[2].add(t.elapsed());
        self.slow = [smooth8, raw8, raw30].map(|info| info.slow_motion);
    }

    /// Where the hand held the ropes during the last step.
    pub fn held_at(&self) -> Vec2<f32> {
        self.held_at
    }

    /// What each panel draws: the smoothed curve of the 8 particles, the 8 particles, the 30.
    pub fn drawn(&self) -> [&[Vec2<f32>]; 3] {
        [&self.curve, self.raw8.positions(), self.raw30.positions()]
    }

    /// The three panels as text lines; with `costs`, a line of cost per frame under each.
    pub fn render(&self, costs: bool) -> Vec<String> {
        // 84 world units across a panel, the pin at the top middle, cells twice as tall as
        // wide like a terminal's.
        let cw = 84.0 / PANEL_W as f32;
        let view = View::new(Vec2::new(-60.0, 2.0 * cw), cw, 2.0 * cw).expect("positive cell size");
        let [curve, raw8, raw30] = self.drawn();
        let panels = [
            ("8 particles, smoothed", curve, self.smooth8.positions()),
            ("8 particles, raw", raw8, raw8),
            ("30 particles, raw", raw30, &[][..]),
        ];
        let mut lines = vec![String::new(); PANEL_H];
        for (k, (title, line, dots)) in panels.into_iter().enumerate() {
            let mut cells = [b' '; PANEL_W * PANEL_H];
            let mut canvas =
                Canvas::new(&mut cells, PANEL_W, PANEL_H).expect("buffer sized for the canvas");
            let wall = [Vec2::new(WALL_X, 10.0), Vec2::new(WALL_X, -150.0)];
            canvas.polyline(&view, &wall, b'|');
            canvas.points(&view, &PEGS.map(|(x, y)| Vec2::new(x, y)), b'@');
            canvas.polyline(&view, line, b'#');
            canvas.points(&view, dots, b'o');
            canvas.text(1, 0, title.as_bytes());
            for (out, row) in lines.iter_mut().zip(canvas.rows()) {
                if k > 0 {
                    out.push('|');
                }
                out.push_str(&String::from_utf8_lossy(row));
            }
        }
        if costs {
            // A rope whose substep cap was hit simulates less than the frame: say so.
            let cell = |c: &Cost, slow: bool| {
                let note = if slow { " SLOW MOTION" } else { "" };
                format!("{:>8.0} ns/frame{note}", c.ns())
            };
            let cells: Vec<String> = self
                .costs
                .iter()
                .zip(self.slow)
                .map(|(c, slow)| format!("{:<w$}", cell(c, slow), w = PANEL_W))
                .collect();
            lines.push(cells.join(" "));
        }
        lines
    }
}
