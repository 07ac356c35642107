//! Sails as PPM images: an 8×8 sail drawn through its particles (a Catmull-Rom surface)
//! beside a 20×20 sail drawn raw, in wireframe and shaded (Lambert with the surface normals),
//! both filling against a thin stay (the 8×8 touches it with its drawn surface, the 20×20 with
//! its particles), and a fleet of 12 sails in one image with the frame time printed.
//!
//! Run: `cargo run --release --example cloth -- OUT_DIR [--size WxH] [--frames N]`
//! (defaults 640x360 and 6 frames, a quarter second apart). Writes `sail_wire_NNN.ppm`,
//! `sail_shaded_NNN.ppm` and `fleet_NNN.ppm` into `OUT_DIR` and prints what each frame cost.

#[path = "common/raster.rs"]
mod raster;

use std::path::PathBuf;
use std::time::Instant;

use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::force::Wind;
use dunas::spring::Material;
use dunas::surface::SurfaceTable;
use dunas::{Cloth, Vec3};
use dunas::{Settings, Smoothing};
use raster::{Camera, Image, lambert};

const STEP: f32 = 1.0 / 60.0;
const STEPS_PER_FRAME: usize = 15;
/// Points per side of the grid drawn from an 8×8 patch.
const DRAWN: usize = 24;
const MAST: [f32; 3] = [0.35, 0.3, 0.25];
const CANVAS: [f32; 3] = [235.0, 225.0, 200.0];
/// A stay downwind of the sail, 5 cm thick (a tenth of the 8×8 sail's particle spacing):
/// the sail fills against it.
const STAY: ([f32; 3], [f32; 3], f32) = ([1.6, 0.5, 1.0], [1.6, -4.5, 1.0], 0.05);

fn stay() -> [Collider<Vec3<f32>>; 1] {
    let (a, b, r) = STAY;
    [
        Collider::capsule(Vec3::new(a[0], a[1], a[2]), Vec3::new(b[0], b[1], b[2]), r)
            .and_then(|c| c.with_friction(0.3, 0.2))
            .expect("a valid stay"),
    ]
}

struct Args {
    out: PathBuf,
    width: usize,
    height: usize,
    frames: usize,
}

fn parse_args() -> Result<Args, String> {
    let mut args = std::env::args().skip(1);
    let mut out = None;
    let (mut width, mut height, mut frames) = (640, 360, 6);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--size" => {
                let v = args.next().ok_or("--size needs WxH")?;
                let (w, h) = v
                    .split_once('x')
                    .ok_or(format!("--size: expected WxH, got {v}"))?;
                width = w.parse().map_err(|_| format!("--size: bad width {w}"))?;
                height = h.parse().map_err(|_| format!("--size: bad height {h}"))?;
                if !(16..=8192).contains(&width) || !(16..=8192).contains(&height) {
                    return Err("--size: each side must be 16 to 8192".into());
                }
            }
            "--frames" => {
                let v = args.next().ok_or("--frames needs a number")?;
                frames = v.parse().map_err(|_| format!("--frames: bad number {v}"))?;
                if !(1..=10_000).contains(&frames) {
                    return Err("--frames: 1 to 10000".into());
                }
            }
            _ if a.starts_with("--") => return Err(format!("unknown option {a}")),
            _ => out = Some(PathBuf::from(a)),
        }
    }
    let out = out.ok_or("usage: cloth OUT_DIR [--size WxH] [--frames N]")?;
    Ok(Args {
        out,
        width,
        height,
        frames,
    })
}

/// A 3 m × 4 m sail on a mast along its first column, its top row on the gaff, 2 kg in all.
/// Spring stiffness does not change with the grid (a membrane), so both sails are the same
/// cloth; wind drag is spread over the particles.
fn sail<const U: usize, const V: usize>(
    wind_speed: f32,
) -> (Cloth<Vec3<f32>, U, V>, Wind<Vec3<f32>>) {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.3,
        ..Settings::default()
    };
    let materials = [
        Material {
            stiffness: 900.0,
            damping: 0.6,
        },
        Material {
            stiffness: 300.0,
            damping: 0.2,
        },
        Material {
            stiffness: 60.0,
            damping: 0.05,
        },
    ];
    let mut cloth = Cloth::rectangle(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(3.0, 0.0, 0.0),
        Vec3::new(0.0, -4.0, 0.0),
        2.0,
        materials,
        settings,
    )
    .expect("valid sail");
    cloth.pin_column(0).expect("column in range");
    cloth.pin_row(0).expect("row in range");
    let mut wind = Wind::still(3.0 / (U * V) as f32);
    wind.velocity = Vec3::new(0.0, 0.0, wind_speed);
    wind.gust = Vec3::new(0.0, 0.0, wind_speed);
    wind.gust_start = 0.5;
    wind.gust_length = 1.0;
    (cloth, wind)
}

fn arr(p: Vec3<f32>) -> [f32; 3] {
    [p.x, p.y, p.z]
}

/// Draws a `nu × nv` grid of points (with normals for shading) through `camera`.
fn draw_grid(
    img: &mut Image,
    cam: &Camera,
    pos: &[Vec3<f32>],
    nor: &[Vec3<f32>],
    nu: usize,
    nv: usize,
    shaded: bool,
) {
    let light = {
        let l = Vec3::new(0.4f32, 0.8, -0.45);
        arr(l.normalize().unwrap_or(l))
    };
    let screen: Vec<[f32; 3]> = pos.iter().map(|&p| cam.project(arr(p))).collect();
    for j in 0..nv - 1 {
        for i in 0..nu - 1 {
            let k = [
                j * nu + i,
                j * nu + i + 1,
                (j + 1) * nu + i,
                (j + 1) * nu + i + 1,
            ];
            if shaded {
                let c = |k: usize| lambert(arr(nor[k]), light, CANVAS);
                img.triangle(
                    [screen[k[0]], screen[k[1]], screen[k[2]]],
                    [c(k[0]), c(k[1]), c(k[2])],
                );
                img.triangle(
                    [screen[k[1]], screen[k[3]], screen[k[2]]],
                    [c(k[1]), c(k[3]), c(k[2])],
                );
            } else {
                let w = [40, 40, 40];
                img.line(
                    [screen[k[0]][0], screen[k[0]][1]],
                    [screen[k[1]][0], screen[k[1]][1]],
                    w,
                );
                img.line(
                    [screen[k[0]][0], screen[k[0]][1]],
                    [screen[k[2]][0], screen[k[2]][1]],
                    w,
                );
            }
        }
    }
    if !shaded {
        let w = [40, 40, 40];
        for i in 0..nu - 1 {
            let (a, b) = (screen[(nv - 1) * nu + i], screen[(nv - 1) * nu + i + 1]);
            img.line([a[0], a[1]], [b[0], b[1]], w);
        }
        for j in 0..nv - 1 {
            let (a, b) = (screen[j * nu + nu - 1], screen[(j + 1) * nu + nu - 1]);
            img.line([a[0], a[1]], [b[0], b[1]], w);
        }
    }
    // The mast, and the stay.
    let m = MAST.map(|c| (c * 255.0) as u8);
    for ((top, foot), width) in [
        (([0.0, 0.5, 0.0], [0.0, -4.5, 0.0]), 1),
        ((STAY.0, STAY.1), 0),
    ] {
        let (top, foot) = (cam.project(top), cam.project(foot));
        for dx in -width..=width {
            img.line(
                [top[0] + dx as f32, top[1]],
                [foot[0] + dx as f32, foot[1]],
                m,
            );
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
    let (mut small, mut small_wind) = sail::<8, 8>(5.0);
    let (mut big, mut big_wind) = sail::<20, 20>(5.0);
    let stay = stay();
    let on_surface =
        Contacts::new(&stay, 0.01, Touch::Drawn(Smoothing::CatmullRom)).expect("valid");
    // The 8×8 sails are drawn through their particles (Catmull-Rom), DRAWN points a side.
    let table = SurfaceTable::<f32, 8, DRAWN>::new(Smoothing::CatmullRom, DRAWN).expect("2..=N");
    let on_particles = Contacts::new(&stay, 0.01, Touch::Particles).expect("valid");
    let mut fleet: Vec<_> = (0..12)
        .map(|k| sail::<8, 8>(3.0 + 0.4 * k as f32))
        .collect();
    let (mut pos, mut nor) = (
        vec![Vec3::default(); DRAWN * DRAWN],
        vec![Vec3::default(); DRAWN * DRAWN],
    );
    let half = |left: bool| Camera {
        yaw: 0.6,
        pitch: 0.25,
        scale: h as f32 / 6.5,
        center: [
            if left {
                w as f32 * 0.25
            } else {
                w as f32 * 0.75
            } - h as f32 * 0.15,
            h as f32 * 0.18,
        ],
    };
    println!("frame | 8x8 step+surface (µs) | 20x20 step (µs) | fleet of 12: simulate + draw (ms)");
    for frame in 0..args.frames {
        let (mut t_small, mut t_big) = (0.0, 0.0);
        for _ in 0..STEPS_PER_FRAME {
            let t = Instant::now();
            small
                .step_touching(STEP, &mut small_wind, &on_surface)
                .expect("the sail stays stable");
            small
                .draw(&table, &table, &mut pos, &mut nor)
                .expect("buffers hold the grid");
            t_small += t.elapsed().as_secs_f64();
            let t = Instant::now();
            big.step_touching(STEP, &mut big_wind, &on_particles)
                .expect("the sail stays stable");
            t_big += t.elapsed().as_secs_f64();
        }
        let big_nor = grid_normals::<20, 20>(big.positions());
        for shaded in [false, true] {
            let mut img = Image::new(w, h, [150, 190, 225]);
            draw_grid(&mut img, &half(true), &pos, &nor, DRAWN, DRAWN, shaded);
            draw_grid(
                &mut img,
                &half(false),
                big.positions(),
                &big_nor,
                20,
                20,
                shaded,
            );
            let name = if shaded { "sail_shaded" } else { "sail_wire" };
            let path = args.out.join(format!("{name}_{frame:03}.ppm"));
            img.write_ppm(&path)
                .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
        }
        // The fleet: 12 sails simulated and drawn into one image.
        let t = Instant::now();
        let mut img = Image::new(w, h, [150, 190, 225]);
        for (k, (cloth, wind)) in fleet.iter_mut().enumerate() {
            for _ in 0..STEPS_PER_FRAME {
                cloth
                    .step_with(STEP, &mut *wind)
                    .expect("the sail stays stable");
            }
            cloth
                .draw(&table, &table, &mut pos, &mut nor)
                .expect("buffers hold the grid");
            let (col, row) = ((k % 4) as f32, (k / 4) as f32);
            let cam = Camera {
                yaw: 0.6,
                pitch: 0.25,
                scale: h as f32 / 16.0,
                center: [
                    w as f32 * (0.1 + 0.23 * col),
                    h as f32 * (0.08 + 0.31 * row),
                ],
            };
            draw_grid(&mut img, &cam, &pos, &nor, DRAWN, DRAWN, true);
        }
        let fleet_ms = t.elapsed().as_secs_f64() * 1e3;
        let path = args.out.join(format!("fleet_{frame:03}.ppm"));
        img.write_ppm(&path)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
        let per = |s: f64| s * 1e6 / STEPS_PER_FRAME as f64;
        println!(
            "{frame:5} | {:19.1} | {:15.1} | {fleet_ms:.2}",
            per(t_small),
            per(t_big)
        );
    }
    let reach = small.positions()[63].z;
    println!(
        "wrote {} frames of {w}x{h} into {} (8x8 sail's free corner is {reach:.2} m downwind)",
        args.frames,
        args.out.display()
    );
}
