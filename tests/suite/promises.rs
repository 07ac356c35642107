//! A step keeps its promise or says so: `DirectChain`'s links within their documented
//! stretch, or the step flagged (`StepInfo::converged`) or refused with the state kept; the
//! stretch a step reports is the one a game measures; an inextensible chain stores no
//! energy in its links.

#[cfg(feature = "fixed")]
use crate::common;
use dunas::Q16;
use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::integrator::{DirectChain, DirectSprings, Integrator};
use dunas::prelude::*;
use dunas::system::{MAX_STRETCH, StepInfo};
use dunas::{Error, Point};

/// The stretch `DirectChain`'s docs promise for its links (0.1%), and the drawn curve's
/// (0.5%): a link measured past the first on a step that reports convergence fails.
const LINKS: f64 = 1e-3;

/// The largest `|length − rest| / rest` of the links of a rope whose links are `rest` long.
fn stretch_of<P: Point>(x: &[P], rest: f64) -> f64 {
    x.windows(2)
        .map(|w| ((w[1] - w[0]).length().to_f64() / rest - 1.0).abs())
        .fold(0.0, f64::max)
}

/// What a step returned, checked against what its docs promise: `Ok` with the stretch it
/// reports equal to the one measured (to `slack`, and to within the stretch's own square:
/// the largest link is picked from the squared lengths), the links within
/// [`LINKS`] of their length unless the step says it did not converge, and never beyond
/// [`MAX_STRETCH`]; or `Err(Diverged)` with the positions as they were.
fn check<P: Point>(
    step: Result<StepInfo<P::Scalar>, Error>,
    before: &[P],
    after: &[P],
    rest: f64,
    slack: f64,
) -> bool {
    let measured = stretch_of(after, rest);
    match step {
        Ok(info) => {
            let reported = info.stretch.to_f64();
            assert!(
                (reported - measured).abs() <= slack + measured * measured,
                "reported {reported}, measured {measured}"
            );
            let (n, d) = MAX_STRETCH;
            assert!(
                measured <= f64::from(n) / f64::from(d) + slack,
                "{measured}"
            );
            assert!(
                !info.converged || measured <= LINKS + slack,
                "a converged step left a link {measured} off"
            );
            info.converged
        }
        Err(e) => {
            assert_eq!(e, Error::Diverged);
            assert_eq!(before, after, "a refused step changed the rope");
            false
        }
    }
}

/// The device catapult's setting: one solve of up to two iterations a frame.
fn device_chain() -> DirectChain {
    DirectChain {
        iterations: 2,
        substeps: 1,
        ..DirectChain::default()
    }
}

/// A 10 m, 2 kg rope of 12 particles (2 000 N/m, `DirectChain::default()`) with a 70 kg
/// player on its end, let go level.
fn player_rope(chain: DirectChain) -> Rope<Vec2<f64>, 12, 12, DirectChain> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        ..Settings::default()
    }
    .with_integrator(chain);
    let material = Material {
        stiffness: 2000.0,
        damping: 0.0,
    };
    let (start, end) = (Vec2::new(0.0, 0.0), Vec2::new(10.0, 0.0));
    let mut rope = Rope::new(start, end, 2.0, material, settings).unwrap();
    rope.hang(11, 70.0).unwrap();
    rope
}

/// One step of 1 s, and one of 10 s, under the player: the links held within their
/// stretch, or the step refused with the rope as it was. (They used to come back `Ok` with
/// the rope 21.65 m and 3 171 m long.)
#[test]
fn a_long_step_holds_the_links_or_is_refused() {
    for dt in [1.0, 10.0] {
        let mut rope = player_rope(DirectChain::default());
        let before = rope.positions().to_vec();
        let step = rope.step(dt);
        eprintln!("{dt} s: {step:?}");
        check(step, &before, rope.positions(), 10.0 / 11.0, 1e-9);
    }
}

/// The device catapult's setting (one solve of two iterations a frame) under the player,
/// and the defaults under a bob 1 000 times the rope's mass (a 1 m, 0.05 kg rope of 10
/// particles with 50 kg on its end), released level for 4 s: every frame within the
/// links' stretch or flagged. (They used to stretch 203% and 1 900%, every frame `Ok`.)
#[test]
fn a_chain_under_a_heavy_load_holds_or_says_so() {
    let device = device_chain();
    let (worst, flagged) = four_seconds(&mut player_rope(device), 10.0 / 11.0);
    eprintln!("player, 2 iterations: links within {worst:.2e}, {flagged} frames flagged");
    assert!(worst <= 5e-3, "{worst}");
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.81),
        ..Settings::default()
    }
    .with_integrator(DirectChain::default());
    let material = Material {
        stiffness: 2000.0,
        damping: 0.0,
    };
    let (start, end) = (Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0));
    let mut rope: Rope<Vec2<f64>, 10, 10, DirectChain> =
        Rope::new(start, end, 0.05, material, settings).unwrap();
    rope.hang(9, 50.0).unwrap();
    let (worst, flagged) = four_seconds(&mut rope, 1.0 / 9.0);
    eprintln!("bob 1 000×: links within {worst:.2e}, {flagged} frames flagged");
    assert!(worst <= 5e-3, "{worst}");
}

/// 240 frames at 60 Hz of a rope whose links are `rest` long, each step checked
/// ([`check`]): the largest stretch over them, and how many frames were flagged.
fn four_seconds<const N: usize>(
    rope: &mut Rope<Vec2<f64>, N, N, DirectChain>,
    rest: f64,
) -> (f64, usize) {
    let (mut worst, mut flagged) = (0.0f64, 0);
    for _ in 0..240 {
        let before = rope.positions().to_vec();
        let step = rope.step(1.0 / 60.0);
        flagged += usize::from(!check(step, &before, rope.positions(), rest, 1e-9));
        worst = worst.max(stretch_of(rope.positions(), rest));
    }
    (worst, flagged)
}

/// The same player rope in `Q16` at the device's setting, wrapping under a box three times
/// its particle spacing wide as it swings (contacts on its particles): no `Diverged`, every
/// frame within the links' stretch or flagged, and all within 0.5%, for 10 s. (It used to
/// be refused from frame 374 on.)
#[cfg(feature = "fixed")]
#[test]
fn a_q16_chain_wrapping_a_box_holds_or_says_so() {
    let q = Q16::from_f64;
    let settings = Settings {
        gravity: Vec2::new(q(0.0), q(-9.81)),
        ..Settings::default()
    }
    .with_integrator(DirectChain {
        iterations: 2,
        substeps: 1,
        ..DirectChain::default()
    });
    let material = Material {
        stiffness: q(2000.0),
        damping: q(0.0),
    };
    let (start, end) = (Vec2::new(q(0.0), q(0.0)), Vec2::new(q(10.0), q(0.0)));
    let mut rope: Rope<Vec2<Q16>, 12, 12, DirectChain> =
        Rope::new(start, end, q(2.0), material, settings).unwrap();
    rope.hang(11, q(70.0)).unwrap();
    let spacing = 10.0 / 11.0;
    let box_ = [Collider::aabb(
        Vec2::new(q(-1.5 * spacing), q(-3.0)),
        Vec2::new(q(1.5 * spacing), q(-2.0)),
    )
    .unwrap()];
    let contacts = Contacts::new(&box_, q(0.05), Touch::Particles).unwrap();
    let (mut flagged, mut worst) = (0, 0.0f64);
    for frame in 0..600 {
        let before = rope.positions().to_vec();
        let step = rope.step_touching(Q16::ratio(1, 60), (), &contacts);
        assert!(step.is_ok(), "frame {frame}: {step:?}");
        flagged += usize::from(!check(step, &before, rope.positions(), spacing, 1e-3));
        worst = worst.max(stretch_of(rope.positions(), spacing));
    }
    eprintln!("Q16 under a box: links within {worst:.2e}, {flagged} frames flagged");
    assert!(worst <= 5e-3, "{worst}");
}

/// An inextensible chain's links store no energy: the same motion has the same energy
/// whatever stiffness its springs name. (Its energy used to peak at 2 643 J with
/// 2·10⁵ N/m and at −0.2 J with 2 000 N/m, on identical trajectories.)
#[test]
fn an_inextensible_chain_stores_no_energy_in_its_links() {
    let rope = |stiffness: f64| {
        let settings = Settings {
            gravity: Vec2::new(0.0, -9.81),
            ..Settings::default()
        }
        .with_integrator(DirectChain::default());
        let material = Material {
            stiffness,
            damping: 0.0,
        };
        let (start, end) = (Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0));
        let mut rope: Rope<Vec2<f64>, 8, 8, DirectChain> =
            Rope::new(start, end, 1.0, material, settings).unwrap();
        rope.hang(7, 10.0).unwrap();
        rope
    };
    let (mut soft, mut stiff) = (rope(2000.0), rope(2e5));
    for _ in 0..120 {
        let _ = soft.step(1.0 / 60.0).unwrap();
        let _ = stiff.step(1.0 / 60.0).unwrap();
        assert_eq!(soft.positions(), stiff.positions(), "the same motion");
        assert_eq!(soft.energy(), stiff.energy());
    }
    // Kinetic and gravitational energy only: what the particles alone add up to.
    let e: f64 = soft
        .positions()
        .iter()
        .zip(soft.velocities())
        .zip(soft.inv_masses())
        .filter(|(_, w)| **w > 0.0)
        .map(|((x, v), w)| (0.5 * v.dot(*v) + 9.81 * x.y) / w)
        .sum();
    assert!(
        (soft.energy() - e).abs() <= 1e-9 * e.abs(),
        "{} {e}",
        soft.energy()
    );
}

/// Errors say what their docs say: a NaN arc length is `NonFinite` named "arc length"; a
/// surface table's count names its sample capacity; a `Q16` stiffness that saturated says
/// so and gives the format's range.
#[test]
fn errors_say_what_their_docs_say() {
    use dunas::spline_rope::SplineRope;
    use dunas::surface::SurfaceTable;
    let material = Material {
        stiffness: 100.0,
        damping: 0.0,
    };
    let settings = Settings::<Vec2<f64>>::default();
    let (start, end) = (Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0));
    let mut rope: SplineRope<Vec2<f64>, 6> =
        SplineRope::new(start, end, 1.0, material, settings).unwrap();
    assert_eq!(
        rope.apply_force(f64::NAN, Vec2::new(1.0, 0.0)),
        Err(Error::NonFinite { name: "arc length" })
    );
    let Err(Error::InvalidParameter { name, expected }) =
        SurfaceTable::<f32, 10, 16>::new(Smoothing::CatmullRom, 37)
    else {
        panic!("37 samples in a table of 16")
    };
    assert_eq!(name, "count");
    assert!(expected.contains("sample capacity"), "{expected}");
    #[cfg(feature = "fixed")]
    {
        let q = Q16::from_f64;
        let settings = Settings {
            gravity: Vec2::new(q(0.0), q(-9.81)),
            ..Settings::default()
        };
        let stiff = Material {
            stiffness: q(1e12),
            damping: q(0.0),
        };
        let (start, end) = (Vec2::new(q(0.0), q(0.0)), Vec2::new(q(1.0), q(0.0)));
        let Err(Error::InvalidParameter { name, expected }) =
            Rope::<Vec2<Q16>, 8>::new(start, end, q(1.0), stiff, settings)
        else {
            panic!("a saturated stiffness")
        };
        assert_eq!(name, "stiffness");
        assert!(
            expected.contains("saturated") && expected.contains("32 767"),
            "{expected}"
        );
    }
}

/// A heavy load pulling a rope round a box keeps its drawn curve out of the box and its
/// links at their length, or says so: the player's rope let go level above a box 3
/// particle spacings wide (the scene of `examples/mcu_wrap.rs`), at the device catapult's
/// setting (one solve of 2 iterations a frame) and at the defaults. The contacts and the
/// links take rounds in each solve, the links holding each particle a contact pushed
/// along its push. Every frame that ends with a drawn point more than 1% of the thickness
/// inside the box, or a link more than 0.1% off, reports `converged: false`; the curve
/// never goes that deep, and no link ends 1% off. (The links used to pull the curve 0.7 m
/// into the box.)
#[test]
fn a_heavy_load_round_a_box_keeps_the_rope_out_of_it_or_says_so() {
    let device = device_chain();
    let (low, high) = (Vec2::new(2.5, -3.5), Vec2::new(2.5 + 30.0 / 11.0, -2.0));
    let block = [Collider::aabb(low, high).unwrap()];
    let thickness = 0.05;
    let contacts = Contacts::new(&block, thickness, Touch::Drawn(Smoothing::CatmullRom)).unwrap();
    for solver in [device, DirectChain::default()] {
        let mut rope = player_rope(solver);
        let mut curve = [Vec2::default(); 64];
        let (mut touching, mut flagged, mut deepest, mut longest) = (0, 0, 0.0f64, 0.0f64);
        for frame in 0..240 {
            let info = rope.step_touching(1.0 / 60.0, (), &contacts).unwrap();
            let n = rope.sample(Smoothing::CatmullRom, &mut curve).unwrap();
            let depth = depth_in(&block[0], &curve[..n]);
            let stretch = rope
                .positions()
                .windows(2)
                .map(|pair| ((pair[1] - pair[0]).length() / (10.0 / 11.0) - 1.0).abs())
                .fold(0.0, f64::max);
            touching += usize::from(depth > -thickness - 1e-3);
            flagged += usize::from(!info.converged);
            (deepest, longest) = (deepest.max(depth), longest.max(stretch));
            if depth > 0.01 * thickness || stretch > 1e-3 {
                assert!(
                    !info.converged,
                    "{solver:?}, frame {frame}: the curve {depth} m into the box and a link \
                     {stretch} off, reported converged"
                );
            }
        }
        eprintln!(
            "{solver:?}: {touching} frames touching, {flagged} flagged, at most {deepest} m \
             inside, links within {longest}"
        );
        assert!(
            touching > 10,
            "{solver:?}: the scene no longer wraps the box"
        );
        assert!(
            deepest <= 0.01 * thickness,
            "{solver:?}: {deepest} m into the box"
        );
        assert!(longest <= 0.01, "{solver:?}: a link {longest} off");
    }
}

/// A load pulling a springy rope round the same box keeps its drawn curve out of the box,
/// under `DirectSprings` (defaults) and `DirectChain` with springs (`inextensible: false`):
/// after each solve the contacts take rounds, with no time passing, until a round moves no
/// particle by more than 0.1% of a link, so a push on one span no longer leaves its
/// neighbour drawn inside. A 20 kg load on 2 000 N/m springs, and a 2 kg one on 500 N/m
/// (and for `DirectChain`, 70 kg on 2 000 N/m). With one round the curve went up to 14 times
/// the thickness into the box under `DirectSprings`, and up to 5 times under `DirectChain` (in f32).
/// The links stretch (springs), but never past the box's width, which the guarantee asks
/// of a collider (at least as wide as the spacing).
#[test]
fn a_load_round_a_box_keeps_a_springy_rope_out_of_it() {
    let springs = DirectChain {
        inextensible: false,
        ..DirectChain::default()
    };
    for (stiffness, load) in [(2000.0, 20.0), (500.0, 2.0)] {
        round_a_box(DirectSprings::default(), stiffness, load);
        round_a_box(springs, stiffness, load);
    }
    round_a_box(springs, 2000.0, 70.0);
}

/// The rope of [`a_load_round_a_box_keeps_a_springy_rope_out_of_it`] under `solver`, its
/// springs `stiffness` N/m and its load `load` kg, for 600 frames: it wraps the box, its
/// drawn curve never more than 1% of the thickness into it.
fn round_a_box<I: Integrator>(solver: I, stiffness: f64, load: f64) {
    let (mut rope, block) = common::rope_round_a_box::<f64, I>(solver, stiffness, load).unwrap();
    let block = [block];
    let thickness = 0.05;
    let contacts = Contacts::new(&block, thickness, Touch::Drawn(Smoothing::CatmullRom)).unwrap();
    let mut curve = [Vec2::default(); 64];
    let (mut touching, mut deepest, mut longest) = (0, f64::MIN, 0.0f64);
    for _ in 0..600 {
        let _ = rope.step_touching(1.0 / 60.0, (), &contacts).unwrap();
        let n = rope.sample(Smoothing::CatmullRom, &mut curve).unwrap();
        let depth = depth_in(&block[0], &curve[..n]);
        let links = rope.positions().windows(2);
        let link = links
            .map(|pair| (pair[1] - pair[0]).length())
            .fold(0.0, f64::max);
        touching += usize::from(depth > -thickness - 1e-3);
        (deepest, longest) = (deepest.max(depth), longest.max(link));
    }
    eprintln!(
        "{solver:?}, {stiffness} N/m, {load} kg: {touching} frames touching, at most {deepest} m \
         inside, longest link {longest} m"
    );
    assert!(
        touching > 30,
        "{solver:?}: the scene no longer wraps the box"
    );
    assert!(
        longest < 30.0 / 11.0,
        "{solver:?}: a link {longest} m long, wider than the box"
    );
    assert!(
        deepest <= 0.01 * thickness,
        "{solver:?}, {stiffness} N/m, {load} kg: {deepest} m into the box"
    );
}

/// How far the deepest point of `curve` is inside `block` (m; negative: outside by that).
fn depth_in(block: &Collider<Vec2<f64>>, curve: &[Vec2<f64>]) -> f64 {
    curve
        .iter()
        .map(|&p| -block.gap(p))
        .fold(f64::MIN, f64::max)
}
