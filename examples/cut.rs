//! Cut the rope: a candy hangs on two ropes (one rope of 9 particles pinned at both ends,
//! the candy hung on its middle particle); a scripted swipe cuts the left rope, the candy
//! swings out on the right one, a second swipe cuts that at the top of the swing, and the
//! candy falls to the monster below. Each swipe is tested against the
//! rope *as drawn* (a natural spline through 9 particles), and cuts the span it crosses.
//!
//! Run: `cargo run --release --example cut` (`q`, Esc or Ctrl-C stops). When standard output
//! is not a terminal it prints a few frames as text.

#[path = "common/term.rs"]
mod term;

use std::io;
use std::time::{Duration, Instant};

use dunas::ascii::{Canvas, View};
use dunas::breaking::Piece;
use dunas::prelude::*;
use term::{Screen, wants_to_quit};

const STEP: f32 = 1.0 / 60.0;
const W: usize = 60;
const H: usize = 20;
const SMOOTHING: Smoothing = Smoothing::NaturalSpline;
/// The scripted swipes: when, and from where to where (metres).
const SWIPES: [(f32, [f32; 2], [f32; 2]); 2] = [
    (1.5, [-3.9, 1.8], [-1.5, 1.8]),
    (3.3, [1.5, 1.8], [3.9, 1.8]),
];
/// The monster's mouth, and the floor.
const MOUTH: [f32; 2] = [5.5, -4.0];

struct Game {
    rope: Rope<Vec2<f32>, 9>,
    points: [Vec2<f32>; 81],
    pieces: [Piece; 9],
    drawn: usize,
    /// The swipe shown this frame, and what it cut.
    swipe: Option<(Vec2<f32>, Vec2<f32>)>,
    cuts: Vec<usize>,
    time: f32,
}

impl Game {
    fn new() -> Game {
        let settings = Settings {
            gravity: Vec2::new(0.0, -9.81),
            damping: 0.3,
            ..Settings::default()
        };
        let material = Material {
            stiffness: 800.0,
            damping: 1.0,
        };
        let mut rope = Rope::new(
            Vec2::new(-3.0, 2.0),
            Vec2::new(3.0, 2.0),
            0.3,
            material,
            settings,
        )
        .expect("a valid rope");
        rope.set_inv_mass(8, 0.0).expect("the right pin");
        rope.hang(4, 1.0).expect("the candy hangs in the middle");
        let mut game = Game {
            rope,
            points: [Vec2::default(); 81],
            pieces: [Piece::EMPTY; 9],
            drawn: 0,
            swipe: None,
            cuts: Vec::new(),
            time: 0.0,
        };
        game.draw();
        game
    }

    fn draw(&mut self) {
        self.drawn = self
            .rope
            .draw(SMOOTHING, &mut self.points, &mut self.pieces)
            .expect("the buffers hold the rope");
    }

    /// One frame: the swipe due now cuts what the player saw last frame, then the rope steps
    /// (the candy stops at the floor) and is drawn.
    fn step(&mut self) {
        self.time += STEP;
        self.swipe = None;
        for (at, from, to) in SWIPES {
            if (self.time - at).abs() < STEP / 2.0 {
                let (from, to) = (Vec2::new(from[0], from[1]), Vec2::new(to[0], to[1]));
                let cut = self
                    .rope
                    .cut(&self.points, &self.pieces[..self.drawn], from, to)
                    .expect("a finite swipe over the drawn rope");
                self.cuts.extend(cut);
                self.swipe = Some((from, to));
            }
        }
        let info = self.rope.step(STEP).expect("the rope stays stable");
        if info.slow_motion {
            eprintln!(
                "t = {:.2} s: slow motion (the substep cap was hit)",
                self.time
            );
        }
        for i in 0..9 {
            let p = self.rope.positions()[i];
            if p.y < MOUTH[1] && self.rope.inv_masses()[i] > 0.0 {
                let _ = self.rope.set_position(i, Vec2::new(p.x, MOUTH[1]));
                let _ = self.rope.set_velocity(i, Vec2::default());
            }
        }
        self.draw();
    }

    fn render(&self) -> Vec<String> {
        let mut cells = vec![b' '; W * H];
        let mut canvas = Canvas::new(&mut cells, W, H).expect("a valid canvas");
        let view =
            View::new(Vec2::new(-4.0, 3.0), 12.0 / W as f32, 8.0 / H as f32).expect("a valid view");
        let (_, floor) = view.cell(Vec2::new(0.0, MOUTH[1]));
        canvas.line((0, floor + 1), (W as i32 - 1, floor + 1), b'=');
        for piece in &self.pieces[..self.drawn] {
            canvas.polyline(&view, &self.points[piece.points.clone()], b'#');
        }
        let (mx, my) = view.cell(Vec2::new(MOUTH[0], MOUTH[1]));
        canvas.text(mx - 2, my, b"\\___/");
        let pins = [self.rope.positions()[0], self.rope.positions()[8]];
        canvas.points(&view, &pins, b'+');
        if let Some((from, to)) = self.swipe {
            canvas.line(view.cell(from), view.cell(to), b'/');
        }
        canvas.points(&view, &self.rope.positions()[4..5], b'@');
        let mut lines: Vec<String> = canvas
            .rows()
            .map(|r| String::from_utf8_lossy(r).into_owned())
            .collect();
        let candy = self.rope.positions()[4];
        let eaten = (candy.y - MOUTH[1]).abs() < 0.05 && (candy.x - MOUTH[0]).abs() < 0.6;
        lines.push(format!(
            " t = {:3.1} s   pieces: {}   cut between particles {:?}{}",
            self.time,
            self.drawn,
            self.cuts.iter().map(|i| (i, i + 1)).collect::<Vec<_>>(),
            if eaten { "   om nom!" } else { "" }
        ));
        lines
    }
}

fn animate() -> io::Result<()> {
    let screen = Screen::enter()?;
    let mut game = Game::new();
    while game.time < 6.0 {
        let frame_end = Instant::now() + Duration::from_secs_f32(STEP);
        game.step();
        let title = " dunas: cut the rope   (q quits)".to_string();
        screen.show(std::iter::once(title).chain(game.render()))?;
        if game.swipe.is_some() {
            std::thread::sleep(Duration::from_millis(250));
        }
        if wants_to_quit(frame_end)? {
            break;
        }
    }
    Ok(())
}

/// Not a terminal: a few frames as text.
fn print_frames() {
    let mut game = Game::new();
    for (n, until) in [1.0f32, 1.5, 2.3, 3.3, 3.8, 5.0].into_iter().enumerate() {
        while game.time < until - 1e-3 {
            game.step();
        }
        println!("frame {} at t = {:.1} s", n + 1, game.time);
        for line in game.render() {
            println!("{}", line.trim_end());
        }
        println!();
    }
}

fn main() {
    term::play("cut", animate, print_frames);
}
