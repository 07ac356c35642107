//! A closed loop: a ring of 12 particles on loop and bending springs, hung from one particle
//! like a hoop on a nail, pushed by a gust, and drawn as a seamless closed B-spline.
//!
//! Run: `cargo run --release --example loop` (prints three frames as text).

use dunas::Settings;
use dunas::ascii::{Canvas, View};
use dunas::force::Wind;
use dunas::smooth::{Smoothed, Smoothing};
use dunas::spring::{Material, Springs};
use dunas::{Rope, Vec2};

const N: usize = 12;
const W: usize = 40;
const H: usize = 20;

fn main() {
    let ring: [Vec2<f32>; N] = core::array::from_fn(|i| {
        let a = std::f32::consts::TAU * i as f32 / N as f32 + std::f32::consts::FRAC_PI_2;
        Vec2::new(12.0 * a.cos(), 12.0 * a.sin() - 12.0)
    });
    // Loop springs between neighbours plus bending springs two apart keep the hoop round.
    let mut springs = Springs::<f32, 24>::closed_loop(
        &ring,
        Material {
            stiffness: 4000.0,
            damping: 2.0,
        },
    )
    .expect("valid");
    for i in 0..N {
        springs
            .connect(&ring, i, (i + 2) % N)
            .expect("valid bending spring");
    }
    let mut inv = [1.0; N];
    inv[0] = 0.0; // the nail
    let settings = Settings {
        gravity: Vec2::new(0.0, -100.0),
        damping: 0.2,
        ..Settings::default()
    };
    let mut hoop = Rope::from_parts(ring, inv, springs, settings).expect("valid loop");
    let mut wind = Wind::still(0.05);
    wind.gust = Vec2::new(600.0, 0.0);
    wind.gust_start = 0.2;
    wind.gust_length = 0.8;
    let mut curve = [Vec2::default(); 61];
    for (frame, until) in [0.3f32, 0.8, 1.6].into_iter().enumerate() {
        while hoop.time() < until - 1e-3 {
            let info = hoop
                .step_with(1.0 / 60.0, &mut wind)
                .expect("the hoop stays stable");
            if info.slow_motion {
                eprintln!(
                    "t = {:.2} s: slow motion (the substep cap was hit)",
                    hoop.time()
                );
            }
        }
        let n = Smoothed::closed(Smoothing::BSpline, hoop.position_array())
            .and_then(|c| c.sample(&mut curve))
            .expect("the hoop stays in range and the buffer holds a point a span");
        let mut cells = [b' '; W * H];
        let mut canvas = Canvas::new(&mut cells, W, H).expect("sized buffer");
        let view = View::new(Vec2::new(-20.0, 2.0), 1.0, 2.0).expect("positive cells");
        canvas.polyline(&view, &curve[..n], b'#');
        canvas.points(&view, hoop.positions(), b'o');
        println!("frame {} at t = {:.1} s", frame + 1, hoop.time());
        for row in canvas.rows() {
            println!("{}", String::from_utf8_lossy(row).trim_end());
        }
        println!();
    }
}
