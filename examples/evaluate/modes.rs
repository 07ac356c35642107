//! (h) Physics on the curve: the hanging rope's first three lateral modes against the
//! continuum, `(j_n / 2)·√(g/L)`, for the spline rope (its control points are the state) and
//! the particle chain, as degrees of freedom are added; and the catenary's sag.

use dunas::prelude::*;
use dunas::spline_rope::SplineRope;

use crate::common::{J0_ZEROS, catenary_sag, j0, spline_rope_sag};
use crate::report::{Run, Series, chart, csv};

const G: f64 = 9.81;
/// Axial stiffness against the rope's weight: `EA / (m g) = 5000`, a stretch of 0.02%.
const EA: f64 = 5000.0 * G;

/// The continuum's shape of mode `n` at distance `s` below the pin of a 1 m rope.
fn shape(n: usize, s: f64) -> f64 {
    j0(J0_ZEROS[n] * (1.0 - s).max(0.0).sqrt())
}

/// The angular frequency of a projection `q(t)`, advanced by `h` seconds per call of
/// `advance`: the peak of its Hann-windowed spectrum within ±30% of `expected`, over twenty
/// periods (robust to the other modes a discrete rope's start shape also excites).
fn frequency(h: f64, expected: f64, mut advance: impl FnMut() -> f64) -> f64 {
    let period = std::f64::consts::TAU / expected;
    let stride = ((period / 50.0 / h) as usize).max(1);
    let steps = (20.0 * period / h) as usize;
    let mut samples = Vec::new();
    for k in 0..steps {
        let q = advance();
        if k % stride == 0 {
            samples.push((k as f64 * h, q));
        }
    }
    let t_end = steps as f64 * h;
    let power = |omega: f64| -> f64 {
        let (mut re, mut im) = (0.0, 0.0);
        for &(t, q) in &samples {
            let w = 0.5 - 0.5 * (std::f64::consts::TAU * t / t_end).cos();
            re += w * q * (omega * t).cos();
            im -= w * q * (omega * t).sin();
        }
        re * re + im * im
    };
    let (lo, hi) = (0.7 * expected, 1.3 * expected);
    let grid = 600;
    let best = (0..=grid)
        .map(|i| lo + (hi - lo) * i as f64 / grid as f64)
        .max_by(|a, b| power(*a).total_cmp(&power(*b)))
        .unwrap_or(expected);
    // Golden-section refinement within one grid step either side.
    let step = (hi - lo) / grid as f64;
    let (mut a, mut b) = (best - step, best + step);
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..60 {
        let (c, d) = (b - ratio * (b - a), a + ratio * (b - a));
        if power(c) > power(d) {
            b = d;
        } else {
            a = c;
        }
    }
    (a + b) / 2.0
}

fn settings(drag: f64) -> Settings<Vec2<f64>> {
    Settings {
        gravity: Vec2::new(0.0, -G),
        damping: drag,
        ..Settings::default()
    }
}

/// Mode `n` of a 1 m, 1 kg spline rope of `K` control points.
fn spline_mode<const K: usize>(n: usize) -> f64 {
    let stretch = Material {
        stiffness: EA,
        damping: 0.02 * EA.sqrt(),
    };
    let mut rope: SplineRope<Vec2<f64>, K> = SplineRope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(0.0, -1.0),
        1.0,
        stretch,
        settings(5.0),
    )
    .expect("a valid rope");
    for _ in 0..480 {
        rope.step(1.0 / 60.0).expect("stable");
    }
    rope.set_settings(settings(0.0)).expect("valid");
    for i in 0..K {
        let p = rope.positions()[i];
        rope.set_position(i, Vec2::new(1e-3 * shape(n, -p.y), p.y))
            .expect("in range");
    }
    let h = 0.5 / rope.stiffness_bound().0;
    let mut curve = vec![Vec2::default(); 201];
    frequency(h, J0_ZEROS[n] / 2.0 * G.sqrt(), || {
        rope.step_once(h).expect("stable");
        let count = rope.sample(&mut curve).expect("room");
        (0..count)
            .map(|k| curve[k].x * shape(n, k as f64 / (count - 1) as f64))
            .sum()
    })
}

/// Mode `n` of a 1 m, 1 kg chain of `N` particles with the same axial stiffness.
fn chain_mode<const N: usize>(n: usize) -> f64 {
    let k = EA * (N - 1) as f64;
    let material = Material {
        stiffness: k,
        damping: 0.02 * k.sqrt(),
    };
    let mut rope: Rope<Vec2<f64>, N> = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(0.0, -1.0),
        1.0,
        material,
        settings(5.0),
    )
    .expect("a valid rope");
    for _ in 0..480 {
        rope.step(1.0 / 60.0).expect("stable");
    }
    rope.set_settings(settings(0.0)).expect("valid");
    for i in 1..N {
        let p = rope.positions()[i];
        rope.set_position(i, Vec2::new(1e-3 * shape(n, -p.y), p.y))
            .expect("in range");
        rope.set_velocity(i, Vec2::default()).expect("free");
    }
    let (omega, gamma) = rope.stiffness_bound();
    let h = 0.5 / (omega + gamma);
    let weights: Vec<f64> = rope
        .inv_masses()
        .iter()
        .map(|&w| if w > 0.0 { 1.0 / w } else { 0.0 })
        .collect();
    frequency(h, J0_ZEROS[n] / 2.0 * G.sqrt(), || {
        rope.step_once(h, ()).expect("stable");
        rope.positions()
            .iter()
            .zip(&weights)
            .map(|(p, m)| m * p.x * shape(n, -p.y))
            .sum()
    })
}

pub fn run(run: &mut Run) {
    let expected: Vec<f64> = J0_ZEROS.iter().map(|j| j / 2.0 * G.sqrt()).collect();
    let error = |got: f64, n: usize| (got / expected[n] - 1.0) * 100.0;
    type Modes = fn(usize) -> f64;
    let splines: Vec<(usize, Modes)> = if run.quick {
        vec![(8, spline_mode::<8>)]
    } else {
        vec![
            (5, spline_mode::<5>),
            (6, spline_mode::<6>),
            (8, spline_mode::<8>),
            (12, spline_mode::<12>),
            (16, spline_mode::<16>),
        ]
    };
    let chains: Vec<(usize, Modes)> = if run.quick {
        vec![(8, chain_mode::<8>)]
    } else {
        vec![
            (5, chain_mode::<5>),
            (8, chain_mode::<8>),
            (16, chain_mode::<16>),
            (30, chain_mode::<30>),
        ]
    };
    let mut rows = Vec::new();
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    let mut table = String::from(
        "| rope | degrees of freedom | mode 1 | mode 2 | mode 3 |\n|---|---|---|---|---|\n",
    );
    let mut spline8 = [f64::NAN; 3];
    let mut chain8 = [f64::NAN; 3];
    for (kind, list) in [("spline rope", &splines), ("particle chain", &chains)] {
        let mut per_mode: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 3];
        for &(dof, modes) in list {
            let errors: Vec<f64> = (0..3).map(|n| error(modes(n), n)).collect();
            for n in 0..3 {
                per_mode[n].push((dof as f64, errors[n].abs()));
                rows.push(vec![
                    kind.into(),
                    dof.to_string(),
                    (n + 1).to_string(),
                    format!("{:.5}", errors[n]),
                ]);
            }
            if dof == 8 {
                let slot = if kind == "spline rope" {
                    &mut spline8
                } else {
                    &mut chain8
                };
                slot.copy_from_slice(&errors);
            }
            table.push_str(&format!(
                "| {kind} | {dof} | {:+.4}% | {:+.4}% | {:+.4}% |\n",
                errors[0], errors[1], errors[2]
            ));
        }
        for (n, points) in per_mode.into_iter().enumerate() {
            series.push((format!("{kind}, mode {}", n + 1), points));
        }
    }
    let plotted: Vec<Series> = series
        .into_iter()
        .map(|(n, p)| Series::line(n, p))
        .collect();
    chart(
        &run.path("modes.svg"),
        "Hanging rope: lateral mode error against the continuum, by degrees of freedom",
        "control points or particles",
        "|frequency error| (%)",
        &plotted,
        true,
    );
    csv(
        &run.path("modes.csv"),
        &["rope", "degrees_of_freedom", "mode", "error_percent"],
        &rows,
    );
    let met = spline8[0].abs() <= 0.2 && spline8[1].abs() <= 0.5 && spline8[2].abs() <= 1.0;
    run.target(
        "with 8 control points, the hanging rope's modes 1, 2, 3 within 0.2%, 0.5%, 1% of the continuum",
        format!(
            "{:+.4}%, {:+.4}%, {:+.4}% (8 particles: {:+.2}%, {:+.2}%, {:+.2}%)",
            spline8[0], spline8[1], spline8[2], chain8[0], chain8[1], chain8[2]
        ),
        met,
        "mode 3 depends on how few spans carry it",
    );
    let exact = catenary_sag(1.0, 1.2);
    let sag8 = (spline_rope_sag::<8>() / exact - 1.0) * 100.0;
    let sag16 = if run.quick {
        f64::NAN
    } else {
        (spline_rope_sag::<16>() / exact - 1.0) * 100.0
    };
    run.target(
        "catenary sag within 0.2% (8 control points)",
        format!("{sag8:+.2}% (16 control points: {sag16:+.3}%)"),
        sag8.abs() <= 0.2,
        "8 control points cannot bend like the catenary and keep their length (3 Gauss points a span \
         against locking; 4 give -3.3%, 2 give -1.2% but spoil mode 3); 16 control points meet it",
    );
    run.section(
        "(h) Physics on the curve: hanging modes",
        &format!(
            "![modes](modes.svg)\n\nA 1 m, 1 kg rope hanging from a pin (`EA = 5000·m·g`), started in the continuum's \
             mode shape `J₀(j_n·√((L−s)/L))` at 1 mm and left to swing; each frequency is the peak of the \
             spectrum of the rope's projection on that shape over twenty periods, against `(j_n/2)·√(g/L)`. \
             The spline rope's state is its control points (`SplineRope`); the particle chain is `Rope` with the \
             same axial stiffness.\n\n{table}\nBetween two pins 1 m apart, a 1.2 m spline rope sags {sag8:+.2}% \
             off the catenary with 8 control points and {sag16:+.3}% with 16. Data: `modes.csv`."
        ),
    );
}
