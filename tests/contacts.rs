//! Contacts against references nobody tuned: a peg thinner than the particle spacing, Coulomb
//! friction on a slope, and a restitution that adds no energy.
#![cfg(any(feature = "std", feature = "libm"))]

use dunas::collider::Collider;
use dunas::contact::{Contacts, Touch};
use dunas::prelude::*;

/// An 8-particle rope, 7 m long (particles 1 m apart), let go taut above a peg of `radius`
/// at the middle of a span (between particles 3 and 4) with its ends then held 6 m apart,
/// settled for 6 s; returns the drawn B-spline and the peg's centre. Without the peg it
/// would sag about 1.5 m.
fn draped(radius: f64, touch: Touch) -> (Vec<Vec2<f64>>, Vec2<f64>) {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.8),
        damping: 2.0,
        ..Settings::default()
    };
    let material = Material {
        stiffness: 3000.0,
        damping: 2.0,
    };
    let mut rope: Rope<Vec2<f64>, 8> = Rope::new(
        Vec2::new(-3.5, 0.0),
        Vec2::new(3.5, 0.0),
        1.0,
        material,
        settings,
    )
    .unwrap();
    rope.set_inv_mass(7, 0.0).unwrap();
    rope.set_position(0, Vec2::new(-3.0, 0.0)).unwrap();
    rope.set_position(7, Vec2::new(3.0, 0.0)).unwrap();
    let centre = Vec2::new(0.0, -1.0);
    let peg = [Collider::ball(centre, radius).unwrap()];
    let contacts = Contacts::new(&peg, 0.0, touch).unwrap();
    for _ in 0..360 {
        rope.step_touching(1.0 / 60.0, (), &contacts).unwrap();
    }
    let mut curve = vec![Vec2::default(); 4096];
    let n = rope.sample(Smoothing::BSpline, &mut curve).unwrap();
    curve.truncate(n);
    (curve, centre)
}

/// Deepest penetration of a drawn curve into a ball (0 when clear).
fn penetration(curve: &[Vec2<f64>], centre: Vec2<f64>, radius: f64) -> f64 {
    curve
        .iter()
        .map(|p| radius - (*p - centre).length())
        .fold(0.0, f64::max)
}

/// (a) The module's promise: curve contacts hold a peg a tenth of the particle spacing
/// within 1% of its radius (plus the golden-section bracket); particle contacts let it
/// through, because no particle ever touches it.
#[test]
fn a_thin_peg_holds_the_drawn_rope_only_with_curve_contacts() {
    let spacing = 1.0;
    let radius = 0.1 * spacing;
    let (curve, centre) = draped(radius, Touch::Curve(Smoothing::BSpline));
    let deep = penetration(&curve, centre, radius);
    eprintln!("curve contacts: deepest {deep:.2e} for a peg of radius {radius:.3}");
    assert!(deep <= 0.01 * radius, "{deep}");
    // The rope really rests on it: its middle is at the peg's top, not 0.5 m below.
    let middle = curve[curve.len() / 2];
    assert!(
        (middle.y - (centre.y + radius)).abs() < 0.02,
        "middle {middle:?}"
    );

    let (curve, centre) = draped(radius, Touch::Particles);
    let lowest = curve.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
    eprintln!("particle contacts: lowest point {lowest:.3}");
    assert!(
        lowest < centre.y - radius,
        "the peg caught it anyway: {lowest}"
    );
}

/// (b) Coulomb friction, closed form: a block (here a short rope lying along the fall line)
/// on a slope of angle θ with friction μ stays put when tan θ < μ and slides when tan θ > μ.
/// Checked 1° either side of atan μ, and the slide against `½ g (sin θ - μ cos θ) t²`.
#[test]
fn a_rope_on_a_slope_sticks_below_atan_mu_and_slides_above() {
    let mu: f64 = 0.5;
    let critical = mu.atan().to_degrees();
    for (degrees, slides) in [
        (5.0, false),
        (15.0, false),
        (critical - 1.0, false),
        (critical + 1.0, true),
    ] {
        let theta = degrees.to_radians();
        let down = Vec2::new(theta.cos(), -theta.sin());
        let normal = Vec2::new(theta.sin(), theta.cos());
        let settings = Settings {
            gravity: Vec2::new(0.0, -9.8),
            ..Settings::default()
        };
        let material = Material {
            stiffness: 2000.0,
            damping: 1.0,
        };
        let start = normal * 0.01;
        let mut rope: Rope<Vec2<f64>, 6> =
            Rope::new(start, start + down * 1.0, 1.0, material, settings).unwrap();
        rope.set_inv_mass(0, 1.0 / 0.1).unwrap(); // free: Rope::new pins the first particle
        let slope = [Collider::half_space(Vec2::new(0.0, 0.0), normal)
            .unwrap()
            .with_friction(mu, mu)
            .unwrap()];
        let contacts = Contacts::new(&slope, 0.01, Touch::Particles).unwrap();
        for _ in 0..120 {
            rope.step_touching(1.0 / 60.0, (), &contacts).unwrap();
        }
        let moved = (rope.positions()[0] - start).dot(down);
        // Sliding for 2 s at g(sin θ - μ cos θ) from rest covers half that times 2².
        let closed_form = 0.5 * 9.8 * (theta.sin() - mu * theta.cos()) * 4.0;
        eprintln!(
            "{degrees:.1}°: moved {moved:.4} m down the slope (closed form {closed_form:.4})"
        );
        if slides {
            assert!(
                (moved - closed_form).abs() < 0.1 * closed_form,
                "{degrees}°: {moved}"
            );
        } else {
            assert!(moved.abs() < 1e-3, "{degrees}°: {moved}");
        }
    }
}

/// (e) A restitution of 0 adds no energy: a rope dropped on the ground never has more energy
/// than when it was let go.
#[test]
fn restitution_zero_adds_no_energy() {
    for touch in [Touch::Particles, Touch::Curve(Smoothing::CatmullRom)] {
        let settings = Settings {
            gravity: Vec2::new(0.0, -9.8),
            ..Settings::default()
        };
        let material = Material {
            stiffness: 2000.0,
            damping: 0.0,
        };
        let mut rope: Rope<Vec2<f64>, 8> = Rope::new(
            Vec2::new(0.0, 1.0),
            Vec2::new(2.0, 1.5),
            1.0,
            material,
            settings,
        )
        .unwrap();
        rope.set_inv_mass(0, 8.0 / 0.5).unwrap();
        let ground = [
            Collider::half_space(Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0))
                .unwrap()
                .with_friction(0.3, 0.2)
                .unwrap(),
        ];
        let contacts = Contacts::new(&ground, 0.02, touch).unwrap();
        let e0 = rope.energy();
        for _ in 0..300 {
            rope.step_touching(1.0 / 60.0, (), &contacts).unwrap();
            assert!(rope.energy() <= e0 + 1e-9 * e0.abs(), "{touch:?}");
        }
    }
}

/// Bad input is an error, never a panic.
#[test]
fn bad_contacts_are_refused() {
    let peg = [Collider::ball(Vec2::new(0.0f32, 0.0), 1.0).unwrap()];
    for bad in [-1.0, f32::NAN, f32::INFINITY, 1e30] {
        assert!(Contacts::new(&peg, bad, Touch::Particles).is_err(), "{bad}");
    }
}

/// Contacts raise the substeps up to the cap and never slow time: a thickness so small that
/// no substep count could keep up still steps the whole frame (it used to be `TooStiff`).
#[test]
fn contacts_never_slow_time() {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.8),
        ..Settings::default()
    };
    let material = Material {
        stiffness: 100.0,
        damping: 0.1,
    };
    let mut rope: Rope<Vec2<f32>, 8> = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(7.0, 0.0),
        1.0,
        material,
        settings,
    )
    .unwrap();
    rope.apply_impulse(7, Vec2::new(0.0, -5.0)).unwrap();
    let ground = [Collider::half_space(Vec2::new(0.0, -100.0), Vec2::new(0.0, 1.0)).unwrap()];
    for thickness in [1e-30, 0.5] {
        let contacts = Contacts::new(&ground, thickness, Touch::Particles).unwrap();
        let info = rope.step_touching(1.0 / 60.0, (), &contacts).unwrap();
        assert_eq!(info.simulated, 1.0 / 60.0, "{thickness}");
        assert!(!info.slow_motion, "{thickness}");
    }
    let contacts = Contacts::new(&ground, 1e-30, Touch::Particles).unwrap();
    let info = rope.step_touching(1.0 / 60.0, (), &contacts).unwrap();
    assert_eq!(info.substeps, dunas::system::MAX_SUBSTEPS);
}
