//! (l) What contacts cost, swept: a frame with contacts against the same frame without, for
//! every integrator, across the number of colliders (near the rope and out of its reach),
//! across the rope's length, and for self-contact in a pile.

use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::integrator::{AnyIntegrator, DirectChain, DirectSprings, ImplicitEuler, Xpbd};
use dunas::prelude::*;

use crate::contacts::{floor_rope, frame_of, spiral_rope};
use crate::report::{Run, Series, chart, csv, fastest_and_median_ns};

/// Every integrator, at its defaults, named as in the tables.
fn methods() -> [(&'static str, AnyIntegrator); 8] {
    [
        ("explicit Euler", AnyIntegrator::ExplicitEuler),
        ("symplectic Euler", AnyIntegrator::SymplecticEuler),
        ("Verlet", AnyIntegrator::Verlet),
        ("RK4", AnyIntegrator::Rk4),
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
            "DirectSprings",
            AnyIntegrator::DirectSprings(DirectSprings::default()),
        ),
    ]
}

/// The contacts scene with `method`: an `N`-particle rope 7 m long (1 kg), its ends held 6 m
/// apart, settled for 6 s without contacts (it sags about 1.5 m).
fn draped<const N: usize>(method: AnyIntegrator) -> Rope<Vec2<f32>, N, N, AnyIntegrator> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.8),
        damping: 2.0,
        ..Settings::default()
    }
    .with_integrator(method);
    let material = Material {
        stiffness: 3000.0,
        damping: 2.0,
    };
    let mut rope = Rope::new(
        Vec2::new(-3.5, 0.0),
        Vec2::new(3.5, 0.0),
        1.0,
        material,
        settings,
    )
    .expect("a rope");
    rope.set_inv_mass(N - 1, 0.0).expect("a particle");
    rope.set_position(0, Vec2::new(-3.0, 0.0))
        .expect("in range");
    rope.set_position(N - 1, Vec2::new(3.0, 0.0))
        .expect("in range");
    for _ in 0..360 {
        let _ = rope.step(1.0 / 60.0).expect("a step");
    }
    rope
}

/// `count` pegs a tenth of an 8-particle rope's spacing thick, spread under the draped rope
/// where it sags onto them (`far`: the same, 100 m to the side).
fn pegs(count: usize, far: bool) -> Vec<Collider<Vec2<f32>>> {
    let shift = if far { 100.0 } else { 0.0 };
    (0..count)
        .map(|i| {
            let x = -2.5 + 5.0 * (i as f32 + 0.5) / count as f32;
            Collider::ball(Vec2::new(x + shift, -1.2), 0.1 * 6.0 / 7.0).expect("a peg")
        })
        .collect()
}

/// A frame of `rope` with `colliders` (touched as `touch`, 2 cm thick) against the bare
/// frame, after 2 s of settling on them: (with contacts / bare, fastest batches; the same,
/// medians).
fn frame_ratio<const N: usize>(
    rope: &Rope<Vec2<f32>, N, N, AnyIntegrator>,
    colliders: &[Collider<Vec2<f32>>],
    touch: Touch,
    reps: usize,
) -> (f64, f64) {
    let contacts = Contacts::new(colliders, 0.02, touch).expect("contacts");
    let mut rope = rope.clone();
    for _ in 0..120 {
        let _ = rope
            .step_touching(1.0 / 60.0, (), &contacts)
            .expect("a step");
    }
    over_bare(&rope, &contacts, reps)
}

/// `rope`'s frame with `contacts` against its bare frame: in the fastest batches, and the
/// medians.
fn over_bare<P: dunas::Point, const N: usize>(
    rope: &Rope<P, N, N, AnyIntegrator>,
    contacts: &Contacts<'_, P>,
    reps: usize,
) -> (f64, f64) {
    let time = |with| fastest_and_median_ns(reps, 10, || frame_of(rope, with));
    let (bare, touching) = (time(None), time(Some(contacts)));
    (touching.0 / bare.0, touching.1 / bare.1)
}

/// Self-contact for `method`: a 16-particle 3D rope (3 m, 1 cm thick) dropped end first onto a
/// floor, 10 s: the mean frame with the floor and self-contact against the bare frame of the
/// same states, while it falls (its first 2 s) and settled (its last 2 s).
fn pile(method: AnyIntegrator) -> (f64, f64) {
    let (bottom, top) = (Vec3::new(0.0, 0.1, 0.0), Vec3::new(0.12, 3.1, 0.07));
    let (mut rope, floor) = floor_rope(method, (bottom, top), 0.0, 0);
    let contacts = Contacts::new(&floor, 0.005, Touch::Drawn(Smoothing::CatmullRom))
        .and_then(|c| c.with_self_contact(0.3))
        .expect("contacts");
    let (mut bare, mut touching) = ([0.0f64; 2], [0.0f64; 2]);
    for frame in 0..600 {
        let t = std::time::Instant::now();
        let mut free = rope.clone();
        let _ = free.step(1.0 / 60.0);
        let b = t.elapsed().as_nanos() as f64;
        std::hint::black_box(&free);
        let t = std::time::Instant::now();
        let _ = rope
            .step_touching(1.0 / 60.0, (), &contacts)
            .expect("a step");
        let c = t.elapsed().as_nanos() as f64;
        let part = match frame {
            0..120 => 0,
            480.. => 1,
            _ => continue,
        };
        (bare[part], touching[part]) = (bare[part] + b, touching[part] + c);
    }
    (touching[0] / bare[0], touching[1] / bare[1])
}

/// A rope at rest on `floor` (a 3D rope of section (g): lying straight, or still in a
/// spiral): its frame with the floor's drawn Catmull-Rom contacts and self-contact against
/// its bare frame (fastest batches, medians).
fn still<const N: usize>(
    rope: &Rope<Vec3<f32>, N, N, AnyIntegrator>,
    floor: &[Collider<Vec3<f32>>],
    reps: usize,
) -> (f64, f64) {
    let contacts = Contacts::new(floor, 0.005, Touch::Drawn(Smoothing::CatmullRom))
        .and_then(|c| c.with_self_contact(0.3))
        .expect("contacts");
    over_bare(rope, &contacts, reps)
}

/// One length of the sweep: 4 near pegs on an `N`-particle rope, at the particles and on
/// the drawn B-spline.
fn length_row<const N: usize>(method: AnyIntegrator, reps: usize) -> [(f64, f64); 2] {
    let rope = draped::<N>(method);
    let pegs = pegs(4, false);
    [
        frame_ratio(&rope, &pegs, Touch::Particles, reps),
        frame_ratio(&rope, &pegs, Touch::Drawn(Smoothing::BSpline), reps),
    ]
}

pub fn run(run: &mut Run) {
    let reps = run.reps();
    let counts: &[usize] = if run.quick {
        &[1, 64]
    } else {
        &[1, 2, 4, 8, 16, 32, 64]
    };
    let lengths: &[usize] = if run.quick {
        &[8, 64]
    } else {
        &[8, 16, 32, 64]
    };
    let methods = methods();
    let methods = if run.quick {
        &methods[1..2]
    } else {
        &methods[..]
    };
    let touches = [
        ("particles", Touch::Particles),
        ("drawn B-spline", Touch::Drawn(Smoothing::BSpline)),
    ];
    let mut rows = Vec::new();
    let mut by_count = Vec::new();
    let mut by_length = Vec::new();
    let mut table = String::from(
        "| integrator | contacts | colliders | near (× bare frame) | far (× bare frame) |\n|---|---|---|---|---|\n",
    );
    for (name, method) in methods {
        let rope = draped::<8>(*method);
        for (touch_name, touch) in touches {
            let mut near_points = Vec::new();
            for &count in counts {
                let near = frame_ratio(&rope, &pegs(count, false), touch, reps);
                let far = frame_ratio(&rope, &pegs(count, true), touch, reps);
                near_points.push((count as f64, near.0));
                table.push_str(&format!(
                    "| {name} | {touch_name} | {count} | {:.2} ({:.2}) | {:.2} ({:.2}) |\n",
                    near.0, near.1, far.0, far.1
                ));
                for (place, r) in [("near", near), ("far", far)] {
                    rows.push(vec![
                        (*name).into(),
                        touch_name.into(),
                        "8".into(),
                        format!("{count}"),
                        place.into(),
                        format!("{:.4}", r.0),
                        format!("{:.4}", r.1),
                    ]);
                }
            }
            if touch == Touch::Drawn(Smoothing::BSpline) {
                by_count.push(Series::line(*name, near_points));
            }
        }
    }
    let mut lengths_table = String::from(
        "| integrator | particles | 4 near pegs at the particles (× bare frame) | on the drawn B-spline |\n|---|---|---|---|\n",
    );
    for (name, method) in methods {
        let mut points = Vec::new();
        for &n in lengths {
            let row = match n {
                8 => length_row::<8>(*method, reps),
                16 => length_row::<16>(*method, reps),
                32 => length_row::<32>(*method, reps),
                _ => length_row::<64>(*method, reps),
            };
            points.push((n as f64, row[1].0));
            lengths_table.push_str(&format!(
                "| {name} | {n} | {:.2} ({:.2}) | {:.2} ({:.2}) |\n",
                row[0].0, row[0].1, row[1].0, row[1].1
            ));
            for ((touch_name, _), r) in touches.iter().zip(row) {
                rows.push(vec![
                    (*name).into(),
                    (*touch_name).into(),
                    format!("{n}"),
                    "4".into(),
                    "near".into(),
                    format!("{:.4}", r.0),
                    format!("{:.4}", r.1),
                ]);
            }
        }
        by_length.push(Series::line(*name, points));
    }
    let mut piles = String::from(
        "| integrator | lying straight (× bare frame) | still in a spiral (24 particles) | \
         falling into the pile | settled in it |\n|---|---|---|---|---|\n",
    );
    let straight = (Vec3::new(0.0, 0.005, 0.0), Vec3::new(3.0, 0.005, 0.0));
    for (name, method) in methods {
        let (rope, floor) = floor_rope(*method, straight, 0.0, 120);
        let lying = still(&rope, &floor, reps);
        let (rope, floor) = spiral_rope(*method);
        let spiral = still(&rope, &floor, reps);
        let (falling, settled) = pile(*method);
        piles.push_str(&format!(
            "| {name} | {:.1} ({:.1}) | {:.1} ({:.1}) | {falling:.0} | {settled:.0} |\n",
            lying.0, lying.1, spiral.0, spiral.1
        ));
        for (state, particles, r) in [
            ("lying straight", "16", lying),
            ("spiral, still", "24", spiral),
            ("pile, falling", "16", (falling, falling)),
            ("pile, settled", "16", (settled, settled)),
        ] {
            rows.push(vec![
                (*name).into(),
                "drawn Catmull-Rom, self-contact".into(),
                particles.into(),
                "1".into(),
                state.into(),
                format!("{:.4}", r.0),
                format!("{:.4}", r.1),
            ]);
        }
    }
    chart(
        &run.path("contact_costs.svg"),
        "An 8-particle rope resting on pegs, contacts on the drawn B-spline: its frame against \
         the bare frame, by the number of pegs",
        "pegs under the rope",
        "frame with contacts / bare frame (fastest batches)",
        &by_count,
        true,
    );
    chart(
        &run.path("contact_lengths.svg"),
        "A rope resting on 4 pegs, contacts on the drawn B-spline: its frame against the bare \
         frame, by the rope's particles",
        "particles",
        "frame with contacts / bare frame (fastest batches)",
        &by_length,
        true,
    );
    csv(
        &run.path("contact_costs.csv"),
        &[
            "integrator",
            "contacts",
            "particles",
            "colliders",
            "state",
            "ratio_fastest",
            "ratio_median",
        ],
        &rows,
    );
    run.section(
        "(l) What contacts cost, swept",
        &format!(
            "![contact costs](contact_costs.svg)\n\n![contact lengths](contact_lengths.svg)\n\n\
             Every integrator at its defaults on the contacts scene (a 7 m rope, 1 kg, its ends \
             held 6 m apart, stiffness 3000 N/m, 2 cm thick): a frame with contacts against the \
             bare frame of the same state (fastest batches, medians in brackets; the two frames \
             take the substeps their own steps plan, so a ratio under 1 is a contact that held \
             the rope still). Pegs 0.086 m thick are spread under the rope where it sags onto \
             them (near), or the same 100 m to the side (far: out of reach, no contact is \
             tested). Chart: `contact_costs.svg` (by pegs), `contact_lengths.svg` (by \
             particles); every figure in `contact_costs.csv`.\n\n### By the number of \
             colliders (8 particles)\n\n{table}\n### By the rope's length (4 near pegs)\n\n\
             {lengths_table}\n### Self-contact, at rest and in a pile\n\nThe ropes of \
             section (g) on a floor, with drawn Catmull-Rom contacts and self-contact: the \
             16-particle 3D rope lying straight and the 24-particle one still in a flat spiral \
             (a frame against the bare frame of the same state, fastest batches, medians in \
             brackets), and the 16-particle one dropped end first into a pile (the mean frame \
             against the mean bare frame of the same states, over its first 2 s, falling, and \
             its last 2 s, settled).\n\n{piles}"
        ),
    );
}
