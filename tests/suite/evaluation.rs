//! The accuracy statements of `docs/guide.md` and of `docs/summary.md` (never its timings), held
//! on smaller versions of the same scenes so that a change that breaks them fails here.
#![cfg(feature = "std")]

use crate::common;
use crate::common::{ExactCurve, Rng, cloth_materials, hausdorff, sharpest_corner};
use dunas::Settings;
use dunas::sampler::{BernsteinTable, DeCasteljau, Sampler, Subdivide};
use dunas::smooth::Smoothing;
use dunas::spring::Material;
use dunas::surface::SurfaceTable;
use dunas::{Bezier, Cloth, Error, Q16, Rope, Vec2, Vec3};

/// `docs/guide.md` "Choosing a sampler": the table, de Casteljau and subdivision keep f32 within
/// 0.01 px at 10⁴ px, degree 3 and 7, 1024 points.
#[test]
fn stable_f32_samplers_stay_within_a_hundredth_of_a_pixel() {
    fn worst<const N: usize>(sampler: &impl Sampler<Vec2<f32>, N>, len: usize) -> f64 {
        let mut rng = Rng(0x5eed ^ (N as u64) << 32 ^ 10_000);
        let mut buf = vec![Vec2::default(); len];
        (0..40)
            .map(|_| {
                let c = ExactCurve::<f32, N>::new(rng.grid_points(10_000));
                let n = sampler.sample(&c.curve, &mut buf).unwrap();
                c.max_error(&buf[..n], (n - 1) as u64)
            })
            .fold(0.0, f64::max)
    }
    for e in [
        worst::<4>(&BernsteinTable::<f32, 4, 1024>::new(), 1024),
        worst::<8>(&BernsteinTable::<f32, 8, 1024>::new(), 1024),
        worst::<4>(&DeCasteljau, 1024),
        worst::<8>(&DeCasteljau, 1024),
        worst::<4>(&Subdivide::default(), 1025),
        worst::<8>(&Subdivide::default(), 1025),
    ] {
        assert!(e <= 0.01, "{e}");
    }
}

/// A rope pinned at both ends 50 px apart with 70 px of rest length, settled, drawn with
/// `points` points (summary (c), at rest).
fn rest_rope<const N: usize, const CAP: usize>(
    smoothing: Smoothing,
    points: usize,
) -> Vec<Vec2<f64>> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -200.0),
        damping: 3.0,
        ..Settings::default()
    };
    let s = (N - 1) as f64;
    let mut r: Rope<Vec2<f64>, N, CAP> = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(70.0, 0.0),
        7.0,
        Material {
            stiffness: 1500.0 * s,
            damping: 0.5 * s,
        },
        settings,
    )
    .unwrap();
    r.set_inv_mass(N - 1, 0.0).unwrap();
    r.set_position(N - 1, Vec2::new(50.0, 0.0)).unwrap();
    for _ in 0..360 {
        let _ = r.step(1.0 / 60.0).unwrap();
    }
    if smoothing == Smoothing::Polyline {
        return r.positions().to_vec();
    }
    let mut out = vec![Vec2::default(); points];
    let n = r.sample(smoothing, &mut out).unwrap();
    out.truncate(n);
    out
}

/// Summary (c), ropes at rest, every rope with the same rest length: the smoothed shape error
/// converges as particles are added (no floor from the setup), the 8-particle Catmull-Rom rope
/// is closer to the fine rope than the raw 8-particle polyline, and the 64 points a frame
/// draws of the B-spline have no corner sharper than 5°.
#[test]
fn smoothed_ropes_converge_and_eight_particles_draw_smooth() {
    let reference = rest_rope::<120, 119>(Smoothing::Polyline, 0);
    let error = |line: Vec<Vec2<f64>>| hausdorff(&line, &reference);
    let raw8 = error(rest_rope::<8, 7>(Smoothing::Polyline, 0));
    let cr8 = error(rest_rope::<8, 7>(Smoothing::CatmullRom, 2048));
    assert!(cr8 < raw8, "Catmull-Rom {cr8} vs raw 8 {raw8}");
    for smoothing in [Smoothing::BSpline, Smoothing::CatmullRom] {
        let e8 = error(rest_rope::<8, 7>(smoothing, 2048));
        let e30 = error(rest_rope::<30, 29>(smoothing, 2048));
        assert!(
            e30 < 0.1 * e8,
            "{smoothing:?} converges: 8 particles {e8}, 30 particles {e30}"
        );
    }
    let (c_b, c_8) = (
        sharpest_corner(&rest_rope::<8, 7>(Smoothing::BSpline, 64)),
        sharpest_corner(&rest_rope::<8, 7>(Smoothing::Polyline, 0)),
    );
    assert!(
        c_b < 5.0 && c_8 > 20.0,
        "corners: smoothed {c_b}°, raw 8 {c_8}°"
    );
}

/// Summary (c), cloth: the lowest point of the Bézier patch drawn over an 8×8 bowl is within
/// the documented 25% of a fine cloth's sag (it sits 21% high: the patch touches only the
/// corners), and the raw 8×8 grid and the natural spline through it within 15%. A surface that
/// fits better still passes.
#[test]
fn a_bezier_patch_over_a_sagging_cloth_stays_within_its_bound() {
    fn bowl<const U: usize>() -> Cloth<Vec3<f64>, U, U> {
        let settings = Settings {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            damping: 2.0,
            ..Settings::default()
        };
        let m = cloth_materials();
        let mut c = Cloth::rectangle(
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(10.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 10.0),
            2.0,
            m,
            settings,
        )
        .unwrap();
        for k in [0, U - 1, (U - 1) * U, U * U - 1] {
            c.set_inv_mass(k, 0.0).unwrap();
        }
        for _ in 0..480 {
            let _ = c.step(1.0 / 60.0).unwrap();
        }
        c
    }
    let lowest = |p: &[Vec3<f64>]| p.iter().map(|q| q.y).fold(f64::INFINITY, f64::min);
    let fine = bowl::<16>();
    let coarse = bowl::<8>();
    let mut patch = [Vec3::default(); 24 * 24];
    coarse
        .patch()
        .unwrap()
        .sample_grid(24, 24, &mut patch)
        .unwrap();
    let (sag_fine, sag_raw, sag_patch) = (
        lowest(fine.positions()),
        lowest(coarse.positions()),
        lowest(&patch),
    );
    eprintln!("lowest point: fine {sag_fine}, raw 8×8 {sag_raw}, patch {sag_patch}");
    assert!(
        (sag_raw - sag_fine).abs() < 0.15 * sag_fine.abs(),
        "raw 8×8 sags like the fine cloth: {sag_raw} vs {sag_fine}"
    );
    assert!(
        (sag_patch - sag_fine).abs() <= 0.25 * sag_fine.abs(),
        "the patch's lowest point: {sag_patch} vs {sag_fine}"
    );
    // The natural spline passes through the particles: it sags like the raw grid (same bound).
    let table = SurfaceTable::<f64, 8, 24>::new(Smoothing::NaturalSpline, 24).unwrap();
    let (mut natural, mut normals) = ([Vec3::default(); 24 * 24], [Vec3::default(); 24 * 24]);
    coarse
        .draw(&table, &table, &mut natural, &mut normals)
        .unwrap();
    let sag_natural = lowest(&natural);
    eprintln!("natural spline's lowest point {sag_natural}");
    assert!(
        (sag_natural - sag_fine).abs() < 0.15 * sag_fine.abs(),
        "the natural spline's lowest point: {sag_natural} vs {sag_fine}"
    );
}

/// Summary (e): Q16.16 subdivision keeps a constant error up to its range, then refuses.
#[test]
fn q16_error_stays_flat_until_the_range_ends() {
    for scale in [1i64, 100, 10_000, 16_000] {
        let grid = [
            [-scale, 0],
            [-scale / 3, scale],
            [scale / 2, -scale],
            [scale, scale / 2],
        ]
        .map(|[x, y]| [x * common::DENOM, y * common::DENOM]);
        let c = ExactCurve::<Q16, 4>::new(grid);
        let mut out = [Vec2::<Q16>::default(); 65];
        let n = Subdivide::default().sample(&c.curve, &mut out).unwrap();
        assert!(c.max_error(&out[..n], 64) < 3e-4, "scale {scale}");
    }
    let far = [
        Vec2::<Q16>::from_f64(0.0, 0.0),
        Vec2::from_f64(17_000.0, 0.0),
    ];
    assert!(matches!(
        Bezier::new(far).err(),
        Some(Error::OutOfRange { .. })
    ));
}
