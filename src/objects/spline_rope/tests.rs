//! The spline rope's unit tests: its factor, basis and steps against exact and `f64` results.

use super::*;

#[test]
fn the_banded_factor_solves_its_matrix() {
    // The mass band of 8 control points (7 diagonals), its first row and column made
    // the identity's as a pin does, and a band of 5 diagonals.
    let (mass, _) = mass_matrix::<8>(1.3, 0.7);
    let mut pinned = mass;
    pinned[0] = [1.0, 0.0, 0.0, 0.0];
    for band in [mass, pinned] {
        let l = ldl(&band, finite_inverse).unwrap();
        let x: [f64; 8] = core::array::from_fn(|i| (i as f64 * 1.7).sin() - 0.3);
        let mut b = band_times(&band, &x);
        solve(&l, &mut b);
        for (got, want) in b.iter().zip(&x) {
            assert!((got - want).abs() < 1e-12, "{got} against {want}");
        }
    }
    let narrow: [[f64; 3]; 6] = core::array::from_fn(|i| [4.0 + i as f64, -1.0, 0.5]);
    let l = ldl(&narrow, finite_inverse).unwrap();
    let x = [1.0, -2.0, 0.5, 3.0, -1.0, 2.0];
    let mut b = band_times(&narrow, &x);
    solve(&l, &mut b);
    for (got, want) in b.iter().zip(&x) {
        assert!((got - want).abs() < 1e-12, "{got} against {want}");
    }
    // Not positive definite: no factor.
    let indefinite: [[f64; 3]; 3] = [[1.0, 2.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
    assert!(ldl(&indefinite, finite_inverse).is_none());
}

#[test]
fn the_basis_is_a_partition_of_unity_with_matching_slopes() {
    for k in [4usize, 5, 8, 12] {
        for step in 0..=40 {
            let u = step as f64 / 40.0 * (k - 3) as f64;
            let (n, dn) = basis(u, k);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{k} {u}");
            assert!(dn.iter().sum::<f64>().abs() < 1e-12, "{k} {u}");
            // Slopes against a difference quotient.
            let h = 1e-6;
            if u > h && u + h < (k - 3) as f64 && (u.fract() > 1e-3 && u.fract() < 1.0 - 1e-3) {
                let (np, _) = basis(u + h, k);
                let (nm, _) = basis(u - h, k);
                for a in 0..4 {
                    assert!(
                        ((np[a] - nm[a]) / (2.0 * h) - dn[a]).abs() < 1e-5,
                        "{k} {u} {a}"
                    );
                }
            }
        }
    }
}

#[test]
fn extraction_reproduces_the_curve() {
    for e in 0..5 {
        let ext = extraction(e, 8);
        let cps: [f64; 8] = core::array::from_fn(|i| (i as f64 * 1.7).sin());
        let bez: [f64; 4] = core::array::from_fn(|r| (0..4).map(|c| ext[r][c] * cps[e + c]).sum());
        for m in 0..=10 {
            let t = m as f64 / 10.0;
            let (n, _, _) = basis_in(e, e as f64 + t, 8);
            let exact: f64 = (0..4).map(|a| n[a] * cps[e + a]).sum();
            let b = (1.0 - t).powi(3) * bez[0]
                + 3.0 * t * (1.0 - t).powi(2) * bez[1]
                + 3.0 * t * t * (1.0 - t) * bez[2]
                + t.powi(3) * bez[3];
            assert!((b - exact).abs() < 1e-12, "span {e} t {t}");
        }
    }
}

/// The drawn spans (inner points on a leg, ends halfway) are the extraction's.
#[test]
fn the_drawn_spans_are_the_extraction() {
    fn check<const K: usize>() {
        let ext: [[[f64; 4]; 4]; K] = core::array::from_fn(|e| {
            if e + 3 < K {
                extraction(e, K)
            } else {
                [[0.0; 4]; 4]
            }
        });
        let pos: [crate::Vec2<f64>; K] = core::array::from_fn(|i| {
            crate::Vec2::new((i as f64 * 1.7).sin(), (i as f64 * 0.9).cos())
        });
        let spans = Spans::new(&ext, &pos);
        for e in 0..K - 3 {
            for r in 0..4 {
                let mut b = crate::Vec2::default();
                for k in 0..4 {
                    b += pos[e + k] * ext[e][r][k];
                }
                let drawn = spans.spans[e].points()[r];
                assert!(drawn.distance(b) < 1e-12, "K {K} span {e} point {r}");
            }
        }
    }
    check::<4>();
    check::<5>();
    check::<6>();
    check::<8>();
    check::<11>();
}

/// An undamped 1 m, 1 kg rope of 8 control points, `EA = 2000`, under `gravity`.
/// The implicit step's stiffness product is symmetric and positive semi-definite, and
/// where every tension pulls (stretched 7%) it is the forces' derivative; where some
/// spans are slack (compressed to 93%), it drops what would make it indefinite.
#[test]
fn the_stiffness_product_is_the_force_derivative() {
    use crate::Vec2;
    for stretch in [1.07, 0.93] {
        let mut r = rope(Vec2::new(0.3, -9.81));
        r.set_bending(0.3).unwrap();
        for i in 0..8 {
            let p = r.pos[i];
            r.pos[i] = Vec2::new(
                p.x * stretch + 0.01 * (i as f64 * 1.3).sin(),
                0.03 * (i as f64 * 0.7).cos(),
            );
        }
        let st = r.strains(&r.pos, None);
        let (_, t) = r.forces(&st, &r.external(&Default::default()), 1.0);
        let mut lin = r.linearized(&st, &t, 1.0, true);
        lin.damping = 0.0;
        let u: [Vec2<f64>; 8] =
            core::array::from_fn(|i| Vec2::new((i as f64).sin(), (i as f64 * 2.1).cos()));
        let ku = r.stiffness_times(&lin, &u);
        let eps = 1e-7;
        let at = |sign: f64| {
            let x: [Vec2<f64>; 8] = core::array::from_fn(|i| r.pos[i] + u[i] * (sign * eps));
            r.forces(&r.strains(&x, None), &r.external(&Default::default()), 1.0)
                .0
        };
        let (plus, minus) = (at(1.0), at(-1.0));
        let w: [Vec2<f64>; 8] =
            core::array::from_fn(|i| Vec2::new((i as f64 * 0.3).cos(), (i as f64).sin()));
        let kw = r.stiffness_times(&lin, &w);
        let dot = |a: &[Vec2<f64>; 8], b: &[Vec2<f64>; 8]| -> f64 {
            a.iter().zip(b).map(|(x, y)| x.dot(*y)).sum()
        };
        let (uku, wkw, ukw, wku) = (dot(&u, &ku), dot(&w, &kw), dot(&u, &kw), dot(&w, &ku));
        assert!(uku >= 0.0 && wkw >= 0.0, "{stretch}: {uku} {wkw}");
        assert!(
            (ukw - wku).abs() < 1e-9 * (uku + wkw),
            "{stretch}: {ukw} {wku}"
        );
        if stretch < 1.0 {
            // Slack: the dropped terms make it differ from the derivative.
            continue;
        }
        for i in 0..8 {
            let fd = (plus[i] - minus[i]) * (-0.5 / eps);
            let scale = 1.0 + fd.length();
            assert!(
                (ku[i] - fd).length() < 1e-6 * scale,
                "{i}: {:?} {:?}",
                ku[i],
                fd
            );
        }
    }
}

/// On a taut rope that bends, the preconditioner inverts the system but for its
/// sideways stiffness: with that left out, `P⁻¹·A·u = u`.
#[test]
fn the_stretch_preconditioner_solves_the_taut_stretch() {
    use crate::Vec2;
    let mut r = rope(Vec2::new(0.3, -9.81));
    for i in 0..8 {
        let p = r.pos[i];
        r.pos[i] = Vec2::new(
            p.x * 1.03 + 0.01 * (i as f64 * 1.3).sin(),
            0.2 * (i as f64 * 0.7).cos(),
        );
    }
    let st = r.strains(&r.pos, None);
    let (_, t) = r.forces(&st, &r.external(&Default::default()), 1.0);
    for h in [1e-3, 1.0 / 60.0, 1.0] {
        let mut lin = r.linearized(&st, &t, h, true);
        assert!(lin.uniform);
        lin.transverse = [[0.0; 3]; 8];
        let drag = 0.1;
        let u = r.free(core::array::from_fn(|i| {
            Vec2::new((i as f64).sin(), (i as f64 * 2.1).cos())
        }));
        r.set_bending(0.5).unwrap();
        let (m, k) = (r.mass_times(&u), r.stiffness_times(&lin, &u));
        let au = r.free(core::array::from_fn(|i| m[i] * (1.0 + drag) + k[i]));
        let pre = r.preconditioner(&lin, h, drag);
        assert!(pre.stretch.is_some());
        let back = r.precondition(&pre, &au);
        for i in 0..8 {
            assert!(
                (back[i] - u[i]).length() < 1e-8,
                "{h} {i}: {:?} {:?}",
                back[i],
                u[i]
            );
        }
    }
}

fn rope(gravity: crate::Vec2<f64>) -> SplineRope<crate::Vec2<f64>, 8> {
    let s = Settings {
        gravity,
        ..Settings::default()
    };
    let m = Material {
        stiffness: 2000.0,
        damping: 0.0,
    };
    let (a, b) = (crate::Vec2::new(0.0, 0.0), crate::Vec2::new(1.0, 0.0));
    SplineRope::new(a, b, 1.0, m, s).unwrap()
}

/// The forces are minus the gradient of the energy (finite differences).
#[test]
fn forces_are_the_energy_gradient() {
    use crate::Vec2;
    let mut r = rope(Vec2::new(0.3, -9.81));
    r.set_bending(0.3).unwrap();
    for i in 0..8 {
        let p = r.pos[i];
        r.pos[i] = Vec2::new(
            p.x * 1.07 + 0.05 * (i as f64 * 1.3).sin(),
            0.2 * (i as f64 * 0.7).cos(),
        );
    }
    let f = r
        .forces(
            &r.strains(&r.pos, Some(&r.vel)),
            &r.external(&Default::default()),
            1.0,
        )
        .0;
    let h = 1e-6;
    for i in 0..8 {
        for axis in 0..2 {
            let mut plus = r.clone();
            let mut minus = r.clone();
            let mut p = plus.pos[i];
            p.set_coord(axis, p.coord(axis) + h);
            plus.pos[i] = p;
            let mut q = minus.pos[i];
            q.set_coord(axis, q.coord(axis) - h);
            minus.pos[i] = q;
            let grad = (plus.energy() - minus.energy()) / (2.0 * h);
            let force = f[i].coord(axis) * r.unit;
            assert!(
                (force + grad).abs() < 1e-4 * (1.0 + force.abs()),
                "{i} {axis}: force {force} grad {grad}"
            );
        }
    }
}

/// The substep rate is the straight rope's largest frequency: against a dense reference
/// (finite differences of the forces along the rope, Gaussian elimination on the free
/// control points' mass, 20 000 power iterations), with pins and bending.
#[test]
fn the_rate_is_the_straight_ropes_largest_frequency() {
    fn check<const K: usize>(pins: &[usize], ei: f64) {
        use crate::Vec2;
        let s = Settings::default();
        let m = Material {
            stiffness: 3000.0,
            damping: 0.0,
        };
        let (a, b) = (Vec2::new(0.0, 0.0), Vec2::new(1.5, 0.0));
        let mut r: SplineRope<Vec2<f64>, K> = SplineRope::new(a, b, 0.7, m, s).unwrap();
        for &i in pins {
            r.set_pinned(i, true).unwrap();
        }
        r.set_bending(ei).unwrap();
        let free: heapless::Vec<usize, 64> = (0..K).filter(|&i| !r.pinned[i]).collect();
        let n = free.len();
        let h = 1e-7;
        let force_x = |r: &SplineRope<Vec2<f64>, K>| {
            r.forces(
                &r.strains(&r.pos, Some(&r.vel)),
                &r.external(&[Vec2::default(); K]),
                1.0,
            )
            .0
        };
        let mut stiff = [[0.0; 64]; 64];
        let mut mass = [[0.0; 64]; 64];
        for (col, &j) in free.iter().enumerate() {
            let (mut plus, mut minus) = (r.clone(), r.clone());
            plus.pos[j].x += h;
            minus.pos[j].x -= h;
            let (fp, fm) = (force_x(&plus), force_x(&minus));
            for (row, &i) in free.iter().enumerate() {
                stiff[row][col] = -(fp[i].x - fm[i].x) / (2.0 * h);
                let (lo, hi) = (i.min(j), i.max(j));
                mass[row][col] = if hi - lo < 4 {
                    r.mass_band[lo][hi - lo]
                } else {
                    0.0
                };
            }
        }
        // x ← M⁻¹ K x by elimination, 20 000 times.
        let mut x = [0.0; 64];
        for (i, xi) in x.iter_mut().enumerate().take(n) {
            *xi = 1.0 + (i as f64 * 0.37).sin();
        }
        let mut lambda = 0.0;
        for _ in 0..20_000 {
            let mut a = mass;
            let mut y = [0.0; 64];
            for i in 0..n {
                y[i] = (0..n).map(|j| stiff[i][j] * x[j]).sum();
            }
            for c in 0..n {
                for i in c + 1..n {
                    let f = a[i][c] / a[c][c];
                    for j in c..n {
                        a[i][j] -= f * a[c][j];
                    }
                    y[i] -= f * y[c];
                }
            }
            for i in (0..n).rev() {
                let t: f64 = (i + 1..n).map(|j| a[i][j] * y[j]).sum();
                y[i] = (y[i] - t) / a[i][i];
            }
            let norm = (0..n).map(|i| y[i] * y[i]).sum::<f64>().sqrt();
            lambda =
                (0..n).map(|i| y[i] * x[i]).sum::<f64>() / (0..n).map(|i| x[i] * x[i]).sum::<f64>();
            for i in 0..n {
                x[i] = y[i] / norm;
            }
        }
        let omega = r.stiffness_bound().0;
        let want = lambda.sqrt();
        assert!(
            (omega - want).abs() < 1e-5 * want,
            "K {K} pins {pins:?} EI {ei}: {omega} against {want}"
        );
    }
    check::<4>(&[], 0.0);
    check::<5>(&[4], 0.0);
    check::<8>(&[], 0.0);
    check::<8>(&[3, 7], 2.0);
    check::<8>(&[1], 40.0);
    check::<16>(&[15], 0.0);
    check::<16>(&[8], 0.5);
}

#[test]
/// The largest frequency of the linearised rope, found by power iteration on finite
/// differences of the forces along a swing, never passes the bound from the straight rope.
fn the_bound_holds_in_motion() {
    use crate::Vec2;
    let mut r = rope(Vec2::new(0.0, -9.81));
    for frame in 0..200 {
        let _ = r.step(1.0 / 60.0).unwrap();
        if frame % 20 != 19 {
            continue;
        }
        // Power iteration on -M⁻¹ ∂f/∂x by finite differences of the forces.
        let f0 = r
            .forces(
                &r.strains(&r.pos, None),
                &r.external(&Default::default()),
                1.0,
            )
            .0;
        let mut x: [Vec2<f64>; 8] = core::array::from_fn(|i| {
            if i == 0 {
                Vec2::default()
            } else {
                Vec2::new(((i * 7) % 3) as f64 - 1.0, ((i * 5) % 4) as f64 - 1.5)
            }
        });
        let mut lambda = 0.0;
        for _ in 0..300 {
            let h = 1e-7;
            let moved: [Vec2<f64>; 8] = core::array::from_fn(|i| r.pos[i] + x[i] * h);
            let f1 = r
                .forces(
                    &r.strains(&moved, None),
                    &r.external(&Default::default()),
                    1.0,
                )
                .0;
            let mut y: [Vec2<f64>; 8] = core::array::from_fn(|i| (f0[i] - f1[i]) * (1.0 / h));
            y[0] = Vec2::default();
            solve(&r.chol, &mut y);
            y[0] = Vec2::default();
            let norm = y.iter().map(|v| v.dot(*v)).sum::<f64>().sqrt();
            let dot: f64 = y.iter().zip(&x).map(|(a, b)| a.dot(*b)).sum();
            let xx: f64 = x.iter().map(|v| v.dot(*v)).sum();
            lambda = dot / xx;
            x = y.map(|v| v * (1.0 / norm));
        }
        assert!(
            lambda.abs().sqrt() <= r.omega * 1.001,
            "frame {frame}: {} > {}",
            lambda.abs().sqrt(),
            r.omega
        );
    }
}
