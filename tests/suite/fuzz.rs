//! Random sequences of the public calls on a rope (stepped explicitly and by the direct
//! solvers) and on a spline rope (with each of its steppers), with hostile values (NaN, ±∞, 0,
//! huge, negative, `usize::MAX`, empty and tiny buffers), in `f32`, `f64` and `Q16`. After
//! every call: nothing panicked, every position and velocity is finite and in range, and a
//! call that returned an error left the rope exactly as it was. And ropes and spline ropes
//! built from random lengths, masses, stiffnesses, dampings and gravities, stepped at random
//! frame lengths: the same, and the spline ropes' energy bounded. And the same for what a
//! scene adds: colliders of every kind touched at the particles or the drawn curve (the
//! reported impulses finite, or clamped and reported in `Q16`), snap limits, cuts, hung and
//! released weights, hands and welds; a sail's wind, contacts, tears and drawing (its normals
//! of unit length), stepped explicitly and by a direct solve of its springs; every constructor
//! fed hostile numbers; and curves, smoothed rows, flattening, sample counts and the
//! fixed-step clock.
#![cfg(all(feature = "std", feature = "fixed"))]

use dunas::Point;
use dunas::breaking::Piece;
use dunas::collider::Collider;
use dunas::contact::{Contacts, Push, Touch};
use dunas::force::{AnchorSpring, SailWind, Wind};
use dunas::integrator::{
    DirectChain, DirectSprings, ExplicitEuler, ImplicitEuler, Integrator, Rk4, SymplecticEuler,
    Verlet, Xpbd,
};
use dunas::prelude::*;
use dunas::smooth::Smoothed;
use dunas::spline_rope::{Bdf2, SplineRope, SplineStepper};
use dunas::spring::Snap;
use dunas::surface::SurfaceTable;
use dunas::system::StepInfo;
use proptest::prelude::*;

/// One public call and its arguments, as `f64`s converted to the format under test.
#[derive(Clone, Debug)]
enum Call {
    Step(f64),
    StepInWind { dt: f64, drag: f64, gust: f64 },
    StepAnchored { dt: f64, x: f64, rest: f64, k: f64 },
    SetPosition(usize, f64, f64),
    SetVelocity(usize, f64, f64),
    Impulse(usize, f64, f64),
    SetInvMass(usize, f64),
    SetSettings(SettingsChange),
    Calibrate { target: f64, dt: f64, steps: u32 },
    Sample { smoothing: u8, len: usize },
    DrawnLength(f64),
}

pub(super) fn hostile() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => -100.0..100.0f64,
        2 => 0.0..0.1f64,
        1 => prop::sample::select(vec![
            f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -0.0, 1e-300, -1.0,
            1e4, -1e4, 16_383.0, 40_000.0, 1e30, f64::MAX, f64::MIN,
        ]),
    ]
}

pub(super) fn index() -> impl Strategy<Value = usize> {
    prop_oneof![4 => 0..8usize, 1 => prop::sample::select(vec![8, 9, usize::MAX])]
}

/// New settings from hostile numbers: gravity (down), air drag, bounds, accuracy.
#[derive(Clone, Copy, Debug)]
struct SettingsChange {
    gravity: f64,
    damping: f64,
    bounds: f64,
    accuracy: u8,
}

impl SettingsChange {
    fn applied<S: Scalar, I: Copy>(&self, old: &Settings<Vec2<S>, I>) -> Settings<Vec2<S>, I> {
        Settings {
            gravity: Vec2::new(S::ZERO, S::from_f64(self.gravity)),
            damping: S::from_f64(self.damping),
            bounds: S::from_f64(self.bounds),
            accuracy: [Accuracy::Fast, Accuracy::Balanced, Accuracy::Fine][self.accuracy as usize],
            ..*old
        }
    }
}

fn settings_change() -> impl Strategy<Value = SettingsChange> {
    (hostile(), hostile(), hostile(), 0..3u8).prop_map(|(gravity, damping, bounds, accuracy)| {
        SettingsChange {
            gravity,
            damping,
            bounds,
            accuracy,
        }
    })
}

fn call() -> impl Strategy<Value = Call> {
    prop_oneof![
        4 => hostile().prop_map(Call::Step),
        1 => (hostile(), hostile(), hostile())
            .prop_map(|(dt, drag, gust)| Call::StepInWind { dt, drag, gust }),
        1 => (hostile(), hostile(), hostile(), hostile())
            .prop_map(|(dt, x, rest, k)| Call::StepAnchored { dt, x, rest, k }),
        2 => (index(), hostile(), hostile()).prop_map(|(i, x, y)| Call::SetPosition(i, x, y)),
        1 => (index(), hostile(), hostile()).prop_map(|(i, x, y)| Call::SetVelocity(i, x, y)),
        1 => (index(), hostile(), hostile()).prop_map(|(i, x, y)| Call::Impulse(i, x, y)),
        1 => (index(), hostile()).prop_map(|(i, w)| Call::SetInvMass(i, w)),
        1 => settings_change().prop_map(Call::SetSettings),
        1 => (hostile(), hostile(), 0..12u32)
            .prop_map(|(target, dt, steps)| Call::Calibrate { target, dt, steps }),
        1 => (0..4u8, 0..130usize).prop_map(|(smoothing, len)| Call::Sample { smoothing, len }),
        1 => hostile().prop_map(Call::DrawnLength),
    ]
}

/// A rope's `new` arguments: its ends, mass, material and settings.
type Start<S> = (Vec2<S>, Vec2<S>, S, Material<S>, Settings<Vec2<S>>);

/// What every rope under test starts from: 7 units level from the origin, 1 mass unit,
/// stiffness 300, gravity 9.81, damping 0.5.
fn start<S: Scalar>() -> Start<S> {
    let s = S::from_f64;
    let settings = Settings {
        gravity: Vec2::new(s(0.0), s(-9.81)),
        damping: s(0.5),
        ..Settings::default()
    };
    let material = Material {
        stiffness: s(300.0),
        damping: s(0.5),
    };
    let ends = (Vec2::new(s(0.0), s(0.0)), Vec2::new(s(7.0), s(0.0)));
    (ends.0, ends.1, s(1.0), material, settings)
}

fn rope<S: Scalar>() -> Rope<Vec2<S>, 8> {
    stepped_rope(SymplecticEuler)
}

/// [`rope`] stepped by `integrator`.
fn stepped_rope<S: Scalar, I: Integrator>(integrator: I) -> Rope<Vec2<S>, 8, 8, I> {
    let (a, b, mass, material, settings) = start::<S>();
    Rope::new(a, b, mass, material, settings.with_integrator(integrator)).unwrap()
}

/// Makes the call; `Err` when the rope refused it, `Ok` otherwise.
fn apply<S: Scalar, I: Integrator>(
    rope: &mut Rope<Vec2<S>, 8, 8, I>,
    call: &Call,
) -> Result<(), Error> {
    let s = S::from_f64;
    let v = |x: f64, y: f64| Vec2::new(s(x), s(y));
    match *call {
        Call::Step(dt) => rope.step(s(dt)).map(drop),
        Call::StepInWind { dt, drag, gust } => {
            let mut wind = Wind::still(s(drag));
            wind.gust = v(gust, 0.0);
            wind.gust_length = s(1.0);
            rope.step_with(s(dt), &mut wind).map(drop)
        }
        Call::StepAnchored { dt, x, rest, k } => {
            let material = Material {
                stiffness: s(k),
                damping: s(0.1),
            };
            let anchor = AnchorSpring::new(7, v(x, 0.0), s(rest), material)?;
            rope.step_with(s(dt), anchor).map(drop)
        }
        Call::SetPosition(i, x, y) => rope.set_position(i, v(x, y)),
        Call::SetVelocity(i, x, y) => rope.set_velocity(i, v(x, y)),
        Call::Impulse(i, x, y) => rope.apply_impulse(i, v(x, y)),
        Call::SetInvMass(i, w) => rope.set_inv_mass(i, s(w)),
        Call::SetSettings(change) => {
            let settings = change.applied(rope.settings());
            rope.set_settings(settings)
        }
        Call::Calibrate { target, dt, steps } => rope
            .calibrate_length(Smoothing::BSpline, s(target), s(dt), steps)
            .map(drop),
        Call::Sample { smoothing, len } => {
            let smoothing = [
                Smoothing::Bezier,
                Smoothing::BSpline,
                Smoothing::CatmullRom,
                Smoothing::Polyline,
            ][smoothing as usize];
            let mut out = vec![Vec2::new(S::ZERO, S::ZERO); len];
            let n = rope.sample(smoothing, &mut out)?;
            assert!(n <= len && n >= 2);
            // The documented bound: inside the particles' hull, or 4/3 of the safe range for
            // Catmull-Rom's overshoot.
            let reach = S::SAFE_RANGE + S::SAFE_RANGE / S::from_i16(3);
            assert!(
                out[..n]
                    .iter()
                    .all(|p| p.is_finite() && (0..2).all(|d| p.coord(d).abs() <= reach))
            );
            assert_eq!(out[0], rope.positions()[0]);
            assert_eq!(out[n - 1], rope.positions()[7]);
            Ok(())
        }
        Call::DrawnLength(accuracy) => {
            let len = rope.drawn_length(Smoothing::CatmullRom, s(accuracy))?;
            assert!(len.is_finite());
            Ok(())
        }
    }
}

/// The calls on a rope stepped by each method that steps springs in its own way: explicitly,
/// by a direct solve of its springs, and by a direct solve of its chain.
fn holds_up<S: Scalar>(calls: &[Call]) {
    fn with<S: Scalar, I: Integrator>(integrator: I, calls: &[Call]) {
        let mut rope = stepped_rope::<S, I>(integrator);
        survives(&mut rope, calls, apply, |r| {
            (r.positions(), r.velocities(), r.settings().bounds)
        });
    }
    with::<S, _>(SymplecticEuler, calls);
    with::<S, _>(DirectSprings::default(), calls);
    with::<S, _>(DirectChain::default(), calls);
}

/// Makes each call on `rope`, then checks what the module promises: a refused call changed
/// nothing, and every position (`state`: positions, velocities, bounds) is in range.
pub(super) fn survives<R: std::fmt::Debug, C: std::fmt::Debug, P: Point>(
    rope: &mut R,
    calls: &[C],
    apply: impl Fn(&mut R, &C) -> Result<(), Error>,
    state: impl Fn(&R) -> (&[P], &[P], P::Scalar),
) {
    for call in calls {
        let before = format!("{rope:?}");
        if apply(rope, call).is_err() {
            assert_eq!(
                format!("{rope:?}"),
                before,
                "{call:?} was refused but changed the rope"
            );
        }
        let (positions, velocities, bounds) = state(rope);
        for p in positions {
            assert!(p.in_safe_range(), "{call:?} left {p:?}");
            assert!(
                (0..P::DIM).all(|d| p.coord(d).abs() <= bounds),
                "{call:?} left {p:?}"
            );
        }
        for v in velocities {
            assert!(v.in_safe_range(), "{call:?} left a velocity {v:?}");
        }
    }
}

/// One public call on a spline rope and its arguments.
#[derive(Clone, Debug)]
enum SplineCall {
    Step(f64),
    StepOnce(f64),
    StepInWind { dt: f64, drag: f64, gust: f64 },
    StepTouching(Touching),
    SetPosition(usize, f64, f64),
    SetVelocity(usize, f64, f64),
    MovePinned(usize, f64, f64, f64),
    SetPinned(usize, bool),
    SetBending(f64),
    ApplyForce(f64, f64, f64),
    WeightsAt(f64),
    SetSettings(SettingsChange),
    Sample(usize),
    Energy,
}

fn spline_call() -> impl Strategy<Value = SplineCall> {
    use SplineCall::*;
    prop_oneof![
        4 => hostile().prop_map(Step),
        1 => hostile().prop_map(StepOnce),
        1 => (hostile(), hostile(), hostile())
            .prop_map(|(dt, drag, gust)| StepInWind { dt, drag, gust }),
        2 => touching().prop_map(StepTouching),
        2 => (index(), hostile(), hostile()).prop_map(|(i, x, y)| SetPosition(i, x, y)),
        1 => (index(), hostile(), hostile()).prop_map(|(i, x, y)| SetVelocity(i, x, y)),
        1 => (index(), hostile(), hostile(), hostile())
            .prop_map(|(i, x, y, dt)| MovePinned(i, x, y, dt)),
        2 => (index(), any::<bool>()).prop_map(|(i, pin)| SetPinned(i, pin)),
        1 => hostile().prop_map(SetBending),
        1 => (hostile(), hostile(), hostile()).prop_map(|(s, x, y)| ApplyForce(s, x, y)),
        1 => hostile().prop_map(WeightsAt),
        1 => settings_change().prop_map(SetSettings),
        1 => (0..130usize).prop_map(Sample),
        1 => Just(Energy),
    ]
}

/// Makes the call; `Err` when the rope refused it, `Ok` otherwise.
fn apply_spline<S: Scalar, I: SplineStepper, const K: usize>(
    rope: &mut SplineRope<Vec2<S>, K, I>,
    call: &SplineCall,
) -> Result<(), Error> {
    let s = S::from_f64;
    let v = |x: f64, y: f64| Vec2::new(s(x), s(y));
    match *call {
        SplineCall::Step(dt) => rope.step(s(dt)).map(drop),
        SplineCall::StepOnce(h) => rope.step_once(s(h)),
        SplineCall::StepInWind { dt, drag, gust } => {
            let mut wind = Wind::still(s(drag));
            wind.gust = v(gust, 0.0);
            wind.gust_length = s(1.0);
            rope.step_with(s(dt), &mut wind).map(drop)
        }
        SplineCall::StepTouching(ref touching) => {
            touching.run(|dt, contacts| rope.step_touching(dt, (), contacts))
        }
        SplineCall::SetPosition(i, x, y) => rope.set_position(i, v(x, y)),
        SplineCall::SetVelocity(i, x, y) => rope.set_velocity(i, v(x, y)),
        SplineCall::MovePinned(i, x, y, dt) => rope.move_pinned(i, v(x, y), s(dt)),
        SplineCall::SetPinned(i, pin) => rope.set_pinned(i, pin),
        SplineCall::SetBending(ei) => rope.set_bending(s(ei)),
        SplineCall::ApplyForce(at, x, y) => rope.apply_force(s(at), v(x, y)),
        SplineCall::WeightsAt(at) => {
            let (first, w) = rope.weights_at(s(at));
            assert!(first <= K - 4);
            let sum = w.iter().fold(0.0, |sum, w| sum + w.to_f64());
            assert!(
                w.iter().all(|w| w.is_finite()) && (sum - 1.0).abs() < 1e-3,
                "{w:?}"
            );
            Ok(())
        }
        SplineCall::SetSettings(change) => rope.set_settings(change.applied(rope.settings())),
        SplineCall::Sample(len) => {
            let mut out = vec![Vec2::new(S::ZERO, S::ZERO); len];
            let n = rope.sample(&mut out)?;
            assert!(n <= len && n >= K - 2);
            // The curve stays in its control points' hull, so in the safe range.
            assert!(out[..n].iter().all(|p| p.in_safe_range()));
            assert_eq!(out[0], rope.positions()[0]);
            assert_eq!(out[n - 1], rope.positions()[K - 1]);
            Ok(())
        }
        SplineCall::Energy => {
            rope.energy();
            Ok(())
        }
    }
}

fn spline_holds_up<S: Scalar, I: SplineStepper, const K: usize>(stepper: I, calls: &[SplineCall]) {
    let (a, b, mass, material, settings) = start::<S>();
    let settings = settings.with_integrator(stepper);
    let mut rope: SplineRope<Vec2<S>, K, I> =
        SplineRope::new(a, b, mass, material, settings).unwrap();
    survives(&mut rope, calls, apply_spline, |r| {
        (&r.positions()[..], &r.velocities()[..], r.settings().bounds)
    });
}

/// Each format with each stepper, and one span (4 control points).
fn spline_ropes_hold_up<S: Scalar>(calls: &[SplineCall]) {
    spline_holds_up::<S, _, 8>(SymplecticEuler, calls);
    spline_holds_up::<S, _, 8>(ImplicitEuler::default(), calls);
    spline_holds_up::<S, _, 8>(Bdf2::default(), calls);
    spline_holds_up::<S, _, 4>(SymplecticEuler, calls);
    spline_holds_up::<S, _, 4>(ImplicitEuler::default(), calls);
}

/// A spline rope's build and its frames: everything spans decades.
#[derive(Clone, Debug)]
struct Build {
    length: f64,
    angle: f64,
    mass: f64,
    stiffness: f64,
    damping: f64,
    gravity: f64,
    gravity_angle: f64,
    drag: f64,
    accuracy: u8,
    dt: f64,
    frames: usize,
    both_ends_pinned: bool,
}

fn build() -> impl Strategy<Value = Build> {
    let decades = |low: f64, high: f64| (low..high).prop_map(|e| 10f64.powf(e));
    (
        (
            decades(-3.0, 4.0),
            0.0..std::f64::consts::TAU,
            decades(-3.0, 3.0),
        ),
        (
            decades(-2.0, 8.0),
            prop_oneof![Just(0.0), decades(-3.0, 3.0)],
        ),
        (
            prop_oneof![Just(0.0), 0.0..1000.0f64],
            0.0..std::f64::consts::TAU,
        ),
        (prop_oneof![Just(0.0), 0.0..5.0f64], 0..3u8, any::<bool>()),
        (
            prop::sample::select(vec![1.0 / 30.0, 1.0 / 60.0, 1.0 / 240.0, 0.1]),
            1..120usize,
        ),
    )
        .prop_map(
            |(
                (length, angle, mass),
                (stiffness, damping),
                (gravity, gravity_angle),
                (drag, accuracy, both_ends_pinned),
                (dt, frames),
            )| Build {
                length,
                angle,
                mass,
                stiffness,
                damping,
                gravity,
                gravity_angle,
                drag,
                accuracy,
                dt,
                frames,
                both_ends_pinned,
            },
        )
}

impl Build {
    /// The settings, material and free end in the format (the start is the origin).
    fn parts<S: Scalar, I>(&self, integrator: I) -> (Settings<Vec2<S>, I>, Material<S>, Vec2<S>) {
        let s = S::from_f64;
        let settings = Settings {
            gravity: Vec2::new(
                s(self.gravity * self.gravity_angle.cos()),
                s(self.gravity * self.gravity_angle.sin()),
            ),
            damping: s(self.drag),
            accuracy: [Accuracy::Fast, Accuracy::Balanced, Accuracy::Fine][self.accuracy as usize],
            ..Settings::default()
        }
        .with_integrator(integrator);
        let material = Material {
            stiffness: s(self.stiffness),
            damping: s(self.damping),
        };
        let end = Vec2::new(
            s(self.length * self.angle.cos()),
            s(self.length * self.angle.sin()),
        );
        (settings, material, end)
    }

    /// Steps `rope` its frames: a refused step changes nothing, every position and
    /// velocity stays in range, and `check` holds after each frame.
    fn steps<R: std::fmt::Debug, S: Scalar>(
        &self,
        rope: &mut R,
        step: impl Fn(&mut R, S) -> Result<(), Error>,
        state: impl Fn(&R) -> Vec<Vec2<S>>,
        check: impl Fn(&R, usize),
    ) {
        for frame in 0..self.frames {
            let before = format!("{rope:?}");
            if let Err(e) = step(rope, S::from_f64(self.dt)) {
                assert_eq!(
                    before,
                    format!("{rope:?}"),
                    "frame {frame}: refused ({e:?}) but changed"
                );
            }
            for p in state(rope) {
                assert!(p.in_safe_range(), "frame {frame}: {p:?}");
            }
            check(rope, frame);
        }
    }
}

/// Builds the spline rope (a refusal is fine) and steps it as [`Build::steps`] does; in
/// `f32` and `f64` its energy never rises above the start's with an implicit stepper (its
/// documented guard; `f32` within 10⁻⁴ of the fall's energy, and both within their
/// rounding), nor past 1000 times the fall's energy explicitly (symplectic Euler's energy
/// is bounded, not conserved: near its stability limit it swings by several times the
/// motion's; past 1000 times it would be blowing up).
fn built_holds_up<S: Scalar, I: SplineStepper, const K: usize>(stepper: I, b: &Build) {
    let (settings, material, end) = b.parts::<S, I>(stepper);
    let origin = Vec2::new(S::ZERO, S::ZERO);
    let mass = S::from_f64(b.mass);
    let Ok(mut rope) = SplineRope::<Vec2<S>, K, I>::new(origin, end, mass, material, settings)
    else {
        return;
    };
    if b.both_ends_pinned {
        rope.set_pinned(K - 1, true).unwrap();
    }
    // The fall's energy: the rope's weight over its length and what its weight stretches it.
    let fall = b.mass * b.gravity * b.length * (1.0 + b.mass * b.gravity / b.stiffness);
    let bound = match stepper.implicit() {
        Some(_) if S::EPSILON.to_f64() > 1e-10 => 1e-4,
        Some(_) => 1e-9,
        None => 1e3,
    };
    let e0 = rope.energy().to_f64();
    // The energy's own rounding: ten of the format's epsilons on the start's energy and on
    // the stretch's scale `EA·L` (a still, straight rope's rounding stretches it).
    let rounding = 10.0 * S::EPSILON.to_f64() * (e0.abs() + b.stiffness * b.length);
    b.steps(
        &mut rope,
        |rope, dt| rope.step(dt).map(drop),
        |rope| [&rope.positions()[..], &rope.velocities()[..]].concat(),
        |rope, frame| {
            let gained = rope.energy().to_f64() - e0;
            assert!(
                S::FIXED_POINT || gained <= bound * fall + rounding,
                "{stepper:?}, {K} control points, frame {frame}: gained {gained:e} (the fall {fall:e})"
            );
        },
    );
}

/// Builds the particle rope (a refusal is fine) and steps it as [`Build::steps`] does.
fn built_rope_holds_up<S: Scalar, I: Integrator, const N: usize>(integrator: I, b: &Build) {
    let (settings, material, end) = b.parts::<S, I>(integrator);
    let origin = Vec2::new(S::ZERO, S::ZERO);
    let mass = S::from_f64(b.mass);
    let Ok(mut rope) = Rope::<Vec2<S>, N, N, I>::new(origin, end, mass, material, settings) else {
        return;
    };
    if b.both_ends_pinned {
        rope.set_inv_mass(N - 1, S::ZERO).unwrap();
    }
    b.steps(
        &mut rope,
        |rope, dt| rope.step(dt).map(drop),
        |rope| [rope.positions(), rope.velocities()].concat(),
        |_, _| {},
    );
}

fn builds_hold_up<S: Scalar>(b: &Build) {
    built_rope_holds_up::<S, _, 2>(SymplecticEuler, b);
    built_rope_holds_up::<S, _, 8>(SymplecticEuler, b);
    built_rope_holds_up::<S, _, 30>(SymplecticEuler, b);
    built_rope_holds_up::<S, _, 8>(ExplicitEuler, b);
    built_rope_holds_up::<S, _, 8>(Verlet, b);
    built_rope_holds_up::<S, _, 8>(Rk4, b);
    built_rope_holds_up::<S, _, 8>(ImplicitEuler::default(), b);
    built_rope_holds_up::<S, _, 8>(Xpbd::default(), b);
    built_rope_holds_up::<S, _, 8>(DirectSprings::default(), b);
    built_rope_holds_up::<S, _, 8>(DirectChain::default(), b);
    built_rope_holds_up::<S, _, 30>(DirectChain::default(), b);
    built_holds_up::<S, _, 4>(SymplecticEuler, b);
    built_holds_up::<S, _, 5>(SymplecticEuler, b);
    built_holds_up::<S, _, 8>(SymplecticEuler, b);
    built_holds_up::<S, _, 16>(SymplecticEuler, b);
    built_holds_up::<S, _, 8>(ImplicitEuler::default(), b);
    built_holds_up::<S, _, 16>(ImplicitEuler::default(), b);
    built_holds_up::<S, _, 8>(Bdf2::default(), b);
}

/// The direct solvers with any count of iterations and of solves a step (0 counts as 1),
/// the chain inextensible or not and halved up to 0 to 15 times (past the cap of 12), on
/// ropes of any build.
fn direct_builds_hold_up<S: Scalar>(
    b: &Build,
    (iterations, substeps, inextensible): (u8, u8, bool),
) {
    built_rope_holds_up::<S, _, 8>(
        DirectSprings {
            iterations,
            substeps,
            measure: iterations % 3 != 0,
            keep_energy: iterations % 2 == 1,
        },
        b,
    );
    let chain = DirectChain {
        iterations,
        inextensible,
        substeps,
        halvings: substeps * 5,
    };
    built_rope_holds_up::<S, _, 8>(chain, b);
}

/// Iterations and solves a step for the direct solvers, and whether the chain is
/// inextensible.
fn solves() -> impl Strategy<Value = (u8, u8, bool)> {
    (0..6u8, 0..4u8, any::<bool>())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn f32_direct_solvers_of_any_build_hold_up(b in build(), solves in solves()) {
        direct_builds_hold_up::<f32>(&b, solves);
    }

    #[test]
    fn f64_direct_solvers_of_any_build_hold_up(b in build(), solves in solves()) {
        direct_builds_hold_up::<f64>(&b, solves);
    }

    #[test]
    fn q16_direct_solvers_of_any_build_hold_up(b in build(), solves in solves()) {
        direct_builds_hold_up::<Q16>(&b, solves);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn f32_ropes_of_any_build_hold_up(b in build()) {
        builds_hold_up::<f32>(&b);
    }

    #[test]
    fn f64_ropes_of_any_build_hold_up(b in build()) {
        builds_hold_up::<f64>(&b);
    }

    #[test]
    fn q16_ropes_of_any_build_hold_up(b in build()) {
        builds_hold_up::<Q16>(&b);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn f32_ropes_survive_hostile_calls(calls in prop::collection::vec(call(), 1..40)) {
        holds_up::<f32>(&calls);
    }

    #[test]
    fn f64_ropes_survive_hostile_calls(calls in prop::collection::vec(call(), 1..40)) {
        holds_up::<f64>(&calls);
    }

    #[test]
    fn q16_ropes_survive_hostile_calls(calls in prop::collection::vec(call(), 1..40)) {
        holds_up::<Q16>(&calls);
    }

    #[test]
    fn f32_spline_ropes_survive_hostile_calls(calls in prop::collection::vec(spline_call(), 1..40)) {
        spline_ropes_hold_up::<f32>(&calls);
    }

    #[test]
    fn f64_spline_ropes_survive_hostile_calls(calls in prop::collection::vec(spline_call(), 1..40)) {
        spline_ropes_hold_up::<f64>(&calls);
    }

    #[test]
    fn q16_spline_ropes_survive_hostile_calls(calls in prop::collection::vec(spline_call(), 1..40)) {
        spline_ropes_hold_up::<Q16>(&calls);
    }
}

/// A collider of any kind from hostile numbers: a ball, a capsule, a half-space, a box or
/// (in 2D) a triangle, moving or still, with friction, restitution and a mass or without.
#[derive(Clone, Debug)]
struct ColliderSpec {
    kind: u8,
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 2],
    radius: f64,
    velocity: Option<[f64; 3]>,
    friction: Option<(f64, f64)>,
    restitution: Option<f64>,
    mass: Option<f64>,
}

fn collider_spec() -> impl Strategy<Value = ColliderSpec> {
    let point = || [hostile(), hostile(), hostile()];
    (
        (0..5u8, point(), point(), [hostile(), hostile()], hostile()),
        (
            prop::option::of(point()),
            prop::option::of((hostile(), hostile())),
            prop::option::of(hostile()),
            prop::option::of(hostile()),
        ),
    )
        .prop_map(
            |((kind, a, b, c, radius), (velocity, friction, restitution, mass))| ColliderSpec {
                kind,
                a,
                b,
                c,
                radius,
                velocity,
                friction,
                restitution,
                mass,
            },
        )
}

impl ColliderSpec {
    /// The collider in `P`'s dimensions (a triangle is a ball in 3D).
    fn build<P: Point>(&self) -> Result<Collider<P>, Error>
    where
        Collider<P>: Polygon<P>,
    {
        let (a, b, r) = (
            point(&self.a),
            point(&self.b),
            P::Scalar::from_f64(self.radius),
        );
        let mut collider = match self.kind {
            0 => Collider::ball(a, r)?,
            1 => Collider::capsule(a, b, r)?,
            2 => Collider::half_space(a, b)?,
            3 => Collider::aabb(a, b)?,
            _ => Collider::triangle([a, b, point(&self.c)])?,
        };
        if let Some(v) = self.velocity {
            collider = collider.moving(point(&v))?;
        }
        if let Some((fs, fk)) = self.friction {
            collider = collider.with_friction(P::Scalar::from_f64(fs), P::Scalar::from_f64(fk))?;
        }
        if let Some(e) = self.restitution {
            collider = collider.with_restitution(P::Scalar::from_f64(e))?;
        }
        if let Some(m) = self.mass {
            collider = collider.with_mass(P::Scalar::from_f64(m))?;
        }
        Ok(collider)
    }
}

/// A point of `P` from the first of `c`'s coordinates.
fn point<P: Point>(c: &[f64]) -> P {
    let mut p = P::default();
    for (d, &x) in c.iter().enumerate().take(P::DIM) {
        p.set_coord(d, P::Scalar::from_f64(x));
    }
    p
}

/// Polygons are 2D: a triangle where the dimensions have one.
pub(super) trait Polygon<P: Point>: Sized {
    fn triangle(corners: [P; 3]) -> Result<Self, Error>;
}

impl<S: Scalar> Polygon<Vec2<S>> for Collider<Vec2<S>> {
    fn triangle(corners: [Vec2<S>; 3]) -> Result<Self, Error> {
        Collider::polygon(&corners)
    }
}

impl<S: Scalar> Polygon<Vec3<S>> for Collider<Vec3<S>> {
    fn triangle(corners: [Vec3<S>; 3]) -> Result<Self, Error> {
        Collider::ball(corners[0], corners[1].x)
    }
}

/// Where contacts touch: the particles, or what one of the four smoothings draws (open or
/// closed).
fn touch(code: u8) -> Touch {
    let smoothing = smoothing(code % 4);
    match code / 4 {
        0 => Touch::Particles,
        1 => Touch::Drawn(smoothing),
        _ => Touch::DrawnLoop(smoothing),
    }
}

pub(super) fn smoothing(code: u8) -> Smoothing {
    [
        Smoothing::Bezier,
        Smoothing::BSpline,
        Smoothing::CatmullRom,
        Smoothing::Polyline,
    ][code as usize % 4]
}

/// A snap limit from hostile numbers: never, a stretch ratio or a tension.
pub(super) fn snap<S: Scalar>((kind, value): (u8, f64)) -> Snap<S> {
    match kind % 3 {
        0 => Snap::Never,
        1 => Snap::Stretch(S::from_f64(value)),
        _ => Snap::Tension(S::from_f64(value)),
    }
}

/// A step against colliders: its frame, colliders, thickness, where it touches and how
/// many impulse slots it reports into.
#[derive(Clone, Debug)]
pub(super) struct Touching {
    dt: f64,
    colliders: Vec<ColliderSpec>,
    thickness: f64,
    touch: u8,
    impulses: usize,
}

pub(super) fn touching() -> impl Strategy<Value = Touching> {
    (
        hostile(),
        prop::collection::vec(collider_spec(), 0..4),
        hostile(),
        0..12u8,
        0..5usize,
    )
        .prop_map(|(dt, colliders, thickness, touch, impulses)| Touching {
            dt,
            colliders,
            thickness,
            touch,
            impulses,
        })
}

impl Touching {
    /// Steps with `step` against the colliders (a refused collider refuses the call); the
    /// reported impulses are zero past the colliders and after a refused step, and finite
    /// unless clamped by `Q16`, which the step then reports as saturated.
    pub(super) fn run<P: Point>(
        &self,
        step: impl FnOnce(P::Scalar, &Contacts<'_, P>) -> Result<StepInfo<P::Scalar>, Error>,
    ) -> Result<(), Error>
    where
        Collider<P>: Polygon<P>,
    {
        let colliders: Vec<Collider<P>> = self
            .colliders
            .iter()
            .map(ColliderSpec::build)
            .collect::<Result<_, _>>()?;
        let mut pushes = vec![Push::default(); self.impulses];
        let thickness = P::Scalar::from_f64(self.thickness);
        let contacts =
            Contacts::new(&colliders, thickness, touch(self.touch))?.with_pushes(&mut pushes);
        let stepped = step(P::Scalar::from_f64(self.dt), &contacts);
        for (k, push) in pushes.iter().enumerate() {
            let clamped = stepped.is_ok_and(|info| P::Scalar::FIXED_POINT && info.saturated);
            let finite = push.impulse.is_finite() && push.shift.is_finite();
            assert!(finite || clamped, "push {k}: {push:?}");
            if k >= colliders.len() || stepped.is_err() {
                assert_eq!(
                    *push,
                    Push::default(),
                    "push {k} past the colliders or refused"
                );
            }
        }
        stepped.map(drop)
    }
}

/// A public call on a rope in a scene: colliders, snap limits, cuts, weights, hands and
/// welds, with its arguments.
#[derive(Clone, Debug)]
enum SceneCall {
    Step(f64),
    Touch(Touching),
    Snap((u8, f64)),
    SpringSnap(usize, (u8, f64)),
    Cut {
        smoothing: u8,
        len: usize,
        from: (f64, f64),
        to: (f64, f64),
    },
    ForgedCut {
        pieces: Vec<(usize, usize, usize, usize)>,
        points: usize,
        from: (f64, f64),
        to: (f64, f64),
    },
    Hang(usize, f64),
    Release(usize, f64),
    LetGo(usize, f64),
    Pin(usize),
    MovePinned(usize, f64, f64, f64),
    Weld(usize, usize),
}

fn scene_call() -> impl Strategy<Value = SceneCall> {
    use SceneCall::*;
    let kind_value = || (0..3u8, hostile());
    let xy = || (hostile(), hostile());
    let small = || prop_oneof![4 => 0..12usize, 1 => Just(usize::MAX)];
    prop_oneof![
        3 => hostile().prop_map(Step),
        4 => touching().prop_map(Touch),
        1 => kind_value().prop_map(Snap),
        1 => (index(), kind_value()).prop_map(|(i, s)| SpringSnap(i, s)),
        2 => (0..4u8, 0..80usize, xy(), xy())
            .prop_map(|(smoothing, len, from, to)| Cut { smoothing, len, from, to }),
        1 => (prop::collection::vec((small(), small(), small(), small()), 0..4), 0..12usize, xy(), xy())
            .prop_map(|(pieces, points, from, to)| ForgedCut { pieces, points, from, to }),
        1 => (index(), hostile()).prop_map(|(i, m)| Hang(i, m)),
        1 => (index(), hostile()).prop_map(|(i, m)| Release(i, m)),
        1 => (index(), hostile()).prop_map(|(i, w)| LetGo(i, w)),
        1 => index().prop_map(Pin),
        1 => (index(), hostile(), hostile(), hostile())
            .prop_map(|(i, x, y, dt)| MovePinned(i, x, y, dt)),
        1 => (index(), index()).prop_map(|(i, j)| Weld(i, j)),
    ]
}

/// Makes the call on the first rope (a weld ties it to the second); `Err` when refused.
fn apply_scene<S: Scalar>(
    (rope, other): &mut (Rope<Vec2<S>, 8>, Rope<Vec2<S>, 8>),
    call: &SceneCall,
) -> Result<(), Error> {
    let s = S::from_f64;
    let v = |(x, y): (f64, f64)| Vec2::new(s(x), s(y));
    match call {
        SceneCall::Step(dt) => rope.step(s(*dt)).map(drop),
        SceneCall::Touch(touching) => {
            touching.run(|dt, contacts| rope.step_touching(dt, (), contacts))
        }
        SceneCall::Snap(limit) => rope.set_snap(snap(*limit)),
        SceneCall::SpringSnap(i, limit) => rope.set_spring_snap(*i, snap(*limit)),
        SceneCall::Cut {
            smoothing: code,
            len,
            from,
            to,
        } => {
            let mut points = vec![Vec2::new(S::ZERO, S::ZERO); *len];
            let mut pieces = [Piece::EMPTY; 8];
            let n = rope.draw(smoothing(*code), &mut points, &mut pieces)?;
            assert!(n <= *len && points[..n].iter().all(|p| p.in_safe_range()));
            let cut = rope.cut(&points, &pieces, v(*from), v(*to))?;
            assert!(cut.is_none_or(|i| i < 7), "cut {cut:?}");
            Ok(())
        }
        SceneCall::ForgedCut {
            pieces,
            points,
            from,
            to,
        } => {
            let pieces: Vec<Piece> = pieces
                .iter()
                .map(|&(a, b, c, d)| Piece {
                    particles: a..b,
                    points: c..d,
                })
                .collect();
            let points = vec![Vec2::new(S::ONE, S::ZERO); *points];
            let cut = rope.cut(&points, &pieces, v(*from), v(*to))?;
            assert!(cut.is_none_or(|i| i < 7), "cut {cut:?}");
            Ok(())
        }
        SceneCall::Hang(i, mass) => rope.hang(*i, s(*mass)),
        SceneCall::Release(i, mass) => {
            let body = rope.release(*i, s(*mass))?;
            assert!(body.position.in_safe_range() && body.velocity.in_safe_range());
            assert!(body.mass > S::ZERO && body.mass.is_finite());
            Ok(())
        }
        SceneCall::LetGo(i, w) => rope.let_go(*i, s(*w)),
        SceneCall::Pin(i) => rope.set_inv_mass(*i, S::ZERO),
        SceneCall::MovePinned(i, x, y, dt) => rope.move_pinned(*i, v((*x, *y)), s(*dt)),
        SceneCall::Weld(i, j) => rope.weld(*i, other, *j),
    }
}

fn scene_holds_up<S: Scalar>(calls: &[SceneCall]) {
    let (a, b, mass, material, settings) = start::<S>();
    let other = Rope::new(b, a, mass, material, settings).unwrap();
    let mut ropes = (rope::<S>(), other);
    survives(&mut ropes, calls, apply_scene, |(r, _)| {
        (r.positions(), r.velocities(), r.settings().bounds)
    });
    let (_, other) = &ropes;
    assert!(other.positions().iter().all(|p| p.in_safe_range()));
}

/// A public call on a cloth (a sail), with its arguments.
#[derive(Clone, Debug)]
enum ClothCall {
    Step(f64),
    Sail {
        dt: f64,
        wind: [f64; 3],
        drag: f64,
        pressure: f64,
    },
    Touch(Touching),
    PinRow(usize),
    PinColumn(usize),
    SetPosition(usize, [f64; 3]),
    Snap([(u8, f64); 3]),
    Cut((f64, f64), (f64, f64)),
    Sample {
        nu: usize,
        nv: usize,
        len: usize,
    },
    Draw {
        smoothing: u8,
        count: usize,
        len: usize,
    },
}

fn cloth_call() -> impl Strategy<Value = ClothCall> {
    use ClothCall::*;
    let xyz = || [hostile(), hostile(), hostile()];
    let limit = || (0..3u8, hostile());
    prop_oneof![
        3 => hostile().prop_map(Step),
        3 => (hostile(), xyz(), hostile(), hostile())
            .prop_map(|(dt, wind, drag, pressure)| Sail { dt, wind, drag, pressure }),
        3 => touching().prop_map(Touch),
        1 => index().prop_map(PinRow),
        1 => index().prop_map(PinColumn),
        1 => (prop_oneof![0..25usize, Just(25), Just(usize::MAX)], xyz())
            .prop_map(|(i, p)| SetPosition(i, p)),
        1 => [limit(), limit(), limit()].prop_map(Snap),
        1 => ((hostile(), hostile()), (hostile(), hostile())).prop_map(|(a, b)| Cut(a, b)),
        1 => (0..12usize, 0..12usize, 0..130usize).prop_map(|(nu, nv, len)| Sample { nu, nv, len }),
        1 => (0..4u8, 0..12usize, 0..100usize)
            .prop_map(|(smoothing, count, len)| Draw { smoothing, count, len }),
    ]
}

type Sail<S, I> = Cloth<Vec3<S>, 5, 5, I>;

/// Makes the call on the cloth; `Err` when refused. What it draws is finite, and a unit
/// normal or zero.
fn apply_cloth<S: Scalar, I: Integrator>(
    cloth: &mut Sail<S, I>,
    call: &ClothCall,
) -> Result<(), Error> {
    let s = S::from_f64;
    let v = |[x, y, z]: [f64; 3]| Vec3::new(s(x), s(y), s(z));
    let drawn = |n: usize, len: usize, points: &[Vec3<S>], normals: &[Vec3<S>]| {
        assert!(n <= len);
        assert!(points[..n].iter().all(|p| p.in_safe_range()));
        for m in &normals[..n] {
            let l = m.length().to_f64();
            assert!(
                m.is_finite() && (l == 0.0 || (l - 1.0).abs() < 0.05),
                "{m:?}"
            );
        }
    };
    match call {
        ClothCall::Step(dt) => cloth.step(s(*dt)).map(drop),
        ClothCall::Sail {
            dt,
            wind,
            drag,
            pressure,
        } => {
            let mut air = Wind::still(s(*drag));
            air.velocity = v(*wind);
            let sail = SailWind::<S>::new(air, s(*pressure))?;
            cloth.step_with(s(*dt), sail).map(drop)
        }
        ClothCall::Touch(touching) => {
            touching.run(|dt, contacts| cloth.step_touching(dt, (), contacts))
        }
        ClothCall::PinRow(j) => cloth.pin_row(*j),
        ClothCall::PinColumn(i) => cloth.pin_column(*i),
        ClothCall::SetPosition(i, p) => cloth.set_position(*i, v(*p)),
        ClothCall::Snap(limits) => cloth.set_snap(limits.map(snap)),
        ClothCall::Cut(a, b) => {
            let torn = cloth.cut(Vec2::new(s(a.0), s(a.1)), Vec2::new(s(b.0), s(b.1)))?;
            assert!(torn <= 5 * 5 * 6);
            Ok(())
        }
        ClothCall::Sample { nu, nv, len } => {
            let mut points = vec![Vec3::new(S::ZERO, S::ZERO, S::ZERO); *len];
            let mut normals = points.clone();
            let n = cloth.sample_patch(*nu, *nv, &mut points, &mut normals)?;
            drawn(n, *len, &points, &normals);
            Ok(())
        }
        ClothCall::Draw {
            smoothing: code,
            count,
            len,
        } => {
            let table = SurfaceTable::<S, 5, 9>::new(smoothing(*code), *count)?;
            let mut points = vec![Vec3::new(S::ZERO, S::ZERO, S::ZERO); *len];
            let mut normals = points.clone();
            let n = cloth.draw(&table, &table, &mut points, &mut normals)?;
            drawn(n, *len, &points, &normals);
            Ok(())
        }
    }
}

/// A 5×5 sail of 4×4 units, level, in the format's gravity, with one edge on a mast:
/// stepped explicitly and by a direct solve of its springs.
fn cloth_holds_up<S: Scalar>(calls: &[ClothCall]) {
    cloth_with::<S, _>(SymplecticEuler, calls);
    cloth_with::<S, _>(DirectSprings::default(), calls);
}

fn cloth_with<S: Scalar, I: Integrator>(integrator: I, calls: &[ClothCall]) {
    let s = S::from_f64;
    let settings = Settings {
        gravity: Vec3::new(s(0.0), s(-9.81), s(0.0)),
        damping: s(0.5),
        ..Settings::default()
    };
    let m = Material {
        stiffness: s(300.0),
        damping: s(0.5),
    };
    let mut cloth: Sail<S, I> = Cloth::rectangle(
        Vec3::new(s(-2.0), s(0.0), s(-2.0)),
        Vec3::new(s(4.0), s(0.0), s(0.0)),
        Vec3::new(s(0.0), s(0.0), s(4.0)),
        s(1.0),
        [m, m, m],
        settings.with_integrator(integrator),
    )
    .unwrap();
    cloth.pin_column(0).unwrap();
    survives(&mut cloth, calls, apply_cloth, |c| {
        (c.positions(), c.velocities(), c.settings().bounds)
    });
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn f32_ropes_in_scenes_survive_hostile_calls(calls in prop::collection::vec(scene_call(), 1..40)) {
        scene_holds_up::<f32>(&calls);
    }

    #[test]
    fn f64_ropes_in_scenes_survive_hostile_calls(calls in prop::collection::vec(scene_call(), 1..40)) {
        scene_holds_up::<f64>(&calls);
    }

    #[test]
    fn q16_ropes_in_scenes_survive_hostile_calls(calls in prop::collection::vec(scene_call(), 1..40)) {
        scene_holds_up::<Q16>(&calls);
    }

    #[test]
    fn f32_cloths_survive_hostile_calls(calls in prop::collection::vec(cloth_call(), 1..30)) {
        cloth_holds_up::<f32>(&calls);
    }

    #[test]
    fn f64_cloths_survive_hostile_calls(calls in prop::collection::vec(cloth_call(), 1..30)) {
        cloth_holds_up::<f64>(&calls);
    }

    #[test]
    fn q16_cloths_survive_hostile_calls(calls in prop::collection::vec(cloth_call(), 1..30)) {
        cloth_holds_up::<Q16>(&calls);
    }
}

/// Every constructor's arguments from hostile numbers: ends, a length, a mass, a material
/// and gravity.
#[derive(Clone, Debug)]
struct Make {
    end: [f64; 3],
    length: f64,
    mass: f64,
    stiffness: f64,
    damping: f64,
    gravity: [f64; 3],
    dt: f64,
}

fn make() -> impl Strategy<Value = Make> {
    let xyz = || [hostile(), hostile(), hostile()];
    (
        xyz(),
        hostile(),
        hostile(),
        hostile(),
        hostile(),
        xyz(),
        hostile(),
    )
        .prop_map(
            |(end, length, mass, stiffness, damping, gravity, dt)| Make {
                end,
                length,
                mass,
                stiffness,
                damping,
                gravity,
                dt,
            },
        )
}

impl Make {
    fn settings<P: Point>(&self) -> Settings<P> {
        Settings {
            gravity: point(&self.gravity),
            ..Settings::default()
        }
    }

    fn material<S: Scalar>(&self) -> Material<S> {
        Material {
            stiffness: S::from_f64(self.stiffness),
            damping: S::from_f64(self.damping),
        }
    }
}

/// Builds a rope, a hanging rope, a spline rope and a cloth from `m`: each refuses, or
/// starts in range and steps once (refused or not) with every position still in range.
fn made_holds_up<S: Scalar>(m: &Make) {
    let s = S::from_f64;
    let (origin2, origin3) = (
        Vec2::new(S::ZERO, S::ZERO),
        Vec3::new(S::ZERO, S::ZERO, S::ZERO),
    );
    let (end, mass, material) = (point::<Vec2<S>>(&m.end), s(m.mass), m.material::<S>());
    let dt = s(m.dt);
    // A floor a little below the start, touched at the curve, reporting its impulse.
    let floor = Touching {
        dt: m.dt,
        colliders: vec![ColliderSpec {
            kind: 2,
            a: [0.0, -0.5, 0.0],
            b: [0.0, 1.0, 0.0],
            c: [0.0; 2],
            radius: 0.0,
            velocity: None,
            friction: Some((0.5, 0.3)),
            restitution: None,
            mass: None,
        }],
        thickness: 0.05,
        touch: 5,
        impulses: 1,
    };
    let in_range = |what: &str, points: &[Vec2<S>]| {
        assert!(
            points.iter().all(|p| p.in_safe_range()),
            "{what}: {points:?}"
        );
    };
    if let Ok(mut rope) = Rope::<Vec2<S>, 8>::new(origin2, end, mass, material, m.settings()) {
        in_range("rope", rope.positions());
        let _ = rope.step(dt);
        in_range("rope", rope.positions());
        floor
            .run(|dt, contacts| rope.step_touching(dt, (), contacts))
            .ok();
        in_range("rope", rope.positions());
    }
    let hung = Rope::<Vec2<S>, 8>::hanging(origin2, end, s(m.length), mass, material, m.settings());
    if let Ok(mut rope) = hung {
        in_range("hanging rope", rope.positions());
        let _ = rope.step(dt);
        in_range("hanging rope", rope.positions());
    }
    let spline = SplineRope::<Vec2<S>, 8>::new(origin2, end, mass, material, m.settings());
    if let Ok(mut rope) = spline {
        in_range("spline rope", rope.positions());
        let energy = rope.energy();
        // Past a float format's range (a mass near its largest value) it overflows to ±∞.
        assert!(!energy.to_f64().is_nan(), "{m:?}: energy {energy:?}");
        let _ = rope.step(dt);
        in_range("spline rope", rope.positions());
        floor
            .run(|dt, contacts| rope.step_touching(dt, (), contacts))
            .ok();
        in_range("spline rope", rope.positions());
    }
    let (du, dv) = (point::<Vec3<S>>(&m.end), point::<Vec3<S>>(&m.gravity));
    let sheet =
        Cloth::<Vec3<S>, 4, 4>::rectangle(origin3, du, dv, mass, [material; 3], m.settings());
    if let Ok(mut cloth) = sheet {
        assert!(cloth.positions().iter().all(|p| p.in_safe_range()));
        let _ = cloth.step(dt);
        assert!(
            cloth.positions().iter().all(|p| p.in_safe_range()),
            "{cloth:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn f32_anything_made_from_hostile_numbers_holds_up(m in make()) {
        made_holds_up::<f32>(&m);
    }

    #[test]
    fn f64_anything_made_from_hostile_numbers_holds_up(m in make()) {
        made_holds_up::<f64>(&m);
    }

    #[test]
    fn q16_anything_made_from_hostile_numbers_holds_up(m in make()) {
        made_holds_up::<Q16>(&m);
    }
}

/// Curves, smoothed rows, flattening, sample counts and the fixed-step clock from hostile
/// numbers.
#[derive(Clone, Debug)]
struct Shapes {
    points: [(f64, f64); 8],
    method: u8,
    t: f64,
    span: usize,
    accuracy: f64,
    len: usize,
    frames: [f64; 4],
}

fn shapes() -> impl Strategy<Value = Shapes> {
    let xy = || (hostile(), hostile());
    (
        [xy(), xy(), xy(), xy(), xy(), xy(), xy(), xy()],
        (0..5u8, hostile(), prop_oneof![0..9usize, Just(usize::MAX)]),
        (
            hostile(),
            0..70usize,
            [hostile(), hostile(), hostile(), hostile()],
        ),
    )
        .prop_map(
            |(points, (method, t, span), (accuracy, len, frames))| Shapes {
                points,
                method,
                t,
                span,
                accuracy,
                len,
                frames,
            },
        )
}

/// What the curve modules promise for any input: no panic; a refusal or points in range
/// (within the curve's box where the curve is convex); lengths, weights and counts finite.
fn shapes_hold_up<S: Scalar>(c: &Shapes) {
    let s = S::from_f64;
    let points: [Vec2<S>; 8] = c.points.map(|(x, y)| Vec2::new(s(x), s(y)));
    let (t, accuracy) = (s(c.t), s(c.accuracy));
    let mut out = vec![Vec2::new(S::ZERO, S::ZERO); c.len];
    if let Ok(curve) = Bezier::new(points) {
        // Within the control points' box, to a few units of rounding of the largest coordinate.
        let (bx, largest) = (curve.bounding_box(), curve.polygon_length());
        let slack = 8.0 * S::EPSILON.to_f64() * (1.0 + largest.to_f64().abs());
        let inside = |p: Vec2<S>| {
            p.in_safe_range()
                && (0..2).all(|d| {
                    let x = p.coord(d).to_f64();
                    x >= bx.min.coord(d).to_f64() - slack && x <= bx.max.coord(d).to_f64() + slack
                })
        };
        assert!(inside(curve.eval(t)), "{:?}", curve.eval(t));
        let (a, b) = curve.split(t);
        assert!(a.points().iter().chain(b.points()).all(|p| inside(*p)));
        let tangent = curve.tangent(t);
        assert!(tangent.is_finite() || S::FIXED_POINT, "{tangent:?}");
        assert!(!curve.arclen(accuracy).to_f64().is_nan());
        if let Ok(n) = curve.sample(&mut out) {
            assert!(n <= c.len && out[..n].iter().all(|p| inside(*p)));
        }
        let cubic = Bezier::new([points[0], points[1], points[2], points[3]]).unwrap();
        if let Ok(n) = dunas::flatten::flatten(&cubic, accuracy, &mut out) {
            assert!(n <= c.len && out[..n].iter().all(|p| p.in_safe_range()));
        }
        if let Ok(n) = dunas::lod::segments(&curve, accuracy) {
            assert!((1..=dunas::lod::MAX_SEGMENTS).contains(&n));
        }
    }
    let method = [
        Smoothing::Bezier,
        Smoothing::BSpline,
        Smoothing::CatmullRom,
        Smoothing::Polyline,
        Smoothing::NaturalSpline,
    ][c.method as usize];
    for smoothed in [
        Smoothed::open(method, &points),
        Smoothed::closed(method, &points),
    ]
    .into_iter()
    .flatten()
    {
        if let Ok(n) = smoothed.sample(&mut out) {
            assert!(n <= c.len && out[..n].iter().all(|p| p.is_finite()));
        }
        assert!(smoothed.point(c.span, t).is_finite());
        let mut weights = [S::ZERO; 8];
        smoothed.weights(c.span, t, &mut weights);
        let sum: f64 = weights.iter().map(|w| w.to_f64()).sum();
        assert!((sum - 1.0).abs() < 1e-3, "{weights:?}");
        assert!(!smoothed.length(accuracy).to_f64().is_nan());
    }
    if let Ok(mut clock) = FixedTimestep::new(s(c.accuracy), s(c.t)) {
        for frame in c.frames {
            assert!(clock.advance(s(frame)) <= clock.max_steps());
            let alpha = clock.alpha();
            assert!(alpha >= S::ZERO && alpha <= S::ONE, "{alpha:?}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn f32_shapes_hold_up(c in shapes()) {
        shapes_hold_up::<f32>(&c);
    }

    #[test]
    fn f64_shapes_hold_up(c in shapes()) {
        shapes_hold_up::<f64>(&c);
    }

    #[test]
    fn q16_shapes_hold_up(c in shapes()) {
        shapes_hold_up::<Q16>(&c);
    }
}
