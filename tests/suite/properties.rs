//! Property tests of the geometry on random input: the invariants every Bézier method
//! must keep, checked against `f64` or exact integer arithmetic.
#![cfg(any(feature = "std", feature = "libm"))]

use dunas::sampler::{BernsteinTable, DeCasteljau, Sampler, Subdivide};
use dunas::smooth::{Smoothed, Smoothing};
use dunas::{Bezier, Patch, Point, Scalar, Vec2, Vec3, lod};
use proptest::prelude::*;

fn pts<const N: usize>(range: f64) -> impl Strategy<Value = [Vec2<f64>; N]> {
    prop::collection::vec((-range..range, -range..range), N)
        .prop_map(|v| core::array::from_fn(|i| Vec2::new(v[i].0, v[i].1)))
}

fn to_f32<const N: usize>(p: &[Vec2<f64>; N]) -> [Vec2<f32>; N] {
    p.map(|q| Vec2::new(q.x as f32, q.y as f32))
}

/// Exact-enough f64 evaluation of the f32 curve's control points (the f32 reference).
fn widen<const N: usize>(p: &[Vec2<f32>; N]) -> Bezier<Vec2<f64>, N> {
    Bezier::new(p.map(|q| Vec2::new(q.x as f64, q.y as f64))).unwrap()
}

fn max_abs<const N: usize>(p: &[Vec2<f32>; N]) -> f64 {
    p.iter()
        .map(|q| q.x.abs().max(q.y.abs()) as f64)
        .fold(0.0, f64::max)
}

macro_rules! sampler_properties {
    ($($name:ident: $N:literal;)*) => {$(
        proptest! {
            #[test]
            fn $name(p in pts::<$N>(1e4)) {
                let p32 = to_f32(&p);
                let c = Bezier::new(p32).unwrap();
                let reference = widen(&p32);
                let r = max_abs(&p32);
                let eps = f32::EPSILON as f64;
                let bbox = c.bounding_box();
                let slack = 4.0 * eps * r;
                let mut out = [Vec2::<f32>::default(); 33];
                let table = BernsteinTable::<f32, $N, 33>::new();
                let samplers: [(&str, &dyn Sampler<Vec2<f32>, $N>, f64); 3] = [
                    ("de Casteljau", &DeCasteljau, 4.0 * ($N - 1) as f64),
                    ("Bernstein", &table, 4.0 * $N as f64),
                    ("subdivide", &Subdivide::default(), (5 + $N) as f64),
                ];
                for (name, s, k) in samplers {
                    let n = s.sample(&c, &mut out).unwrap();
                    prop_assert_eq!(n, 33);
                    prop_assert_eq!(out[0], c.start(), "{} start", name);
                    prop_assert_eq!(out[32], c.end(), "{} end", name);
                    for (i, q) in out.iter().enumerate() {
                        let exact = reference.eval(i as f64 / 32.0);
                        let err = (exact.x - q.x as f64).hypot(exact.y - q.y as f64);
                        prop_assert!(err <= k * eps * r, "{} sample {}: {} > bound {}", name, i, err, k * eps * r);
                        // Convex hull property, up to rounding.
                        let grown = dunas::Aabb {
                            min: bbox.min - Vec2::splat(slack as f32),
                            max: bbox.max + Vec2::splat(slack as f32),
                        };
                        prop_assert!(grown.contains(*q), "{} sample {} outside the control box", name, i);
                    }
                }
            }
        }
    )*};
}

sampler_properties! {
    samplers_n2: 2; samplers_n3: 3; samplers_n4: 4; samplers_n5: 5; samplers_n6: 6;
    samplers_n8: 8; samplers_n11: 11; samplers_n16: 16;
}

#[test]
fn bernstein_weights_are_a_partition_of_unity() {
    let t = BernsteinTable::<f64, 9, 50>::new();
    let t32 = BernsteinTable::<f32, 16, 50>::new();
    for i in 0..50 {
        let row = t.row(i).unwrap();
        let sum: f64 = row.iter().sum();
        assert!((sum - 1.0).abs() <= 9.0 * f64::EPSILON);
        assert!(row.iter().all(|&w| (0.0..=1.0).contains(&w)));
        let sum32: f32 = t32.row(i).unwrap().iter().sum();
        assert!((sum32 - 1.0).abs() <= 16.0 * f32::EPSILON);
    }
    assert!(t.row(50).is_none());
}

proptest! {
    #[test]
    fn split_halves_trace_the_same_curve(p in pts::<6>(1e3), t in 0.01f64..0.99, s in 0.0f64..=1.0) {
        let c = Bezier::new(p).unwrap();
        let (l, r) = c.split(t);
        prop_assert_eq!(l.start(), c.start());
        prop_assert_eq!(r.end(), c.end());
        prop_assert!((l.end() - r.start()).length() <= 1e-9);
        prop_assert!((l.eval(s) - c.eval(s * t)).length() <= 1e-9);
        prop_assert!((r.eval(s) - c.eval(t + s * (1.0 - t))).length() <= 1e-9);
        let (hl, hr) = c.split_half();
        prop_assert!((hl.eval(s) - c.eval(s * 0.5)).length() <= 1e-9);
        prop_assert!((hr.eval(s) - c.eval(0.5 + s * 0.5)).length() <= 1e-9);
    }

    #[test]
    fn sampling_commutes_with_affine_maps(
        p in pts::<5>(1e3),
        m in prop::array::uniform4(-3.0f64..3.0),
        shift in (-1e3f64..1e3, -1e3f64..1e3),
    ) {
        let map = |q: Vec2<f64>| Vec2::new(m[0] * q.x + m[1] * q.y + shift.0, m[2] * q.x + m[3] * q.y + shift.1);
        let c = Bezier::new(p).unwrap();
        let mapped = Bezier::new(p.map(map)).unwrap();
        let (mut a, mut b) = ([Vec2::default(); 17], [Vec2::default(); 17]);
        c.sample(&mut a).unwrap();
        mapped.sample(&mut b).unwrap();
        for (qa, qb) in a.iter().zip(&b) {
            prop_assert!((map(*qa) - *qb).length() <= 1e-9);
        }
    }

    #[test]
    fn tangent_matches_a_central_difference(p in pts::<7>(100.0), t in 0.01f64..0.99) {
        let c = Bezier::new(p).unwrap();
        let h = 1e-6;
        let fd = (c.eval(t + h) - c.eval(t - h)) * (0.5 / h);
        prop_assert!((c.tangent(t) - fd).length() <= 1e-5 * (1.0 + fd.length()));
    }

    #[test]
    fn arclen_meets_the_requested_accuracy(p in pts::<5>(100.0), acc in prop::sample::select(vec![1.0, 1e-2, 1e-4, 1e-7])) {
        let c = Bezier::new(p).unwrap();
        // Reference: Richardson-extrapolated dense chords (error far below 1e-7 here).
        let chords = |n: usize| -> f64 {
            (0..n).map(|i| c.eval(i as f64 / n as f64).distance(c.eval((i + 1) as f64 / n as f64))).sum()
        };
        let (l1, l2) = (chords(1 << 13), chords(1 << 14));
        let exact = (4.0 * l2 - l1) / 3.0;
        let got = c.arclen(acc);
        prop_assert!((got - exact).abs() <= acc + 1e-8 * exact, "{} vs {} at {}", got, exact, acc);
        prop_assert!(got <= c.polygon_length() + 1e-9);
        prop_assert!(got >= c.start().distance(c.end()) - 1e-9);
    }

    #[test]
    fn catmull_rom_passes_through_random_particles(p in pts::<7>(500.0)) {
        let mut out = [Vec2::default(); 6 * 4 + 1];
        Smoothed::open(Smoothing::CatmullRom, &p).unwrap().sample(&mut out).unwrap();
        for (k, pk) in p.iter().enumerate() {
            prop_assert!((out[4 * k] - *pk).length() <= 1e-9);
        }
    }
}

/// Largest parametric distance between a curve and the polyline of its `n + 1` uniform
/// samples, measured at 64 points per segment.
fn polyline_deviation<const N: usize>(c: &Bezier<Vec2<f64>, N>, n: usize) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..n {
        let (t0, t1) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
        let (a, b) = (c.eval(t0), c.eval(t1));
        for k in 1..64 {
            let s = k as f64 / 64.0;
            let on_curve = c.eval(t0 + s * (t1 - t0));
            worst = worst.max((on_curve - a.lerp(b, s)).length());
        }
    }
    worst
}

proptest! {
    #[test]
    fn wang_count_keeps_random_curves_within_tolerance(
        p in pts::<4>(300.0),
        q in pts::<6>(300.0),
        tol in prop::sample::select(vec![0.05, 0.25, 1.0, 4.0]),
    ) {
        let cubic = Bezier::new(p).unwrap();
        let n = lod::segments(&cubic, tol).unwrap();
        prop_assert!(polyline_deviation(&cubic, n) <= tol);
        let quintic = Bezier::new(q).unwrap();
        let n = lod::segments(&quintic, tol).unwrap();
        prop_assert!(polyline_deviation(&quintic, n) <= tol);
    }

    #[test]
    fn wang_count_for_patches_bounds_bilinear_quads(
        z in prop::collection::vec(-50.0f64..50.0, 16),
        tol in prop::sample::select(vec![0.1, 0.5, 2.0]),
    ) {
        let patch = Patch::new(core::array::from_fn::<_, 4, _>(|j| {
            core::array::from_fn::<_, 4, _>(|i| Vec3::new(30.0 * i as f64, 30.0 * j as f64, z[4 * j + i]))
        })).unwrap();
        let (nu, nv) = lod::patch_segments(&patch, tol).unwrap();
        let mut worst = 0.0f64;
        for i in 0..nu {
            for j in 0..nv {
                let (u0, u1) = (i as f64 / nu as f64, (i + 1) as f64 / nu as f64);
                let (v0, v1) = (j as f64 / nv as f64, (j + 1) as f64 / nv as f64);
                let corners = [patch.eval(u0, v0), patch.eval(u1, v0), patch.eval(u0, v1), patch.eval(u1, v1)];
                for a in 1..8 {
                    for b in 1..8 {
                        let (s, t) = (a as f64 / 8.0, b as f64 / 8.0);
                        let bilinear = corners[0].lerp(corners[1], s).lerp(corners[2].lerp(corners[3], s), t);
                        let exact = patch.eval(u0 + s * (u1 - u0), v0 + t * (v1 - v0));
                        worst = worst.max((exact - bilinear).length());
                    }
                }
            }
        }
        prop_assert!(worst <= tol, "deviation {} over tolerance {} with {}×{}", worst, tol, nu, nv);
    }
}

#[test]
fn wang_count_on_cusps_loops_and_inflections() {
    let cases: [[Vec2<f64>; 4]; 4] = [
        // Cusp: the middle legs cross so the speed vanishes.
        [
            Vec2::new(0.0, 0.0),
            Vec2::new(300.0, 300.0),
            Vec2::new(0.0, 300.0),
            Vec2::new(300.0, 0.0),
        ],
        // Loop.
        [
            Vec2::new(0.0, 0.0),
            Vec2::new(400.0, 300.0),
            Vec2::new(-100.0, 300.0),
            Vec2::new(300.0, 0.0),
        ],
        // Inflection (S shape).
        [
            Vec2::new(0.0, 0.0),
            Vec2::new(100.0, 300.0),
            Vec2::new(200.0, -300.0),
            Vec2::new(300.0, 0.0),
        ],
        // Nearly straight with a tiny wiggle.
        [
            Vec2::new(0.0, 0.0),
            Vec2::new(100.0, 0.01),
            Vec2::new(200.0, -0.01),
            Vec2::new(300.0, 0.0),
        ],
    ];
    for p in cases {
        let c = Bezier::new(p).unwrap();
        for tol in [0.01, 0.1, 0.25, 1.0] {
            let n = lod::segments(&c, tol).unwrap();
            let dev = polyline_deviation(&c, n);
            assert!(dev <= tol, "{p:?} tol {tol}: {n} segments deviate {dev}");
            if n > 2 {
                // Wang's bound is within a factor of a few of what is needed.
                let fewer = polyline_deviation(&c, n / 4);
                assert!(fewer > tol / 16.0, "{p:?} tol {tol}: n/4 gives {fewer}");
            }
        }
    }
}

#[cfg(feature = "fixed")]
mod q16 {
    use super::*;
    use dunas::Q16;

    fn clamp(x: i128) -> i32 {
        x.clamp(i32::MIN as i128, i32::MAX as i128) as i32
    }

    /// Round-to-nearest division of exact integers, ties away from zero.
    fn div_round(n: i128, d: i128) -> i128 {
        let q = n / d;
        let r = n % d;
        if 2 * r.abs() >= d.abs() {
            q + if (n < 0) == (d < 0) { 1 } else { -1 }
        } else {
            q
        }
    }

    proptest! {
        #[test]
        fn q16_operators_saturate_and_never_wrap(a in any::<i32>(), b in any::<i32>()) {
            let (x, y) = (Q16::from_bits(a), Q16::from_bits(b));
            let (a, b) = (a as i128, b as i128);
            prop_assert_eq!((x + y).to_bits(), clamp(a + b));
            prop_assert_eq!((x - y).to_bits(), clamp(a - b));
            // Product rounded half up: floor((a·b + 2^15) / 2^16).
            prop_assert_eq!((x * y).to_bits(), clamp((a * b + (1 << 15)) >> 16));
            if b != 0 {
                prop_assert_eq!((x / y).to_bits(), clamp(div_round(a << 16, b)));
            }
            let wide_norm = ((a * a + b * b) as u128).isqrt() as i128;
            prop_assert_eq!(Q16::norm(&[x, y]).to_bits(), clamp(wide_norm));
            // The length with its inverse: the same length, and an inverse within 2⁻¹⁴
            // relative or one unit (saturated for the tiniest vectors); the quick reciprocal
            // within 2⁻¹³ or one unit, 0 for what is not positive.
            let (length, inverse) = Vec2::new(x, y).length_and_inverse();
            prop_assert_eq!(length.to_bits(), clamp(wide_norm));
            let exact = |r: f64| r.min(i32::MAX as f64);
            if wide_norm > 0 {
                let want = exact(2f64.powi(32) / ((a * a + b * b) as f64).sqrt());
                let got = inverse.to_bits() as f64;
                prop_assert!((got - want).abs() <= (want / 16384.0).max(1.0), "{got} {want}");
            } else {
                prop_assert_eq!(inverse, Q16::ZERO);
            }
            let recip = x.approx_recip().to_bits() as f64;
            if a > 0 {
                let want = exact(2f64.powi(32) / a as f64);
                prop_assert!((recip - want).abs() <= (want / 8192.0).max(1.0), "{recip} {want}");
            } else {
                prop_assert_eq!(recip, 0.0);
            }
        }

        #[test]
        fn q16_curves_hit_their_ends_and_stay_in_the_box(
            raw in prop::collection::vec(-16383i32..=16383, 10),
        ) {
            let p: [Vec2<Q16>; 5] = core::array::from_fn(|i| {
                Vec2::new(Q16::from_bits(raw[2 * i] << 16), Q16::from_bits(raw[2 * i + 1] << 16))
            });
            let c = Bezier::new(p).unwrap();
            let mut out = [Vec2::<Q16>::default(); 33];
            for n in [Subdivide::default().sample(&c, &mut out).unwrap(), DeCasteljau.sample(&c, &mut out).unwrap()] {
                prop_assert_eq!(out[0], c.start());
                prop_assert_eq!(out[n - 1], c.end());
                let b = c.bounding_box();
                let one = Vec2::splat(Q16::EPSILON * Q16::from_i16(8));
                let grown = dunas::Aabb { min: b.min - one, max: b.max + one };
                for q in &out[..n] {
                    prop_assert!(q.is_finite() && grown.contains(*q));
                }
            }
        }
    }
}
