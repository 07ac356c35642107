//! Closed loops: a ring of 12 particles on loop and bending springs, hung from one particle
//! like a hoop on a nail, pushed by a gust, and drawn as a seamless closed B-spline (`#`);
//! beside it a jelly, a ring of 10 particles blown up by the gas inside it
//! (`force::Pressure`), dropped on the floor, squashing and bouncing (`*`).
//!
//! Run: `cargo run --release --example loop` (prints three frames as text).

use dunas::Settings;
use dunas::ascii::{Canvas, View};
use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::force::{Pressure, Wind};
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
    // The jelly: 10 particles on a ring of radius 4, soft springs, gas at 120 units of
    // pressure, dropped from above the floor at y = -34.
    let blob: [Vec2<f32>; 10] = core::array::from_fn(|i| {
        let a = std::f32::consts::TAU * i as f32 / 10.0;
        Vec2::new(14.0 + 4.0 * a.cos(), -20.0 + 4.0 * a.sin())
    });
    let blob_springs = Springs::<f32, 10>::closed_loop(
        &blob,
        Material {
            stiffness: 300.0,
            damping: 1.0,
        },
    )
    .expect("valid");
    let mut jelly = Rope::from_parts(blob, [1.0; 10], blob_springs, settings).expect("valid jelly");
    let mut gas = Pressure::at(120.0, Pressure::area(&blob)).expect("valid gas");
    let floor = [Collider::half_space(Vec2::new(0.0, -34.0), Vec2::new(0.0, 1.0)).expect("valid")];
    let on_floor = Contacts::new(&floor, 0.5, Touch::Particles).expect("valid");
    let mut curve = [Vec2::default(); 61];
    let mut blob_curve = [Vec2::default(); 51];
    for (frame, until) in [0.3f32, 0.8, 1.6].into_iter().enumerate() {
        while jelly.time() < until - 1e-3 {
            let _ = jelly
                .step_touching_particles(1.0 / 60.0, &mut gas, &on_floor)
                .expect("the jelly stays stable");
        }
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
        let m = Smoothed::closed(Smoothing::BSpline, jelly.position_array())
            .and_then(|c| c.sample(&mut blob_curve))
            .expect("the jelly stays in range");
        canvas.polyline(&view, &blob_curve[..m], b'*');
        canvas.points(&view, jelly.positions(), b'o');
        println!(
            "frame {} at t = {:.1} s (the jelly's area {:.0} units², from {:.0})",
            frame + 1,
            hoop.time(),
            Pressure::area(jelly.positions()),
            Pressure::area(&blob)
        );
        for row in canvas.rows() {
            println!("{}", String::from_utf8_lossy(row).trim_end());
        }
        println!();
    }
}
