//! The scripted scene whose state checksums ([`MassSpring::state_hash`]) every platform
//! must agree on, frame by frame, for rollback netplay: the catapult rope (8 particles,
//! 70 units, a bob of 2) held by a hand that moves every frame (the game's input), swinging
//! against a ball with contacts on its drawn Catmull-Rom curve, reeled in to 45 units and
//! paid out again, cut across by a swipe at frame 300, and what the hand still holds reeled
//! in to 30. [`hashes`] folds its 600 frames' checksums into one; `tests/golden.txt` holds
//! the value in `Q16` and `f32`, which the host (`tests/suite/rollback.rs`), the
//! Cortex-M0 and M4F (`examples/mcu_peg.rs`) and a `.wasm` under node (`examples/golden.rs`)
//! must reproduce.
//!
//! [`MassSpring::state_hash`]: dunas::MassSpring::state_hash

// Each crate that shares it uses part of it.
#![allow(dead_code)]

use dunas::StateHash;
use dunas::breaking::Piece;
use dunas::prelude::*;

/// Frames the scene runs.
pub const FRAMES: u32 = 600;
/// The frame whose swipe cuts the rope.
pub const CUT_AT: u32 = 300;

/// The rope, its ball, its drawn curve and pieces, and the frames so far.
#[derive(Clone)]
pub struct Scene<S: Scalar> {
    pub rope: Rope<Vec2<S>, 8>,
    ball: [Collider<Vec2<S>>; 1],
    points: [Vec2<S>; 33],
    pieces: [Piece; 8],
    drawn: usize,
    pub frame: u32,
}

impl<S: Scalar> Scene<S> {
    /// The scene at frame 0.
    pub fn new() -> Result<Self, Error> {
        let px = |v: i16| S::from_i16(v);
        let settings = Settings {
            gravity: Vec2::new(px(0), px(-200)),
            damping: S::ratio(1, 10),
            ..Settings::default()
        };
        let material = Material {
            stiffness: px(300),
            damping: S::ratio(1, 2),
        };
        let end = Vec2::new(px(45), -S::ratio(536, 10));
        let mut rope = Rope::new(Vec2::new(px(0), px(0)), end, px(7), material, settings)?;
        rope.hang(7, px(2))?;
        Ok(Scene {
            rope,
            ball: [Collider::ball(Vec2::new(px(-6), px(-30)), px(4))?],
            points: [Vec2::new(S::ZERO, S::ZERO); 33],
            pieces: [Piece::EMPTY; 8],
            drawn: 0,
            frame: 0,
        })
    }

    /// One frame with the scripted input ([`input`]).
    pub fn advance(&mut self) -> Result<(), Error> {
        self.advance_with(input(self.frame))
    }

    /// One frame: the hand to `hand_x` (the game's input), the reel (in, out, and in again
    /// after the cut), the swipe at [`CUT_AT`], the step with the ball's contacts, the
    /// drawing.
    pub fn advance_with(&mut self, hand_x: i8) -> Result<(), Error> {
        self.play(hand_x, true)
    }

    /// [`advance_with`](Self::advance_with) without the reel (to meter what reeling costs).
    pub fn advance_plain(&mut self, hand_x: i8) -> Result<(), Error> {
        self.play(hand_x, false)
    }

    fn play(&mut self, hand_x: i8, reels: bool) -> Result<(), Error> {
        let px = |v: i16| S::from_i16(v);
        let dt = S::ratio(1, 60);
        self.rope
            .move_pinned(0, Vec2::new(px(i16::from(hand_x)), px(0)), dt)?;
        // (target, units a second)
        let reel = match self.frame {
            _ if !reels => None,
            30..=160 => Some((45, 12)),
            180..=280 => Some((70, 15)),
            400..=500 => Some((30, 20)),
            _ => None,
        };
        if let Some((target, speed)) = reel {
            self.rope.reel(px(target), px(speed), dt)?;
        }
        if self.frame == CUT_AT {
            let swipe = (Vec2::new(px(-60), px(-20)), Vec2::new(px(60), px(-40)));
            let drawn = &self.pieces[..self.drawn];
            self.rope.cut(&self.points, drawn, swipe.0, swipe.1)?;
        }
        let contacts = Contacts::new(&self.ball, px(2), Touch::Drawn(Smoothing::CatmullRom))?;
        let _ = self.rope.step_touching(dt, (), &contacts)?;
        self.drawn = self
            .rope
            .draw(Smoothing::CatmullRom, &mut self.points, &mut self.pieces)?;
        self.frame += 1;
        Ok(())
    }
}

/// The value `tests/golden.txt` holds for `format` (`q16` or `f32`), if it holds one.
pub fn expected(format: &str) -> Option<u64> {
    let line = include_str!("../../tests/golden.txt")
        .lines()
        .find_map(|l| l.strip_prefix(format)?.strip_prefix('='))?;
    u64::from_str_radix(line.trim(), 16).ok()
}

/// The hand's x at `frame`, the scene's scripted input: a zigzag 20 units wide, 40 frames
/// a stroke.
pub fn input(frame: u32) -> i8 {
    let stroke = (frame % 80) as i8;
    (if stroke < 40 { stroke } else { 80 - stroke }) / 2 - 10
}

/// Every frame's [`MassSpring::state_hash`](dunas::MassSpring::state_hash), folded into one.
pub fn hashes<S: Scalar>() -> Result<u64, Error> {
    let mut scene = Scene::<S>::new()?;
    let mut all = StateHash::new();
    while scene.frame < FRAMES {
        scene.advance()?;
        all.add_u64(scene.rope.state_hash());
    }
    Ok(all.finish())
}
