//! (g) Contacts: how far the drawn rope sinks past a peg's top against what a frame costs,
//! particle contacts against contacts on the drawn curve, across peg radius / particle spacing;
//! and what each collider adds to a frame.

use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::integrator::{DirectChain, DirectSprings, Integrator, SymplecticEuler};
use dunas::{Material, Point as _, Rope, Settings, Smoothing, Vec2, Vec3};

use crate::common::draped_rope;
use crate::report::{Run, Series, chart, csv, fastest_and_median_ns, median_ns, num};

/// Seconds of settling before anything is measured.
const SETTLE_FRAMES: usize = 360;
/// The peg's centre: below the middle of the 8-particle rope's middle span.
const PEG: (f64, f64) = (0.0, -1.0);

/// How the rope touches, and how it is drawn and judged.
struct Mode {
    name: &'static str,
    touch: Touch,
    drawn: Smoothing,
}

const MODES: [Mode; 3] = [
    Mode {
        name: "particle contacts, drawn as B-spline",
        touch: Touch::Particles,
        drawn: Smoothing::BSpline,
    },
    Mode {
        name: "curve contacts, B-spline",
        touch: Touch::Drawn(Smoothing::BSpline),
        drawn: Smoothing::BSpline,
    },
    Mode {
        name: "curve contacts, Catmull-Rom",
        touch: Touch::Drawn(Smoothing::CatmullRom),
        drawn: Smoothing::CatmullRom,
    },
];

/// How far the drawn curve passes below the top of a ball at its centre's `x` (0 when it
/// rests on or above it): 2048 points, the crossing interpolated.
fn sink(curve: &[Vec2<f32>], centre: (f64, f64), radius: f64) -> f64 {
    let top = centre.1 + radius;
    curve
        .windows(2)
        .filter_map(|w| {
            let (a, b) = (w[0], w[1]);
            let (ax, bx) = (f64::from(a.x), f64::from(b.x));
            if (ax - centre.0) * (bx - centre.0) > 0.0 || ax == bx {
                return None;
            }
            let s = (centre.0 - ax) / (bx - ax);
            Some(f64::from(a.y) + s * f64::from(b.y - a.y))
        })
        .map(|y| (top - y).max(0.0))
        .fold(0.0, f64::max)
}

/// The settled rope and the median cost of one more frame (ns).
fn settled<const N: usize>(
    colliders: &[Collider<Vec2<f32>>],
    touch: Touch,
    reps: usize,
) -> (Rope<Vec2<f32>, N>, f64) {
    let rope: Rope<Vec2<f32>, N> = draped_rope(colliders, touch, SETTLE_FRAMES);
    let contacts = Contacts::new(colliders, 0.0, touch).expect("valid contacts");
    let ns = median_ns(reps, 20, || frame_of(&rope, Some(&contacts)));
    (rope, ns)
}

/// One 60 Hz frame of a copy of `rope`: with `contacts`, or bare.
pub fn frame_of<P: dunas::Point, const N: usize, const CAP: usize, I: Integrator>(
    rope: &Rope<P, N, CAP, I>,
    contacts: Option<&Contacts<'_, P>>,
) {
    let mut r = rope.clone();
    let dt = <P::Scalar as dunas::Scalar>::ratio(1, 60);
    let _ = match contacts {
        Some(c) => r.step_touching(dt, (), c),
        None => r.step(dt),
    }
    .expect("a step");
    std::hint::black_box(&r);
}

pub fn run(run: &mut Run) {
    let reps = run.reps();
    let ratios: &[f64] = if run.quick {
        &[0.1, 0.5]
    } else {
        &[0.05, 0.1, 0.2, 0.5, 1.0]
    };
    let spacing = 6.0 / 7.0; // ends held 6 m apart, 7 spans
    let mut rows = Vec::new();
    let mut series: Vec<Vec<(f64, f64)>> = vec![Vec::new(); MODES.len()];
    let mut table = String::from(
        "| peg radius / spacing | contacts | sinks past the peg's top (× radius) | frame (ns) |\n|---|---|---|---|\n",
    );
    let mut caught_at_tenth = true;
    for &ratio in ratios {
        let radius = ratio * spacing;
        let peg = [
            Collider::ball(Vec2::new(PEG.0 as f32, PEG.1 as f32), radius as f32).expect("a peg"),
        ];
        for (k, mode) in MODES.iter().enumerate() {
            let (rope, ns) = settled::<8>(&peg, mode.touch, reps);
            let mut curve = [Vec2::default(); 2048];
            let n = rope.sample(mode.drawn, &mut curve).expect("a curve");
            let depth = sink(&curve[..n], PEG, radius) / radius;
            if ratio >= 0.1 && k > 0 && depth > 0.01 {
                caught_at_tenth = false;
            }
            series[k].push((ns, depth.max(1e-4)));
            table.push_str(&format!(
                "| {ratio} | {} | {} | {ns:.0} |\n",
                mode.name,
                num(depth)
            ));
            rows.push(vec![
                format!("{ratio}"),
                mode.name.into(),
                format!("{depth:.6}"),
                format!("{ns:.1}"),
            ]);
        }
    }
    let plotted: Vec<Series> = MODES
        .iter()
        .zip(series)
        .map(|(m, p)| Series::line(m.name, p))
        .collect();
    chart(
        &run.path("contacts.svg"),
        "A rope of 8 on a peg: how far the drawn rope sinks past the peg's top, against the frame's cost \
         (one point per peg radius / spacing: 0.05 to 1)",
        "frame cost, f32 (ns)",
        "sink past the peg's top (× radius, 1e-4 = none)",
        &plotted,
        true,
    );
    csv(
        &run.path("contacts.csv"),
        &[
            "radius_over_spacing",
            "contacts",
            "sink_over_radius",
            "frame_ns",
        ],
        &rows,
    );

    // What each collider adds: pegs of a tenth of the spacing, spread under the rope.
    let pegs = |count: usize| -> Vec<Collider<Vec2<f32>>> {
        (0..count)
            .map(|i| {
                let x = -2.5 + 5.0 * (i as f32 + 0.5) / count.max(1) as f32;
                Collider::ball(Vec2::new(x, -1.2), 0.1 * spacing as f32).expect("a peg")
            })
            .collect()
    };
    let counts = [0usize, 1, 2, 4, 8];
    let mut per_collider = String::from(
        "| colliders | particle contacts (ns) | curve contacts, B-spline (ns) |\n|---|---|---|\n",
    );
    let mut slopes = [0.0; 2];
    let mut base = [0.0; 2];
    for &count in &counts {
        let pegs = pegs(count);
        let mut cells = Vec::new();
        for (m, touch) in TOUCHES.into_iter().enumerate() {
            let (_, ns) = settled::<8>(&pegs, touch, reps);
            if count == 0 {
                base[m] = ns;
            }
            if count == 8 {
                slopes[m] = (ns - base[m]) / 8.0;
            }
            cells.push(format!("{ns:.0}"));
        }
        per_collider.push_str(&format!("| {count} | {} | {} |\n", cells[0], cells[1]));
    }
    let four = four_pegs_cost(&pegs(4), reps);
    let step_ns = four.step.0;
    // What the pegs add over the bare step, from the rounds' least (`.0`) or median (`.1`)
    // figures.
    type Pick = fn((f64, f64)) -> f64;
    let ratio4 =
        |m: usize, pick: Pick| (pick(four.with[m]) - pick(four.without[m])) / pick(four.step);
    let (fastest, median): (Pick, Pick) = (|f| f.0, |f| f.1);
    run.target(
        "contacts against 4 colliders on an 8-particle rope (f32) add ≤ 1× its step at the \
         particles, ≤ 2× on the drawn curve",
        format!(
            "particles {:.2}×, curve {:.2}× (fastest of interleaved rounds; medians {:.2}× and \
             {:.2}×; step {step_ns:.0} ns)",
            ratio4(0, fastest),
            ratio4(1, fastest),
            ratio4(0, median),
            ratio4(1, median)
        ),
        ratio4(0, fastest) <= 1.0 && ratio4(1, fastest) <= 2.0,
        "the contacts run once a frame (at a thickness of 0, while no point can close on a peg \
         by an eighth of its radius), and then curve contacts take a box per span (each taken \
         once a pass), a box test per span and peg, a capsule test of each span near a peg, a \
         search for the nearest point (9 samples and Newton steps) on each span the capsule \
         does not clear, the push's particle weights, and a redraw of the spans a push moved \
         (every span of an 8-particle rope) as a peg comes within their boxes grown by the push",
    );
    let (far_added, (far_substeps, bare_substeps)) = far_collider_cost(reps);
    run.target(
        "a collider out of reach this frame adds no substep and ≤ 5% of the step's cost",
        format!(
            "{:.1}% of the step; {far_substeps} substep(s), {bare_substeps} without it",
            far_added * 100.0
        ),
        far_added <= 0.05 && far_substeps == bare_substeps,
        "before it knows that nothing is in reach, the frame takes a pass over the particles \
         (their box and top speed, a root) and a box test of each collider's path: a fixed \
         cost that an 8-particle rope's short step shows",
    );
    run.target(
        "curve contacts catch pegs down to 0.1× the particle spacing",
        if caught_at_tenth {
            "caught (sink < 1% of the radius) from 0.1× up".into()
        } else {
            "not caught at every ratio ≥ 0.1×".into()
        },
        caught_at_tenth,
        "see the contacts table",
    );
    let costs = self_contact_costs(reps);
    // What the floor adds to the bare step (the frame with it less the step).
    let added = |(step, floor): (f64, f64)| (floor - step).max(0.0) / step;
    let lying = &costs.lying;
    let floor_lying = added((lying.step, lying.floor));
    let fastest_lying = added((lying.fastest_step, lying.fastest_floor));
    run.target(
        "a floor alone under a rope resting on it adds ≤ 1× its step on the drawn curve",
        format!(
            "adds {floor_lying:.2}× (fastest {fastest_lying:.2}×; 16 particles, Catmull-Rom, \
             step {:.0} ns, {:.0} ns with the floor)",
            lying.step, lying.floor
        ),
        floor_lying <= 1.0,
        "the floor's contacts run once a frame (a rope at rest moves less than its thickness \
         in a frame), but each span on it then takes its deepest point in closed form, its \
         particle weights and a push, and the 7 spans its particles weigh in are drawn again \
         (each once, when next read)",
    );
    for (what, target, state) in [
        ("settled in a pile on a floor (5 drops)", 10.0, &costs.piled),
        (
            "falling into the pile (5 drops, 600 frames)",
            20.0,
            &costs.falling,
        ),
        ("still in a flat spiral (24 particles)", 10.0, &costs.spiral),
    ] {
        run.target(
            &format!(
                "a rope {what}, drawn-curve contacts and self-contact, costs ≤ {target}× its \
                 bare step"
            ),
            format!(
                "{:.0}× (fastest {:.0}×; frame {:.0} µs, bare step {:.0} ns)",
                state.both / state.step,
                state.fastest_both / state.fastest_step,
                state.both / 1e3,
                state.step
            )
            .replace(" (fastest NaN×;", " (mean of its frames;"),
            state.both <= target * state.step,
            "the floor's contacts run at every substep while self-contact holds two spans \
             apart (else as often as keeps two parts from closing by half the thickness), \
             self-contact once a span moved an eighth of the diameter (and in the first and \
             last, holding apart in between what the first pushed apart), in rounds with the \
             floor until no \
             overlap is over 1% of the diameter (a pile is contacts stacked on contacts); each \
             round meets each pair of spans whose boxes meet (searched by exact chord \
             distances then Newton steps, followed by Newton steps from where the step found \
             it, or held apart by how little its spans moved) and redraws the spans each push \
             moved",
        );
    }
    // The player's rope of `examples/mcu_wrap.rs` wrapping its box, under `DirectChain`.
    let reps = if run.quick { 3 } else { 7 };
    let device = DirectChain {
        iterations: 2,
        substeps: 1,
        ..DirectChain::default()
    };
    let wrap = round_a_box(device, (2000.0, 70.0), reps);
    run.target(
        "DirectChain with contacts: a 70 kg player's 12-particle rope wrapping a box 3 spacings \
         wide (one solve of 2 iterations a frame, 600 frames) keeps its drawn curve within 1% of \
         the thickness of the box and every link within 0.1% at the end of each step",
        format!(
            "deepest {:.2}% of the thickness into the box, links within {:.3}%, {} of 600 frames \
             flagged unconverged, {} ending against it (within 1 mm of the thickness); {:.1}× the \
             frame without the box (fastest {:.1}×)",
            wrap.deepest * 100.0,
            wrap.stretch * 100.0,
            wrap.flagged,
            wrap.touching,
            wrap.ratio.1,
            wrap.ratio.0
        ),
        wrap.deepest <= 0.01 && wrap.stretch <= 0.001,
        "where the player pulls the rope round a corner, the links' solve, which does not see \
         the box, pulls the rope in by centimetres, and the rounds of contacts and links after \
         it (each pushed particle held along its push) end with a link beyond 0.1% or do not \
         agree within 8 rounds: those steps say so",
    );
    // The same scene under `DirectSprings` (defaults), a 20 kg load on its springs.
    let springy = round_a_box(DirectSprings::default(), (2000.0, 20.0), reps);
    run.target(
        "DirectSprings with contacts: a 20 kg load's 12-particle rope (2 000 N/m) wrapping the \
         same box (defaults, 600 frames) keeps its drawn curve within 1% of the thickness of \
         the box at the end of each step",
        format!(
            "deepest {:.2}% of the thickness into the box, {} of 600 frames flagged \
             unconverged, {} ending against it; {:.1}× the frame without the box (fastest \
             {:.1}×)",
            springy.deepest * 100.0,
            springy.flagged,
            springy.touching,
            springy.ratio.1,
            springy.ratio.0
        ),
        springy.deepest <= 0.01,
        "a solve's pushes are large, and after 8 rounds of contacts one still moved a particle \
         by more than 0.1% of a link, dragging a span pushed out before back in",
    );
    // The towel of the test `a_towel_folded_over_a_rod_never_passes_through_itself`.
    let (crossings, closest, with) =
        crate::common::towel_over_a_rod(Smoothing::CatmullRom, true, 5);
    let (without_crossings, _, without) =
        crate::common::towel_over_a_rod(Smoothing::CatmullRom, false, 5);
    run.target(
        "a cloth folded over a rod: no crossing of its drawn surface",
        format!(
            "{crossings} crossings, drawn points of cells 3 apart {closest:.4} m apart at the \
             closest (diameter 0.02 m); {without_crossings} crossings without self-contact"
        ),
        crossings == 0,
        "each cell's box is its Bézier control points' box (the convex hull property); the \
         cells whose boxes meet take a search of 3×3 samples and a pattern search on each \
         side, and rounds of pushes",
    );
    let line = |s: &Frame| {
        format!(
            "{:.0} ns bare step, {:.0} ns with the floor, {:.0} ns with the floor and \
             self-contact ({:.0}×, the median of 5 interleaved rounds; fastest of their \
             batches {:.0}×)",
            s.step,
            s.floor,
            s.both,
            s.both / s.step,
            s.fastest_both / s.fastest_step
        )
    };
    let moving = |s: &Frame| {
        format!(
            "{:.0} ns bare step, {:.0} ns with the floor and self-contact ({:.0}×)",
            s.step,
            s.both,
            s.both / s.step
        )
    };
    let self_contact = format!(
        "Self-contact (`Contacts::with_self_contact`) of a 3D rope of 16 particles, 1 cm thick, on a \
         floor with contacts on its drawn Catmull-Rom curve, each frame against the same rope's \
         bare step (no contacts), medians. Lying straight: {}. Settled in a pile after falling end \
         first (the five drops of the test `a_rope_dropped_in_a_pile_never_passes_through_itself`, \
         a frame of each in turn: a pile is chaotic, and one pile's cost is not another's): {}. \
         Falling into it, the mean of the five drops' 600 frames: {}. Whipped (lying straight, \
         its held end then swung twice a second round a tilted circle 0.3 m across, from the \
         floor up to 0.3 m), the mean of 600 frames from each of the five starts: {}. \
         A rope of 24 particles lying still in a flat spiral: {}.\n\nA towel of 10×10 particles (0.9 × 0.6 m, f64) dropped over a rod 2 cm thick, \
         its left half pushed into its right one after 2 s, with contacts on its drawn \
         Catmull-Rom surface 1 cm thick: {:.2} ms a frame with self-contact, {:.2} ms without \
         ({:.2}×; the rod's contacts ask for 47 substeps a frame).\n\n",
        line(&costs.lying),
        line(&costs.piled),
        moving(&costs.falling),
        moving(&costs.whipped),
        line(&costs.spiral),
        with * 1e3,
        without * 1e3,
        with / without
    );
    run.section(
        "(g) Contacts",
        &format!(
            "![contacts](contacts.svg)\n\nAn 8-particle rope settled for 6 s on a peg below the middle of a span; \
             the drawn curve is judged on 2048 points by how far it passes below the peg's top (0: it rests \
             on it). Particle contacts let every peg narrower than the spacing through, since no particle \
             ever touches it; contacts on the drawn curve hold it. Frames are f32 medians on this machine.\n\n\
             {table}\nCost per collider (pegs of 0.1× the spacing, each under the rope; the rope's own step \
             is {step_ns:.0} ns): particle contacts add {:.0} ns, curve contacts {:.0} ns a collider.\n\n\
             {per_collider}\n{self_contact}Data: `contacts.csv`.",
            slopes[0], slopes[1]
        ),
    );
}

/// The 16-particle rope of the self-contact scenes, stepped by `I`.
pub type FloorRope<I> = Rope<Vec3<f32>, 16, 16, I>;

/// How much wider along x than 1 cm the helix of each of the five drops of the test
/// `a_rope_dropped_in_a_pile_never_passes_through_itself` starts (m): a pile is chaotic, so
/// its cost is measured on all five.
pub const DROPS: [f32; 5] = [0.0, 1e-7, 1e-4, 2e-4, -1e-4];

/// A 16-particle 3D rope (3 m, 0.6 kg, 1 cm thick) stepped by `method` on a floor, settled
/// `frames` frames after starting from `start` to `end` (a helix 1 cm across, `wider` more
/// along x), with self-contact: the rope, and the floor it lies on.
pub fn floor_rope<I: Integrator>(
    method: I,
    (start, end): (Vec3<f32>, Vec3<f32>),
    wider: f32,
    frames: usize,
) -> (FloorRope<I>, [Collider<Vec3<f32>>; 1]) {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.3,
        ..Settings::default()
    }
    .with_integrator(method);
    let material = Material {
        stiffness: 3000.0,
        damping: 2.0,
    };
    let mut rope = Rope::new(start, end, 0.6, material, settings).expect("a rope");
    for i in 0..16 {
        let a = i as f32 * 0.9;
        let helix = Vec3::new((0.01 + wider) * a.cos(), 0.0, 0.01 * a.sin());
        let p = rope.positions()[i] + helix;
        rope.set_position(i, p).expect("in range");
    }
    let floor = [
        Collider::half_space(Vec3::default(), Vec3::new(0.0, 1.0, 0.0))
            .and_then(|c| c.with_friction(0.5, 0.4))
            .expect("a floor"),
    ];
    let contacts = Contacts::new(&floor, 0.005, Touch::Drawn(Smoothing::CatmullRom))
        .and_then(|c| c.with_self_contact(0.3))
        .expect("contacts");
    for _ in 0..frames {
        let _ = rope
            .step_touching(1.0 / 60.0, (), &contacts)
            .expect("a step");
    }
    (rope, floor)
}

/// A frame's cost (ns): the bare step, with the floor, with the floor and self-contact; and
/// the fastest batches of the first and last.
struct Frame {
    step: f64,
    floor: f64,
    both: f64,
    fastest_step: f64,
    fastest_floor: f64,
    fastest_both: f64,
}

/// What self-contact costs a rope in each state a game meets.
struct SelfContactCosts {
    lying: Frame,
    piled: Frame,
    falling: Frame,
    whipped: Frame,
    spiral: Frame,
}

/// A frame of `ropes` (taken in turn) on `floor`: bare, with the floor's drawn-curve
/// contacts, and with self-contact too, in 5 interleaved rounds.
fn frame_costs<const N: usize>(
    ropes: &[Rope<Vec3<f32>, N>],
    floor: &[Collider<Vec3<f32>>; 1],
    reps: usize,
) -> Frame {
    let touch = Touch::Drawn(Smoothing::CatmullRom);
    let plain = Contacts::new(floor, 0.005, touch).expect("contacts");
    let itself = plain.with_self_contact(0.3).expect("contacts");
    let frame = |contacts: Option<&Contacts<'_, Vec3<f32>>>| {
        let mut turn = 0;
        fastest_and_median_ns(reps, 20 * ropes.len(), || {
            let mut r = ropes[turn % ropes.len()].clone();
            turn += 1;
            let _ = match contacts {
                Some(c) => r.step_touching(1.0 / 60.0, (), c),
                None => r.step(1.0 / 60.0),
            }
            .expect("a step");
            std::hint::black_box(&r);
        })
    };
    // Interleaved rounds: measured one after another, the three would see different
    // minutes of a shared machine. Each kind's fastest batch of all rounds, and the median
    // of the rounds' medians.
    let rounds: Vec<[(f64, f64); 3]> = (0..5)
        .map(|_| [frame(None), frame(Some(&plain)), frame(Some(&itself))])
        .collect();
    let kind = |k: usize| {
        let fastest = rounds.iter().map(|r| r[k].0).fold(f64::INFINITY, f64::min);
        let mut medians: Vec<f64> = rounds.iter().map(|r| r[k].1).collect();
        medians.sort_by(f64::total_cmp);
        (fastest, medians[medians.len() / 2])
    };
    let (step, floor_only, both) = (kind(0), kind(1), kind(2));
    Frame {
        step: step.1,
        floor: floor_only.1,
        both: both.1,
        fastest_step: step.0,
        fastest_floor: floor_only.0,
        fastest_both: both.0,
    }
}

/// The costs of self-contact for the 16-particle rope lying straight, settled in a pile
/// (the five drops of [`DROPS`]), falling into it and whipped by its held end (the means of
/// 600 frames of each of the five against the bare step's means over the same frames), and
/// for a 24-particle rope still in a flat spiral.
fn self_contact_costs(reps: usize) -> SelfContactCosts {
    let straight = (Vec3::new(0.0, 0.005, 0.0), Vec3::new(3.0, 0.005, 0.0));
    let (rope, floor) = floor_rope(SymplecticEuler, straight, 0.0, 120);
    let lying = frame_costs(&[rope], &floor, reps);
    let (start, top) = (Vec3::new(0.0, 0.1, 0.0), Vec3::new(0.12, 3.1, 0.07));
    let piles = DROPS.map(|wider| floor_rope(SymplecticEuler, (start, top), wider, 600).0);
    let piled = frame_costs(&piles, &floor, reps);
    let falling = DROPS.map(|wider| {
        let (rope, floor) = floor_rope(SymplecticEuler, (start, top), wider, 0);
        moving_costs(rope, &floor, |_, _| {})
    });
    // Lying straight, then its held end swung round a tilted circle 0.3 m across twice a
    // second (about 2 m/s), from the floor up to 0.3 m: the rope whips round and over itself.
    let whipped = DROPS.map(|wider| {
        let (rope, floor) = floor_rope(SymplecticEuler, straight, wider, 120);
        moving_costs(rope, &floor, |rope, frame| {
            let a = std::f32::consts::TAU * 2.0 * (frame + 1) as f32 / 60.0;
            let hand = Vec3::new(
                0.15 * a.sin(),
                0.005 + 0.15 * (1.0 - a.cos()),
                0.15 * (1.0 - a.cos()),
            );
            rope.move_pinned(0, hand, 1.0 / 60.0).expect("in range");
        })
    });
    let (rope, floor) = spiral_rope(SymplecticEuler);
    let spiral = frame_costs(&[rope], &floor, reps);
    SelfContactCosts {
        lying,
        piled,
        falling: Frame::mean(&falling),
        whipped: Frame::mean(&whipped),
        spiral,
    }
}

impl Frame {
    /// The mean of the means of several moving ropes' frames.
    fn mean(frames: &[Frame]) -> Frame {
        let mean = |f: fn(&Frame) -> f64| frames.iter().map(f).sum::<f64>() / frames.len() as f64;
        Frame {
            step: mean(|f| f.step),
            floor: f64::NAN,
            both: mean(|f| f.both),
            fastest_step: f64::NAN,
            fastest_floor: f64::NAN,
            fastest_both: f64::NAN,
        }
    }
}

/// 600 frames of `rope` on `floor` with drawn-curve contacts and self-contact, `drive` moving
/// it before each (the frame's number), each timed against the bare step of the same state:
/// the means of both (the frames differ, so only their means compare).
fn moving_costs(
    mut rope: Rope<Vec3<f32>, 16>,
    floor: &[Collider<Vec3<f32>>; 1],
    drive: impl Fn(&mut Rope<Vec3<f32>, 16>, usize),
) -> Frame {
    let contacts = Contacts::new(floor, 0.005, Touch::Drawn(Smoothing::CatmullRom))
        .and_then(|c| c.with_self_contact(0.3))
        .expect("contacts");
    let (mut bare, mut touching) = (Vec::new(), Vec::new());
    for frame in 0..600 {
        drive(&mut rope, frame);
        let t = std::time::Instant::now();
        let mut free = rope.clone();
        let _ = free.step(1.0 / 60.0).expect("a step");
        bare.push(t.elapsed().as_nanos() as f64);
        std::hint::black_box(&free);
        let t = std::time::Instant::now();
        let _ = rope
            .step_touching(1.0 / 60.0, (), &contacts)
            .expect("a step");
        touching.push(t.elapsed().as_nanos() as f64);
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    Frame {
        step: mean(&bare),
        floor: f64::NAN,
        both: mean(&touching),
        fastest_step: f64::NAN,
        fastest_floor: f64::NAN,
        fastest_both: f64::NAN,
    }
}

/// The spiral's rope: 24 particles in 3D.
pub type SpiralRope<I> = Rope<Vec3<f32>, 24, 24, I>;

/// A 24-particle 3D rope (4.6 m, 0.9 kg, 1 cm thick) stepped by `method`, laid in a flat
/// spiral on a floor (its turns 6 cm apart), settled for 2 s with self-contact.
pub fn spiral_rope<I: Integrator>(method: I) -> (SpiralRope<I>, [Collider<Vec3<f32>>; 1]) {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.3,
        ..Settings::default()
    }
    .with_integrator(method);
    let material = Material {
        stiffness: 3000.0,
        damping: 2.0,
    };
    // r = a + b θ, the particles 0.2 m apart along it.
    let (a, b, spacing) = (0.15f32, 0.06 / core::f32::consts::TAU, 0.2f32);
    let mut points = [Vec3::default(); 24];
    let mut theta = 0.0f32;
    for p in &mut points {
        let r = a + b * theta;
        *p = Vec3::new(r * theta.cos(), 0.005, r * theta.sin());
        theta += spacing / r;
    }
    let length = points
        .windows(2)
        .map(|w| (w[1] - w[0]).length())
        .sum::<f32>();
    let mut rope: SpiralRope<I> = Rope::new(
        Vec3::new(0.0, 0.005, 0.0),
        Vec3::new(length, 0.005, 0.0),
        0.9,
        material,
        settings,
    )
    .expect("a rope");
    for (i, &p) in points.iter().enumerate() {
        rope.set_position(i, p).expect("in range");
    }
    let floor = [
        Collider::half_space(Vec3::default(), Vec3::new(0.0, 1.0, 0.0))
            .and_then(|c| c.with_friction(0.5, 0.4))
            .expect("a floor"),
    ];
    let contacts = Contacts::new(&floor, 0.005, Touch::Drawn(Smoothing::CatmullRom))
        .and_then(|c| c.with_self_contact(0.3))
        .expect("contacts");
    for _ in 0..120 {
        let _ = rope
            .step_touching(1.0 / 60.0, (), &contacts)
            .expect("a step");
    }
    (rope, floor)
}

/// What a ball out of reach (80 m off, flying away at 30 m/s) adds to an 8-particle rope's
/// frame, as a share of its bare step, and the substeps that frame takes with it and without.
fn far_collider_cost(reps: usize) -> (f64, (u16, u16)) {
    let rope: Rope<Vec2<f32>, 8> = draped_rope(&[], Touch::Particles, SETTLE_FRAMES);
    let ball = [Collider::ball(Vec2::new(80.0, 0.0), 0.1)
        .and_then(|c| c.moving(Vec2::new(30.0, 0.0)))
        .expect("a ball")];
    let contacts = Contacts::new(&ball, 0.02, Touch::Drawn(Smoothing::BSpline)).expect("contacts");
    let substeps = (
        rope.clone()
            .step_touching(1.0 / 60.0, (), &contacts)
            .expect("a step")
            .substeps,
        rope.clone().step(1.0 / 60.0).expect("a step").substeps,
    );
    let time =
        |touching: bool| median_ns(reps, 50, || frame_of(&rope, touching.then_some(&contacts)));
    // Interleaved rounds, the least of each: the difference (about 5% of an 8-particle
    // step, 150 instructions) is small beside the noise.
    let (mut bare, mut with) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..15 {
        bare = bare.min(time(false));
        with = with.min(time(true));
    }
    ((with - bare).max(0.0) / bare, substeps)
}

/// The touches of the per-collider table and of the 4-peg target: at the particles, and on
/// the drawn B-spline.
const TOUCHES: [Touch; 2] = [Touch::Particles, Touch::Drawn(Smoothing::BSpline)];

/// The frames of the 4-peg target, each as (fastest, median) ns: the bare step, and for each
/// of [`TOUCHES`] the rope's frame with no collider and with `pegs`.
struct FourPegs {
    step: (f64, f64),
    without: [(f64, f64); 2],
    with: [(f64, f64); 2],
}

/// [`FourPegs`] from interleaved rounds (the bare step, then each touch with no collider and
/// with `pegs`), each round the median of `reps` batches: the least and the median of the
/// rounds' figures. Measured one after another, the frames compared would see different
/// minutes of a shared machine.
fn four_pegs_cost(pegs: &[Collider<Vec2<f32>>], reps: usize) -> FourPegs {
    let bare: Rope<Vec2<f32>, 8> = draped_rope(&[], Touch::Particles, SETTLE_FRAMES);
    let scenes = TOUCHES.map(|touch| {
        let without: Rope<Vec2<f32>, 8> = draped_rope(&[], touch, SETTLE_FRAMES);
        let with: Rope<Vec2<f32>, 8> = draped_rope(pegs, touch, SETTLE_FRAMES);
        (touch, without, with)
    });
    let none: [Collider<Vec2<f32>>; 0] = [];
    let mut rounds: Vec<[f64; 5]> = Vec::new();
    for _ in 0..7 {
        let mut round = [
            median_ns(reps, 20, || frame_of(&bare, None)),
            0.0,
            0.0,
            0.0,
            0.0,
        ];
        for (m, (touch, without, with)) in scenes.iter().enumerate() {
            let nothing = Contacts::new(&none, 0.0, *touch).expect("contacts");
            let touching = Contacts::new(pegs, 0.0, *touch).expect("contacts");
            round[1 + 2 * m] = median_ns(reps, 20, || frame_of(without, Some(&nothing)));
            round[2 + 2 * m] = median_ns(reps, 20, || frame_of(with, Some(&touching)));
        }
        rounds.push(round);
    }
    let figure = |k: usize| {
        let mut t: Vec<f64> = rounds.iter().map(|r| r[k]).collect();
        t.sort_by(f64::total_cmp);
        (t[0], t[t.len() / 2])
    };
    FourPegs {
        step: figure(0),
        without: [figure(1), figure(3)],
        with: [figure(2), figure(4)],
    }
}

/// What the player's rope wrapping its box measured: the deepest a drawn point went into
/// the box over the thickness, the largest link stretch, the frames flagged unconverged and
/// ending against the box (within 1 mm of the thickness), and the frame's cost over the same rope's without the box (fastest, median).
struct Wrap {
    deepest: f64,
    stretch: f64,
    flagged: usize,
    touching: usize,
    ratio: (f64, f64),
}

/// The scene of `examples/mcu_wrap.rs` in f32 (`tests/common`'s `rope_round_a_box`, a
/// `load` in kg on springs of `stiffness` N/m), stepped 600 frames at 60 Hz by `solver`. The
/// player's rope: `DirectChain` at one solve of up to 2 iterations, 70 kg on 2 000 N/m.
fn round_a_box<I: Integrator>(solver: I, (stiffness, load): (f64, f64), reps: usize) -> Wrap {
    let (mut rope, block) =
        crate::common::rope_round_a_box::<f32, I>(solver, stiffness, load).expect("the scene");
    let block = [block];
    let thickness = 0.05;
    let contacts =
        Contacts::new(&block, thickness, Touch::Drawn(Smoothing::CatmullRom)).expect("contacts");
    let run = |rope: &crate::common::BoxRope<f32, I>, touching: bool| {
        let mut rope = rope.clone();
        for _ in 0..600 {
            let info = match touching {
                true => rope.step_touching(1.0 / 60.0, (), &contacts),
                false => rope.step(1.0 / 60.0),
            };
            let _ = std::hint::black_box(info.expect("a step"));
        }
    };
    let with = fastest_and_median_ns(reps, 1, || run(&rope, true));
    let bare = fastest_and_median_ns(reps, 1, || run(&rope, false));
    let mut wrap = Wrap {
        deepest: 0.0,
        stretch: 0.0,
        flagged: 0,
        touching: 0,
        ratio: (with.0 / bare.0, with.1 / bare.1),
    };
    let mut curve = [Vec2::new(0.0f32, 0.0); 64];
    for _ in 0..600 {
        let info = rope
            .step_touching(1.0 / 60.0, (), &contacts)
            .expect("a step");
        let n = rope
            .sample(Smoothing::CatmullRom, &mut curve)
            .expect("a curve");
        let depth = curve[..n].iter().map(|&p| -f64::from(block[0].gap(p)));
        let depth = depth.fold(f64::MIN, f64::max);
        let links = rope.positions().windows(2);
        let stretch =
            links.map(|w| (f64::from((w[1] - w[0]).length()) / (10.0 / 11.0) - 1.0).abs());
        wrap.deepest = wrap.deepest.max(depth / thickness as f64);
        wrap.stretch = wrap.stretch.max(stretch.fold(0.0, f64::max));
        wrap.flagged += usize::from(!info.converged);
        wrap.touching += usize::from(depth > -(thickness as f64) - 1e-3);
    }
    wrap
}
