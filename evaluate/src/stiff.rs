//! Section (i): stiff ropes, where the spline rope's steppers part. The explicit one's
//! substeps grow with `√EA` until their cap slows time down; the implicit ones take one
//! step a frame whatever the stiffness: backward Euler damps the swing, BDF2 far less.

use dunas::integrator::{ImplicitEuler, SymplecticEuler};
use dunas::prelude::*;
use dunas::spline_rope::{Bdf2, SplineRope, SplineStepper};

use crate::common::{hausdorff, released_spline_rope};
use crate::report::{Run, Series, chart, csv, median_ns, num};

const DT: f64 = 1.0 / 60.0;
/// When the shapes are compared: one second after a level release.
const AT: f64 = 1.0;
/// Points drawn to compare shapes.
const DRAWN: usize = 65;

/// The drawn curve of `rope` (f64 coordinates).
fn drawn<S: Scalar, I: SplineStepper>(rope: &SplineRope<Vec2<S>, 8, I>) -> Vec<Vec2<f64>> {
    let mut out = [Vec2::<S>::default(); DRAWN];
    let n = rope.sample(&mut out).expect("room");
    out[..n]
        .iter()
        .map(|p| Vec2::new(p.x.to_f64(), p.y.to_f64()))
        .collect()
}

/// The reference at `AT`: the same rope in f64, symplectic Euler at a tenth of its
/// stability limit, step by step (no cap, no slow motion).
fn reference(ea: f64) -> Vec<Vec2<f64>> {
    let mut r = released_spline_rope::<f64, _>(ea, SymplecticEuler);
    r.set_settings(Settings {
        gravity: Vec2::new(0.0, -9.81),
        accuracy: Accuracy::Fine,
        ..Settings::default()
    })
    .expect("valid settings");
    let (omega, gamma) = r.stiffness_bound();
    let steps = (AT * (omega + gamma) / 0.2).ceil();
    for _ in 0..steps as usize {
        r.step_once(AT / steps).expect("stable");
    }
    drawn(&r)
}

/// One stepper at one stiffness: f32 ns per 60 Hz frame (step and 65 points), the share
/// of the frame's time it simulates (below 1 in slow motion), and its shape error at `AT`
/// (f64, against `reference`, m).
fn measure<I: SplineStepper>(run: &Run, ea: f64, stepper: I, reference: &[Vec2<f64>]) -> [f64; 3] {
    let mut fast = released_spline_rope::<f32, _>(ea, stepper);
    let start = fast.clone();
    let mut out = [Vec2::<f32>::default(); DRAWN];
    let mut frames = 0;
    let mut share: f64 = 1.0;
    let ns = median_ns(run.reps(), 30, || {
        frames += 1;
        if frames % 60 == 0 {
            fast = start.clone();
        }
        let info = fast.step(DT as f32).expect("stable");
        share = share.min(info.simulated as f64 / DT);
        std::hint::black_box(fast.sample(&mut out).expect("room"));
    });
    let mut exact = released_spline_rope::<f64, _>(ea, stepper);
    let mut time = 0.0;
    while time < AT - 1e-9 {
        time += exact.step(DT).expect("stable").simulated;
    }
    [ns, share, hausdorff(&drawn(&exact), reference)]
}

pub fn run(run: &mut Run) {
    let stiffnesses: &[f64] = if run.quick {
        &[1e3, 1e5]
    } else {
        &[1e3, 1e4, 1e5, 1e6, 1e7]
    };
    let mut rows = Vec::new();
    let mut table = String::from(
        "| `EA` (N) | explicit: ns per frame | time simulated | shape error mm | backward Euler: ns per \
         frame | shape error mm | BDF2: ns per frame | shape error mm |\n|---|---|---|---|---|---|---|---|\n",
    );
    let mut costs: [Vec<(f64, f64)>; 3] = Default::default();
    for &ea in stiffnesses {
        let reference = reference(ea);
        let measured = [
            ("explicit", measure(run, ea, SymplecticEuler, &reference)),
            (
                "backward Euler",
                measure(run, ea, ImplicitEuler::default(), &reference),
            ),
            ("BDF2", measure(run, ea, Bdf2::default(), &reference)),
        ];
        let [explicit, implicit, bdf2] = measured.map(|(_, m)| m);
        table.push_str(&format!(
            "| {ea:.0e} | {:.0} | {:.0}% | {} | {:.0} | {} | {:.0} | {} |\n",
            explicit[0],
            explicit[1] * 100.0,
            num(explicit[2] * 1e3),
            implicit[0],
            num(implicit[2] * 1e3),
            bdf2[0],
            num(bdf2[2] * 1e3),
        ));
        for (k, (name, m)) in measured.iter().enumerate() {
            rows.push(vec![
                format!("{ea:e}"),
                name.to_string(),
                format!("{:.1}", m[0]),
                format!("{:.4}", m[1]),
                format!("{:.6}", m[2]),
            ]);
            costs[k].push((ea, m[0]));
        }
    }
    let [explicit_cost, implicit_cost, bdf2_cost] = costs;
    chart(
        &run.path("stiff.svg"),
        "Spline rope (8 control points, f32): cost of a 60 Hz frame against axial stiffness",
        "EA (N) on a 1 m, 1 kg rope",
        "ns per frame (step and 65 points)",
        &[
            Series::line("symplectic Euler (substeps from the bound)", explicit_cost),
            Series::line("backward Euler (one Newton-solved step)", implicit_cost),
            Series::line("BDF2 (one Newton-solved step)", bdf2_cost),
        ],
        true,
    );
    csv(
        &run.path("stiff.csv"),
        &[
            "ea",
            "stepper",
            "ns_per_frame",
            "time_simulated",
            "shape_error_m",
        ],
        &rows,
    );
    run.section(
        "(i) Stiff ropes: explicit against implicit",
        &format!(
            "![stiff](stiff.svg)\n\nA 1 m, 1 kg `SplineRope` of 8 control points released level, no damping \
             given. Cost: an f32 frame at 60 Hz (step and 65 points), median. Time simulated: the least share of \
             a frame the explicit steps cover (below 100%, its substeps hit their cap of 64 and time slows down). \
             Shape error: the f64 rope's drawn curve after 1 s against symplectic Euler at a tenth of its limit, \
             step by step. Explicit steps at `Accuracy::Fast`; the implicit ones one a frame with 16 \
             conjugate-gradient iterations (BDF2 takes backward Euler steps past the stiffness it was \
             tested to hold its energy at: `h²·ω² = 2²²` in f64, `8·10³` in f32).\n\n{table}\nThe explicit rope's substeps grow with `√EA` \
             until their cap slows time; the implicit ones' cost grows only with their Newton and \
             conjugate-gradient iterations, and backward Euler's error is its damping of the swing. \
             Data: `stiff.csv`."
        ),
    );
}
