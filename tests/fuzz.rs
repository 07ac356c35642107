//! Random sequences of the public calls on a rope and on a spline rope (with each of its
//! steppers), with hostile values (NaN, ±∞, 0, huge, negative, `usize::MAX`, empty and tiny
//! buffers), in `f32`, `f64` and `Q16`. After every call: nothing panicked, every position
//! and velocity is finite and in range, and a call that returned an error left the rope
//! exactly as it was. And ropes and spline ropes built from random lengths, masses,
//! stiffnesses, dampings and gravities, stepped at random frame lengths: the same, and the
//! spline ropes' energy bounded.
#![cfg(all(feature = "std", feature = "fixed"))]

use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::force::{AnchorSpring, Wind};
use dunas::integrator::{
    ExplicitEuler, ImplicitEuler, Integrator, Rk4, SymplecticEuler, Verlet, Xpbd,
};
use dunas::prelude::*;
use dunas::spline_rope::{Bdf2, SplineRope, SplineStepper};
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

fn hostile() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => -100.0..100.0f64,
        2 => 0.0..0.1f64,
        1 => prop::sample::select(vec![
            f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -0.0, 1e-300, -1.0,
            1e4, -1e4, 16_383.0, 40_000.0, 1e30, f64::MAX, f64::MIN,
        ]),
    ]
}

fn index() -> impl Strategy<Value = usize> {
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
    let (a, b, mass, material, settings) = start::<S>();
    Rope::new(a, b, mass, material, settings).unwrap()
}

/// Makes the call; `Err` when the rope refused it, `Ok` otherwise.
fn apply<S: Scalar>(rope: &mut Rope<Vec2<S>, 8>, call: &Call) -> Result<(), Error> {
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

fn holds_up<S: Scalar>(calls: &[Call]) {
    let mut rope = rope::<S>();
    survives(&mut rope, calls, apply, |r| {
        (r.positions(), r.velocities(), r.settings().bounds)
    });
}

/// Makes each call on `rope`, then checks what the module promises: a refused call changed
/// nothing, and every position (`state`: positions, velocities, bounds) is in range.
fn survives<R: std::fmt::Debug, C: std::fmt::Debug, S: Scalar>(
    rope: &mut R,
    calls: &[C],
    apply: impl Fn(&mut R, &C) -> Result<(), Error>,
    state: impl Fn(&R) -> (&[Vec2<S>], &[Vec2<S>], S),
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
                p.x.abs() <= bounds && p.y.abs() <= bounds,
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
    StepInWind {
        dt: f64,
        drag: f64,
        gust: f64,
    },
    StepTouching {
        dt: f64,
        x: f64,
        y: f64,
        radius: f64,
        thickness: f64,
    },
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
        2 => (hostile(), hostile(), hostile(), hostile(), hostile()).prop_map(
            |(dt, x, y, radius, thickness)| StepTouching { dt, x, y, radius, thickness }
        ),
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
        SplineCall::StepTouching {
            dt,
            x,
            y,
            radius,
            thickness,
        } => {
            let ball = [Collider::ball(v(x, y), s(radius))?];
            let contacts = Contacts::new(&ball, s(thickness), Touch::Particles)?;
            rope.step_touching(s(dt), (), &contacts).map(drop)
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
    built_holds_up::<S, _, 4>(SymplecticEuler, b);
    built_holds_up::<S, _, 5>(SymplecticEuler, b);
    built_holds_up::<S, _, 8>(SymplecticEuler, b);
    built_holds_up::<S, _, 16>(SymplecticEuler, b);
    built_holds_up::<S, _, 8>(ImplicitEuler::default(), b);
    built_holds_up::<S, _, 16>(ImplicitEuler::default(), b);
    built_holds_up::<S, _, 8>(Bdf2::default(), b);
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
