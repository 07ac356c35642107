//! Section (j): stiff ropes and sails, where substeps bought stiffness and the direct solvers
//! (`DirectChain`, `DirectSprings`) do not need them. Every integrator on the catapult's rope
//! whirled with its penguin, across stiffness and across the bob's mass; the energy each
//! keeps of a released rope's swing; a 30-particle rope swinging; and the boat scene's sail
//! across stiffness.

use dunas::integrator::{
    AnyIntegrator, DirectChain, DirectSprings, ImplicitEuler, SymplecticEuler, Xpbd,
};
use dunas::prelude::*;

use crate::report::{Run, Series, chart, csv, median_ns, num};

/// The methods compared, with their names in the tables.
fn methods() -> [(&'static str, AnyIntegrator); 8] {
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
        (
            "DirectSprings",
            AnyIntegrator::DirectSprings(DirectSprings::default()),
        ),
        (
            "DirectSprings, energy kept",
            AnyIntegrator::DirectSprings(DirectSprings {
                keep_energy: true,
                ..DirectSprings::default()
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
/// 10⁵ N/m, its springs undamped, `damping` the drag of `Settings::damping`) let go level
/// from a pin; the median nanoseconds of its frame (f64) and the substeps a frame.
fn swing(run: &Run, method: AnyIntegrator, damping: f64) -> (f64, f64, u16) {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping,
        ..Settings::default()
    }
    .with_integrator(method);
    let material = Material {
        stiffness: 1e5,
        damping: 0.0,
    };
    let start: Rope<Vec2<f64>, 8, 8, AnyIntegrator> = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        1.0,
        material,
        settings,
    )
    .expect("a valid rope");
    let rest: f64 = (1..8)
        .map(|i| -9.81 * (i as f64 / 7.0) / start.inv_masses()[i])
        .sum();
    let released = start.energy() - rest;
    let mut rope = start.clone();
    let mut substeps = 0;
    for _ in 0..600 {
        match rope.step(1.0 / 60.0) {
            Ok(info) => substeps = substeps.max(info.substeps),
            Err(_) => return (f64::NAN, f64::NAN, substeps),
        }
    }
    let kept = (rope.energy() - rest) / released;
    let (mut rope, mut n) = (start.clone(), 0);
    let ns = median_ns(run.reps(), 30, || {
        n += 1;
        if n > 600 {
            (rope, n) = (start.clone(), 0);
        }
        std::hint::black_box(rope.step(1.0 / 60.0).ok());
    });
    (kept, ns, substeps)
}

/// A 1 m, 1 kg rope of 30 particles, axial stiffness `EA` = 1 000 N (29 000 N/m a spring),
/// undamped, let go 30° from hanging straight down with every link at its static stretch
/// (the weight below it over `k`): the largest stretch of the whole rope over 5 s (0.49% at
/// rest; the swing's tension adds up to a quarter) and the median nanoseconds of a frame
/// (step only).
fn rope30(run: &Run, method: AnyIntegrator) -> (f64, f64) {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        ..Settings::default()
    }
    .with_integrator(method);
    let k = 1000.0 * 29.0;
    let material = Material {
        stiffness: k,
        damping: 0.0,
    };
    let along = Vec2::new(30f32.to_radians().sin(), -30f32.to_radians().cos());
    let mut start: Rope<Vec2<f32>, 30, 30, AnyIntegrator> =
        Rope::new(Vec2::new(0.0, 0.0), along, 1.0, material, settings).expect("a valid rope");
    let w = start.inv_masses().to_vec();
    let mut reach = 0.0f32;
    for i in 1..30 {
        let below: f32 = (i..30).map(|p| 9.81 / w[p]).sum();
        reach += 1.0 / 29.0 + below / k;
        start.set_position(i, along * reach).expect("in range");
    }
    let mut rope = start.clone();
    let mut stretch = 0.0f64;
    for _ in 0..300 {
        if rope.step(1.0 / 60.0).is_err() {
            return (f64::INFINITY, f64::NAN);
        }
        let length: f32 = rope
            .positions()
            .windows(2)
            .map(|p| p[0].distance(p[1]))
            .sum();
        stretch = stretch.max(f64::from(length) - 1.0);
    }
    let (mut rope, mut n) = (start.clone(), 0);
    let ns = median_ns(run.reps(), 30, || {
        n += 1;
        if n > 300 {
            (rope, n) = (start.clone(), 0);
        }
        std::hint::black_box(rope.step(1.0 / 60.0).ok());
    });
    (stretch, ns)
}

/// The boat scene's 8×8 sail (`tests/common`'s `boat_sail`: springs 900/300/60 N/m times
/// `scale`) and its 5 m/s wind, gusting by `gust`.
fn boat_sail<S: Scalar>(
    method: AnyIntegrator,
    scale: f64,
    gust: f64,
) -> crate::common::BoatSail<S, AnyIntegrator> {
    crate::common::boat_sail(method, scale, gust).expect("a valid sail")
}

/// The sail in a steady wind after 15 s: its particles' positions (the balance, once at rest).
fn sail_balance<S: Scalar>(method: AnyIntegrator, scale: f64) -> Option<Vec<Vec3<f64>>> {
    let (mut sail, mut wind) = boat_sail::<S>(method, scale, 0.0);
    for _ in 0..900 {
        let _ = sail.step_with(S::ratio(1, 60), &mut wind).ok()?;
    }
    let at = |x: S| x.to_f64();
    Some(
        sail.positions()
            .iter()
            .map(|p| Vec3::new(at(p.x), at(p.y), at(p.z)))
            .collect(),
    )
}

/// Median nanoseconds of a frame of the sail in its gusty wind (step only, f32) and the
/// substeps a frame.
fn sail_ns(run: &Run, method: AnyIntegrator, scale: f64) -> (f64, u16) {
    let (start, wind) = boat_sail::<f32>(method, scale, 4.0);
    let (mut sail, mut wind, mut n, mut substeps) = (start.clone(), wind, 0, 0);
    let ns = median_ns(run.reps(), 10, || {
        n += 1;
        if n > 600 {
            (sail, n) = (start.clone(), 0);
        }
        if let Ok(info) = sail.step_with(1.0 / 60.0, &mut wind) {
            substeps = info.substeps;
        }
    });
    (ns, substeps)
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
    let mut energy = String::from(
        "| method | substeps a frame | ns per frame | energy of the swing kept after 10 s | with a drag of 0.1/s |\n|---|---|---|---|---|\n",
    );
    let mut energy_series = Vec::new();
    let mut direct_costs = Vec::new();
    let mut direct_kept = Vec::new();
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
        let (kept, ns, substeps) = swing(run, method, 0.0);
        let (dragged, _, _) = swing(run, method, 0.1);
        energy.push_str(&format!(
            "| {name} | {substeps} | {ns:.0} | {} | {} |\n",
            pct(kept),
            pct(dragged)
        ));
        energy_series.push(Series::dots(name, vec![(ns, kept * 100.0)]));
        if name.starts_with("Direct") {
            direct_kept.push((name, kept));
        }
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
    chart(
        &run.path("chains_energy.svg"),
        "Undamped 8-particle rope released level (f64): energy of its swing kept after 10 s",
        "ns per frame (f64)",
        "energy kept (%)",
        &energy_series,
        false,
    );
    let lively = direct_kept.iter().map(|&(_, k)| k).fold(0.0f64, f64::max);
    let kept: Vec<String> = direct_kept
        .iter()
        .map(|(name, k)| format!("{name} {}", pct(*k)))
        .collect();
    run.target(
        "an undamped swing keeps ≥ 90% of its energy over 10 s, a direct solver at one solve a frame",
        kept.join(", "),
        lively >= 0.9,
        "an implicit solve damps as backward Euler does, each mode by about 1 / (1 + (ωh)²) of its energy a \
         solve (chains_energy.svg)",
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
    // A 30-particle rope swinging: what each method costs under 1% stretch.
    let mut thirty = String::from(
        "| method | ns per frame | largest stretch of the rope | cost against symplectic Euler |\n|---|---|---|---|\n",
    );
    let long: Vec<_> = methods()
        .into_iter()
        .filter(|(name, _)| *name != "DirectChain")
        .map(|(name, method)| (name, rope30(run, method)))
        .collect();
    let explicit = long[0].1.1;
    let mut cheapest: Option<(&str, f64)> = None;
    for &(name, (stretch, ns)) in &long {
        thirty.push_str(&format!(
            "| {name} | {ns:.0} | {} | {:.2}× |\n",
            pct(stretch),
            ns / explicit
        ));
        let direct = name.starts_with("Direct");
        if direct && stretch <= 0.01 && cheapest.is_none_or(|(_, c)| ns < c) {
            cheapest = Some((name, ns));
        }
    }
    let (name, ns) = cheapest.unwrap_or(("none", f64::INFINITY));
    run.target(
        "30-particle rope within 1% stretch: a direct solver at least 4× cheaper than symplectic Euler",
        format!("{name}: {:.1}× cheaper", explicit / ns),
        explicit >= 4.0 * ns && long[0].1.0 <= 0.01,
        "a direct solve a frame still costs several force evaluations on a long rope, and DirectSprings \
         goes on iterating (a pass over the springs and its measure each, up to 16) while what a solve leaves \
         is more than half of its motion, which a turning stiff rope's is",
    );
    // The boat scene's sail across stiffness: cost and distance from its balance.
    let scales: &[f64] = if run.quick {
        &[1.0, 100.0]
    } else {
        &[1.0, 10.0, 100.0]
    };
    let sail_methods = [
        ("symplectic Euler", AnyIntegrator::SymplecticEuler),
        ("Verlet", AnyIntegrator::Verlet),
        (
            "backward Euler",
            AnyIntegrator::ImplicitEuler(ImplicitEuler::default()),
        ),
        ("XPBD", AnyIntegrator::Xpbd(Xpbd::default())),
        (
            "DirectSprings",
            AnyIntegrator::DirectSprings(DirectSprings::default()),
        ),
        (
            "DirectSprings, energy kept",
            AnyIntegrator::DirectSprings(DirectSprings {
                keep_energy: true,
                ..DirectSprings::default()
            }),
        ),
    ];
    let mut sails = String::from(
        "| method | stiffness × | ns per frame | substeps | farthest particle from the balance |\n|---|---|---|---|---|\n",
    );
    let mut sail_series = Vec::new();
    let mut sail_costs = Vec::new();
    let (mut own_sail, mut direct_sail, mut direct_far) = (f64::NAN, f64::NAN, 0.0f64);
    let references: Vec<_> = scales
        .iter()
        .map(|&scale| sail_balance::<f64>(AnyIntegrator::SymplecticEuler, scale))
        .collect();
    for (name, method) in sail_methods {
        let mut costs = Vec::new();
        for (&scale, reference) in scales.iter().zip(&references) {
            let (ns, substeps) = sail_ns(run, method, scale);
            let far = match (sail_balance::<f32>(method, scale), reference) {
                (Some(got), Some(reference)) => got
                    .iter()
                    .zip(reference)
                    .map(|(a, b)| a.distance(*b))
                    .fold(0.0, f64::max),
                _ => f64::INFINITY,
            };
            sails.push_str(&format!(
                "| {name} | {scale:.0} | {ns:.0} | {substeps} | {} mm |\n",
                num(far * 1e3)
            ));
            costs.push((scale, ns));
            if scale == 1.0 && name == "symplectic Euler" {
                own_sail = ns;
            }
            if name == "DirectSprings" {
                sail_costs.push(ns);
                direct_far = direct_far.max(far);
                if scale == 1.0 {
                    direct_sail = ns;
                }
            }
        }
        sail_series.push(Series::line(name, costs));
    }
    chart(
        &run.path("chains_sail.svg"),
        "The boat scene's 8×8 sail in gusty wind (f32): cost of a 60 Hz step",
        "spring stiffness, times the boat's own",
        "ns per frame (step)",
        &sail_series,
        true,
    );
    let (lo, hi) = sail_costs
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &c| {
            (lo.min(c), hi.max(c))
        });
    run.target(
        "DirectSprings: the boat sail within 1 mm of its balance at every stiffness, one solve a frame",
        format!("{} mm", num(direct_far * 1e3)),
        direct_far <= 1e-3,
        "an iteration turns stiff springs only part of the way (projective dynamics' locking, about m / (h² k)), \
         so a stiff sail fills slowly where its solves stop short",
    );
    run.target(
        "DirectSprings: the boat sail's frame cost across stiffness within 1.5×",
        format!("{:.2}×", hi / lo),
        hi <= 1.5 * lo,
        "a measured solve stops once within its tolerance and keeping pace with the motion (leaving at most \
         half of how far it moved a particle): at the sail's own stiffness after a few iterations, 10 and 100 \
         times stiffer after up to 16, each iteration turning the stiff springs only part of the way \
         (projective dynamics' locking); with at most 4 a solve it was 1.93×, and the stiff sail lagged in \
         slow motion (tests/suite/converge.rs, direct_springs_keep_a_stiff_sail_in_time: 36 mm behind the \
         fully iterated solve 100 times stiffer, of a 150 mm swing; 9.5 mm now)",
    );
    run.target(
        "DirectSprings: the boat sail's frame at its own stiffness cheaper than symplectic Euler's",
        format!("{:.2}× symplectic Euler's", direct_sail / own_sail),
        direct_sail < own_sail,
        "",
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
    // A stiff cloth let swing at `DirectSprings`' defaults: how far it hangs after 10 s, and
    // how far it moves in its 10th second.
    let direct = DirectSprings::default();
    let hangs: Vec<(f64, &str, (f64, f64))> = [1e3, 1e4]
        .iter()
        .flat_map(|&ea| {
            [
                (ea, "8×8", cloth_drop::<8, _>(ea, direct, 60)),
                (ea, "20×20", cloth_drop::<20, _>(ea, direct, 60)),
            ]
        })
        .collect();
    // The converged motion: symplectic Euler at 480 Hz, with substeps from stiffness (at
    // 960 Hz it moves the same; at 240 Hz the stiff 20×20 is not yet converged).
    let converged: Vec<(f64, &str, (f64, f64))> = if run.quick {
        Vec::new()
    } else {
        [1e3, 1e4]
            .iter()
            .flat_map(|&ea| {
                [
                    (ea, "8×8", cloth_drop::<8, _>(ea, SymplecticEuler, 480)),
                    (ea, "20×20", cloth_drop::<20, _>(ea, SymplecticEuler, 480)),
                ]
            })
            .collect()
    };
    let figures = |f: &dyn Fn(&(f64, f64)) -> String| {
        hangs
            .iter()
            .map(|(ea, size, drop)| format!("{size} EA {ea:.0e}: {}", f(drop)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    run.target(
        "DirectSprings defaults: a 1 m cloth, 8×8 and 20×20, held by two corners hangs within 1% of the \
         statics' 1.00 m after 10 s, at EA 10³ and 10⁴ N",
        figures(&|(drop, _)| format!("{drop:.3} m")),
        hangs.iter().all(|(_, _, (drop, _))| (drop - 1.0).abs() <= 0.01),
        "projective dynamics' locking: an iteration turns a stiff spring by about m / (h² k)",
    );
    let reference = converged
        .iter()
        .map(|(ea, size, (_, moved))| format!("{size} EA {ea:.0e}: {:.2} mm", moved * 1e3))
        .collect::<Vec<_>>()
        .join(", ");
    run.target(
        "DirectSprings defaults: the same cloths at rest (moving less than 1 mm) in their 10th second",
        format!(
            "{}{}",
            figures(&|(_, moved)| format!("{:.1} mm", moved * 1e3)),
            if reference.is_empty() {
                String::new()
            } else {
                format!(" (the converged motion, symplectic Euler at 480 Hz: {reference})")
            }
        ),
        hangs.iter().all(|(_, _, (_, moved))| *moved < 1e-3),
        "what a solve leaves unconverged keeps the cloth creeping towards its balance",
    );
    run.section(
        "(j) Stiff ropes and sails: springs solved together",
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
             stretches a link; a whipping chain keeps feeding such velocity; `DirectSprings` damps as backward Euler \
             does; `DirectSprings, energy kept` gives back what its solve's damping takes), and the median cost of a \
             frame (f64):\n\n![energy](chains_energy.svg)\n\n{energy}\nA 1 m, 1 kg rope of 30 particles (axial stiffness 1 000 N, 29 000 N/m a spring, \
             undamped) let go 30° from straight down, each link at its static stretch, for 5 s, in f32 (step only; \
             the rope's stretch is 0.49% at rest):\n\n{thirty}\n\
             ![sail](chains_sail.svg)\n\nThe boat scene's 8×8 sail (2 kg, springs 900/300/60 N/m times the factor, \
             pinned on mast, gaff and boom) in its 5 m/s wind gusting by 4 m/s, in f32: the cost of a step (median), \
             its substeps, and, in a steady wind after 15 s, its farthest particle from the balance symplectic Euler \
             reaches in f64:\n\n{sails}\nData: `chains.csv`."
        ),
    );
}

/// How far below its pins the stiff cloth (`tests/common`'s `hung_cloth`: 1 m, 1 kg,
/// `U`×`U`, held level by two corners, axial stiffness `ea` N, a drag of 2/s) hangs after
/// 10 s stepped by `solver` at `rate` Hz (statics: 1.00 m), and the farthest any particle
/// moved in its 10th second (m).
fn cloth_drop<const U: usize, I: Integrator>(ea: f64, solver: I, rate: usize) -> (f64, f64) {
    let Ok(mut cloth) = crate::common::hung_cloth::<U, I>(ea, solver) else {
        return (f64::NAN, f64::NAN);
    };
    let mut second = cloth.positions().to_vec();
    for frame in 0..10 * rate {
        if frame == 9 * rate {
            second = cloth.positions().to_vec();
        }
        if cloth.step(1.0 / rate as f64).is_err() {
            return (f64::NAN, f64::NAN);
        }
    }
    let moved = (cloth.positions().iter().zip(&second))
        .map(|(a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    (
        -cloth.positions().iter().map(|p| p.y).fold(0.0, f64::min),
        moved,
    )
}

/// A share as a percentage with the figures that matter, `∞` for infinity.
fn pct(share: f64) -> String {
    if share.is_finite() {
        format!("{}%", num(share * 100.0))
    } else {
        "∞ (refused)".into()
    }
}
