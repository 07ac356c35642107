//! The grappling hook on the page: the game of `examples/common/grapple.rs` played with the
//! mouse or a finger (a tap on a hook in reach throws the rope to it; a press anywhere else
//! reels in while it lasts), followed by a camera along the cave.

use dunas::{Point as _, Vec2};

use crate::draw_list::{DrawList, Style};
use crate::grapple::{CLIMBER_RADIUS, DRAWN, FLOOR, Grapple, HOOKS, PARTICLES, REACH, SHORTEST};
use crate::view::View;

/// The share of the way to its aim the camera moves each frame.
const EASE: f32 = 0.08;
/// How much of the cave the camera shows round the climber (m): wide, and from below the
/// floor to above the roof.
const SHOWN_WIDTH: f32 = 16.0;
const SHOWN_BOTTOM: f32 = FLOOR - 0.8;
const SHOWN_TOP: f32 = 13.5;

/// A game on a canvas.
pub struct GrapplePage {
    pub game: Grapple,
    pub view: View,
    size: [f32; 2],
    /// The x the camera is centred on now (m).
    centre: f32,
}

impl GrapplePage {
    pub fn new(width: f32, height: f32) -> GrapplePage {
        let game = Grapple::new();
        let centre = aim(&game);
        let size = [width.max(1.0), height.max(1.0)];
        GrapplePage {
            view: frame(centre, size),
            game,
            size,
            centre,
        }
    }

    /// The canvas changed size: the same game, framed anew.
    pub fn resize(&mut self, width: f32, height: f32) {
        self.size = [width.max(1.0), height.max(1.0)];
        self.view = frame(self.centre, self.size);
    }

    /// One frame: the game steps, the camera follows the climber.
    pub fn step(&mut self) {
        self.game.step();
        self.centre += (aim(&self.game) - self.centre) * EASE;
        self.view = frame(self.centre, self.size);
    }

    /// A press at a canvas pixel: on a hook in reach, the rope is thrown to it; anywhere
    /// else the reel winds in until [`lift`](Self::lift). Once on the last hook, a new game.
    pub fn press(&mut self, x: f32, y: f32) {
        if self.game.won() {
            *self = GrapplePage::new(self.size[0], self.size[1]);
            return;
        }
        // A finger is about 40 CSS px wide: a hook within 2 m or 24 px of it counts.
        let at = self.view.world(x, y);
        let slack = 24.0 / self.view.scale;
        let near = (0..HOOKS.len())
            .filter(|&i| HOOKS[i].distance(at) <= slack.max(2.0))
            .min_by(|&a, &b| HOOKS[a].distance(at).total_cmp(&HOOKS[b].distance(at)));
        match near {
            Some(i) if i != self.game.hook => {
                self.game.throw(i);
            }
            _ => self.game.reeling = true,
        }
    }

    /// The press ended: the reel stops.
    pub fn lift(&mut self) {
        self.game.reeling = false;
    }

    /// Whether a throw from where the climber is would catch hook `i`.
    fn in_reach(&self, i: usize) -> bool {
        let d = HOOKS[i].distance(self.game.climber());
        i != self.game.hook && (SHORTEST..=REACH).contains(&d)
    }

    /// The frame's records.
    pub fn draw(&self, list: &mut DrawList) {
        let view = &self.view;
        let px = |p: Vec2<f32>| view.pixel(p);
        // The roof: a rock edge just above the hooks, between them.
        let mut roof = vec![px(Vec2::new(HOOKS[0].x - 30.0, HOOKS[0].y + 0.6))];
        roof.extend(HOOKS.iter().map(|h| px(*h + Vec2::new(0.0, 0.25))));
        roof.push(px(Vec2::new(
            HOOKS[HOOKS.len() - 1].x + 30.0,
            HOOKS[HOOKS.len() - 1].y + 0.6,
        )));
        list.points(Style::Roof, roof);
        let [_, floor] = px(Vec2::new(0.0, FLOOR));
        list.push(Style::Snow, &[0.0, floor, self.size[0], floor]);
        for (i, &hook) in HOOKS.iter().enumerate() {
            let [x, y] = px(hook);
            let reach = f32::from(u8::from(self.in_reach(i)));
            list.push(Style::Hook, &[x, y, 0.18 * view.scale, reach]);
        }
        if self.game.won() {
            let [x, y] = px(HOOKS[HOOKS.len() - 1]);
            list.push(Style::Target, &[x, y - 0.3 * view.scale]);
        }
        let mut points = [Vec2::default(); DRAWN];
        let n = self.game.drawn(&mut points);
        list.points(Style::Rope, points[..n].iter().map(|&p| px(p)));
        let particles = self.game.rope.positions();
        list.points(Style::Particles, particles.iter().map(|&p| px(p)));
        let [x, y] = px(particles[PARTICLES - 1]);
        list.push(Style::Penguin, &[x, y, CLIMBER_RADIUS * view.scale]);
    }
}

/// Where the camera would centre (m): on the climber, within the cave's hooks.
fn aim(game: &Grapple) -> f32 {
    let (first, last) = (HOOKS[0].x, HOOKS[HOOKS.len() - 1].x);
    game.climber().x.clamp(first - 2.0, last + 2.0)
}

/// The view of the cave centred on `centre`: [`SHOWN_WIDTH`] wide and from
/// [`SHOWN_BOTTOM`] to [`SHOWN_TOP`] high, whichever the canvas holds whole.
fn frame(centre: f32, [width, height]: [f32; 2]) -> View {
    let half = SHOWN_WIDTH / 2.0;
    View::fit(
        Vec2::new(centre - half, SHOWN_BOTTOM),
        Vec2::new(centre + half, SHOWN_TOP),
        width,
        height,
    )
}
