//! Every sampler against the exact integer reference: inside the documented bounds where
//! the docs say it works, outside them where the docs say it fails.
#![cfg(any(feature = "std", feature = "libm"))]

use crate::common::{self, ExactCurve, Rng};
use dunas::sampler::{BernsteinTable, DeCasteljau, ForwardDiff, Horner, Sampler, Subdivide};
use dunas::{Point, Scalar, Vec2};

/// Largest control coordinate `R` and longest control leg `D` of a grid curve.
fn sizes<const N: usize>(grid: &[[i64; 2]; N]) -> (f64, f64) {
    let d = common::DENOM as f64;
    let r = grid
        .iter()
        .flatten()
        .map(|&c| c.abs() as f64 / d)
        .fold(0.0, f64::max);
    let leg = grid
        .windows(2)
        .map(|w| ((w[1][0] - w[0][0]) as f64).hypot((w[1][1] - w[0][1]) as f64) / d)
        .fold(0.0, f64::max);
    (r, leg)
}

/// Worst error over `curves` random curves and the worst ratio error / documented bound.
fn measure<S: Scalar, const N: usize>(
    sampler: &impl Sampler<Vec2<S>, N>,
    len: usize,
    scale: i64,
    bound: impl Fn(f64, f64, usize) -> f64,
) -> (f64, f64) {
    let mut rng = Rng(0xdeca ^ scale as u64 ^ (N as u64) << 40 ^ len as u64);
    let mut buf = vec![Vec2::<S>::default(); len];
    let (mut worst, mut worst_ratio) = (0.0f64, 0.0f64);
    for _ in 0..25 {
        let c = ExactCurve::<S, N>::new(rng.grid_points(scale));
        let n = sampler.sample(&c.curve, &mut buf).unwrap();
        assert_eq!(buf[0], c.curve.start(), "first sample is the start point");
        assert_eq!(buf[n - 1], c.curve.end(), "last sample is the end point");
        let err = c.max_error(&buf[..n], (n - 1) as u64);
        let (r, leg) = sizes(&c.grid);
        worst = worst.max(err);
        worst_ratio = worst_ratio.max(err / bound(r, leg, n));
    }
    (worst, worst_ratio)
}

fn eps<S: Scalar>() -> f64 {
    S::EPSILON.to_f64()
}

fn log2(n: usize) -> f64 {
    (n as f64 - 1.0).log2()
}

/// The bounds of the sampler docs, for curves with N points.
fn de_casteljau_bound<S: Scalar, const N: usize>(r: f64, leg: f64, _n: usize) -> f64 {
    let float = 4.0 * (N - 1) as f64 * eps::<S>() * r;
    if S::FIXED_POINT {
        float + (N - 1) as f64 * leg * 2f64.powi(-17)
    } else {
        float
    }
}
fn table_bound<S: Scalar, const N: usize>(r: f64, _: f64, _: usize) -> f64 {
    4.0 * N as f64 * eps::<S>() * r
}
fn horner_bound<S: Scalar, const N: usize>(r: f64, _: f64, _: usize) -> f64 {
    2f64.powi(N as i32 - 1) * N as f64 * eps::<S>() * r
}
fn forward_bound<S: Scalar, const N: usize>(r: f64, _: f64, n: usize) -> f64 {
    n as f64 * 2f64.powi(N as i32 - 1) * eps::<S>() * r
}
fn subdivide_bound<S: Scalar, const N: usize>(r: f64, _: f64, n: usize) -> f64 {
    if S::FIXED_POINT {
        log2(n) * (N - 1) as f64 / 2.0 * 2f64.powi(-16)
    } else {
        (log2(n) + N as f64) * eps::<S>() * r
    }
}

/// The convex samplers hold their bounds for every N from 2 to 16 in every float format.
macro_rules! stable_samplers_hold_bounds {
    ($($name:ident: $S:ty, $N:literal;)*) => {$(
        #[test]
        fn $name() {
            // m^(N-1) must stay exact in i128: 65 points up to N = 16.
            let len = if $N > 9 { 65 } else { 257 };
            for scale in [100, 10_000] {
                let checks = [
                    ("de Casteljau", measure::<$S, $N>(&DeCasteljau, len, scale, de_casteljau_bound::<$S, $N>)),
                    ("subdivide", measure::<$S, $N>(&Subdivide::default(), len, scale, subdivide_bound::<$S, $N>)),
                    ("Bernstein", measure::<$S, $N>(&BernsteinTable::<$S, $N, 65>::new(), 65, scale, table_bound::<$S, $N>)),
                ];
                for (name, (err, ratio)) in checks {
                    assert!(ratio <= 1.0, "{name} N={} scale={scale}: error {err:e} is {ratio:.2}× its bound", $N);
                }
            }
        }
    )*};
}

stable_samplers_hold_bounds! {
    f32_n2: f32, 2; f32_n3: f32, 3; f32_n4: f32, 4; f32_n5: f32, 5; f32_n6: f32, 6;
    f32_n7: f32, 7; f32_n8: f32, 8; f32_n9: f32, 9; f32_n10: f32, 10; f32_n11: f32, 11;
    f32_n12: f32, 12; f32_n13: f32, 13; f32_n14: f32, 14; f32_n15: f32, 15; f32_n16: f32, 16;
    f64_n2: f64, 2; f64_n4: f64, 4; f64_n8: f64, 8; f64_n12: f64, 12; f64_n16: f64, 16;
}

#[test]
fn horner_holds_its_bound_in_floats_and_fails_the_pixel_target_at_degree_7() {
    let (err3, r3) = measure::<f32, 4>(&Horner, 1024, 10_000, horner_bound::<f32, 4>);
    let (err7, r7) = measure::<f32, 8>(&Horner, 1024, 10_000, horner_bound::<f32, 8>);
    assert!(r3 <= 1.0 && r7 <= 1.0, "bound: {r3} {r7}");
    assert!(
        err3 <= 0.01,
        "cubic in f32 at 1e4 px is inside the documented range: {err3}"
    );
    assert!(
        err7 > 0.01,
        "degree 7 in f32 at 1e4 px is documented to miss 0.01 px: {err7}"
    );
    let (err_f64, _) = measure::<f64, 8>(&Horner, 1024, 10_000, horner_bound::<f64, 8>);
    assert!(err_f64 <= 0.01);
}

#[test]
fn forward_differencing_drifts_with_the_count() {
    let (small, r1) = measure::<f32, 4>(&ForwardDiff, 1024, 100, forward_bound::<f32, 4>);
    let (large, r2) = measure::<f32, 4>(&ForwardDiff, 1024, 10_000, forward_bound::<f32, 4>);
    let (deg7, r3) = measure::<f32, 8>(&ForwardDiff, 1024, 10_000, forward_bound::<f32, 8>);
    assert!(r1 <= 1.0 && r2 <= 1.0 && r3 <= 1.0, "bound: {r1} {r2} {r3}");
    assert!(
        small <= 0.01,
        "degree 3, 100 px, 1024 samples is inside the range: {small}"
    );
    assert!(
        large > 0.01,
        "at 1e4 px it is documented to miss 0.01 px: {large}"
    );
    assert!(deg7 > 1.0, "degree 7 at 1e4 px drifts by pixels: {deg7}");
    let (few, _) = measure::<f32, 4>(&ForwardDiff, 64, 10_000, forward_bound::<f32, 4>);
    assert!(few < large, "fewer steps, less drift: {few} vs {large}");
    let (f64_err, _) = measure::<f64, 8>(&ForwardDiff, 1024, 10_000, forward_bound::<f64, 8>);
    assert!(f64_err <= 0.01, "f64 is inside the range: {f64_err}");
}

#[cfg(feature = "fixed")]
mod q16 {
    use super::*;
    use dunas::Q16;

    #[test]
    fn subdivide_is_the_accurate_q16_method_at_any_scale() {
        for scale in [100, 10_000] {
            let (e4, r4) = measure::<Q16, 4>(
                &Subdivide::default(),
                1025,
                scale,
                subdivide_bound::<Q16, 4>,
            );
            let (e8, r8) = measure::<Q16, 8>(
                &Subdivide::default(),
                1025,
                scale,
                subdivide_bound::<Q16, 8>,
            );
            assert!(r4 <= 1.0 && r8 <= 1.0, "scale {scale}: {r4} {r8}");
            assert!(e4 < 1e-3 && e8 < 1e-3, "scale {scale}: {e4} {e8}");
        }
    }

    #[test]
    fn de_casteljau_in_q16_pays_for_the_rounded_parameter() {
        let (err, ratio) =
            measure::<Q16, 4>(&DeCasteljau, 64, 10_000, de_casteljau_bound::<Q16, 4>);
        assert!(ratio <= 1.0, "{ratio}");
        // t = i/63 rounded to 2^-16 moves points by tenths of a pixel at 1e4 px.
        assert!(err > 0.05, "{err}");
        let (sub, _) =
            measure::<Q16, 4>(&Subdivide::default(), 65, 10_000, subdivide_bound::<Q16, 4>);
        assert!(
            sub * 100.0 < err,
            "dyadic parameters are far better: {sub} vs {err}"
        );
    }

    #[test]
    fn horner_and_forward_differencing_fail_in_q16() {
        let (h3, _) = measure::<Q16, 4>(&Horner, 64, 100, horner_bound::<Q16, 4>);
        assert!(
            h3 <= 0.01,
            "cubic at 100 px is inside Horner's Q16 range: {h3}"
        );
        let (h7, _) = measure::<Q16, 8>(&Horner, 64, 100, horner_bound::<Q16, 8>);
        assert!(h7 > 1.0, "degree 7 saturates the power coefficients: {h7}");
        let (fd, _) = measure::<Q16, 4>(&ForwardDiff, 64, 100, forward_bound::<Q16, 4>);
        assert!(
            fd > 1.0,
            "forward differences underflow 2^-16 even at 64 samples: {fd}"
        );
    }
}

#[test]
fn buffers_too_small_are_errors_not_panics() {
    let c = ExactCurve::<f32, 4>::new(Rng(3).grid_points(100));
    let mut one = [Vec2::<f32>::default(); 1];
    let too_small = Err(dunas::Error::BufferTooSmall { needed: 2, got: 1 });
    assert_eq!(DeCasteljau.sample(&c.curve, &mut one), too_small);
    assert_eq!(Horner.sample(&c.curve, &mut one), too_small);
    assert_eq!(ForwardDiff.sample(&c.curve, &mut one), too_small);
    assert_eq!(Subdivide::default().sample(&c.curve, &mut one), too_small);
    assert_eq!(
        DeCasteljau.sample(&c.curve, &mut []),
        Err(dunas::Error::BufferTooSmall { needed: 2, got: 0 })
    );
    let table = BernsteinTable::<f32, 4, 16>::new();
    let mut short = [Vec2::<f32>::default(); 15];
    assert_eq!(
        table.sample(&c.curve, &mut short),
        Err(dunas::Error::BufferTooSmall {
            needed: 16,
            got: 15
        })
    );
}

#[test]
fn subdivide_writes_the_largest_dyadic_count_that_fits() {
    let c = ExactCurve::<f64, 4>::new(Rng(5).grid_points(100));
    let mut buf = [Vec2::<f64>::default(); 100];
    assert_eq!(Subdivide::default().sample(&c.curve, &mut buf), Ok(65));
    assert_eq!(Subdivide::default().sample(&c.curve, &mut buf[..2]), Ok(2));
    assert_eq!(Subdivide::default().sample(&c.curve, &mut buf[..4]), Ok(3));
    assert_eq!(Subdivide { max_level: 3 }.sample(&c.curve, &mut buf), Ok(9));
    assert_eq!(
        c.max_error(&buf[..9], 8),
        0.0,
        "dyadic parameters are exact in f64 here"
    );
}

/// Splines and loops go through the same engine as single curves: a `BernsteinTable` of the
/// span size samples a B-spline like the default sampler, and a `Q16` closed loop takes the
/// dyadic path (`K·2^k + 1` points, each within the subdivision bound of the `f64` loop).
#[cfg(feature = "fixed")]
#[test]
fn splines_and_loops_use_every_sampler() {
    use dunas::Q16;
    use dunas::smooth::{Smoothed, Smoothing};
    let ring: [Vec2<f64>; 6] = core::array::from_fn(|i| {
        let a = i as f64 * std::f64::consts::TAU / 6.0;
        Vec2::new(300.0 * a.cos(), 200.0 * a.sin())
    });
    let (mut by_default, mut by_table) = ([Vec2::default(); 64], [Vec2::default(); 64]);
    let open = Smoothed::open(Smoothing::BSpline, &ring).unwrap();
    let n = open.sample(&mut by_default).unwrap();
    let m = open
        .sample_with(&BernsteinTable::<f64, 4, 13>::new(), &mut by_table)
        .unwrap();
    assert_eq!((n, m), (61, 61));
    for (a, b) in by_default.iter().zip(&by_table).take(n) {
        assert!((*a - *b).length() < 1e-9, "{a:?} vs {b:?}");
    }

    let fixed = ring.map(|p| Vec2::<Q16>::from_f64(p.x, p.y));
    let to_f64 = |q: Vec2<Q16>| Vec2::new(q.x.to_f64(), q.y.to_f64());
    let mut float_out = [Vec2::default(); 49];
    let mut fixed_out = [Vec2::<Q16>::default(); 60]; // room for 9 a span: the dyadic 8 is used
    let floats = Smoothed::closed(Smoothing::CatmullRom, &fixed.map(to_f64))
        .unwrap()
        .sample(&mut float_out)
        .unwrap();
    let fixeds = Smoothed::closed(Smoothing::CatmullRom, &fixed)
        .unwrap()
        .sample(&mut fixed_out)
        .unwrap();
    assert_eq!((floats, fixeds), (49, 49));
    // The handles' rounded 1/6 (2⁻¹⁷ of a neighbour distance up to 600 px: 4.6e-3 px) plus
    // three halvings of a cubic (3·3/2 units of 2⁻¹⁶).
    let bound = 600.0 * 2f64.powi(-17) + 4.5 * 2f64.powi(-16);
    for (f, q) in float_out.iter().zip(&fixed_out) {
        assert!((*f - to_f64(*q)).length() < bound, "{f:?} vs {q:?}");
    }
    assert_eq!(fixed_out[0], fixed_out[48]);
}
