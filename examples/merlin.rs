//! The thesis's Merlin rope: a wizard hanging from a flying sleigh on a rope whose every
//! particle is also tied to the first (a hub), beside the same rope as a plain chain.
//!
//! The hub springs keep each particle at its distance from the sleigh, so the rope swings like
//! a stiff but bendy pole instead of whipping: the configuration a game designer tuned for a
//! fun ride rather than realism. Both ropes are drawn as smoothed B-splines.
//!
//! Run: `cargo run --release --example merlin` (prints three frames as text).

use dunas::Settings;
use dunas::ascii::{Canvas, View};
use dunas::smooth::Smoothing;
use dunas::spring::{Material, Springs};
use dunas::{Rope, Vec2};

const N: usize = 8;
const W: usize = 38;
const H: usize = 18;

fn rope(hub: bool) -> Rope<Vec2<f32>, N, 13> {
    let pos: [Vec2<f32>; N] = core::array::from_fn(|i| Vec2::new(-6.0 * i as f32, -4.0 * i as f32));
    let material = Material {
        stiffness: 2500.0,
        damping: 2.0,
    };
    let springs = if hub {
        Springs::hub(&pos, material)
    } else {
        Springs::chain(&pos, material)
    };
    let mut inv = [1.0; N];
    inv[0] = 0.0; // the sleigh
    inv[N - 1] = 0.2; // Merlin
    let settings = Settings {
        gravity: Vec2::new(0.0, -150.0),
        damping: 0.3,
        ..Settings::default()
    };
    Rope::from_parts(pos, inv, springs.expect("valid topology"), settings).expect("valid rope")
}

/// The sleigh flies right and bobs.
fn sleigh(t: f32) -> Vec2<f32> {
    Vec2::new(0.0, 6.0 * (t * 2.5).sin())
}

fn main() {
    let mut ropes = [rope(true), rope(false)];
    let mut curve = [Vec2::default(); 48];
    for (frame, until) in [0.8f32, 1.6, 2.4].into_iter().enumerate() {
        while ropes[0].time() < until - 1e-3 {
            for r in ropes.iter_mut() {
                let t = r.time();
                r.set_position(0, sleigh(t)).expect("in range");
                let info = r.step(1.0 / 60.0).expect("the rope stays stable");
                if info.slow_motion {
                    eprintln!("t = {t:.2} s: slow motion (the substep cap was hit)");
                }
            }
        }
        println!(
            "frame {} at t = {:.1} s: hub rope (Merlin) | plain chain",
            frame + 1,
            ropes[0].time()
        );
        let view = View::new(Vec2::new(-38.0, 12.0), 2.0, 4.0).expect("positive cells");
        let mut panels = Vec::new();
        for r in &ropes {
            let mut cells = [b' '; W * H];
            let mut canvas = Canvas::new(&mut cells, W, H).expect("sized buffer");
            let n = r
                .sample(Smoothing::BSpline, &mut curve)
                .expect("buffer holds 2+");
            canvas.polyline(&view, &curve[..n], b'#');
            canvas.points(&view, &r.positions()[..1], b'S');
            canvas.points(&view, &r.positions()[N - 1..], b'M');
            panels.push(
                canvas
                    .rows()
                    .map(|row| String::from_utf8_lossy(row).into_owned())
                    .collect::<Vec<_>>(),
            );
        }
        for (a, b) in panels[0].iter().zip(&panels[1]) {
            println!("{a}|{b}");
        }
        println!();
    }
}
