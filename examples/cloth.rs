//! The boat scene, as PPM frames: gaff-rigged boats on a sea, their sails filled by gusty wind
//! (`SailWind`, pressure on every facet) and drawn through their particles (a natural spline
//! surface, C² and through every particle).
//!
//! - `sail_wire_NNN.ppm` and `sail_shaded_NNN.ppm`: an 8×8 smoothed sail beside a 20×20 raw
//!   one, each on its boat, wireframe and shaded (Lambert with the surface normals); the 8×8
//!   sail fills against a thin stay with its drawn surface, the 20×20 one with its particles.
//! - `fleet_NNN.ppm`: a fleet (25 boats unless `--boats N`) on the sea, each sail drawn at the
//!   level of detail its distance allows (`lod::surface_segments` at half a pixel).
//!
//! Run: `cargo run --release --example cloth -- OUT_DIR [--size WxH] [--frames N] [--boats N]
//! [--png FILE]` (defaults 640x360, 6 frames a quarter second apart, 25 boats). `--png` also
//! writes the last frames as one contact sheet (the README's picture is
//! `cargo run --release --example cloth -- target/boats --png docs/boats.png`). Prints what
//! each frame cost.

#[path = "common/boats.rs"]
mod boats;
#[path = "common/buoys.rs"]
mod buoys;
#[path = "common/raster.rs"]
mod raster;
#[path = "common/sea.rs"]
mod sea;

use std::path::PathBuf;
use std::time::Instant;

use boats::{
    Boat, CANVAS, Camera, DEPTH_PER_METRE, MAST, SEA, SKY, SPARS, arr, fleet, fleet_camera,
    fleet_view, hull, sail, shade,
};
use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::integrator::{DirectSprings, SymplecticEuler};
use dunas::surface::SurfaceTable;
use dunas::{Smoothing, Vec3, lod};
use raster::Image;
use sea::{Harbour, riding};

const STEP: f32 = 1.0 / 60.0;
const STEPS_PER_FRAME: usize = 15;
/// The most samples a side of a drawn sail (its table size).
const DRAWN: usize = 24;
const SMOOTHING: Smoothing = Smoothing::NaturalSpline;
/// A stay downwind of the sail, 5 cm thick (a tenth of the 8×8 sail's particle spacing):
/// the sail fills against it.
const STAY: ([f32; 3], [f32; 3], f32) = ([1.7, 4.6, 0.75], [1.7, 0.4, 0.75], 0.05);

struct Args {
    out: PathBuf,
    width: usize,
    height: usize,
    frames: usize,
    boats: usize,
    png: Option<PathBuf>,
}

fn parse_args() -> Result<Args, String> {
    let mut args = std::env::args().skip(1);
    let mut out = None;
    let mut png = None;
    let (mut width, mut height, mut frames, mut boats) = (640, 360, 6, 25);
    let number = |v: Option<String>, what: &str| -> Result<usize, String> {
        v.and_then(|v| v.parse().ok())
            .filter(|&n| n > 0)
            .ok_or(format!("{what} needs a positive number"))
    };
    while let Some(a) = args.next() {
        match a.as_str() {
            "--size" => {
                let v = args.next().ok_or("--size needs WxH")?;
                let (w, h) = v
                    .split_once('x')
                    .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
                    .filter(|&(w, h): &(usize, usize)| w >= 32 && h >= 32)
                    .ok_or("--size needs WxH, each at least 32")?;
                (width, height) = (w, h);
            }
            "--frames" => frames = number(args.next(), "--frames")?,
            "--boats" => boats = number(args.next(), "--boats")?,
            "--png" => png = Some(PathBuf::from(args.next().ok_or("--png needs a file")?)),
            other if out.is_none() && !other.starts_with('-') => out = Some(PathBuf::from(other)),
            other => return Err(format!("unknown argument {other}")),
        }
    }
    Ok(Args {
        out: out
            .ok_or("usage: cloth OUT_DIR [--size WxH] [--frames N] [--boats N] [--png FILE]")?,
        width,
        height,
        frames,
        boats,
        png,
    })
}

/// The sky, the sea below the horizon at `horizon` (pixels from the top), darker towards the
/// viewer, with painted swell lines that move with time `t` (none when `t` is `None`: the
/// simulated sea is drawn over it).
fn seascape(w: usize, h: usize, horizon: f32, t: Option<f32>) -> Image {
    let mut img = Image::new(w, h, SKY);
    for y in horizon.max(0.0) as usize..h {
        let near = (y as f32 - horizon) / (h as f32 - horizon).max(1.0);
        let k = 1.0 - 0.45 * near;
        let c = SEA.map(|c| (c * k + 40.0 * (1.0 - near)) as u8);
        img.line([0.0, y as f32], [w as f32, y as f32], c);
    }
    // Swell: crests that bunch up towards the horizon.
    for n in (1..14).take_while(|_| t.is_some()) {
        let t = t.unwrap_or_default();
        let d = n as f32 + (t * 0.4).fract();
        let y = horizon + (h as f32 - horizon) * (1.0 - 1.0 / (0.35 * d + 1.0)) * 1.25;
        let amp = 1.0 + 0.35 * d;
        let light = SEA.map(|c| (c * 1.35 + 30.0).min(255.0) as u8);
        let mut prev = [0.0, y];
        for x in (0..=w).step_by(8) {
            let p = [
                x as f32,
                y + amp * (x as f32 * 0.05 / amp + t * 1.5 + n as f32).sin(),
            ];
            img.line(prev, p, light);
            prev = p;
        }
    }
    img.clear_depth();
    img
}

/// A hull (flat-shaded triangles) and its mast, boom and gaff, through `cam`.
fn draw_boat(img: &mut Image, cam: &Camera) {
    for (tri, base) in hull() {
        let [a, b, c] = tri.map(|p| Vec3::new(p[0], p[1], p[2]));
        let n = (b - a).cross(c - a).normalize().unwrap_or_default();
        let color = shade(arr(n), base);
        img.triangle(tri.map(|p| cam.project(p)), [color; 3]);
    }
    for (a, b) in SPARS {
        let (a, b) = (cam.project(a), cam.project(b));
        let width = (cam.scale / 40.0).clamp(0.0, 2.0) as i32;
        for dx in -width..=width {
            let shift = |p: [f32; 3]| [p[0] + dx as f32, p[1], p[2] - 0.01 * DEPTH_PER_METRE];
            img.line_3d(shift(a), shift(b), MAST);
        }
    }
}

/// Draws a `nu × nv` grid of points (with normals for shading) through `camera`.
fn draw_sail(
    img: &mut Image,
    cam: &Camera,
    (pos, nor): (&[Vec3<f32>], &[Vec3<f32>]),
    (nu, nv): (usize, usize),
    shaded: bool,
) {
    let screen: Vec<[f32; 3]> = pos.iter().map(|&p| cam.project(arr(p))).collect();
    if shaded {
        img.grid(&screen[..nu * nv], nu, |_, p| shade(arr(nor[p]), CANVAS));
        return;
    }
    let ink = [40, 40, 40];
    let flat = |k: usize| [screen[k][0], screen[k][1]];
    for j in 0..nv {
        for i in 0..nu {
            let k = j * nu + i;
            if i + 1 < nu {
                img.line(flat(k), flat(k + 1), ink);
            }
            if j + 1 < nv {
                img.line(flat(k), flat(k + nu), ink);
            }
        }
    }
}

/// Normals of a raw particle grid from central differences of its neighbours.
fn grid_normals<const U: usize, const V: usize>(p: &[Vec3<f32>]) -> Vec<Vec3<f32>> {
    (0..U * V)
        .map(|k| {
            let (i, j) = (k % U, k / U);
            let du = p[j * U + (i + 1).min(U - 1)] - p[j * U + i.saturating_sub(1)];
            let dv = p[(j + 1).min(V - 1) * U + i] - p[j.saturating_sub(1) * U + i];
            du.cross(dv).normalize().unwrap_or(Vec3::new(0.0, 0.0, 1.0))
        })
        .collect()
}

/// A sail's drawn points and normals, and its counts a direction.
type Drawn = (Vec<Vec3<f32>>, Vec<Vec3<f32>>, usize, usize);

/// The lifebuoys afloat, and the tables they are drawn with.
type Floating = (Vec<buoys::Buoy>, buoys::Tables);

/// The fleet on its sea in a `w × h` image, each boat riding the waves with its drawn sail.
fn draw_fleet(
    w: usize,
    h: usize,
    boats: &[Boat],
    drawn: &[Drawn],
    harbour: &Harbour,
    floating: &Floating,
) -> Image {
    let mut img = seascape(w, h, fleet_view(h).0, None);
    harbour.draw(&mut img);
    for buoy in &floating.0 {
        buoy.draw(&mut img, &floating.1);
    }
    for (k, (boat, (p, n, nu, nv))) in boats.iter().zip(drawn).enumerate() {
        let cam = riding(fleet_camera(w, h, boat.at, boat.yaw), harbour.lift(k));
        draw_boat(&mut img, &cam);
        draw_sail(&mut img, &cam, (p, n), (*nu, *nv), true);
    }
    img
}

fn main() {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("cloth: {e}");
            std::process::exit(2);
        }
    };
    if let Err(e) = std::fs::create_dir_all(&args.out) {
        eprintln!("cloth: cannot create {}: {e}", args.out.display());
        std::process::exit(1);
    }
    let (w, h) = (args.width, args.height);
    let (mut small, mut small_wind) = sail::<_, 8, 8>(DirectSprings::default(), 5.0, 0.5);
    let (mut big, mut big_wind) = sail::<_, 20, 20>(SymplecticEuler, 5.0, 0.5);
    let (a, b, r) = STAY;
    let stay = [
        Collider::capsule(Vec3::new(a[0], a[1], a[2]), Vec3::new(b[0], b[1], b[2]), r)
            .and_then(|c| c.with_friction(0.3, 0.2))
            .expect("a valid stay"),
    ];
    let on_surface = Contacts::new(&stay, 0.01, Touch::Drawn(SMOOTHING)).expect("valid");
    let on_particles = Contacts::new(&stay, 0.01, Touch::Particles).expect("valid");
    // Sail tables for every sample count, built once and shared by every sail.
    let tables: Vec<SurfaceTable<f32, 8, DRAWN>> = (2..=DRAWN)
        .map(|n| SurfaceTable::new(SMOOTHING, n).expect("2..=DRAWN"))
        .collect();
    let table = |n: usize| &tables[n - 2];
    let full = table(DRAWN);
    let mut boats = fleet(args.boats);
    let mut harbour = Harbour::new(&boats).unwrap_or_else(|e| {
        eprintln!("cloth: {e}");
        std::process::exit(2);
    });
    let mut floating: Floating = (buoys::buoys(&harbour), buoys::tables());
    let (mut pos, mut nor) = (
        vec![Vec3::default(); DRAWN * DRAWN],
        vec![Vec3::default(); DRAWN * DRAWN],
    );
    let side = |left: bool| Camera {
        yaw: 0.75,
        pitch: 0.2,
        scale: h as f32 / 8.0,
        center: [w as f32 * if left { 0.22 } else { 0.68 }, h as f32 * 0.72],
        depth: 0.0,
        lift: [0.0; 3],
    };
    println!(
        "frame | 8x8 step+surface (µs) | 20x20 step (µs) | fleet of {}: a step + surfaces (ms) | mean samples a sail | the sea's step (ms) | 3 lifebuoys' step (ms) | raster (ms)",
        args.boats
    );
    let mut last = Vec::new();
    // Steps that hit the substep cap (slow motion), shown after the table.
    let mut slow = 0u32;
    for frame in 0..args.frames {
        let (mut t_small, mut t_big) = (0.0, 0.0);
        for _ in 0..STEPS_PER_FRAME {
            let t = Instant::now();
            let info = small
                .step_touching(STEP, &mut small_wind, &on_surface)
                .expect("the sail stays stable");
            slow += u32::from(info.slow_motion);
            small
                .draw(full, full, &mut pos, &mut nor)
                .expect("buffers hold the grid");
            t_small += t.elapsed().as_secs_f64();
            let t = Instant::now();
            let info = big
                .step_touching(STEP, &mut big_wind, &on_particles)
                .expect("the sail stays stable");
            slow += u32::from(info.slow_motion);
            t_big += t.elapsed().as_secs_f64();
        }
        let time = frame as f32 * STEPS_PER_FRAME as f32 * STEP;
        let big_nor = grid_normals::<20, 20>(big.positions());
        let mut pair = Vec::new();
        for shaded in [false, true] {
            let mut img = seascape(w, h, h as f32 * 0.3, Some(time));
            for (left, grid, normals, n) in [
                (true, &pos[..], &nor[..], DRAWN),
                (false, big.positions(), &big_nor[..], 20),
            ] {
                draw_boat(&mut img, &side(left));
                draw_sail(&mut img, &side(left), (grid, normals), (n, n), shaded);
            }
            let name = if shaded { "sail_shaded" } else { "sail_wire" };
            let path = args.out.join(format!("{name}_{frame:03}.ppm"));
            img.write_ppm(&path)
                .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
            pair.push(img);
        }
        // The fleet: every sail stepped, then drawn at its level of detail (half a pixel).
        // Its cost is that of a 60 Hz game frame: one step and one drawing of every sail.
        let (mut stepping, mut drawing) = (0.0, 0.0);
        let mut drawn = Vec::with_capacity(boats.len());
        let mut samples = 0;
        for boat in &mut boats {
            let t = Instant::now();
            for _ in 0..STEPS_PER_FRAME {
                let info = boat
                    .sail
                    .step_with(STEP, &mut boat.wind)
                    .expect("the sail stays stable");
                slow += u32::from(info.slow_motion);
            }
            stepping += t.elapsed().as_secs_f64();
            let t = Instant::now();
            let cam = fleet_camera(w, h, boat.at, boat.yaw);
            let tolerance = 0.5 / cam.scale;
            let (su, sv) = lod::surface_segments(boat.sail.position_array(), SMOOTHING, tolerance)
                .expect("the sail is in range");
            let (nu, nv) = ((su + 1).min(DRAWN), (sv + 1).min(DRAWN));
            let (mut p, mut n) = (
                vec![Vec3::default(); nu * nv],
                vec![Vec3::default(); nu * nv],
            );
            samples += boat
                .sail
                .draw(table(nu), table(nv), &mut p, &mut n)
                .expect("buffers hold the grid");
            drawing += t.elapsed().as_secs_f64();
            drawn.push((p, n, nu, nv));
        }
        let fleet_ms = (stepping / STEPS_PER_FRAME as f64 + drawing) * 1e3;
        let (mut sea_s, mut buoys_s) = (0.0, 0.0);
        for _ in 0..STEPS_PER_FRAME {
            let t = Instant::now();
            harbour.step(STEP).expect("the sea stays stable");
            sea_s += t.elapsed().as_secs_f64();
            let t = Instant::now();
            for buoy in &mut floating.0 {
                buoy.step(STEP, &harbour).expect("the buoy stays stable");
            }
            buoys_s += t.elapsed().as_secs_f64();
        }
        let (sea_ms, buoys_ms) = (
            sea_s * 1e3 / STEPS_PER_FRAME as f64,
            buoys_s * 1e3 / STEPS_PER_FRAME as f64,
        );
        let t = Instant::now();
        let img = draw_fleet(w, h, &boats, &drawn, &harbour, &floating);
        let raster_ms = t.elapsed().as_secs_f64() * 1e3;
        let path = args.out.join(format!("fleet_{frame:03}.ppm"));
        img.write_ppm(&path)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
        let per = |s: f64| s * 1e6 / STEPS_PER_FRAME as f64;
        println!(
            "{frame:5} | {:21.1} | {:15.1} | {fleet_ms:35.2} | {:19.0} | {sea_ms:23.3} | {buoys_ms:27.3} | {raster_ms:.1}",
            per(t_small),
            per(t_big),
            samples as f64 / boats.len() as f64,
        );
        pair.push(draw_fleet(2 * w, h, &boats, &drawn, &harbour, &floating));
        last = pair;
    }
    if slow > 0 {
        println!(
            "slow motion: {slow} steps hit the substep cap and simulated less than their time"
        );
    }
    if let Some(png) = &args.png {
        // The contact sheet: the two sails shaded and in wireframe, the fleet below.
        let mut sheet = Image::new(2 * w, 2 * h, [0, 0, 0]);
        if let [wire, shaded, fleet] = &last[..] {
            sheet.paste(shaded, 0, 0);
            sheet.paste(wire, w, 0);
            sheet.paste(fleet, 0, h);
        }
        sheet
            .write_png(png)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", png.display()));
        println!("wrote the contact sheet {}", png.display());
    }
    let reach = small.positions()[27].z;
    println!(
        "wrote {} frames of {w}x{h} into {} (the 8x8 sail bellies {reach:.2} m downwind)",
        args.frames,
        args.out.display()
    );
}
