//! Section (k): sleep. A scene of 100 objects at rest (ropes lying on a floor, sails in a
//! light breeze) and 100 ropes hanging in still air, each stepped asleep against the same
//! objects awake; a woken rope's first frame against an awake one's; and how far a rope
//! that sleeps ends from the same rope kept awake.

use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::force::{SailWind, Wind};
use dunas::integrator::DirectSprings;
use dunas::prelude::*;
use dunas::shape::Shape;
use dunas::spring::Topology;
use dunas::{MassSpring, Point};
use std::ops::DerefMut;

use crate::report::{Run, fastest_and_median_ns, num};

type Sail = Cloth<Vec3<f32>, 8, 8, DirectSprings>;

/// 50 ropes (8 particles, 7 m, 1 kg, symplectic Euler) lying on a floor with contacts on the
/// drawn curve, and 50 sails (8×8, 3 m by 4 m, `DirectSprings` at its defaults) on a mast and
/// a boom in a 3 m/s breeze; all damped at 2/s, sleep at its defaults.
#[derive(Clone)]
struct Scene {
    ropes: Vec<Rope<Vec2<f32>, 8>>,
    sails: Vec<Sail>,
}

const MATERIAL: Material<f32> = Material {
    stiffness: 400.0,
    damping: 1.0,
};

fn rope(from: Vec2<f32>, to: Vec2<f32>) -> Rope<Vec2<f32>, 8> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        damping: 2.0,
        ..Settings::default()
    };
    let mut r = Rope::new(from, to, 1.0, MATERIAL, settings).expect("a valid rope");
    r.set_sleep(Some(Sleep::default()))
        .expect("the default sleep");
    r
}

fn scene() -> Scene {
    let sail_settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 2.0,
        ..Settings::default()
    }
    .with_integrator(DirectSprings::default());
    let sailcloth = Material {
        stiffness: 2000.0,
        damping: 1.0,
    };
    let sail = || {
        let (top, right, down) = (
            Vec3::new(0.0, 4.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(0.0, -4.0, 0.0),
        );
        let mut s: Sail = Cloth::rectangle(top, right, down, 0.5, [sailcloth; 3], sail_settings)
            .expect("a valid sail");
        s.pin_column(0).expect("the mast");
        s.pin_row(7).expect("the boom");
        s.set_sleep(Some(Sleep::default()))
            .expect("the default sleep");
        s
    };
    Scene {
        ropes: (0..50)
            .map(|i| {
                let x = 10.0 * i as f32;
                rope(Vec2::new(x, 0.2), Vec2::new(x + 7.0, 0.2))
            })
            .collect(),
        sails: (0..50).map(|_| sail()).collect(),
    }
}

/// Steps every object of `scene` a 60 Hz frame; how many slept through it.
fn frame(scene: &mut Scene, contacts: &Contacts<'_, Vec2<f32>>, wind: &SailWind<f32>) -> usize {
    let mut asleep = 0;
    for r in &mut scene.ropes {
        let info = r
            .step_touching(1.0 / 60.0, (), contacts)
            .expect("a rope step");
        asleep += usize::from(info.asleep);
    }
    for s in &mut scene.sails {
        let info = s
            .step_with(1.0 / 60.0, &mut wind.clone())
            .expect("a sail step");
        asleep += usize::from(info.asleep);
    }
    asleep
}

/// Steps every rope a 60 Hz frame; how many slept through it.
fn hanging_frame(ropes: &mut [Rope<Vec2<f32>, 8>]) -> usize {
    let steps = ropes
        .iter_mut()
        .map(|r| r.step(1.0 / 60.0).expect("a rope step"));
    steps.filter(|info| info.asleep).count()
}

/// The same objects with sleep off.
fn awake<O, P, Sh, T, I>(objects: &mut [O])
where
    O: DerefMut<Target = MassSpring<P, Sh, T, I>>,
    P: Point,
    Sh: Shape,
    T: Topology<P::Scalar>,
    I: Integrator,
{
    for o in objects {
        o.set_sleep(None).expect("sleep off");
    }
}

/// Rounds of asleep frames, then of awake ones: the fastest and the median of each.
fn compare(run: &Run, mut asleep: impl FnMut(), mut awake: impl FnMut()) -> [(f64, f64); 2] {
    let inner = if run.quick { 20 } else { 100 };
    let a = fastest_and_median_ns(run.reps(), inner, &mut asleep);
    let b = fastest_and_median_ns(run.reps(), inner / 10, &mut awake);
    [a, b]
}

pub fn run(run: &mut Run) {
    let floor = [Collider::half_space(Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0)).expect("a floor")];
    let contacts =
        Contacts::new(&floor, 0.02, Touch::Drawn(Smoothing::CatmullRom)).expect("contacts");
    let mut air = Wind::still(0.0);
    air.velocity = Vec3::new(0.0, 0.0, 3.0);
    let wind = SailWind::new(air, 0.7).expect("a breeze");

    let mut sleeping = scene();
    let settled = (1..=6000).find(|_| frame(&mut sleeping, &contacts, &wind) == 100);
    let mut kept_awake = sleeping.clone();
    awake(&mut kept_awake.ropes);
    awake(&mut kept_awake.sails);
    let [scene_asleep, scene_awake] = compare(
        run,
        || {
            frame(&mut sleeping, &contacts, &wind);
        },
        || {
            frame(&mut kept_awake, &contacts, &wind);
        },
    );

    let mut hanging: Vec<_> = (0..100)
        .map(|_| rope(Vec2::new(0.0, 0.0), Vec2::new(3.0, -6.0)))
        .collect();
    let hung = (1..=3000).find(|_| hanging_frame(&mut hanging) == 100);
    let mut hanging_awake = hanging.clone();
    awake(&mut hanging_awake);
    let [ropes_asleep, ropes_awake] = compare(
        run,
        || {
            hanging_frame(&mut hanging);
        },
        || {
            hanging_frame(&mut hanging_awake);
        },
    );

    // A woken rope's first frame (on the floor, contacts on the drawn curve), against a
    // frame of the same rope awake: each round starts from the rope asleep.
    let (asleep_rope, awake_rope) = (sleeping.ropes[0].clone(), kept_awake.ropes[0].clone());
    let mut r = asleep_rope.clone();
    let woken = fastest_and_median_ns(run.reps(), 1, || {
        r.clone_from(&asleep_rope);
        r.wake();
        let _ = r.step_touching(1.0 / 60.0, (), &contacts);
    });
    let mut r = awake_rope.clone();
    let plain = fastest_and_median_ns(run.reps(), 1, || {
        r.clone_from(&awake_rope);
        let _ = r.step_touching(1.0 / 60.0, (), &contacts);
    });

    // How far a rope that sleeps ends from the same rope awake: 30 s hanging, a hand
    // moving its top 0.3 m at 15 s, against the docs' bound `2 · speed / damping`.
    let mut pair = vec![rope(Vec2::new(0.0, 0.0), Vec2::new(3.0, -6.0)); 2];
    awake(&mut pair[1..]);
    let (mut apart, mut slept) = (0.0f32, 0);
    for frame in 0..1800 {
        if frame == 900 {
            for r in &mut pair {
                r.move_pinned(0, Vec2::new(0.3, 0.0), 1.0 / 60.0)
                    .expect("the hand");
            }
        }
        slept += hanging_frame(&mut pair[..1]);
        hanging_frame(&mut pair[1..]);
        let (a, b) = (pair[0].positions(), pair[1].positions());
        let far = a.iter().zip(b).map(|(p, q)| (*p - *q).length());
        apart = far.fold(apart, f32::max);
    }
    let bound = 2.0 * Sleep::<f32>::default().speed / 2.0;

    let share = |asleep: (f64, f64), awake: (f64, f64)| (asleep.0 / awake.0, asleep.1 / awake.1);
    let (scene_share, ropes_share) = (
        share(scene_asleep, scene_awake),
        share(ropes_asleep, ropes_awake),
    );
    let first = (woken.0 / plain.0, woken.1 / plain.1);
    let frames = |n: Option<usize>| n.map_or("never".to_string(), |n| format!("{n} frames"));
    run.section(
        "(k) Sleep: objects at rest",
        &format!(
            "Host f32, objects damped at 2/s with `Sleep::default()` (asleep after 30 frames slower than \
             1 cm/s). The scene: 50 ropes (8 particles, 7 m, symplectic Euler) lying on a floor with contacts \
             on the drawn curve, and 50 sails (8×8, `DirectSprings`) on a mast and a boom in a 3 m/s breeze; \
             all asleep after {}. 100 ropes hanging in still air: asleep after {}. Each frame of the \
             objects asleep is timed against the same objects with sleep off (at rest, a frame leaves them \
             as they were, so both are stepped in place), in repeated rounds; fastest round, median in \
             brackets.\n\n\
             | what | asleep (ns a frame) | awake (ns a frame) | asleep / awake |\n|---|---|---|---|\n\
             | the scene of 100 | {} ({}) | {} ({}) | {:.2}% ({:.2}%) |\n\
             | 100 hanging ropes | {} ({}) | {} ({}) | {:.2}% ({:.2}%) |\n\n\
             A woken rope's first frame (on the floor, woken by `wake()`) takes {} ns ({}), {:.2}× ({:.2}×) \
             an awake frame's {} ns ({}). A hanging rope that sleeps (asleep {slept} of 1 800 frames; a hand \
             moves its top at frame 900) stays within {} m of the same rope awake; the docs' bound is \
             `2 · speed / damping` = {} m.",
            frames(settled),
            frames(hung),
            num(scene_asleep.0),
            num(scene_asleep.1),
            num(scene_awake.0),
            num(scene_awake.1),
            100.0 * scene_share.0,
            100.0 * scene_share.1,
            num(ropes_asleep.0),
            num(ropes_asleep.1),
            num(ropes_awake.0),
            num(ropes_awake.1),
            100.0 * ropes_share.0,
            100.0 * ropes_share.1,
            num(woken.0),
            num(woken.1),
            first.0,
            first.1,
            num(plain.0),
            num(plain.1),
            num(f64::from(apart)),
            num(f64::from(bound)),
        ),
    );
    run.target(
        "Sleep: 100 objects at rest (ropes on a floor, sails in a breeze) asleep ≤ 2% of their awake frame",
        format!("{:.2}% ({:.2}% median)", 100.0 * scene_share.0, 100.0 * scene_share.1),
        settled.is_some() && scene_share.0 <= 0.02,
        "the scene never fell asleep, or the asleep frame's checks cost more",
    );
    run.target(
        "Sleep: 100 ropes hanging in still air asleep ≤ 2% of their awake frame",
        format!(
            "{:.2}% ({:.2}% median)",
            100.0 * ropes_share.0,
            100.0 * ropes_share.1
        ),
        hung.is_some() && ropes_share.0 <= 0.02,
        "the ropes never fell asleep, or the asleep frame's checks cost more",
    );
    run.target(
        "Sleep: a woken rope's first frame ≤ 1.5× a frame awake",
        format!("{:.2}× ({:.2}× median)", first.0, first.1),
        first.0 <= 1.5,
        "timing noise on the shared machine",
    );
    run.target(
        "Sleep: a rope that sleeps within `2 · speed / damping` of the same rope awake",
        format!(
            "{} m against {} m",
            num(f64::from(apart)),
            num(f64::from(bound))
        ),
        apart <= bound,
        "",
    );
}
