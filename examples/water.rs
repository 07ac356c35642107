//! Water a 2D game's boats ride: a 12 m pool of 48 columns (`water::Water`), a crate dropped
//! in on the left making waves, a raft floating on the right riding them, the surface drawn
//! as a Catmull-Rom curve through the columns (`~`), the bodies as boxes (`#`).
//!
//! Run: `cargo run --release --example water` (prints three frames as text).
use dunas::ascii::{Canvas, View};
use dunas::water::{Floater, Water};
use dunas::{Smoothing, Vec2};

const COLUMNS: usize = 48;
const W: usize = 60;
const H: usize = 16;

fn main() {
    let mut pool = Water::<f32, COLUMNS>::new(0.0, 0.25, 2.0, 3.0, 1000.0)
        .and_then(|w| w.with_damping(0.3))
        .expect("a valid pool");
    // A crate held 1 m above the surface, and a raft at rest on it.
    let mut bodies = [
        Floater::new(2.5, 3.0, 0.8, 0.6, 250.0).expect("a valid crate"),
        Floater::new(8.5, 1.9, 1.6, 0.3, 160.0).expect("a valid raft"),
    ];
    let mut curve = [Vec2::default(); 4 * (COLUMNS - 1) + 1];
    let view = View::new(Vec2::new(0.0, 4.0), 0.2, 0.25).expect("positive cells");
    let mut time = 0.0f32;
    for (frame, until) in [0.5f32, 1.5, 4.0].into_iter().enumerate() {
        while time < until - 1e-3 {
            let info = pool
                .step(1.0 / 60.0, 9.81, &mut bodies)
                .expect("the pool stays calm enough");
            if info.slow_motion {
                eprintln!("t = {time:.2} s: slow motion (the substep cap was hit)");
            }
            time += 1.0 / 60.0;
        }
        let n = pool
            .draw(Smoothing::CatmullRom, &mut curve)
            .expect("the buffer holds 4 points a span");
        let mut cells = [b' '; W * H];
        let mut canvas = Canvas::new(&mut cells, W, H).expect("sized buffer");
        canvas.polyline(&view, &curve[..n], b'~');
        for b in &bodies {
            let (l, r) = (b.x - b.width / 2.0, b.x + b.width / 2.0);
            let (bottom, top) = (b.bottom, b.bottom + b.height);
            let outline = [
                Vec2::new(l, bottom),
                Vec2::new(r, bottom),
                Vec2::new(r, top),
                Vec2::new(l, top),
                Vec2::new(l, bottom),
            ];
            canvas.polyline(&view, &outline, b'#');
        }
        println!(
            "frame {} at t = {:.1} s (the raft's bottom {:.2} m, the far wall's surface {:.3} m)",
            frame + 1,
            time,
            bodies[1].bottom,
            pool.heights()[COLUMNS - 1]
        );
        for row in canvas.rows() {
            println!("{}", String::from_utf8_lossy(row).trim_end());
        }
        println!();
    }
}
