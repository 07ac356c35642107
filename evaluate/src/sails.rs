//! (c, sails) Smoothed sails against raw grids: 10 m sails of 4×4 to 32×32 particles, at rest
//! (a bowl pinned at its corners) and in wind (tied to a mast, a gaff and a boom, filled by
//! `SailWind`), cost per frame against shape error and creases versus a 32×32 sail stepped
//! at 240 Hz; and a fleet of 100 sails drawn at their level of detail.

use std::collections::HashMap;

use dunas::force::{SailWind, Wind};
use dunas::surface::SurfaceTable;
use dunas::{Cloth, Point, Scalar, Settings, Smoothing, Vec3, lod};

use crate::common::cloth_materials;
use crate::report::{Run, Series, chart, csv, median_ns, num};

const SIZE: f64 = 10.0;
const MASS: f64 = 2.0;
const DT: f64 = 1.0 / 60.0;
/// Wind speed (m/s) and pressure coefficient `½ρC` (kg/m³) of the wind scene.
const WIND: f64 = 3.0;
const PRESSURE: f64 = 0.7;
/// The camera: 60 px a metre (the sail 600 px tall), half a pixel of tolerance.
const TOLERANCE: f64 = 0.5 / 60.0;
/// Most samples a direction (the tables' size).
const MAX_DRAWN: usize = 64;

#[derive(Clone, Copy, PartialEq, Eq)]
enum Scene {
    /// Horizontal, pinned at the four corners, settled into a bowl (8 s).
    Rest,
    /// Upright, gaff-rigged: luff on the mast (column 0), head on the gaff (row 0), foot on
    /// the boom (last row), the leech free; in a steady wind across it, after 6 s.
    Wind,
}

impl Scene {
    fn name(self) -> &'static str {
        match self {
            Scene::Rest => "rest",
            Scene::Wind => "wind",
        }
    }

    fn seconds(self) -> f64 {
        match self {
            Scene::Rest => 8.0,
            Scene::Wind => 6.0,
        }
    }
}

fn s<S: Scalar>(x: f64) -> S {
    S::from_f64(x)
}

fn sail<S: Scalar, const U: usize>(scene: Scene) -> Cloth<Vec3<S>, U, U> {
    let settings = Settings {
        gravity: Vec3::new(S::ZERO, s(-9.81), S::ZERO),
        damping: s(if scene == Scene::Rest { 2.0 } else { 1.0 }),
        ..Settings::default()
    };
    let (origin, du, dv) = match scene {
        Scene::Rest => (
            Vec3::default(),
            Vec3::new(s(SIZE), S::ZERO, S::ZERO),
            Vec3::new(S::ZERO, S::ZERO, s(SIZE)),
        ),
        Scene::Wind => (
            Vec3::new(S::ZERO, s(SIZE), S::ZERO),
            Vec3::new(s(SIZE), S::ZERO, S::ZERO),
            Vec3::new(S::ZERO, s(-SIZE), S::ZERO),
        ),
    };
    let mut c =
        Cloth::rectangle(origin, du, dv, s(MASS), cloth_materials(), settings).expect("valid");
    match scene {
        Scene::Rest => {
            for k in [0, U - 1, (U - 1) * U, U * U - 1] {
                c.set_inv_mass(k, S::ZERO).expect("in range");
            }
        }
        Scene::Wind => {
            c.pin_column(0).expect("in range");
            c.pin_row(0).expect("in range");
            c.pin_row(U - 1).expect("in range");
        }
    }
    c
}

fn wind<S: Scalar>(scene: Scene) -> SailWind<S> {
    let mut air = Wind::still(S::ZERO);
    air.velocity = Vec3::new(S::ZERO, S::ZERO, s(WIND));
    let pressure = if scene == Scene::Wind { PRESSURE } else { 0.0 };
    SailWind::new(air, s(pressure)).expect("valid")
}

/// The sail after its scene's seconds at time step `dt`.
fn settled<const U: usize>(scene: Scene, dt: f64) -> Cloth<Vec3<f64>, U, U> {
    let mut c = sail::<f64, U>(scene);
    let mut w = wind::<f64>(scene);
    for _ in 0..(scene.seconds() / dt).round() as usize {
        let _ = c.step_with(dt, &mut w).expect("stable");
    }
    c
}

/// Densifies a grid of points bilinearly to about 48×48 (so distances are to the surface, not
/// to its vertices).
fn densify(p: &[Vec3<f64>], nu: usize, nv: usize) -> Vec<Vec3<f64>> {
    let per_u = (48 / (nu - 1)).max(1);
    let per_v = (48 / (nv - 1)).max(1);
    let mut out = Vec::new();
    for j in 0..(nv - 1) * per_v + 1 {
        for i in 0..(nu - 1) * per_u + 1 {
            let (ci, cj) = ((i / per_u).min(nu - 2), (j / per_v).min(nv - 2));
            let (s, t) = (
                (i - ci * per_u) as f64 / per_u as f64,
                (j - cj * per_v) as f64 / per_v as f64,
            );
            let q = |a: usize, b: usize| p[b * nu + a];
            out.push(
                q(ci, cj)
                    .lerp(q(ci + 1, cj), s)
                    .lerp(q(ci, cj + 1).lerp(q(ci + 1, cj + 1), s), t),
            );
        }
    }
    out
}

/// Symmetric Hausdorff distance between two point clouds.
fn cloud_distance(a: &[Vec3<f64>], b: &[Vec3<f64>]) -> f64 {
    let one = |x: &[Vec3<f64>], y: &[Vec3<f64>]| {
        x.iter()
            .map(|&p| {
                y.iter()
                    .map(|&q| (p - q).length())
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    one(a, b).max(one(b, a))
}

/// The sharpest crease of a drawn `nu × nv` grid: the largest angle (degrees) between the
/// normals of two facets that share an edge (a facet's normal from its diagonals).
fn sharpest_crease(p: &[Vec3<f64>], nu: usize, nv: usize) -> f64 {
    let normal = |i: usize, j: usize| {
        let q = |a: usize, b: usize| p[b * nu + a];
        (q(i + 1, j + 1) - q(i, j))
            .cross(q(i, j + 1) - q(i + 1, j))
            .normalize()
            .unwrap_or_default()
    };
    let mut worst: f64 = 0.0;
    for j in 0..nv - 1 {
        for i in 0..nu - 1 {
            let n = normal(i, j);
            for (a, b) in [(i + 1, j), (i, j + 1)] {
                if a < nu - 1 && b < nv - 1 {
                    let cos = n.dot(normal(a, b)).clamp(-1.0, 1.0);
                    worst = worst.max(cos.acos().to_degrees());
                }
            }
        }
    }
    worst
}

/// Sample counts a direction at the camera's tolerance, capped at the tables' size.
fn lod_counts<S: Scalar, const U: usize>(
    grid: &[[Vec3<S>; U]; U],
    smoothing: Smoothing,
    tolerance: S,
) -> (usize, usize) {
    let (su, sv) = lod::surface_segments(grid, smoothing, tolerance).expect("in range");
    ((su + 1).min(MAX_DRAWN), (sv + 1).min(MAX_DRAWN))
}

/// The drawn surface of a sail at its level of detail (the particles when `Polyline`), and
/// its counts a direction.
fn drawn<const U: usize>(
    c: &Cloth<Vec3<f64>, U, U>,
    smoothing: Smoothing,
) -> (Vec<Vec3<f64>>, usize, usize) {
    if smoothing == Smoothing::Polyline {
        return (c.positions().to_vec(), U, U);
    }
    let (nu, nv) = lod_counts(c.position_array(), smoothing, TOLERANCE);
    let tu = SurfaceTable::<f64, U, MAX_DRAWN>::new(smoothing, nu).expect("2..=N");
    let tv = SurfaceTable::<f64, U, MAX_DRAWN>::new(smoothing, nv).expect("2..=N");
    let (mut pos, mut nor) = (
        vec![Vec3::default(); nu * nv],
        vec![Vec3::default(); nu * nv],
    );
    c.draw(&tu, &tv, &mut pos, &mut nor).expect("buffer");
    (pos, nu, nv)
}

/// Nanoseconds of one f32 frame: a 60 Hz step (substeps from stiffness) in the scene's wind,
/// plus, when smoothed, the level of detail and the drawn grid with normals at it (tables
/// built once per count, as a game caches them). The raw grid is drawn as its particles.
fn frame_ns<const U: usize>(run: &Run, scene: Scene, smoothing: Smoothing) -> f64 {
    let mut c = sail::<f32, U>(scene);
    let mut w = wind::<f32>(scene);
    for _ in 0..(scene.seconds() / DT) as usize {
        let _ = c.step_with(DT as f32, &mut w).expect("stable");
    }
    let mut tables: HashMap<usize, SurfaceTable<f32, U, MAX_DRAWN>> = HashMap::new();
    let (mut pos, mut nor) = (
        vec![Vec3::<f32>::default(); MAX_DRAWN * MAX_DRAWN],
        vec![Vec3::<f32>::default(); MAX_DRAWN * MAX_DRAWN],
    );
    median_ns(run.reps().min(11), 5, || {
        let _ = c.step_with(DT as f32, &mut w).expect("stable");
        if smoothing != Smoothing::Polyline {
            let (nu, nv) = lod_counts(c.position_array(), smoothing, TOLERANCE as f32);
            for n in [nu, nv] {
                tables
                    .entry(n)
                    .or_insert_with(|| SurfaceTable::new(smoothing, n).expect("2..=N"));
            }
            std::hint::black_box(c.draw(&tables[&nu], &tables[&nv], &mut pos, &mut nor))
                .expect("buffer");
        }
    })
}

struct Row {
    n: usize,
    smoothing: Smoothing,
    scene: Scene,
    drawn: (usize, usize),
    ns: f64,
    error: f64,
    crease: f64,
}

const SMOOTHINGS: [Smoothing; 4] = [
    Smoothing::NaturalSpline,
    Smoothing::CatmullRom,
    Smoothing::BSpline,
    Smoothing::Bezier,
];

fn name(s: Smoothing) -> &'static str {
    match s {
        Smoothing::NaturalSpline => "natural spline",
        Smoothing::CatmullRom => "Catmull-Rom",
        Smoothing::BSpline => "B-spline",
        Smoothing::Bezier => "one Bézier patch",
        Smoothing::Polyline => "raw grid",
    }
}

fn rows_for<const U: usize>(
    run: &Run,
    references: &[Vec<Vec3<f64>>; 2],
    smoothings: &[Smoothing],
    rows: &mut Vec<Row>,
) {
    for (k, scene) in [Scene::Rest, Scene::Wind].into_iter().enumerate() {
        let c = settled::<U>(scene, DT);
        for &smoothing in smoothings {
            let (points, nu, nv) = drawn(&c, smoothing);
            rows.push(Row {
                n: U,
                smoothing,
                scene,
                drawn: (nu, nv),
                ns: frame_ns::<U>(run, scene, smoothing),
                error: cloud_distance(&densify(&points, nu, nv), &references[k]),
                crease: sharpest_crease(&points, nu, nv),
            });
        }
    }
}

/// The first raw grid (fewest particles) that is as close as `level.error` and, when
/// `smooth`, also has no sharper crease than `level.crease`.
fn first_raw<'a>(rows: &'a [Row], scene: Scene, level: &Row, smooth: bool) -> Option<&'a Row> {
    let mut raw: Vec<&Row> = rows
        .iter()
        .filter(|r| r.scene == scene && r.smoothing == Smoothing::Polyline)
        .collect();
    raw.sort_by_key(|r| r.n);
    raw.into_iter()
        .find(|r| r.error <= level.error && (!smooth || r.crease <= level.crease))
}

/// The largest raw grid measured in `scene`.
fn largest_raw(rows: &[Row], scene: Scene) -> Option<&Row> {
    rows.iter()
        .filter(|r| r.scene == scene && r.smoothing == Smoothing::Polyline)
        .max_by_key(|r| r.n)
}

/// The fleet: 100 sails of 8×8 in wind, each its own distance from the camera (20 to 200 m,
/// so its tolerance in metres grows with the distance), stepped and drawn at its level of
/// detail with normals. Returns (ns for the whole fleet, mean samples a sail).
fn fleet_ns(run: &Run) -> (f64, f64) {
    const BOATS: usize = 100;
    let mut sails: Vec<(Cloth<Vec3<f32>, 8, 8>, f32)> = (0..BOATS)
        .map(|k| {
            let mut c = sail::<f32, 8>(Scene::Wind);
            let mut w = wind::<f32>(Scene::Wind);
            for _ in 0..(k % 30) {
                let _ = c.step_with(DT as f32, &mut w).expect("stable");
            }
            // At 20 m a metre is 60 px (as in the tables above); farther, proportionally less.
            let distance = 20.0 + 180.0 * k as f32 / (BOATS - 1) as f32;
            (c, TOLERANCE as f32 * distance / 20.0)
        })
        .collect();
    let mut w = wind::<f32>(Scene::Wind);
    let mut tables: HashMap<usize, SurfaceTable<f32, 8, MAX_DRAWN>> = HashMap::new();
    let (mut pos, mut nor) = (
        vec![Vec3::<f32>::default(); MAX_DRAWN * MAX_DRAWN],
        vec![Vec3::<f32>::default(); MAX_DRAWN * MAX_DRAWN],
    );
    let mut samples = 0usize;
    let mut frames = 0usize;
    let ns = median_ns(run.reps().min(7), 1, || {
        frames += 1;
        for (c, tol) in &mut sails {
            let _ = c.step_with(DT as f32, &mut w).expect("stable");
            let (nu, nv) = lod_counts(c.position_array(), Smoothing::NaturalSpline, *tol);
            for n in [nu, nv] {
                tables.entry(n).or_insert_with(|| {
                    SurfaceTable::new(Smoothing::NaturalSpline, n).expect("2..=N")
                });
            }
            samples += std::hint::black_box(c.draw(&tables[&nu], &tables[&nv], &mut pos, &mut nor))
                .expect("buffer");
        }
    });
    (ns, samples as f64 / (frames * BOATS) as f64)
}

/// Nanoseconds of the 8×8 sail's f32 step in wind, and of drawing it 24×24 with normals.
fn step_and_draw24(run: &Run) -> (f64, f64) {
    let mut c = sail::<f32, 8>(Scene::Wind);
    let mut w = wind::<f32>(Scene::Wind);
    for _ in 0..(Scene::Wind.seconds() / DT) as usize {
        let _ = c.step_with(DT as f32, &mut w).expect("stable");
    }
    let table = SurfaceTable::<f32, 8, 24>::new(Smoothing::NaturalSpline, 24).expect("2..=N");
    let (mut pos, mut nor) = ([Vec3::<f32>::default(); 576], [Vec3::<f32>::default(); 576]);
    let draw = median_ns(run.reps(), 20, || {
        std::hint::black_box(c.draw(&table, &table, &mut pos, &mut nor)).expect("buffer");
    });
    let start = c.clone();
    let mut frames = 0;
    let step = median_ns(run.reps(), 20, || {
        frames += 1;
        if frames % 120 == 0 {
            c = start.clone();
        }
        let _ = c.step_with(DT as f32, &mut w).expect("stable");
    });
    (step, draw)
}

pub fn run(run: &mut Run) -> String {
    let references = [Scene::Rest, Scene::Wind].map(|scene| {
        let c = settled::<32>(scene, 1.0 / 240.0);
        densify(c.positions(), 32, 32)
    });
    let mut rows = Vec::new();
    let raw = [Smoothing::Polyline];
    let mut both = SMOOTHINGS.to_vec();
    both.push(Smoothing::Polyline);
    rows_for::<4>(run, &references, &both, &mut rows);
    rows_for::<8>(run, &references, &both, &mut rows);
    rows_for::<16>(run, &references, &raw, &mut rows);
    rows_for::<24>(run, &references, &raw, &mut rows);
    if !run.quick {
        rows_for::<6>(run, &references, &both, &mut rows);
        rows_for::<12>(run, &references, &both, &mut rows);
        rows_for::<20>(run, &references, &raw, &mut rows);
        rows_for::<32>(run, &references, &raw, &mut rows);
    }
    let mut text = String::new();
    let mut worst_ratio = f64::INFINITY;
    for scene in [Scene::Rest, Scene::Wind] {
        let series: Vec<Series> = SMOOTHINGS
            .iter()
            .chain(&raw)
            .map(|&m| {
                let mut pts: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.scene == scene && r.smoothing == m)
                    .map(|r| (r.ns, r.error))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                Series::line(name(m), pts)
            })
            .collect();
        let file = format!("cloth_{}.svg", scene.name());
        chart(
            &run.path(&file),
            &format!(
                "Sails 4×4 to 32×32 ({}): cost per frame against shape error vs 32×32 at 240 Hz",
                scene.name()
            ),
            "ns per frame (f32 step at 60 Hz + drawing at the level of detail)",
            "shape error (m, Hausdorff)",
            &series,
            true,
        );
        text.push_str(&format!(
            "![sails {0}]({file})\n\n| {0}: 8×8 | drawn | ns per frame | shape error m | sharpest crease | first raw grid as close | ratio | first raw grid as close and as smooth | ratio |\n|---|---|---|---|---|---|---|---|---|\n",
            scene.name()
        ));
        for &m in SMOOTHINGS.iter().chain(&raw) {
            let Some(r8) = rows
                .iter()
                .find(|r| r.scene == scene && r.smoothing == m && r.n == 8)
            else {
                continue;
            };
            // None matching: the true grid is larger than the largest measured, and costlier.
            let largest = largest_raw(&rows, scene);
            let cell = |hit: Option<&Row>| match (hit, largest) {
                (Some(r), _) => (
                    format!("{0}×{0} ({1:.0} ns)", r.n, r.ns),
                    format!("{:.1}×", r.ns / r8.ns),
                ),
                (None, Some(l)) => (
                    format!("larger than {0}×{0} ({1:.0} ns)", l.n, l.ns),
                    format!("> {:.1}×", l.ns / r8.ns),
                ),
                (None, None) => (String::new(), String::new()),
            };
            let (close, close_ratio) = if m == Smoothing::Polyline {
                (String::new(), String::new())
            } else {
                cell(first_raw(&rows, scene, r8, false))
            };
            let (smooth, smooth_ratio) = if m == Smoothing::Polyline {
                (String::new(), String::new())
            } else {
                cell(first_raw(&rows, scene, r8, true))
            };
            if m == Smoothing::NaturalSpline {
                let matched = first_raw(&rows, scene, r8, true).or(largest);
                worst_ratio = worst_ratio.min(matched.map_or(0.0, |r| r.ns / r8.ns));
            }
            text.push_str(&format!(
                "| {} | {}×{} | {:.0} | {} | {:.1}° | {close} | {close_ratio} | {smooth} | {smooth_ratio} |\n",
                name(m),
                r8.drawn.0,
                r8.drawn.1,
                r8.ns,
                num(r8.error),
                r8.crease,
            ));
        }
        text.push('\n');
    }
    let csv_rows: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.scene.name().into(),
                r.n.to_string(),
                name(r.smoothing).into(),
                format!("{}x{}", r.drawn.0, r.drawn.1),
                format!("{:.0}", r.ns),
                format!("{:.4e}", r.error),
                format!("{:.2}", r.crease),
            ]
        })
        .collect();
    csv(
        &run.path("cloth.csv"),
        &[
            "scene",
            "grid",
            "drawing",
            "drawn",
            "ns_per_frame",
            "shape_error_m",
            "sharpest_crease_deg",
        ],
        &csv_rows,
    );
    run.target(
        "8×8 sail (step + drawn grid with normals at its level of detail) at least 5× cheaper per frame than the first raw grid as close and as smooth",
        format!("natural spline, worse scene: at least {worst_ratio:.1}×"),
        worst_ratio >= 5.0,
        "see the sail tables of section (c)",
    );
    let error = |scene: Scene, m: Smoothing| {
        rows.iter()
            .find(|r| r.scene == scene && r.smoothing == m && r.n == 8)
            .map_or(f64::NAN, |r| r.error)
    };
    let (natural, raw8) = (
        error(Scene::Rest, Smoothing::NaturalSpline),
        error(Scene::Rest, Smoothing::Polyline),
    );
    run.target(
        "at rest, the 8×8 natural-spline sail's shape error no worse than the raw 8×8 grid's",
        format!("{} m against {} m", num(natural), num(raw8)),
        natural <= raw8,
        "the surface through the particles adds its own bulge between them",
    );
    let (step, draw) = step_and_draw24(run);
    run.target(
        "drawing 24×24 with normals from an 8×8 sail costs at most 1.5× its step",
        format!(
            "{draw:.0} ns against a {step:.0} ns step: {:.2}×",
            draw / step
        ),
        draw <= 1.5 * step,
        "",
    );
    let (fleet, samples) = fleet_ns(run);
    run.target(
        "a fleet of 100 sails stepped and drawn with normals within 16.6 ms on one core",
        format!(
            "{:.2} ms ({samples:.0} samples a sail at its distance)",
            fleet / 1e6
        ),
        fleet <= 16.6e6,
        "",
    );
    text.push_str(&format!(
        "The 8×8 sail in wind (f32): step {step:.0} ns, drawing it 24×24 with normals (natural spline) \
         {draw:.0} ns ({:.2}× the step). A fleet of 100 such sails, 20 to 200 m from a camera that puts \
         60 px in a metre at 20 m, each drawn at its own level of detail ({samples:.0} samples a sail on \
         average): {:.2} ms a frame.\n\n",
        draw / step,
        fleet / 1e6
    ));
    text
}
