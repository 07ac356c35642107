//! Section (j): stiff chains, where substeps bought stiffness and `DirectChain` does not need
//! them. Every integrator on the catapult's rope whirled with its penguin, across stiffness
//! and across the bob's mass, and the energy each keeps of a released rope's swing.

use dunas::integrator::{AnyIntegrator, DirectChain, ImplicitEuler, Xpbd};
use dunas::prelude::*;

use crate::report::{Run, Series, chart, csv, median_ns, num};

/// The methods compared, with their names in the tables.
fn methods() -> [(&'static str, AnyIntegrator); 6] {
    [
        ("symplectic Euler", AnyIntegrator::SymplecticEuler),
        ("Verlet", AnyIntegrator::Verlet),
        (
            "backward Euler",
            AnyIntegrator::ImplicitEuler(ImplicitEuler::default()),
        ),
        ("XPBD", AnyIntegrator::Xpbd(Xpbd::default())),
        (
            "DirectChain",
            AnyIntegrator::DirectChain(DirectChain::default()),
        ),
        (
            "DirectChain, springs",
            AnyIntegrator::DirectChain(DirectChain {
                inextensible: false,
                ..DirectChain::default()
            }),
        ),
    ]
}

type Chain = Rope<Vec2<f32>, 8, 8, AnyIntegrator>;

/// The catapult's rope (1.6 m, 0.4 kg, 8 particles, springs of `k` N/m) with `bob` kg on
/// its end, hanging from a hand at (0.5, 0).
fn catapult_rope(method: AnyIntegrator, k: f32, bob: f32) -> Chain {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping: 0.05,
        ..Settings::default()
    }
    .with_integrator(method);
    let material = Material {
        stiffness: k,
        damping: 4.0,
    };
    let mut rope = Rope::new(
        Vec2::new(0.5, 0.0),
        Vec2::new(0.5, -1.6),
        0.4,
        material,
        settings,
    )
    .expect("a valid rope");
    rope.hang(7, bob).expect("a free end");
    rope
}

/// Where the hand is at `t`: 0.75 turns a second on a 0.5 m circle after a second of
/// spin-up (the catapult's first whirl).
fn hand(t: f32) -> Vec2<f32> {
    let turns = (t.min(1.0) * t.min(1.0) * 0.5 + (t - 1.0).max(0.0)) * 0.75;
    let a = core::f32::consts::TAU * turns;
    Vec2::new(0.5 * a.cos(), 0.5 * a.sin())
}

/// One 60 Hz frame of the whirl: the hand moves, the rope steps; `None` once a step is
/// refused. Returns the share of the frame simulated.
fn frame(rope: &mut Chain, t: f32) -> Option<f32> {
    rope.move_pinned(0, hand(t), 1.0 / 60.0).ok()?;
    let info = rope.step(1.0 / 60.0).ok()?;
    Some(info.simulated * 60.0)
}

/// The whirl for 5 s: the largest stretch of a link (or infinity once a step is refused) and
/// the least share of a frame simulated.
fn whirl(method: AnyIntegrator, k: f32, bob: f32) -> (f64, f64) {
    let mut rope = catapult_rope(method, k, bob);
    let (mut stretch, mut share) = (0.0f64, 1.0f64);
    for n in 1..=300 {
        let Some(s) = frame(&mut rope, n as f32 / 60.0) else {
            return (f64::INFINITY, share);
        };
        share = share.min(f64::from(s));
        for pair in rope.positions().windows(2) {
            let l = f64::from(pair[0].distance(pair[1]));
            stretch = stretch.max(l / (1.6 / 7.0) - 1.0);
        }
    }
    (stretch, share)
}

/// Median nanoseconds of a whirl frame and its 64 drawn points, the rope restarted every
/// 5 s.
fn frame_ns(run: &Run, method: AnyIntegrator, k: f32) -> f64 {
    let start = catapult_rope(method, k, 3.0);
    let (mut rope, mut n, mut curve) = (start.clone(), 0, [Vec2::default(); 64]);
    median_ns(run.reps(), 30, || {
        n += 1;
        if n > 300 || frame(&mut rope, n as f32 / 60.0).is_none() {
            (rope, n) = (start.clone(), 0);
        }
        std::hint::black_box(rope.sample(Smoothing::CatmullRom, &mut curve).ok());
    })
}

/// The share of a released swing's energy left after 10 s: an 8-particle rope (1 m, 1 kg,
/// 10⁵ N/m, undamped) let go level from a pin.
fn energy_kept(method: AnyIntegrator) -> f64 {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        ..Settings::default()
    }
    .with_integrator(method);
    let material = Material {
        stiffness: 1e5,
        damping: 0.0,
    };
    let mut rope: Rope<Vec2<f64>, 8, 8, AnyIntegrator> = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        1.0,
        material,
        settings,
    )
    .expect("a valid rope");
    let rest: f64 = (1..8)
        .map(|i| -9.81 * (i as f64 / 7.0) / rope.inv_masses()[i])
        .sum();
    let released = rope.energy() - rest;
    for _ in 0..600 {
        if rope.step(1.0 / 60.0).is_err() {
            return f64::NAN;
        }
    }
    (rope.energy() - rest) / released
}

pub fn run(run: &mut Run) {
    let stiffnesses: &[f32] = if run.quick {
        &[1e2, 4e3, 1e6]
    } else {
        &[1e2, 4e3, 1e4, 1e6, 1e8]
    };
    let ratios: &[f32] = if run.quick {
        &[1.0, 100.0]
    } else {
        &[1.0, 10.0, 100.0, 1000.0]
    };
    let mut rows = Vec::new();
    let mut cost_series = Vec::new();
    let mut stretch_series = Vec::new();
    let mut by_stiffness = String::from(
        "| method | `k` (N/m) | ns per frame | largest link stretch | time simulated |\n|---|---|---|---|---|\n",
    );
    let mut by_mass =
        String::from("| method | bob / rope mass | largest link stretch |\n|---|---|---|\n");
    let mut energy = String::from("| method | energy of the swing kept after 10 s |\n|---|---|\n");
    let mut direct_costs = Vec::new();
    let mut direct_stretch = (f64::NAN, f64::NAN);
    // The catapult's own springs (4 000 N/m): symplectic Euler's frame and DirectChain's.
    let mut own = (f64::NAN, f64::NAN);
    for (name, method) in methods() {
        let mut costs = Vec::new();
        for &k in stiffnesses {
            let ns = frame_ns(run, method, k);
            let (stretch, share) = whirl(method, k, 3.0);
            by_stiffness.push_str(&format!(
                "| {name} | {k:.0e} | {ns:.0} | {} | {:.0}% |\n",
                pct(stretch),
                share * 100.0
            ));
            rows.push(vec![
                name.to_string(),
                format!("{k:e}"),
                "7.5".into(),
                format!("{ns:.1}"),
                format!("{stretch:.6}"),
                format!("{share:.4}"),
            ]);
            costs.push((f64::from(k), ns));
            if k == 4e3 && name == "symplectic Euler" {
                own.0 = ns;
            }
            if name == "DirectChain" {
                direct_costs.push(ns);
                if k == 4e3 {
                    (direct_stretch.0, own.1) = (stretch, ns);
                }
            }
        }
        cost_series.push(Series::line(name, costs));
        let mut stretches = Vec::new();
        for &ratio in ratios {
            let (stretch, _) = whirl(method, 4000.0, ratio * 0.4);
            by_mass.push_str(&format!("| {name} | {ratio:.0} | {} |\n", pct(stretch)));
            stretches.push((f64::from(ratio), stretch.min(100.0)));
            if name == "DirectChain" && ratio == 100.0 {
                direct_stretch.1 = stretch;
            }
        }
        stretch_series.push(Series::line(name, stretches));
        let kept = energy_kept(method);
        energy.push_str(&format!("| {name} | {} |\n", pct(kept)));
    }
    chart(
        &run.path("chains_cost.svg"),
        "Catapult rope (8 particles, f32), whirled with its penguin: cost of a 60 Hz frame",
        "spring stiffness k (N/m)",
        "ns per frame (step and 64 points)",
        &cost_series,
        true,
    );
    chart(
        &run.path("chains_stretch.svg"),
        "Catapult rope whirled with a bob (k = 4000 N/m): largest link stretch",
        "bob mass over rope mass",
        "largest stretch (1 = 100%)",
        &stretch_series,
        true,
    );
    csv(
        &run.path("chains.csv"),
        &[
            "method",
            "k",
            "bob_over_rope",
            "ns_per_frame",
            "largest_stretch",
            "time_simulated",
        ],
        &rows,
    );
    let (lo, hi) = direct_costs
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &c| {
            (lo.min(c), hi.max(c))
        });
    let spread = hi / lo;
    run.target(
        "DirectChain: frame cost from k = 10² to 10⁸ within 1.5×",
        format!("{spread:.2}×"),
        spread <= 1.5,
        "timing noise on the shared machine",
    );
    run.target(
        "DirectChain: the catapult rope's frame within 2× symplectic Euler's on its own springs",
        format!("{:.2}×", own.1 / own.0),
        own.1 <= 2.0 * own.0,
        "4 solves of 4 Newton iterations, each a square root, a division and a line search a link",
    );
    run.target(
        "DirectChain: catapult rope under its penguin within 0.5%",
        pct(direct_stretch.0),
        direct_stretch.0 <= 5e-3,
        "",
    );
    if !run.quick {
        run.target(
            "DirectChain: a bob 100× the rope's mass within 0.5%",
            pct(direct_stretch.1),
            direct_stretch.1 <= 5e-3,
            "the Newton iterations do not converge in the whip",
        );
    }
    run.section(
        "(j) Stiff chains: the rope's links solved together",
        &format!(
            "![cost](chains_cost.svg)\n\n![stretch](chains_stretch.svg)\n\nThe catapult's rope (1.6 m, 0.4 kg, \
             8 particles, spring damping 4 N·s/m) hung from a hand whirling 0.75 turns a second on a 0.5 m circle \
             after a second of spin-up, for 5 s, in f32. Cost: a frame at 60 Hz (step and 64 Catmull-Rom points), \
             median. Stretch: the largest of any link over the whirl (∞: a step was refused). Time simulated: the \
             least share of a frame covered (below 100%, the substep cap slowed time). `DirectChain` takes one \
             substep a frame (its default: 4 solves of 4 Newton iterations); the explicit methods take substeps \
             from the springs' stiffness; `DirectChain, springs` keeps the springs' stiffness instead of holding \
             the links.\n\nAcross stiffness, with the 3 kg penguin (7.5× the rope):\n\n{by_stiffness}\nAcross the \
             bob's mass, `k` = 4 000 N/m:\n\n{by_mass}\nEnergy: an undamped 8-particle rope (1 m, 1 kg, 10⁵ N/m) \
             released level, the share of its swing's energy left after 10 s (a solve removes the velocity that \
             stretches a link; a whipping chain keeps feeding such velocity):\n\n{energy}\nData: `chains.csv`."
        ),
    );
}

/// A share as a percentage with the figures that matter, `∞` for infinity.
fn pct(share: f64) -> String {
    if share.is_finite() {
        format!("{}%", num(share * 100.0))
    } else {
        "∞ (refused)".into()
    }
}
