//! Loads a cloth from the thesis's two XML files (a scene and a mass-spring description),
//! hangs it from its top row, simulates three seconds and prints a frame of the smoothed patch.
//!
//! Run: `cargo run --release --features xml --example load_xml -- examples/data/cloth_scene.xml examples/data/cloth_physics.xml`
//!
//! A malformed file ends with `file:line:column: what is wrong` and exit status 1.

use std::path::Path;

use dunas::ascii::{Canvas, View};
use dunas::spring::Topology;
use dunas::{Patch, Vec3, xml};

const W: usize = 48;
const H: usize = 22;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [scene, physics] = &args[..] else {
        eprintln!("usage: load_xml SCENE.xml PHYSICS.xml");
        std::process::exit(2);
    };
    // The thesis's sample is a 4×4 patch with 54 connections; the sizes are compile-time.
    let mut cloth = match xml::load_cloth::<f32, 4, 4, 64>(Path::new(scene), Path::new(physics)) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("load_xml: {e}");
            std::process::exit(1);
        }
    };
    for i in 0..4 {
        cloth.set_inv_mass(i, 0.0).expect("index in range"); // hang it from the top row
    }
    for _ in 0..180 {
        let _ = cloth.step(1.0 / 60.0).expect("the cloth stays stable");
    }
    let patch = Patch::new(*cloth.position_array()).expect("positions stay in range");
    let mut grid = [Vec3::default(); 12 * 12];
    patch
        .sample_grid(12, 12, &mut grid)
        .expect("buffer holds the grid");
    let mut cells = [b' '; W * H];
    let mut canvas = Canvas::new(&mut cells, W, H).expect("sized buffer");
    let view = View::new(Vec3::new(-12.0, 10.0, 0.0), 0.5, 1.0).expect("positive cells");
    for row in grid.chunks(12) {
        canvas.polyline(&view, row, b'~');
    }
    canvas.points(&view, cloth.positions(), b'o');
    let springs = cloth.topology().spring_count();
    println!(
        "{scene} and {physics}: 16 particles, {springs} springs, after 3 s hanging from the top row"
    );
    for row in canvas.rows() {
        println!("{}", String::from_utf8_lossy(row).trim_end());
    }
}
