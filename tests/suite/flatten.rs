//! Adaptive flattening against a dense reference: every point of the curve (2001 samples)
//! within the tolerance of the polyline, for random cubics at several tolerances.
#![cfg(any(feature = "std", feature = "libm"))]

use crate::common;
use crate::common::Rng;
use dunas::{Bezier, Error, Vec2, flatten};

/// Largest distance from 2001 points of `c` to the polyline `poly`.
fn deviation(c: &Bezier<Vec2<f64>, 4>, poly: &[Vec2<f64>]) -> f64 {
    (0..=2000)
        .map(|i| common::to_polyline(c.eval(i as f64 / 2000.0), poly))
        .fold(0.0, f64::max)
}

#[test]
fn flattened_cubics_stay_within_the_tolerance() {
    let mut rng = Rng(0xf1a7);
    let mut out = vec![Vec2::default(); 4096];
    for tol in [0.05, 0.25, 1.0, 2.0] {
        let mut worst = 0.0f64;
        for _ in 0..200 {
            let p: [Vec2<f64>; 4] = core::array::from_fn(|_| {
                Vec2::new(rng.grid(200) as f64 / 16.0, rng.grid(200) as f64 / 16.0)
            });
            let c = Bezier::new(p).unwrap();
            let n = flatten::flatten(&c, tol, &mut out).unwrap();
            assert_eq!(n, flatten::segments(&c, tol).unwrap() + 1);
            assert_eq!((out[0], out[n - 1]), (c.start(), c.end()));
            let d = deviation(&c, &out[..n]);
            if d > worst {
                eprintln!("tol {tol}: {d:.4} over {n} points for {p:?}");
            }
            worst = worst.max(d);
        }
        eprintln!("tol {tol}: worst {worst:.4}");
        assert!(worst <= tol, "tol {tol}: {worst}");
    }
}

#[test]
fn bad_tolerances_and_small_buffers_are_errors() {
    let c = Bezier::new([
        Vec2::new(0.0f32, 0.0),
        Vec2::new(10.0, 20.0),
        Vec2::new(20.0, -20.0),
        Vec2::new(30.0, 0.0),
    ])
    .unwrap();
    for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert!(matches!(
            flatten::segments(&c, bad),
            Err(Error::InvalidParameter { .. })
        ));
    }
    let mut out = [Vec2::default(); 2];
    assert!(matches!(
        flatten::flatten(&c, 0.01, &mut out),
        Err(Error::BufferTooSmall { .. })
    ));
}
