//! Step cost of every integrator for ropes of 8 and 30 particles and cloths of 8×8 and
//! 20×20, the cost of a whole rope frame (step + 64-point curve), contacts against 4
//! colliders, the spline rope's substep, curve and frame, and the state sizes.
//!
//! Run: `cargo bench -p dunas-evaluate --bench physics`. The sizes are printed first.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use dunas::Settings;
use dunas::integrator::{AnyIntegrator, DirectChain, DirectSprings, ImplicitEuler, Xpbd};
use dunas::sampler::{BernsteinTable, Sampler};
use dunas::smooth::Smoothing;
use dunas::spring::Material;
use dunas::{Bezier, Cloth, Rope, Vec2, Vec3};

const INTEGRATORS: [(&str, AnyIntegrator); 8] = [
    ("explicit_euler", AnyIntegrator::ExplicitEuler),
    ("symplectic_euler", AnyIntegrator::SymplecticEuler),
    ("verlet", AnyIntegrator::Verlet),
    ("rk4", AnyIntegrator::Rk4),
    (
        "implicit_euler_cg8",
        AnyIntegrator::ImplicitEuler(ImplicitEuler { iterations: 8 }),
    ),
    ("xpbd_4", AnyIntegrator::Xpbd(Xpbd { substeps: 4 })),
    (
        "direct_chain",
        AnyIntegrator::DirectChain(DirectChain {
            iterations: 4,
            inextensible: true,
            substeps: 4,
            halvings: 6,
        }),
    ),
    (
        "direct_springs",
        AnyIntegrator::DirectSprings(DirectSprings {
            iterations: 1,
            substeps: 1,
            measure: false,
            keep_energy: false,
        }),
    ),
];

/// A swinging rope of `N` particles, 70 px long, the same material and mass at any `N`
/// (stiffness per spring scales with `N - 1` so the whole rope stretches alike).
fn rope<const N: usize, const CAP: usize>(
    integrator: AnyIntegrator,
) -> Rope<Vec2<f32>, N, CAP, AnyIntegrator> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -200.0),
        damping: 0.1,
        ..Settings::default()
    }
    .with_integrator(integrator);
    let k = 400.0 * (N - 1) as f32 / 7.0;
    let mut r = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(70.0, 0.0),
        7.0,
        Material {
            stiffness: k,
            damping: 2.0,
        },
        settings,
    )
    .unwrap();
    r.set_inv_mass(N - 1, 0.25).unwrap();
    for _ in 0..20 {
        let _ = r.step(1.0 / 60.0).unwrap();
    }
    // One step of the benchmarks' length: `DirectSprings` keeps its factor for it.
    let _ = r.step_once(1.0 / 240.0, ()).unwrap();
    r
}

fn cloth<const U: usize, const V: usize>(
    integrator: AnyIntegrator,
) -> Cloth<Vec3<f32>, U, V, AnyIntegrator> {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.2,
        ..Settings::default()
    }
    .with_integrator(integrator);
    let m = Material {
        stiffness: 300.0,
        damping: 0.5,
    };
    let mut c = Cloth::rectangle(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, -2.0, 0.0),
        1.0,
        [m, m, m],
        settings,
    )
    .unwrap();
    c.pin_row(0).unwrap();
    for _ in 0..20 {
        let _ = c.step(1.0 / 60.0).unwrap();
    }
    let _ = c.step_once(1.0 / 240.0, ()).unwrap();
    c
}

/// Times `f` on a fresh copy of `state` each iteration (the copy is not timed), so that an
/// unstable method or a rope coming to rest does not change what is measured.
fn bench_on<T: Clone, R>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    state: &T,
    mut f: impl FnMut(&mut T) -> R,
) {
    g.bench_function(name, |b| {
        b.iter_batched_ref(|| state.clone(), |s| f(black_box(s)), BatchSize::SmallInput)
    });
}

/// One fixed-size step (`step_once`, 1/240 s): the integrator's own cost, without the
/// substeps a stiffness would add.
fn steps(c: &mut Criterion) {
    let h = 1.0 / 240.0;
    for (name, integrator) in INTEGRATORS {
        let mut g = c.benchmark_group(format!("step/{name}"));
        bench_on(&mut g, "rope8", &rope::<8, 7>(integrator), |r| {
            r.step_once(h, ())
        });
        bench_on(&mut g, "rope30", &rope::<30, 29>(integrator), |r| {
            r.step_once(h, ())
        });
        bench_on(&mut g, "cloth8x8", &cloth::<8, 8>(integrator), |r| {
            r.step_once(h, ())
        });
        bench_on(&mut g, "cloth20x20", &cloth::<20, 20>(integrator), |r| {
            r.step_once(h, ())
        });
        g.finish();
    }
}

/// A whole rope frame: one symplectic Euler step of 1/240 s and a 64-point curve.
fn frames(c: &mut Criterion) {
    let h = 1.0 / 240.0;
    let mut g = c.benchmark_group("frame");
    let mut out = [Vec2::<f32>::default(); 64];
    let r8 = rope::<8, 7>(AnyIntegrator::SymplecticEuler);
    bench_on(&mut g, "rope8_bspline64", &r8, |r| {
        let _ = r.step_once(h, ()).unwrap();
        r.sample(Smoothing::BSpline, &mut out).unwrap()
    });
    let table = BernsteinTable::<f32, 8, 64>::new();
    bench_on(&mut g, "rope8_bezier_table64", &r8, |r| {
        let _ = r.step_once(h, ()).unwrap();
        table
            .sample(&Bezier::new(*r.position_array()).unwrap(), &mut out)
            .unwrap()
    });
    bench_on(&mut g, "rope8_bezier_decasteljau64", &r8, |r| {
        let _ = r.step_once(h, ()).unwrap();
        r.sample(Smoothing::Bezier, &mut out).unwrap()
    });
    let r30 = rope::<30, 29>(AnyIntegrator::SymplecticEuler);
    bench_on(&mut g, "rope30_polyline64", &r30, |r| {
        let _ = r.step_once(h, ()).unwrap();
        r.sample(Smoothing::Polyline, &mut out).unwrap()
    });
    g.finish();
}

/// A 60 Hz rope frame (substeps from stiffness) alone and with contacts against 4 colliders
/// (ground, wall, two thin pegs), at the particles and on the drawn B-spline. Thickness 0, so
/// the substep count is the same and the difference is what the contacts cost.
fn contacts(c: &mut Criterion) {
    use dunas::collider::Collider;
    use dunas::contact::{Contacts, Touch};
    let colliders = [
        Collider::half_space(Vec2::new(0.0, -40.0), Vec2::new(0.0, 1.0)).unwrap(),
        Collider::half_space(Vec2::new(75.0, 0.0), Vec2::new(-1.0, 0.0)).unwrap(),
        Collider::ball(Vec2::new(20.0, -10.0), 1.0).unwrap(),
        Collider::capsule(Vec2::new(40.0, -25.0), Vec2::new(50.0, -25.0), 1.0).unwrap(),
    ];
    let mut g = c.benchmark_group("contacts");
    let r8 = rope::<8, 7>(AnyIntegrator::SymplecticEuler);
    bench_on(&mut g, "rope8_step", &r8, |r| r.step(1.0 / 60.0).unwrap());
    for (name, touch) in [
        ("rope8_step_4_colliders_particles", Touch::Particles),
        (
            "rope8_step_4_colliders_curve",
            Touch::Drawn(Smoothing::BSpline),
        ),
    ] {
        let contacts = Contacts::new(&colliders, 0.0, touch).unwrap();
        bench_on(&mut g, name, &r8, |r| {
            r.step_touching(1.0 / 60.0, (), &contacts).unwrap()
        });
    }
    g.finish();
}

/// An 8×8 sail: a 60 Hz step, and drawing a 24×24 grid with normals through the separable
/// surface tables (Catmull-Rom, B-spline) or the single Bézier patch.
fn surfaces(c: &mut Criterion) {
    use dunas::surface::{SurfaceTable, sample};
    let mut g = c.benchmark_group("surface");
    let sail = cloth::<8, 8>(AnyIntegrator::SymplecticEuler);
    bench_on(&mut g, "sail8_step", &sail, |s| s.step(1.0 / 60.0).unwrap());
    let (mut pos, mut nor) = ([Vec3::default(); 576], [Vec3::default(); 576]);
    for (name, smoothing) in [
        ("sail8_draw24_catmull_rom", Smoothing::CatmullRom),
        ("sail8_draw24_bspline", Smoothing::BSpline),
        ("sail8_draw24_bezier_table", Smoothing::Bezier),
    ] {
        let table = SurfaceTable::<f32, 8, 24>::new(smoothing, 24).unwrap();
        bench_on(&mut g, name, &sail, |s| {
            sample(s.position_array(), &table, &table, &mut pos, &mut nor).unwrap()
        });
    }
    bench_on(&mut g, "sail8_draw24_patch", &sail, |s| {
        s.sample_patch(24, 24, &mut pos, &mut nor).unwrap()
    });
    g.finish();
}

/// Breaking: a 60 Hz rope step with and without snap limits on its springs (the check runs
/// once a step), and a cut of its drawn 64-point Catmull-Rom curve by a swipe across it.
fn breaking(c: &mut Criterion) {
    use dunas::breaking::Piece;
    use dunas::spring::Snap;
    let mut g = c.benchmark_group("breaking");
    let plain = rope::<8, 7>(AnyIntegrator::SymplecticEuler);
    let mut snapping = plain.clone();
    snapping.set_snap(Snap::Tension(1.0e6)).unwrap();
    bench_on(&mut g, "rope8_step", &plain, |r| {
        r.step(1.0 / 60.0).unwrap()
    });
    bench_on(&mut g, "rope8_step_snap", &snapping, |r| {
        r.step(1.0 / 60.0).unwrap()
    });
    let (mut points, mut pieces) = ([Vec2::<f32>::default(); 64], [Piece::EMPTY; 8]);
    let n = plain
        .draw(Smoothing::CatmullRom, &mut points, &mut pieces)
        .unwrap();
    let aim = points[pieces[0].points.end / 2];
    let (from, to) = (aim + Vec2::new(-5.0, 20.0), aim + Vec2::new(5.0, -20.0));
    bench_on(&mut g, "rope8_cut64", &plain, |r| {
        r.cut(&points, &pieces[..n], from, to).unwrap()
    });
    g.finish();
}

/// A frame that reels the rope in (`Rope::reel`, then the step) against a plain frame, with
/// symplectic Euler and with `DirectChain`.
fn reel(c: &mut Criterion) {
    let mut g = c.benchmark_group("reel");
    for (name, method) in [
        ("symplectic_euler", AnyIntegrator::SymplecticEuler),
        (
            "direct_chain",
            AnyIntegrator::DirectChain(DirectChain::default()),
        ),
    ] {
        let rope = rope::<8, 7>(method);
        let target = 0.5 * rope.length();
        bench_on(&mut g, &format!("rope8_{name}_step"), &rope, |r| {
            r.step(1.0 / 60.0).unwrap()
        });
        bench_on(&mut g, &format!("rope8_{name}_reel_step"), &rope, |r| {
            r.reel(target, 1.0, 1.0 / 60.0).unwrap();
            r.step(1.0 / 60.0).unwrap()
        });
    }
    g.finish();
}

fn sizes(_: &mut Criterion) {
    use core::mem::size_of;
    println!(
        "size_of Rope<Vec2<f32>, 8>         = {} B",
        size_of::<Rope<Vec2<f32>, 8>>()
    );
    println!(
        "size_of Rope<Vec2<f32>, 30>        = {} B",
        size_of::<Rope<Vec2<f32>, 30>>()
    );
    println!(
        "size_of Cloth<Vec3<f32>, 8, 8>     = {} B",
        size_of::<Cloth<Vec3<f32>, 8, 8>>()
    );
    println!(
        "size_of Cloth<Vec3<f32>, 20, 20>   = {} B",
        size_of::<Cloth<Vec3<f32>, 20, 20>>()
    );
}

/// The spline rope of 8 control points (the swinging rope's length, mass and whole-rope
/// stiffness): one substep of 1/240 s, the 64-point curve, and a 60 Hz frame of both; the
/// same frame stepped implicitly (one backward Euler step).
fn spline_rope(c: &mut Criterion) {
    use dunas::integrator::ImplicitEuler;
    use dunas::spline_rope::SplineRope;
    let settings = Settings {
        gravity: Vec2::new(0.0, -200.0),
        damping: 0.1,
        ..Settings::default()
    };
    let stretch = Material {
        stiffness: 400.0 * 70.0,
        damping: 2.0,
    };
    let mut r: SplineRope<Vec2<f32>, 8> = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(70.0, 0.0),
        7.0,
        stretch,
        settings,
    )
    .unwrap();
    for _ in 0..20 {
        let _ = r.step(1.0 / 60.0).unwrap();
    }
    let mut out = [Vec2::<f32>::default(); 64];
    let mut g = c.benchmark_group("spline_rope");
    bench_on(&mut g, "substep8", &r, |r| r.step_once(1.0 / 240.0));
    bench_on(&mut g, "sample64", &r, |r| r.sample(&mut out));
    bench_on(&mut g, "frame8_sample64", &r, |r| {
        let _ = r.step(1.0 / 60.0).unwrap();
        r.sample(&mut out).unwrap()
    });
    let mut implicit: SplineRope<Vec2<f32>, 8, ImplicitEuler> = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(70.0, 0.0),
        7.0,
        stretch,
        settings.with_integrator(ImplicitEuler::default()),
    )
    .unwrap();
    for _ in 0..20 {
        let _ = implicit.step(1.0 / 60.0).unwrap();
    }
    bench_on(&mut g, "implicit_frame8_sample64", &implicit, |r| {
        let _ = r.step(1.0 / 60.0).unwrap();
        r.sample(&mut out).unwrap()
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(800))
        .sample_size(30);
    targets = sizes, steps, frames, contacts, surfaces, breaking, reel, spline_rope
}
criterion_main!(benches);
