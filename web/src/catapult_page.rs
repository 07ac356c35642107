//! The catapult on the page: the game of `examples/common/catapult.rs` played with the mouse
//! (a click lets go, a swipe across the rope cuts it), drawn as the smooth rope with its 8
//! raw particles over it.

use dunas::Vec2;
use dunas::breaking::Piece;

use crate::catapult::{Catapult, DRAWN, GROUND, Penguin, landing_x};
use crate::draw_list::{DrawList, Style};
use crate::view::View;

/// The world the canvas shows (m): the hand's circle, the snow, and where penguins land.
const WORLD_MIN: Vec2<f32> = Vec2::new(-9.0, -3.6);
const WORLD_MAX: Vec2<f32> = Vec2::new(11.0, 3.0);
/// The penguin's and the hand's radii (m).
const PENGUIN_RADIUS: f32 = 0.3;
const HAND_RADIUS: f32 = 0.1;

/// A game on a canvas.
pub struct CatapultPage {
    pub game: Catapult,
    pub view: View,
    /// The canvas width (pixels).
    width: f32,
}

impl CatapultPage {
    pub fn new(width: f32, height: f32) -> CatapultPage {
        CatapultPage {
            game: Catapult::played(),
            view: View::fit(WORLD_MIN, WORLD_MAX, width, height),
            width,
        }
    }

    /// A click at a canvas pixel: lets go of the penguin while it whirls; once it has landed,
    /// a new game.
    pub fn click(&mut self) {
        match self.game.penguin {
            Penguin::Swinging => self.game.let_go(),
            Penguin::Flying(_) => {}
            Penguin::Landed { .. } => self.game = Catapult::played(),
        }
    }

    /// A swipe between two canvas pixels; returns whether it cut the rope.
    pub fn swipe(&mut self, from: [f32; 2], to: [f32; 2]) -> bool {
        let (a, b) = (
            self.view.world(from[0], from[1]),
            self.view.world(to[0], to[1]),
        );
        self.game.cut(a, b)
    }

    /// Where the closed-form arc from the release meets the snow (m), once released.
    pub fn arc_x(&self) -> Option<f32> {
        let (from, launch) = self.game.released?;
        Some(landing_x(from, launch, self.game.rope.settings().gravity.y))
    }

    /// The frame's records.
    pub fn draw(&self, list: &mut DrawList) {
        let view = &self.view;
        let px = |p: Vec2<f32>| view.pixel(p);
        let [_, snow] = px(Vec2::new(0.0, GROUND));
        list.push(Style::Snow, &[0.0, snow, self.width, snow]);
        if let Some(x) = self.arc_x() {
            list.push(Style::Target, &px(Vec2::new(x, GROUND)));
        }
        list.points(Style::Trail, self.game.trail().iter().map(|&p| px(p)));
        let (mut points, mut pieces) = ([Vec2::default(); DRAWN], [Piece::EMPTY; 8]);
        let n = self.game.drawn(&mut points, &mut pieces);
        let particles = self.game.rope.positions();
        for piece in &pieces[..n] {
            list.points(
                Style::Rope,
                points[piece.points.clone()].iter().map(|&p| px(p)),
            );
            let raw = &particles[piece.particles.clone()];
            list.points(Style::Particles, raw.iter().map(|&p| px(p)));
        }
        let ([hx, hy], [ox, oy]) = (px(particles[0]), px(Vec2::default()));
        list.push(Style::Hand, &[hx, hy, HAND_RADIUS * view.scale, ox, oy]);
        // A landed penguin sits on the snow.
        let lift = match self.game.penguin {
            Penguin::Landed { .. } => PENGUIN_RADIUS,
            _ => 0.0,
        };
        let [x, y] = px(self.game.penguin_at() + Vec2::new(0.0, lift));
        list.push(Style::Penguin, &[x, y, PENGUIN_RADIUS * view.scale]);
    }
}
