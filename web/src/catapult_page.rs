//! The catapult on the page: the game of `examples/common/catapult.rs` played with the mouse
//! or a finger (a click or a tap lets go, a swipe across the rope cuts it), drawn as the
//! smooth rope with its 8 raw particles over it, by a camera that frames the whirl and then
//! the flight, on a canvas of any shape (a phone held either way).

use dunas::breaking::Piece;
use dunas::{Point as _, Vec2};

use crate::catapult::{self, Catapult, DRAWN, GROUND, Penguin, landing_x};
use crate::draw_list::{DrawList, Style};
use crate::view::View;

/// The penguin's and the hand's radii (m).
const PENGUIN_RADIUS: f32 = 0.3;
const HAND_RADIUS: f32 = 0.1;
/// Room kept round what the camera frames (m).
const MARGIN: f32 = 0.4;
/// The share of the way to its aim the camera moves each frame (about a third of a second
/// to get most of the way).
const EASE: f32 = 0.1;

/// A game on a canvas.
pub struct CatapultPage {
    pub game: Catapult,
    pub view: View,
    /// The canvas size (pixels).
    size: [f32; 2],
    /// The world box the camera shows now (m): it eases towards [`aim`](Self::aim).
    shown: (Vec2<f32>, Vec2<f32>),
}

impl CatapultPage {
    pub fn new(width: f32, height: f32) -> CatapultPage {
        let game = Catapult::played();
        let shown = aim(&game);
        let size = [width.max(1.0), height.max(1.0)];
        CatapultPage {
            view: View::fit(shown.0, shown.1, size[0], size[1]),
            game,
            size,
            shown,
        }
    }

    /// The canvas changed size: the same game, framed anew.
    pub fn resize(&mut self, width: f32, height: f32) {
        self.size = [width.max(1.0), height.max(1.0)];
        self.view = View::fit(self.shown.0, self.shown.1, self.size[0], self.size[1]);
    }

    /// One frame: the game steps, and the camera moves towards what it should frame.
    pub fn step(&mut self) {
        self.game.step();
        let (min, max) = aim(&self.game);
        let ease = |from: Vec2<f32>, to: Vec2<f32>| from + (to - from) * EASE;
        self.shown = (ease(self.shown.0, min), ease(self.shown.1, max));
        self.view = View::fit(self.shown.0, self.shown.1, self.size[0], self.size[1]);
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
        list.push(Style::Snow, &[0.0, snow, self.size[0], snow]);
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

/// What the camera frames (m): the snow under the catapult and the whole whirl (the hand's
/// circle, the rope, the penguin) while the penguin whirls; from the release, also the
/// penguin, the top of its arc and where the arc meets the snow.
fn aim(game: &Catapult) -> (Vec2<f32>, Vec2<f32>) {
    // A band of snow below, and less room above the whirl than below it.
    let reach = catapult::HAND_RADIUS + catapult::ROPE_LENGTH + PENGUIN_RADIUS;
    let (mut min, mut max) = (
        Vec2::new(-reach - MARGIN, GROUND - 1.5 * MARGIN),
        Vec2::new(reach + MARGIN, reach + 0.5 * MARGIN),
    );
    if !matches!(game.penguin, Penguin::Swinging) {
        let at = game.penguin_at();
        let margin = Vec2::new(PENGUIN_RADIUS + MARGIN, PENGUIN_RADIUS + MARGIN);
        (min, max) = (min.min_coords(at - margin), max.max_coords(at + margin));
        if let Some((from, launch)) = game.released {
            let g = game.rope.settings().gravity.y;
            let x = landing_x(from, launch, g);
            let top = from.y + launch.y.max(0.0).powi(2) / (2.0 * -g);
            if x.is_finite() && top.is_finite() {
                (min.x, max.x) = (min.x.min(x - 2.0 * MARGIN), max.x.max(x + 2.0 * MARGIN));
                max.y = max.y.max(top + PENGUIN_RADIUS + MARGIN);
            }
        }
    }
    (min, max)
}
