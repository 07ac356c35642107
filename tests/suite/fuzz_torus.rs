//! Random sequences of the public calls on a torus blown up by its gas (steps with the gas,
//! contacts of every kind, positions, snap limits, letting the gas out, drawing through
//! closed tables), with hostile values, in `f32`, `f64` and `Q16`: nothing panics, every
//! position and velocity stays finite and in range, a refused call leaves the torus as it
//! was, and what it draws is finite with unit or zero normals. And tori built from hostile
//! numbers: refused with an `Err`, or built and stepped without a NaN.
#![cfg(all(feature = "std", feature = "fixed"))]

use super::fuzz::{Touching, hostile, smoothing, snap, survives, touching};
use dunas::Torus;
use dunas::force::Pressure;
use dunas::prelude::*;
use dunas::surface::SurfaceTable;
use proptest::prelude::*;

/// A public call on a torus, with its arguments.
#[derive(Clone, Debug)]
enum TorusCall {
    Blow {
        dt: f64,
        amount: f64,
    },
    Touch(Touching, f64),
    SetPosition(usize, [f64; 3]),
    SetVelocity(usize, [f64; 3]),
    Snap([(u8, f64); 3]),
    Pop(f64),
    Draw {
        smoothing: u8,
        count: usize,
        len: usize,
    },
}

fn torus_call() -> impl Strategy<Value = TorusCall> {
    use TorusCall::*;
    let xyz = || [hostile(), hostile(), hostile()];
    let limit = || (0..3u8, hostile());
    let particle = || prop_oneof![0..30usize, Just(30), Just(usize::MAX)];
    prop_oneof![
        4 => (hostile(), hostile()).prop_map(|(dt, amount)| Blow { dt, amount }),
        3 => (touching(), hostile()).prop_map(|(t, amount)| Touch(t, amount)),
        1 => (particle(), xyz()).prop_map(|(i, p)| SetPosition(i, p)),
        1 => (particle(), xyz()).prop_map(|(i, v)| SetVelocity(i, v)),
        1 => [limit(), limit(), limit()].prop_map(Snap),
        1 => hostile().prop_map(Pop),
        1 => (0..5u8, 0..40usize, 0..400usize)
            .prop_map(|(smoothing, count, len)| Draw { smoothing, count, len }),
    ]
}

type Tube<S> = Torus<S, 6, 5>;

/// Makes the call on the torus; `Err` when refused.
fn apply_torus<S: Scalar>(t: &mut Tube<S>, call: &TorusCall) -> Result<(), Error> {
    let s = S::from_f64;
    let v = |[x, y, z]: [f64; 3]| Vec3::new(s(x), s(y), s(z));
    match call {
        TorusCall::Blow { dt, amount } => {
            let mut gas = Pressure::new(s(*amount))?;
            t.step_with(s(*dt), &mut gas).map(drop)
        }
        TorusCall::Touch(touching, amount) => {
            let mut gas = Pressure::new(s(*amount))?;
            touching.run(|dt, contacts| t.step_touching(dt, &mut gas, contacts))
        }
        TorusCall::SetPosition(i, p) => t.set_position(*i, v(*p)),
        TorusCall::SetVelocity(i, p) => t.set_velocity(*i, v(*p)),
        TorusCall::Snap(limits) => t.set_snap(limits.map(snap)),
        TorusCall::Pop(amount) => {
            let mut gas = Pressure::at(s(*amount), t.volume())?;
            gas.pop();
            assert_eq!(gas.amount(), S::ZERO);
            Ok(())
        }
        TorusCall::Draw {
            smoothing: code,
            count,
            len,
        } => {
            let tu = SurfaceTable::<S, 6, 31>::closed(smoothing(*code), *count)?;
            let tv = SurfaceTable::<S, 5, 31>::closed(smoothing(*code), *count)?;
            let mut points = vec![Vec3::new(S::ZERO, S::ZERO, S::ZERO); *len];
            let mut normals = points.clone();
            let n = t.draw(&tu, &tv, &mut points, &mut normals)?;
            assert!(n <= *len);
            assert!(points[..n].iter().all(|p| p.is_finite()));
            for m in &normals[..n] {
                let l = m.length().to_f64();
                assert!(
                    m.is_finite() && (l == 0.0 || (l - 1.0).abs() < 0.05),
                    "{m:?}"
                );
            }
            Ok(())
        }
    }
}

fn torus_holds_up<S: Scalar>(calls: &[TorusCall]) {
    let s = S::from_f64;
    let settings = Settings {
        gravity: Vec3::new(s(0.0), s(-9.81), s(0.0)),
        damping: s(0.3),
        ..Settings::default()
    };
    let m = Material {
        stiffness: s(300.0),
        damping: s(0.5),
    };
    let mut t: Tube<S> = Torus::new(
        Vec3::new(s(0.0), s(1.0), s(0.0)),
        s(1.0),
        s(0.3),
        s(1.0),
        [m, m, m],
        settings,
    )
    .unwrap();
    survives(&mut t, calls, apply_torus, |t| {
        (t.positions(), t.velocities(), t.settings().bounds)
    });
    assert!(t.volume().is_finite() || S::FIXED_POINT);
}

/// A torus built from hostile numbers: refused, or stepped a second with hostile gas and
/// no NaN.
fn torus_builds<S: Scalar>(numbers: [f64; 6]) {
    let s = S::from_f64;
    let [radius, tube, mass, stiffness, amount, y] = numbers;
    let m = Material {
        stiffness: s(stiffness),
        damping: s(0.5),
    };
    let settings = Settings {
        gravity: Vec3::new(s(0.0), s(-9.81), s(0.0)),
        ..Settings::default()
    };
    let Ok(mut t) = Tube::<S>::new(
        Vec3::new(s(0.0), s(y), s(0.0)),
        s(radius),
        s(tube),
        s(mass),
        [m; 3],
        settings,
    ) else {
        return;
    };
    let Ok(mut gas) = Pressure::new(s(amount)) else {
        return;
    };
    for _ in 0..60 {
        if t.step_with(s(1.0 / 60.0), &mut gas).is_err() {
            break;
        }
    }
    assert!(
        t.positions()
            .iter()
            .chain(t.velocities())
            .all(|p| p.in_safe_range())
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn f32_tori_survive_hostile_calls(calls in prop::collection::vec(torus_call(), 1..25)) {
        torus_holds_up::<f32>(&calls);
    }

    #[test]
    fn f64_tori_survive_hostile_calls(calls in prop::collection::vec(torus_call(), 1..25)) {
        torus_holds_up::<f64>(&calls);
    }

    #[test]
    fn q16_tori_survive_hostile_calls(calls in prop::collection::vec(torus_call(), 1..25)) {
        torus_holds_up::<Q16>(&calls);
    }

    #[test]
    fn tori_of_any_build_hold_up(numbers in [hostile(), hostile(), hostile(), hostile(), hostile(), hostile()]) {
        torus_builds::<f32>(numbers);
        torus_builds::<f64>(numbers);
        torus_builds::<Q16>(numbers);
    }
}
