//! Exact references shared by the tests and the measuring examples.
#![allow(dead_code)]

use dunas::Settings;
use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::integrator::AnyIntegrator;
use dunas::shape::Line;
use dunas::spring::{Material, Springs};
use dunas::surface::SurfaceTable;
use dunas::{
    Accuracy, Bezier, Cloth, Error, Integrator, MassSpring, Point, Scalar, Smoothing, Vec2, Vec3,
};

/// Control points on a grid of `1 / DENOM`: exactly representable in f32, f64 and Q16.
pub const DENOM: i64 = 16;

/// A curve with integer-grid control points, kept both exactly and in format `S`.
pub struct ExactCurve<S: Scalar, const N: usize> {
    /// Control point coordinates times `DENOM`.
    pub grid: [[i64; 2]; N],
    /// The same curve in the format under test.
    pub curve: Bezier<Vec2<S>, N>,
}

impl<S: Scalar, const N: usize> ExactCurve<S, N> {
    pub fn new(grid: [[i64; 2]; N]) -> Self {
        let pts =
            grid.map(|[x, y]| Vec2::from_f64(x as f64 / DENOM as f64, y as f64 / DENOM as f64));
        ExactCurve {
            grid,
            curve: Bezier::new(pts).expect("grid points are in range"),
        }
    }

    /// The exact point at `t = i / m`, rounded once to f64.
    ///
    /// `Σ C(d,k) (m-i)^(d-k) i^k P_k / (m^d · DENOM)` in 128-bit integers: exact while
    /// `m^d · 2^(d+1) · |P|·DENOM < 2^127` (d = 7, m = 1024, |P| = 10^4: about 2^93).
    pub fn exact(&self, i: u64, m: u64) -> [f64; 2] {
        let d = (N - 1) as u32;
        let (i, m) = (i as i128, m as i128);
        let mut num = [0i128; 2];
        let mut binom: i128 = 1;
        for k in 0..=d {
            let w = binom * (m - i).pow(d - k) * i.pow(k);
            for (c, n) in num.iter_mut().enumerate() {
                *n += w * self.grid[k as usize][c] as i128;
            }
            binom = binom * (d - k) as i128 / (k + 1) as i128;
        }
        let den = m.pow(d) * DENOM as i128;
        num.map(|n| n as f64 / den as f64)
    }

    /// Largest distance between `samples` (taken at `t = i / m`) and the exact curve.
    pub fn max_error(&self, samples: &[Vec2<S>], m: u64) -> f64 {
        samples
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let [x, y] = self.exact(i as u64, m);
                if !p.is_finite() {
                    return f64::INFINITY;
                }
                (p.x.to_f64() - x).hypot(p.y.to_f64() - y)
            })
            .fold(0.0, f64::max)
    }
}

/// A small deterministic generator (xorshift64*), so measurements repeat exactly.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in `-scale..=scale` on the `1 / DENOM` grid.
    pub fn grid(&mut self, scale: i64) -> i64 {
        let span = (2 * scale * DENOM + 1) as u64;
        (self.next_u64() % span) as i64 - scale * DENOM
    }

    pub fn grid_points<const N: usize>(&mut self, scale: i64) -> [[i64; 2]; N] {
        core::array::from_fn(|_| [self.grid(scale), self.grid(scale)])
    }
}

/// Times of upward zero crossings of a sampled signal (linear interpolation).
pub fn up_crossings(samples: &[(f64, f64)]) -> Vec<f64> {
    samples
        .windows(2)
        .filter(|w| w[0].1 < 0.0 && w[1].1 >= 0.0)
        .map(|w| w[0].0 + (w[1].0 - w[0].0) * (-w[0].1) / (w[1].1 - w[0].1))
        .collect()
}

/// Mean period between upward crossings.
pub fn period(samples: &[(f64, f64)]) -> f64 {
    let c = up_crossings(samples);
    assert!(c.len() >= 3, "too few oscillations");
    (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64
}

/// Catenary parameter `a` with `2a·sinh(span / 2a) = length`, by bisection.
pub fn catenary_a(span: f64, length: f64) -> f64 {
    let (mut lo, mut hi) = (1e-3f64, 1e6f64);
    for _ in 0..200 {
        let mid = (lo * hi).sqrt();
        if 2.0 * mid * (span / (2.0 * mid)).sinh() > length {
            lo = mid
        } else {
            hi = mid
        }
    }
    (lo * hi).sqrt()
}

/// Eigenvalues and eigenvectors of a small symmetric matrix by cyclic Jacobi rotations.
#[allow(clippy::needless_range_loop)] // rotations index rows and columns in step
pub fn jacobi_eigen<const N: usize>(mut a: [[f64; N]; N]) -> ([f64; N], [[f64; N]; N]) {
    let mut v = [[0.0; N]; N];
    for (i, row) in v.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for _ in 0..100 {
        for p in 0..N {
            for q in p + 1..N {
                if a[p][q].abs() < 1e-300 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let (c, s) = (1.0 / (t * t + 1.0).sqrt(), t / (t * t + 1.0).sqrt());
                for k in 0..N {
                    let (akp, akq) = (a[k][p], a[k][q]);
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for k in 0..N {
                    let (apk, aqk) = (a[p][k], a[q][k]);
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for row in v.iter_mut() {
                    let (vkp, vkq) = (row[p], row[q]);
                    row[p] = c * vkp - s * vkq;
                    row[q] = s * vkp + c * vkq;
                }
            }
        }
    }
    (core::array::from_fn(|i| a[i][i]), v)
}

/// Distance from `p` to the polyline `line`.
pub fn to_polyline(p: Vec2<f64>, line: &[Vec2<f64>]) -> f64 {
    line.windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            let len2 = d.dot(d);
            let t = if len2 > 0.0 {
                ((p - w[0]).dot(d) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p - (w[0] + d * t)).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Symmetric Hausdorff distance between two polylines (each densified to 256 points).
pub fn hausdorff(a: &[Vec2<f64>], b: &[Vec2<f64>]) -> f64 {
    let dense = |l: &[Vec2<f64>]| -> Vec<Vec2<f64>> {
        let per = (256 / (l.len() - 1)).max(1);
        let mut out = Vec::new();
        for w in l.windows(2) {
            for k in 0..per {
                out.push(w[0].lerp(w[1], k as f64 / per as f64));
            }
        }
        out.push(l[l.len() - 1]);
        out
    };
    let (da, db) = (dense(a), dense(b));
    let one =
        |x: &[Vec2<f64>], y: &[Vec2<f64>]| x.iter().map(|&p| to_polyline(p, y)).fold(0.0, f64::max);
    one(&da, b).max(one(&db, a))
}

/// The sharpest corner of a drawn polyline: the largest turning angle (degrees) between
/// consecutive segments. What the eye sees as a kink, whatever the shape error.
pub fn sharpest_corner(line: &[Vec2<f64>]) -> f64 {
    line.windows(3)
        .filter_map(|w| {
            let (a, b) = (w[1] - w[0], w[2] - w[1]);
            let (la, lb) = (a.length(), b.length());
            (la > 1e-9 && lb > 1e-9)
                .then(|| (a.dot(b) / (la * lb)).clamp(-1.0, 1.0).acos().to_degrees())
        })
        .fold(0.0, f64::max)
}

/// A chain of `N` particles (total mass 1, stiffness `k`) hanging from pins at (±span/2, 0),
/// started on a V of the right length so its springs begin at rest, stepped `steps` times by
/// `dt` with `integrator` and linear damping 2.
pub fn chain_between_pins<const N: usize, const CAP: usize>(
    span: f64,
    length: f64,
    k: f64,
    integrator: AnyIntegrator,
    steps: usize,
    dt: f64,
) -> MassSpring<Vec2<f64>, Line<N>, Springs<f64, CAP>, AnyIntegrator> {
    let seg = length / (N - 1) as f64;
    let half_dx = span / 2.0 / ((N - 1) as f64 / 2.0);
    let dy = (seg * seg - half_dx * half_dx).sqrt();
    let pos: [Vec2<f64>; N] = core::array::from_fn(|i| {
        let from_mid = (i as f64 - (N - 1) as f64 / 2.0).abs();
        Vec2::new(
            -span / 2.0 + i as f64 * half_dx,
            -((N - 1) as f64 / 2.0 - from_mid) * dy,
        )
    });
    let mut springs = Springs::new(Material {
        stiffness: k,
        damping: 0.0,
    });
    for i in 0..N - 1 {
        springs
            .connect_with_rest(N, i, i + 1, seg)
            .expect("valid spring");
    }
    let mut inv = [N as f64; N];
    inv[0] = 0.0;
    inv[N - 1] = 0.0;
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping: 2.0,
        ..Settings::default()
    }
    .with_integrator(integrator);
    let mut sys = MassSpring::new(pos, inv, springs, settings).expect("valid chain");
    for _ in 0..steps {
        let _ = sys.step(dt).expect("stable");
    }
    sys
}

/// The largest vertical distance of `points` to the catenary hanging from (±span/2, 0) with
/// the given length, relative to the catenary's sag.
pub fn catenary_sag_error(points: &[Vec2<f64>], span: f64, length: f64) -> f64 {
    let a = catenary_a(span, length);
    let c = -a * (span / (2.0 * a)).cosh();
    let sag = -(a + c);
    points
        .iter()
        .map(|p| (p.y - (a * (p.x / a).cosh() + c)).abs() / sag)
        .fold(0.0, f64::max)
}

/// The sail materials of the evaluation and its tests: structural, shear and bending springs.
pub fn cloth_materials<S: dunas::Scalar>() -> [Material<S>; 3] {
    [(800.0, 0.5), (300.0, 0.2), (50.0, 0.05)].map(|(k, c)| Material {
        stiffness: S::from_f64(k),
        damping: S::from_f64(c),
    })
}

/// The energy its fall releases, `m·g·L/2`, for [`released_rope`]: the scale of its energy error.
pub const RELEASED_ROPE_FALL_ENERGY: f64 = 7.0 * 200.0 * 70.0 / 2.0;

/// A released, undamped 8-particle rope (70 units long, 7 mass units, stiff springs, gravity
/// 200), pinned at its first particle and lying horizontal: what the energy checks step.
pub fn released_rope<I: dunas::Integrator>(
    integrator: I,
    accuracy: dunas::Accuracy,
) -> dunas::Rope<Vec2<f64>, 8, 7, I> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -200.0),
        accuracy,
        ..Settings::default()
    }
    .with_integrator(integrator);
    let material = Material {
        stiffness: 1500.0 * 7.0,
        damping: 0.0,
    };
    dunas::Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(70.0, 0.0),
        7.0,
        material,
        settings,
    )
    .expect("a valid rope")
}

/// The contacts scene: an `N`-particle rope 7 m long (1 kg, gravity 9.8), let go taut at
/// height 0 with its ends then held 6 m apart, stepped `frames` frames at 60 Hz against
/// `colliders` with `touch`. Without colliders its middle would sag about 1.5 m.
pub fn draped_rope<S: Scalar, const N: usize>(
    colliders: &[dunas::collider::Collider<Vec2<S>>],
    touch: dunas::contact::Touch,
    frames: usize,
) -> dunas::Rope<Vec2<S>, N> {
    let f = |x: f64| S::from_f64(x);
    let settings = Settings {
        gravity: Vec2::new(f(0.0), f(-9.8)),
        damping: f(2.0),
        ..Settings::default()
    };
    let material = Material {
        stiffness: f(3000.0),
        damping: f(2.0),
    };
    let mut rope = dunas::Rope::new(
        Vec2::new(f(-3.5), f(0.0)),
        Vec2::new(f(3.5), f(0.0)),
        f(1.0),
        material,
        settings,
    )
    .expect("a valid rope");
    rope.set_inv_mass(N - 1, S::ZERO).expect("a particle");
    rope.set_position(0, Vec2::new(f(-3.0), f(0.0)))
        .expect("in range");
    rope.set_position(N - 1, Vec2::new(f(3.0), f(0.0)))
        .expect("in range");
    let contacts =
        dunas::contact::Contacts::new(colliders, S::ZERO, touch).expect("valid contacts");
    for _ in 0..frames {
        let _ = rope
            .step_touching(f(1.0 / 60.0), (), &contacts)
            .expect("a step");
    }
    rope
}

/// A 1 m, 1 kg rope of 30 particles (axial stiffness 1000 N, damping 2/s) hanging from its
/// top, settled for 10 s at 60 Hz.
pub fn settled_hanging_rope<S: Scalar, I: dunas::Integrator>(
    integrator: I,
) -> dunas::Rope<Vec2<S>, 30, 30, I> {
    let f = |x: f64| S::from_f64(x);
    let settings = Settings {
        gravity: Vec2::new(f(0.0), f(-9.81)),
        damping: f(2.0),
        ..Settings::default()
    }
    .with_integrator(integrator);
    let material = Material {
        stiffness: f(1000.0 * 29.0),
        damping: f(0.5),
    };
    let mut rope = dunas::Rope::new(
        Vec2::new(f(0.0), f(0.0)),
        Vec2::new(f(0.0), f(-1.0)),
        f(1.0),
        material,
        settings,
    )
    .expect("a valid rope");
    for _ in 0..600 {
        let _ = rope.step(f(1.0 / 60.0)).expect("a step");
    }
    rope
}

/// The first three zeros of J₀: the hanging chain's modes are `(j_n / 2)·√(g/L)`.
pub const J0_ZEROS: [f64; 3] = [
    2.404_825_557_695_773,
    5.520_078_110_286_311,
    8.653_727_912_911_012,
];

/// J₀ by its power series (exact to rounding for |x| < 12).
pub fn j0(x: f64) -> f64 {
    let (mut term, mut sum) = (1.0, 1.0);
    for k in 1..60 {
        term *= -(x * x / 4.0) / (k as f64 * k as f64);
        sum += term;
    }
    sum
}

/// The catenary `y = a·cosh(x/a)` through two pins `span` apart with arc length `length`:
/// its sag below the pins (`2a·sinh(span / 2a) = length`, by bisection on `a`).
pub fn catenary_sag(span: f64, length: f64) -> f64 {
    let (mut lo, mut hi) = (1e-3, 1e3);
    for _ in 0..200 {
        let a: f64 = (lo * hi).sqrt();
        if 2.0 * a * (span / (2.0 * a)).sinh() > length {
            lo = a;
        } else {
            hi = a;
        }
    }
    let a = (lo * hi).sqrt();
    a * ((span / (2.0 * a)).cosh() - 1.0)
}

/// The sag of a spline rope of `K` control points stepped by `stepper`, 1.2 m and 1.2 kg,
/// of axial stiffness `ea` (`10⁵ N`: `EA/(ρ g L) ≈ 10⁴`), squeezed evenly between pins 1 m
/// apart and settled for 20 s.
pub fn spline_rope_sag<const K: usize, I: dunas::spline_rope::SplineStepper>(
    stepper: I,
    ea: f64,
) -> f64 {
    use dunas::spline_rope::SplineRope;
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping: 3.0,
        ..Settings::default()
    }
    .with_integrator(stepper);
    let stretch = Material {
        stiffness: ea,
        damping: 10.0,
    };
    let mut rope: SplineRope<Vec2<f64>, K, I> = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(1.2, 0.0),
        1.2,
        stretch,
        settings,
    )
    .expect("a valid rope");
    // Squeezed evenly between the pins, slack everywhere: it falls into its shape.
    for i in 0..K {
        let p = rope.positions()[i];
        rope.set_position(i, Vec2::new(p.x / 1.2, 0.0))
            .expect("in range");
    }
    rope.set_pinned(K - 1, true).expect("in range");
    for _ in 0..1200 {
        let _ = rope.step(1.0 / 60.0).expect("stable");
    }
    let mut curve = [Vec2::default(); 401];
    let n = rope.sample(&mut curve).expect("room");
    -curve[..n].iter().map(|p| p.y).fold(f64::INFINITY, f64::min)
}

/// A 1 m, 1 kg cantilever of bending stiffness `EI = 100 N·m²` (stretch `EA = 10⁴ N`, strain
/// damping 10 N·s, drag 5/s) stepped by `stepper`: 8 control points built level, clamped by
/// pinning the first two (the end's tangent), under `gravity`.
fn cantilever<I: dunas::spline_rope::SplineStepper>(
    stepper: I,
    gravity: f64,
) -> dunas::spline_rope::SplineRope<Vec2<f64>, 8, I> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -gravity),
        damping: 5.0,
        ..Settings::default()
    }
    .with_integrator(stepper);
    let stretch = Material {
        stiffness: 1e4,
        damping: 10.0,
    };
    let (start, end) = (Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0));
    let mut beam = dunas::spline_rope::SplineRope::new(start, end, 1.0, stretch, settings)
        .expect("a valid rope");
    beam.set_bending(100.0).expect("a valid stiffness");
    beam.set_pinned(1, true).expect("in range");
    beam
}

/// Beam theory's tip deflection of that cantilever under `g = 9.81`: `ρ·g·L⁴ / (8·EI)`.
pub fn cantilever_sag_exact() -> f64 {
    9.81 / (8.0 * 100.0)
}

/// The cantilever's tip deflection (m) after settling 10 s under `g = 9.81`.
pub fn cantilever_sag<I: dunas::spline_rope::SplineStepper>(stepper: I) -> f64 {
    let mut beam = cantilever(stepper, 9.81);
    for _ in 0..600 {
        let _ = beam.step(1.0 / 60.0).expect("stable");
    }
    -beam.positions()[7].y
}

/// The cantilever's first mode (rad/s, measured, and beam theory's `1.8751²·√(EI/(ρL⁴))`):
/// settled under gravity, released with gravity off and no damping at `Accuracy::Fine`, the
/// mean period of the tip's upward crossings of the axis over 20 periods.
pub fn cantilever_first_mode() -> (f64, f64) {
    let mut beam = cantilever(dunas::integrator::SymplecticEuler, 9.81);
    for _ in 0..600 {
        let _ = beam.step(1.0 / 60.0).expect("stable");
    }
    beam.set_settings(Settings {
        accuracy: Accuracy::Fine,
        ..Settings::default()
    })
    .expect("valid settings");
    for i in 0..8 {
        beam.set_velocity(i, Vec2::default()).expect("in range");
    }
    let h = 1.0 / 4000.0;
    let (mut last, mut time) = (beam.positions()[7].y, 0.0);
    let (mut crossings, mut first, mut latest) = (0, 0.0, 0.0);
    while crossings < 21 && time < 5.0 {
        let info = beam.step(h).expect("stable");
        assert!(!info.slow_motion, "the substeps stay under their cap");
        time += h;
        let y = beam.positions()[7].y;
        if last < 0.0 && y >= 0.0 {
            latest = time - h * y / (y - last);
            if crossings == 0 {
                first = latest;
            }
            crossings += 1;
        }
        last = y;
    }
    let measured = 2.0 * std::f64::consts::PI * (crossings - 1).max(1) as f64 / (latest - first);
    (measured, 1.875_104_068_711_961_f64.powi(2) * 10.0)
}

/// A 1 m, 1 kg spline rope of 8 control points and axial stiffness `ea` (N), no damping
/// given, pinned at its start and released level under `g = 9.81`, stepped by `stepper`.
pub fn released_spline_rope<S: Scalar, I: dunas::spline_rope::SplineStepper>(
    ea: f64,
    stepper: I,
) -> dunas::spline_rope::SplineRope<Vec2<S>, 8, I> {
    let settings = Settings {
        gravity: Vec2::new(S::ZERO, S::from_f64(-9.81)),
        ..Settings::default()
    }
    .with_integrator(stepper);
    let stretch = Material {
        stiffness: S::from_f64(ea),
        damping: S::ZERO,
    };
    let (start, end) = (Vec2::new(S::ZERO, S::ZERO), Vec2::new(S::ONE, S::ZERO));
    dunas::spline_rope::SplineRope::new(start, end, S::ONE, stretch, settings)
        .expect("a valid rope")
}

/// Particles a side of the towel, and its drawn points a side (3 a cell).
pub const TOWEL: usize = 10;
pub const TOWEL_DRAWN: usize = 3 * (TOWEL - 1) + 1;

/// A towel (10×10 particles, 0.9 × 0.6 m, 0.3 kg) dropped over a rod 2 cm thick; after 2 s
/// a push of 6 m/s² on its left half drives that half into the right one, for 3 s more.
/// Returns, over checks every `every` frames of the surface as drawn (3 points a cell), the
/// most crossings found (an edge of the drawn mesh through a triangle of it 3 or more cells
/// away) and the closest two drawn points of cells 3 or more apart; and the steps' mean
/// seconds a frame.
pub fn towel_over_a_rod(
    smoothing: Smoothing,
    self_contact: bool,
    every: usize,
) -> (usize, f64, f64) {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.8, 0.0),
        damping: 0.5,
        ..Settings::default()
    };
    let cloth = Material {
        stiffness: 800.0,
        damping: 0.5,
    };
    let bending = Material {
        stiffness: 20.0,
        damping: 0.1,
    };
    let mut towel: Cloth<Vec3<f64>, TOWEL, TOWEL> = Cloth::rectangle(
        Vec3::new(-0.45, 1.05, -0.3),
        Vec3::new(0.9, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 0.6),
        0.3,
        [cloth, cloth, bending],
        settings,
    )
    .unwrap();
    let rod = [
        Collider::capsule(Vec3::new(0.0, 1.0, -1.0), Vec3::new(0.0, 1.0, 1.0), 0.02)
            .unwrap()
            .with_friction(0.6, 0.5)
            .unwrap(),
    ];
    let contacts = Contacts::new(&rod, 0.01, Touch::Drawn(smoothing)).unwrap();
    let contacts = if self_contact {
        contacts.with_self_contact(0.3).unwrap()
    } else {
        contacts
    };
    let table = SurfaceTable::<f64, TOWEL, TOWEL_DRAWN>::new(smoothing, TOWEL_DRAWN).unwrap();
    let mut drawn = vec![Vec3::default(); TOWEL_DRAWN * TOWEL_DRAWN];
    let mut normals = drawn.clone();
    let (mut crossings, mut closest, mut seconds) = (0, f64::INFINITY, 0.0);
    for frame in 0..300 {
        let mut push = LeftHalf(if frame >= 120 { 6.0 } else { 0.0 });
        let start = std::time::Instant::now();
        let _ = towel
            .step_touching(1.0 / 60.0, &mut push, &contacts)
            .unwrap();
        seconds += start.elapsed().as_secs_f64();
        if frame % every == every - 1 {
            towel
                .draw(&table, &table, &mut drawn, &mut normals)
                .unwrap();
            let (now, near) = self_crossings(&drawn);
            crossings = crossings.max(now);
            closest = closest.min(near);
        }
    }
    (crossings, closest, seconds / 300.0)
}

/// Pushes the particles of the left half of a `TOWEL`-wide cloth along +x (m/s²).
pub struct LeftHalf(pub f64);

impl dunas::force::ForceField<Vec3<f64>> for LeftHalf {
    fn apply(
        &mut self,
        _: f64,
        _: &dunas::force::Bodies<'_, Vec3<f64>>,
        out: &mut dunas::force::Accelerations<'_, Vec3<f64>>,
    ) {
        for k in (0..out.len()).filter(|k| k % TOWEL < TOWEL / 2) {
            out.add_acceleration(k, Vec3::new(self.0, 0.0, 0.0));
        }
    }
}

/// The crossings of a drawn mesh (`TOWEL_DRAWN` points a side, row by row) with itself:
/// every edge tested against every triangle of a cell 3 or more away; and the closest two
/// points of such cells.
pub fn self_crossings(p: &[Vec3<f64>]) -> (usize, f64) {
    let n = TOWEL_DRAWN;
    let cell = |k: usize| ((k % n).min(n - 2) / 3, (k / n).min(n - 2) / 3);
    let apart = |a: usize, b: usize| {
        let ((ua, va), (ub, vb)) = (cell(a), cell(b));
        ua.abs_diff(ub) >= 3 || va.abs_diff(vb) >= 3
    };
    let mut closest = f64::INFINITY;
    for a in 0..p.len() {
        for b in a + 1..p.len() {
            if apart(a, b) {
                closest = closest.min((p[a] - p[b]).length());
            }
        }
    }
    let corners: Vec<usize> = (0..(n - 1) * (n - 1))
        .map(|c| (c % (n - 1)) + (c / (n - 1)) * n)
        .collect();
    let triangles: Vec<[usize; 3]> = corners
        .iter()
        .flat_map(|&k| [[k, k + 1, k + n], [k + 1, k + n + 1, k + n]])
        .collect();
    // Every edge once: along a row, along a column, and each quad's diagonal.
    let edges: Vec<(usize, usize)> = (0..n * n)
        .flat_map(|k| [(k, k + 1), (k, k + n)])
        .filter(|&(a, b)| b < n * n && (b != a + 1 || b % n != 0))
        .chain(corners.iter().map(|&k| (k + 1, k + n)))
        .collect();
    let mut crossings = 0;
    for &(a, b) in &edges {
        for t in triangles.iter().filter(|t| apart(a, t[0])) {
            if crosses((p[a], p[b]), [p[t[0]], p[t[1]], p[t[2]]]) {
                crossings += 1;
            }
        }
    }
    (crossings, closest)
}

/// Whether segment `a`–`b` passes through triangle `t`.
fn crosses((a, b): (Vec3<f64>, Vec3<f64>), t: [Vec3<f64>; 3]) -> bool {
    let normal = (t[1] - t[0]).cross(t[2] - t[0]);
    let (da, db) = ((a - t[0]).dot(normal), (b - t[0]).dot(normal));
    if da * db > 0.0 || da == db {
        return false;
    }
    let x = a + (b - a) * (da / (da - db));
    let inside = |p: Vec3<f64>, q: Vec3<f64>| (q - p).cross(x - p).dot(normal) >= 0.0;
    inside(t[0], t[1]) && inside(t[1], t[2]) && inside(t[2], t[0])
}

/// The stiff cloth `DirectSprings`' locking is measured on (`tests/suite/converge.rs`, the
/// evaluation's `evaluate/src/chains.rs`):
/// a 1 m, 1 kg, `U`×`U` cloth held level by two corners of one edge, its springs of axial
/// stiffness `ea` (N; `ea · (U − 1)` N/m a spring, bending a tenth of it), under a drag of
/// 2/s, stepped by `solver` (f64; statics: it hangs 1.00 m below its pins; the evaluation
/// also steps it by symplectic Euler at 480 Hz, its converged motion).
///
/// # Errors
/// The cloth's ([`Cloth::rectangle`], `set_inv_mass`): a stiffness that is not positive.
pub fn hung_cloth<const U: usize, I: Integrator>(
    ea: f64,
    solver: I,
) -> Result<Cloth<Vec3<f64>, U, U, I>, Error> {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 2.0,
        ..Settings::default()
    }
    .with_integrator(solver);
    let k = ea * (U as f64 - 1.0);
    let materials = [k, k, 0.1 * k].map(|k| Material {
        stiffness: k,
        damping: 0.0,
    });
    let (origin, du, dv) = (
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
    );
    let mut cloth = Cloth::rectangle(origin, du, dv, 1.0, materials, settings)?;
    cloth.set_inv_mass(0, 0.0)?;
    cloth.set_inv_mass(U - 1, 0.0)?;
    Ok(cloth)
}

/// The sail of [`boat_sail`] and its wind.
pub type BoatSail<S, I> = (Cloth<Vec3<S>, 8, 8, I>, dunas::force::SailWind<S>);

/// The boat scene's sail in format `S`: 8×8, 3 m on the boom and 4 m on the mast, 2 kg,
/// springs 900/300/60 N/m times `scale`, pinned on mast, gaff and boom, stepped by
/// `integrator` under a drag of 0.3/s; and its 5 m/s wind, gusting by `gust` m/s for 1.5 s
/// every 3 s.
///
/// # Errors
/// The cloth's or the wind's: a `scale` that leaves a stiffness not positive.
pub fn boat_sail<S: Scalar, I: Integrator>(
    integrator: I,
    scale: f64,
    gust: f64,
) -> Result<BoatSail<S, I>, Error> {
    use dunas::force::{SailWind, Wind};
    let f = S::from_f64;
    let settings = Settings {
        gravity: Vec3::new(f(0.0), f(-9.81), f(0.0)),
        damping: f(0.3),
        ..Settings::default()
    }
    .with_integrator(integrator);
    let materials = [(900.0, 0.6), (300.0, 0.2), (60.0, 0.05)].map(|(k, c)| Material {
        stiffness: f(k * scale),
        damping: f(c),
    });
    let (origin, du, dv) = (
        Vec3::new(f(0.0), f(4.5), f(0.0)),
        Vec3::new(f(3.0), f(0.0), f(0.0)),
        Vec3::new(f(0.0), f(-4.0), f(0.0)),
    );
    let mut sail = Cloth::rectangle(origin, du, dv, f(2.0), materials, settings)?;
    sail.pin_column(0)?;
    sail.pin_row(0)?;
    sail.pin_row(7)?;
    let mut air = Wind::still(f(0.02));
    air.velocity = Vec3::new(f(0.0), f(0.0), f(5.0));
    air.gust = Vec3::new(f(0.0), f(0.0), f(gust));
    air.gust_start = f(0.5);
    air.gust_length = f(1.5);
    air.gust_every = f(3.0);
    Ok((sail, SailWind::new(air, f(0.7))?))
}

/// The rope of [`rope_round_a_box`].
pub type BoxRope<S, I> = dunas::Rope<Vec2<S>, 12, 12, I>;

/// The box of [`rope_round_a_box`].
pub type BoxCollider<S> = Collider<Vec2<S>>;

/// The scene of `examples/mcu_wrap.rs` in format `S`: a 10 m, 2 kg rope of 12 particles held
/// at one end and a `load` (kg) on the other, let go level above a box 3 particle spacings
/// wide, its springs `stiffness` N/m (damped 1 N·s/m) under a drag of 0.1/s, stepped by
/// `solver`; and the box. Its contacts take the drawn Catmull-Rom curve, 5 cm thick.
///
/// # Errors
/// The rope's ([`Rope::new`](dunas::Rope::new), `hang`): a stiffness or load that is not
/// positive.
pub fn rope_round_a_box<S: Scalar, I: Integrator>(
    solver: I,
    stiffness: f64,
    load: f64,
) -> Result<(BoxRope<S, I>, BoxCollider<S>), Error> {
    let at = |x: f64, y: f64| Vec2::new(S::from_f64(x), S::from_f64(y));
    let settings = Settings {
        gravity: at(0.0, -9.81),
        damping: S::from_f64(0.1),
        ..Settings::default()
    }
    .with_integrator(solver);
    let material = Material {
        stiffness: S::from_f64(stiffness),
        damping: S::ONE,
    };
    let two = S::from_f64(2.0);
    let mut rope = dunas::Rope::new(at(0.0, 0.0), at(10.0, 0.0), two, material, settings)?;
    rope.hang(11, S::from_f64(load))?;
    let block = Collider::aabb(at(2.5, -3.5), at(2.5 + 30.0 / 11.0, -2.0))?;
    Ok((rope, block))
}
