//! The catapult game (the thesis's first sample): a hand whirls a rope with a penguin on its
//! end, lets go at the click, and the penguin flies a ballistic arc into the snow. The rope
//! is 8 particles drawn as a Catmull-Rom curve; the hand moves the rope's first particle with
//! `move_pinned` (so the rope feels its speed), the penguin hangs on the last with `hang`, and
//! `release` hands it back as a `Body` with the rope's momentum.
//!
//! Run: `cargo run --release --example catapult` (`q`, Esc or Ctrl-C stops). When standard
//! output is not a terminal it prints a few frames as text, and where the penguin landed
//! against the closed-form arc from where it left the rope.

#[path = "common/catapult.rs"]
mod catapult;
#[path = "common/term.rs"]
mod term;

use std::io;
use std::time::{Duration, Instant};

use catapult::{Catapult, Penguin, landing_x};
use dunas::Point;
use term::{Screen, wants_to_quit};

const W: usize = 72;
const H: usize = 20;

fn status(game: &Catapult) -> String {
    let line = match game.penguin {
        Penguin::Swinging => format!(" t = {:4.1} s   whirling...", game.time()),
        Penguin::Flying(body) => format!(
            " t = {:4.1} s   flying at {:.1} m/s",
            game.time(),
            body.velocity.length()
        ),
        Penguin::Landed { x, from, launch } => format!(
            " landed at x = {x:.3} m; the closed-form arc from ({:.2}, {:.2}) m at ({:.2}, {:.2}) m/s lands at {:.3} m",
            from.x,
            from.y,
            launch.x,
            launch.y,
            landing_x(from, launch, -9.81)
        ),
    };
    // The rope's links are solved together each frame: it holds its length under the
    // penguin, and each step says whether it kept every link within 0.1%
    // (`StepInfo::converged`).
    let line = format!(
        "{line}   (largest stretch {:.1}%, {} frames beyond 0.1%)",
        game.largest_stretch * 100.0,
        game.unconverged_frames
    );
    match game.slow_frames {
        0 => line,
        n => {
            format!("{line}   (slow motion in {n} frames: the rope is too stiff for its substeps)")
        }
    }
}

fn animate() -> io::Result<()> {
    let screen = Screen::enter()?;
    let mut game = Catapult::new();
    let mut landed_for = 0;
    loop {
        let frame_end = Instant::now() + Duration::from_secs_f32(catapult::STEP);
        game.step();
        let title = " dunas catapult   (q quits)".to_string();
        let lines = std::iter::once(title)
            .chain(game.render(W, H))
            .chain(std::iter::once(status(&game)));
        screen.show(lines)?;
        if matches!(game.penguin, Penguin::Landed { .. }) {
            landed_for += 1;
        }
        if landed_for > 180 || wants_to_quit(frame_end)? {
            return Ok(());
        }
    }
}

/// Not a terminal: a few frames as text, then the landing.
fn print_frames() {
    let mut game = Catapult::new();
    let mut frame = 0;
    for until in [2.0f32, 3.6, 4.2] {
        while game.time() < until && !matches!(game.penguin, Penguin::Landed { .. }) {
            game.step();
        }
        frame += 1;
        println!("frame {frame} at t = {:.1} s", game.time());
        for line in game.render(W, H) {
            println!("{}", line.trim_end());
        }
        println!("{}\n", status(&game));
    }
    while !matches!(game.penguin, Penguin::Landed { .. }) && game.time() < 30.0 {
        game.step();
    }
    println!("frame {} at t = {:.1} s", frame + 1, game.time());
    for line in game.render(W, H) {
        println!("{}", line.trim_end());
    }
    println!("{}", status(&game));
}

fn main() {
    term::play("catapult", animate, print_frames);
}
