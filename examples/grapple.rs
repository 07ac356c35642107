//! The grappling hook: a climber swings on a rope from a hook in a cave's roof, reels itself
//! in, and throws the rope to the next hook, hook after hook to the last (the computer
//! plays). The rope is 8 particles solved together each frame (`DirectChain`), reeled with
//! `Rope::reel`, drawn as a Catmull-Rom curve; a new throw is a new rope from the hook to
//! the climber, who keeps their speed.
//!
//! Run: `cargo run --release --example grapple` (`q`, Esc or Ctrl-C stops). When standard
//! output is not a terminal it prints a few frames as text and how far the rope's chain
//! ever got from its length. In the browser (`web/`) the player throws and reels.

#[path = "common/grapple.rs"]
mod grapple;
#[path = "common/term.rs"]
mod term;

use std::io;
use std::time::{Duration, Instant};

use grapple::{Grapple, HOOKS};
use term::{Screen, wants_to_quit};

const W: usize = 72;
const H: usize = 20;

fn status(game: &Grapple) -> String {
    let climber = game.climber();
    format!(
        " t = {:4.1} s   hook {} of {}, rope {:.1} m{}   climber at ({:.1}, {:.1}) m   chain within {:.2}% of the rope's length ({} steps flagged by a solve on the way){}",
        game.time(),
        game.hook + 1,
        HOOKS.len(),
        game.rope.length(),
        if game.reeling { " (reeling in)" } else { "" },
        climber.x,
        climber.y,
        game.largest_off * 100.0,
        game.unconverged_frames,
        if game.won() {
            "   on the last hook!"
        } else {
            ""
        },
    )
}

fn animate() -> io::Result<()> {
    let screen = Screen::enter()?;
    let mut game = Grapple::new();
    let mut won_for = 0;
    loop {
        let frame_end = Instant::now() + Duration::from_secs_f32(grapple::STEP);
        game.auto();
        game.step();
        let title = " dunas grappling hook   (q quits)".to_string();
        let lines = std::iter::once(title)
            .chain(game.render(W, H))
            .chain(std::iter::once(status(&game)));
        screen.show(lines)?;
        won_for += u32::from(game.won());
        if won_for > 120 || game.time() > 60.0 || wants_to_quit(frame_end)? {
            return Ok(());
        }
    }
}

/// Not a terminal: a few frames as text, then the end.
fn print_frames() {
    let mut game = Grapple::new();
    for until in [1.0f32, 4.0, 9.0] {
        while game.time() < until {
            game.auto();
            game.step();
        }
        println!("t = {:.1} s", game.time());
        for line in game.render(W, H) {
            println!("{}", line.trim_end());
        }
        println!("{}\n", status(&game));
    }
    while !game.won() && game.time() < 60.0 {
        game.auto();
        game.step();
    }
    for line in game.render(W, H) {
        println!("{}", line.trim_end());
    }
    println!("{}", status(&game));
}

fn main() {
    term::play("grapple", animate, print_frames);
}
