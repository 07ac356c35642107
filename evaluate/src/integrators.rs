//! (b) Integrators: cost per simulated second against error versus analytic references (the
//! damped oscillator, the pendulum, the hanging chain's fundamental mode, the catenary),
//! sweeping the time step, the substeps and the solver budgets.

use std::f64::consts::PI;
use std::time::Instant;

use dunas::integrator::{AnyIntegrator, ImplicitEuler, Integrator, Xpbd};
use dunas::shape::Line;
use dunas::spring::{Material, Springs};
use dunas::{Accuracy, MassSpring, Settings, Vec2};

use crate::common::{
    RELEASED_ROPE_FALL_ENERGY, catenary_sag_error, chain_between_pins, jacobi_eigen, period,
    released_rope,
};
use crate::report::{Run, Series, chart, csv, num};

type Chain<const N: usize, const CAP: usize> =
    MassSpring<Vec2<f64>, Line<N>, Springs<f64, CAP>, AnyIntegrator>;

const EXPLICIT: [(&str, AnyIntegrator); 5] = [
    ("SymplecticEuler", AnyIntegrator::SymplecticEuler),
    ("Verlet", AnyIntegrator::Verlet),
    ("Rk4", AnyIntegrator::Rk4),
    (
        "ImplicitEuler(16)",
        AnyIntegrator::ImplicitEuler(ImplicitEuler { iterations: 16 }),
    ),
    ("Xpbd(1)", AnyIntegrator::Xpbd(Xpbd { substeps: 1 })),
];

/// Runs `steps` calls of `step` and returns (wall ns spent, samples of `probe` after each).
fn timed<T>(
    sys: &mut T,
    steps: usize,
    mut step: impl FnMut(&mut T),
    mut probe: impl FnMut(&T) -> f64,
) -> (f64, Vec<f64>) {
    let mut samples = Vec::with_capacity(steps);
    let mut spent = 0.0;
    for _ in 0..steps {
        let t = Instant::now();
        step(sys);
        spent += t.elapsed().as_nanos() as f64;
        samples.push(probe(sys));
    }
    (spent, samples)
}

/// Steps `sys` (substeps from stiffness) for `seconds` in frames of `dt`: CPU ns per
/// simulated second and the period of `probe`'s oscillation.
fn timed_period<const N: usize, const CAP: usize>(
    sys: &mut Chain<N, CAP>,
    dt: f64,
    seconds: f64,
    probe: impl FnMut(&Chain<N, CAP>) -> f64,
) -> (f64, f64) {
    let steps = (seconds / dt).round() as usize;
    let (spent, xs) = timed(
        sys,
        steps,
        |s| {
            let _ = s.step(dt).expect("stable");
        },
        probe,
    );
    let samples: Vec<(f64, f64)> = xs
        .iter()
        .enumerate()
        .map(|(i, &x)| ((i + 1) as f64 * dt, x))
        .collect();
    (spent / seconds, period(&samples))
}

/// Damped oscillator ω0 = 10, ζ = 0.02: the largest deviation from the closed form over 2 s,
/// relative to the amplitude, with a fixed step h (no substeps).
fn oscillator(integrator: AnyIntegrator, h: f64) -> (f64, f64) {
    let (k, c, a) = (100.0, 0.4, 0.1);
    let pos = [Vec2::new(0.0, 0.0), Vec2::new(10.0 + a, 0.0)];
    let mut springs = Springs::new(Material {
        stiffness: k,
        damping: c,
    });
    springs.connect_with_rest(2, 0, 1, 10.0).expect("valid");
    let settings = Settings {
        ..Settings::default()
    }
    .with_integrator(integrator);
    let mut sys: Chain<2, 1> = MassSpring::new(pos, [0.0, 1.0], springs, settings).expect("valid");
    let steps = (2.0 / h).round() as usize;
    let (spent, xs) = timed(
        &mut sys,
        steps,
        |s| {
            let _ = s.step_once(h, ()).expect("stable");
        },
        |s| s.positions()[1].x - 10.0,
    );
    let (w0, zeta) = (10.0f64, 0.02f64);
    let wd = w0 * (1.0 - zeta * zeta).sqrt();
    let err = xs
        .iter()
        .enumerate()
        .map(|(i, x)| {
            let t = (i + 1) as f64 * h;
            let exact =
                a * (-zeta * w0 * t).exp() * ((wd * t).cos() + zeta * w0 / wd * (wd * t).sin());
            (x - exact).abs() / a
        })
        .fold(0.0, f64::max);
    (spent / 2.0, err)
}

/// Small-angle pendulum (stiff spring, automatic substeps): period error.
fn pendulum(integrator: AnyIntegrator, dt: f64) -> (f64, f64) {
    let (g, len, theta, k) = (9.81f64, 1.0f64, 0.05f64, 1e5);
    let stretched = len + g / k;
    let exact = 2.0 * PI * (stretched / g).sqrt() * (1.0 + theta * theta / 16.0);
    let pos = [
        Vec2::new(0.0, 0.0),
        Vec2::new(stretched * theta.sin(), -stretched * theta.cos()),
    ];
    let mut springs = Springs::new(Material {
        stiffness: k,
        damping: 0.0,
    });
    springs.connect_with_rest(2, 0, 1, len).expect("valid");
    let settings = Settings {
        gravity: Vec2::new(0.0, -g),
        ..Settings::default()
    }
    .with_integrator(integrator);
    let mut sys: Chain<2, 1> = MassSpring::new(pos, [0.0, 1.0], springs, settings).expect("valid");
    let (ns_per_s, measured) = timed_period(&mut sys, dt, 8.0, |s| s.positions()[1].x);
    (ns_per_s, (measured - exact).abs() / exact)
}

/// Fundamental mode of a chain of 8 below a pin (automatic substeps): frequency error against
/// the discrete chain's eigenvalue.
fn chain_mode(integrator: AnyIntegrator, dt: f64) -> (f64, f64) {
    const N: usize = 8;
    let (g, len, k) = (9.81f64, 2.0f64, 1e5);
    let l = len / N as f64;
    let mut a = [[0.0; N]; N];
    for i in 0..N {
        let (above, below) = ((N - i) as f64, (N - i - 1) as f64);
        a[i][i] = above + below;
        if i + 1 < N {
            a[i][i + 1] = -below;
            a[i + 1][i] = -below;
        }
    }
    let (lambda, vecs) = jacobi_eigen(a);
    let idx = (0..N)
        .min_by(|&x, &y| lambda[x].total_cmp(&lambda[y]))
        .expect("N > 0");
    let exact = (g / l * lambda[idx]).sqrt();
    let peak = (0..N).map(|i| vecs[i][idx].abs()).fold(0.0, f64::max);
    let mut pos = [Vec2::new(0.0, 0.0); N + 1];
    for i in 0..N {
        let seg = l + (N - i) as f64 * g / k;
        let x = 0.002 * len * vecs[i][idx] / peak;
        let dx = x - pos[i].x;
        pos[i + 1] = Vec2::new(x, pos[i].y - (seg * seg - dx * dx).sqrt());
    }
    let mut springs = Springs::new(Material {
        stiffness: k,
        damping: 0.0,
    });
    for i in 0..N {
        springs
            .connect_with_rest(N + 1, i, i + 1, l)
            .expect("valid");
    }
    let mut inv = [1.0; N + 1];
    inv[0] = 0.0;
    let settings = Settings {
        gravity: Vec2::new(0.0, -g),
        ..Settings::default()
    }
    .with_integrator(integrator);
    let mut sys: Chain<{ N + 1 }, N> = MassSpring::new(pos, inv, springs, settings).expect("valid");
    let (ns_per_s, measured_period) =
        timed_period(&mut sys, dt, 4.0 * 2.0 * PI / exact, |s| s.positions()[N].x);
    let measured = 2.0 * PI / measured_period;
    (ns_per_s, (measured - exact).abs() / exact)
}

/// A chain of 40 settling between two pins: the sag error against the catenary after 10 s
/// at 30 Hz, for the solver budgets of the unconditionally stable methods.
fn catenary(integrator: AnyIntegrator) -> (f64, f64) {
    let start = Instant::now();
    let sys = chain_between_pins::<40, 39>(4.0, 5.0, 1e7, integrator, 300, 1.0 / 30.0);
    let spent = start.elapsed().as_nanos() as f64;
    (spent / 10.0, catenary_sag_error(sys.positions(), 4.0, 5.0))
}

/// A released, undamped 8-particle rope (70 px, 7 mass units, stiff springs) stepped at 60 Hz
/// for 3 s at an accuracy level: CPU ns per simulated second and the largest swing of its
/// total energy, relative to the energy its fall releases (`m·g·L/2`). The exact answer is 0.
fn energy_swing(integrator: AnyIntegrator, accuracy: Accuracy) -> (f64, f64) {
    let mut rope = released_rope(integrator, accuracy);
    let (e0, scale) = (rope.energy(), RELEASED_ROPE_FALL_ENERGY);
    let (spent, energies) = timed(
        &mut rope,
        180,
        |r| {
            let _ = r.step(1.0 / 60.0).expect("stable");
        },
        |r| r.energy(),
    );
    let swing = energies
        .iter()
        .map(|e| (e - e0).abs() / scale)
        .fold(0.0, f64::max);
    (spent / 3.0, swing)
}

/// The energy chart: every integrator at every accuracy level; returns its Markdown.
fn energy_chart(run: &Run, rows: &mut Vec<Vec<String>>) -> String {
    let levels = [Accuracy::Fast, Accuracy::Balanced, Accuracy::Fine];
    let mut series = Vec::new();
    let mut table = String::from("| integrator | Fast | Balanced | Fine |\n|---|---|---|---|\n");
    for (name, integrator) in EXPLICIT {
        let mut pts = Vec::new();
        let mut cells = Vec::new();
        for accuracy in levels {
            // The cheapest of a few runs: the swing is deterministic, the time is not.
            let runs: Vec<(f64, f64)> = (0..if run.quick { 1 } else { 5 })
                .map(|_| energy_swing(integrator, accuracy))
                .collect();
            let ns = runs.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
            let swing = runs[0].1;
            rows.push(vec![
                "energy".into(),
                format!("{name} {accuracy:?}"),
                "0.016667".into(),
                format!("{ns:.0}"),
                format!("{swing:.3e}"),
            ]);
            pts.push((ns, swing.max(1e-9)));
            cells.push(format!("{}% at {:.0} µs/s", num(100.0 * swing), ns / 1e3));
        }
        table.push_str(&format!("| {name} | {} |\n", cells.join(" | ")));
        series.push(Series::line(name, pts));
    }
    chart(
        &run.path("integ_energy.svg"),
        "Released undamped 8-particle rope, 3 s at 60 Hz: energy swing at Fast, Balanced, Fine",
        "CPU ns per simulated second",
        "largest energy swing / energy released",
        &series,
        true,
    );
    format!(
        "![energy](integ_energy.svg)\n\nEnergy swing of a released undamped rope (exact: none) \
         and its cost, per `Accuracy` level (substeps at 9/10, 1/2 and 1/10 of the stability \
         limit). The implicit method and XPBD have no stability limit, so the levels leave them at \
         one step a frame, where their numerical damping takes the energy out:\n\n{table}"
    )
}

pub fn run(run: &mut Run) {
    let mut rows = Vec::new();
    let steps: &[f64] = if run.quick {
        &[1.0 / 60.0, 1.0 / 240.0]
    } else {
        &[
            1.0 / 30.0,
            1.0 / 60.0,
            1.0 / 120.0,
            1.0 / 240.0,
            1.0 / 480.0,
            1.0 / 960.0,
        ]
    };
    let mut sections = Vec::new();
    type Reference = fn(AnyIntegrator, f64) -> (f64, f64);
    let references: [(&str, &str, &str, Reference); 3] = [
        (
            "oscillator",
            "integ_oscillator.svg",
            "Damped oscillator (ω0 = 10, ζ = 0.02): max deviation / amplitude, fixed step",
            oscillator,
        ),
        (
            "pendulum",
            "integ_pendulum.svg",
            "Small-angle pendulum on a stiff spring: period error, substeps from stiffness",
            pendulum,
        ),
        (
            "chain_mode",
            "integ_modes.svg",
            "Chain of 8 hanging from a pin: fundamental frequency error vs its eigenvalue",
            chain_mode,
        ),
    ];
    for (reference, file, title, f) in references {
        let mut series = Vec::new();
        for (name, integrator) in EXPLICIT {
            let mut pts = Vec::new();
            for &dt in steps {
                // The oscillator uses fixed steps: skip the ones outside an explicit method's limit.
                if reference == "oscillator"
                    && integrator
                        .stability_limit::<f64>()
                        .is_some_and(|l| 10.0 * dt >= l * 0.95)
                {
                    continue;
                }
                let (ns_per_s, err) = f(integrator, dt);
                rows.push(vec![
                    reference.into(),
                    name.into(),
                    format!("{dt:.6}"),
                    format!("{ns_per_s:.0}"),
                    format!("{err:.3e}"),
                ]);
                pts.push((ns_per_s, err));
            }
            series.push(Series::line(name, pts));
        }
        chart(
            &run.path(file),
            title,
            "CPU ns per simulated second",
            "relative error",
            &series,
            true,
        );
        sections.push(format!("![{reference}]({file})"));
    }
    let mut series = Vec::new();
    let budgets: &[u8] = if run.quick {
        &[4, 16]
    } else {
        &[2, 4, 8, 16, 32, 64]
    };
    for (name, make) in [
        (
            "ImplicitEuler(iterations)",
            (|b| AnyIntegrator::ImplicitEuler(ImplicitEuler { iterations: b }))
                as fn(u8) -> AnyIntegrator,
        ),
        ("Xpbd(substeps)", |b| {
            AnyIntegrator::Xpbd(Xpbd { substeps: b })
        }),
    ] {
        let mut pts = Vec::new();
        for &b in budgets {
            let (ns_per_s, err) = catenary(make(b));
            rows.push(vec![
                "catenary".into(),
                format!("{name}={b}"),
                "0.033333".into(),
                format!("{ns_per_s:.0}"),
                format!("{err:.3e}"),
            ]);
            pts.push((ns_per_s, err));
        }
        series.push(Series::line(name, pts));
    }
    chart(
        &run.path("integ_catenary.svg"),
        "Chain of 40 between two pins after 10 s at 30 Hz: sag error vs the catenary",
        "CPU ns per simulated second",
        "max error / sag",
        &series,
        true,
    );
    sections.push("![catenary](integ_catenary.svg)".into());
    let energy = energy_chart(run, &mut rows);
    csv(
        &run.path("integrators.csv"),
        &[
            "reference",
            "integrator",
            "dt_s",
            "ns_per_simulated_s",
            "relative_error",
        ],
        &rows,
    );
    let best = |reference: &str| {
        rows.iter()
            .filter(|r| r[0] == reference)
            .min_by(|a, b| {
                a[4].parse::<f64>()
                    .unwrap_or(f64::MAX)
                    .total_cmp(&b[4].parse::<f64>().unwrap_or(f64::MAX))
            })
            .map(|r| {
                format!(
                    "{} at dt {} s: {}",
                    r[1],
                    r[2],
                    num(r[4].parse().unwrap_or(f64::NAN))
                )
            })
            .unwrap_or_default()
    };
    let text = format!(
        "{}\n\nEach line sweeps the step (1/30 to 1/960 s) or the solver budget; the explicit methods' \
         steps outside their stability limit are left out of the fixed-step oscillator. Best per \
         reference: oscillator {}; pendulum {}; chain mode {}; catenary {}. Data: `integrators.csv`.",
        sections.join("\n"),
        best("oscillator"),
        best("pendulum"),
        best("chain_mode"),
        best("catenary")
    ) + "\n\n"
        + &energy;
    run.section("(b) Integrators: cost against error", &text);
}
