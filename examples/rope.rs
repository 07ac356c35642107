//! The main demo: the same catapult rope three ways, side by side in the terminal.
//!
//! Left, 8 particles drawn through a B-spline curve (the Dunas way); middle, the same 8 particles
//! drawn raw; right, 30 particles drawn raw, what a plain mass-spring rope needs to look smooth.
//! Each rope hangs from a pin with a heavy weight on its end, is released sideways, and a gust
//! of wind passes at 3 s. Under each panel: that rope's cost per frame (physics step, plus the
//! 64 curve points for the smoothed one), measured live.
//!
//! Run: `cargo run --release --example rope` (`--seconds N` to change the 10 s run; `q`, Esc
//! or Ctrl-C to stop). When standard output is not a terminal it prints a few frames as text.

#[path = "common/rope_scene.rs"]
mod rope_scene;
#[path = "common/term.rs"]
mod term;

use std::io;
use std::time::{Duration, Instant};

use dunas::FixedTimestep;
use rope_scene::Scene;
use term::{Screen, wants_to_quit};

const STEP: f32 = 1.0 / 60.0;
const FRAME: Duration = Duration::from_millis(33);

fn seconds_from_args() -> Result<f32, String> {
    let mut args = std::env::args().skip(1);
    let mut seconds = 10.0;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--seconds" => {
                let v = args.next().ok_or("--seconds needs a value")?;
                seconds = v
                    .parse::<f32>()
                    .map_err(|_| format!("--seconds: not a number: {v}"))?;
                if !(seconds > 0.0 && seconds.is_finite()) {
                    return Err("--seconds must be positive".into());
                }
            }
            "-h" | "--help" => {
                println!("usage: rope [--seconds N]   (q, Esc or Ctrl-C stops)");
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument: {other}")),
        }
    }
    Ok(seconds)
}

fn animate(seconds: f32) -> io::Result<()> {
    let mut scene = Scene::new();
    let mut clock = FixedTimestep::new(STEP, 0.25).expect("valid clock");
    let screen = Screen::enter()?;
    let start = Instant::now();
    let mut last = start;
    while start.elapsed().as_secs_f32() < seconds {
        let now = Instant::now();
        for _ in 0..clock.advance((now - last).as_secs_f32()) {
            scene.step(STEP);
        }
        last = now;
        let title = format!(" dunas rope demo   t = {:4.1} s   (q quits)", scene.time());
        screen.show(std::iter::once(title).chain(scene.render(true)))?;
        if wants_to_quit(now + FRAME)? {
            break;
        }
    }
    Ok(())
}

/// Not a terminal: a few frames as plain text.
fn print_frames() {
    let mut scene = Scene::new();
    for (n, at) in [0.4f32, 1.6, 2.3].into_iter().enumerate() {
        while scene.time() < at - 1e-3 {
            scene.step(STEP);
        }
        println!("frame {} at t = {:.1} s", n + 1, scene.time());
        for line in scene.render(true) {
            println!("{}", line.trim_end());
        }
        println!();
    }
}

fn main() {
    let seconds = match seconds_from_args() {
        Ok(s) => s,
        Err(e) => {
            eprintln!("rope: {e}");
            std::process::exit(2);
        }
    };
    term::play("rope", || animate(seconds), print_frames);
}
