//! Breaking, cutting and holding, against references nobody tuned: the static tension of a
//! hanging chain, conservation of momentum and mass, and a ballistic arc.

use dunas::Error;
use dunas::breaking::Piece;
use dunas::prelude::*;
use dunas::spring::Snap;

const G: f64 = 9.81;

/// A vertical rope of 8 particles, 7 m and 1 kg, hanging from the origin, with a bob of
/// `bob` kg on its end, settled (no snapping) for 12 s.
fn hanging(bob: f64) -> Rope<Vec2<f64>, 8> {
    let settings = Settings {
        gravity: Vec2::new(0.0, -G),
        damping: 2.0,
        ..Settings::default()
    };
    let material = Material {
        stiffness: 3000.0,
        damping: 20.0,
    };
    let mut rope = Rope::new(
        Vec2::new(0.0, 0.0),
        Vec2::new(0.0, -7.0),
        1.0,
        material,
        settings,
    )
    .unwrap();
    rope.hang(7, bob).unwrap();
    for _ in 0..720 {
        let _ = rope.step(1.0 / 60.0).unwrap();
    }
    rope
}

/// The static tension of the top spring: the bob and the rope below that spring's middle
/// (the pinned particle's half segment hangs on the support), `(m_bob + m·(1 - 1/14))·g`.
fn top_tension(bob: f64) -> f64 {
    (bob + 1.0 - 1.0 / 14.0) * G
}

#[test]
fn a_rope_with_a_bob_snaps_at_its_static_tension() {
    for bob in [0.5, 2.0, 10.0] {
        let tension = top_tension(bob);
        // Just above the tension it holds.
        let mut holds = hanging(bob);
        holds.set_snap(Snap::Tension(tension * 1.01)).unwrap();
        for _ in 0..120 {
            assert_eq!(holds.step(1.0 / 60.0).unwrap().snapped, 0, "bob {bob}");
        }
        assert_eq!(holds.pieces().count(), 1);
        // Just below, it snaps at the top, and only there.
        let mut snaps = hanging(bob);
        snaps.set_snap(Snap::Tension(tension * 0.99)).unwrap();
        assert_eq!(snaps.step(1.0 / 60.0).unwrap().snapped, 1, "bob {bob}");
        let pieces: Vec<_> = snaps.pieces().collect();
        assert_eq!(pieces, vec![0..1, 1..8]);
    }
}

#[test]
fn a_stretch_limit_is_a_length() {
    let mut rope = hanging(2.0);
    // The top spring is stretched by tension / k over its rest length of 1 m.
    let extension = top_tension(2.0) / 3000.0;
    rope.set_snap(Snap::Stretch(1.0 + extension * 1.01))
        .unwrap();
    assert_eq!(rope.step(1.0 / 60.0).unwrap().snapped, 0);
    rope.set_spring_snap(0, Snap::Stretch(1.0 + extension * 0.99))
        .unwrap();
    assert_eq!(rope.step(1.0 / 60.0).unwrap().snapped, 1);
}

#[test]
fn a_broken_spring_never_comes_back() {
    let mut rope = hanging(1.0);
    rope.set_spring_snap(3, Snap::Stretch(1.0001)).unwrap();
    assert_eq!(rope.step(1.0 / 60.0).unwrap().snapped, 1);
    // Put the two halves back together, at rest: nothing joins them, and the lower half
    // falls freely while the upper one hangs.
    let rest: Vec<_> = (0..8).map(|i| Vec2::new(0.0, -(i as f64))).collect();
    for (i, &p) in rest.iter().enumerate() {
        rope.set_position(i, p).unwrap();
        if i > 0 {
            rope.set_velocity(i, Vec2::default()).unwrap();
        }
    }
    for _ in 0..60 {
        assert_eq!(rope.step(1.0 / 60.0).unwrap().snapped, 0);
        assert!(!rope.topology().joins(3, 4));
    }
    assert_eq!(rope.pieces().collect::<Vec<_>>(), vec![0..4, 4..8]);
    let gap = rope.positions()[3].y - rope.positions()[4].y;
    assert!(gap > 2.0, "the lower piece fell {gap} m away");
}

/// Σ m·v over the free particles, from their inverse masses.
fn momentum(rope: &Rope<Vec2<f64>, 8>) -> Vec2<f64> {
    let mut p = Vec2::default();
    for (&w, &v) in rope.inv_masses().iter().zip(rope.velocities()) {
        if w > 0.0 {
            p += v * (1.0 / w);
        }
    }
    p
}

#[test]
fn releasing_a_bob_conserves_momentum() {
    let mut rope = hanging(3.0);
    rope.set_velocity(7, Vec2::new(4.0, 1.0)).unwrap();
    rope.set_velocity(5, Vec2::new(-1.0, 0.5)).unwrap();
    let before = momentum(&rope);
    let penguin = rope.release(7, 3.0).unwrap();
    let after = momentum(&rope) + penguin.momentum();
    assert!(
        (after - before).length() <= 1e-12 * before.length(),
        "{before:?} {after:?}"
    );
    assert_eq!(penguin.velocity, Vec2::new(4.0, 1.0));
    assert_eq!(penguin.mass, 3.0);
    // The particle keeps its own share of the rope, 1/14 kg.
    assert!((1.0 / rope.inv_masses()[7] - 1.0 / 14.0).abs() < 1e-12);
}

#[test]
fn a_cut_rope_keeps_its_mass_in_its_pieces() {
    let mut rope = hanging(0.0001);
    let total: f64 = rope.inv_masses()[1..].iter().map(|w| 1.0 / w).sum();
    let (mut points, mut pieces) = ([Vec2::default(); 64], [Piece::EMPTY; 8]);
    rope.draw(Smoothing::CatmullRom, &mut points, &mut pieces)
        .unwrap();
    // A swipe across the rope 2.5 m down: between particles 2 and 3.
    let hit = rope
        .cut(
            &points,
            &pieces[..1],
            Vec2::new(-1.0, -2.5),
            Vec2::new(1.0, -2.5),
        )
        .unwrap();
    assert_eq!(hit, Some(2));
    let n = rope
        .draw(Smoothing::CatmullRom, &mut points, &mut pieces)
        .unwrap();
    assert_eq!(n, 2);
    let mass = |r: &core::ops::Range<usize>| -> f64 {
        r.clone()
            .filter(|&i| rope.inv_masses()[i] > 0.0)
            .map(|i| 1.0 / rope.inv_masses()[i])
            .sum()
    };
    let pieces_mass: f64 = pieces[..n].iter().map(|p| mass(&p.particles)).sum();
    assert!((pieces_mass - total).abs() < 1e-12);
    // Each piece's curve starts and ends on its end particles.
    for p in &pieces[..n] {
        assert_eq!(points[p.points.start], rope.positions()[p.particles.start]);
        assert_eq!(
            points[p.points.end - 1],
            rope.positions()[p.particles.end - 1]
        );
    }
    // The same swipe again finds nothing left to cut there.
    let again = rope
        .cut(
            &points,
            &pieces[..n],
            Vec2::new(-1.0, -2.5),
            Vec2::new(1.0, -2.5),
        )
        .unwrap();
    assert_eq!(again, None);
}

/// A smoothed rope is cut where it was drawn: a swipe through the drawn curve between two
/// particles cuts that span, even where the particles' own polygon is far from the swipe.
#[test]
fn a_swipe_cuts_where_the_rope_was_drawn() {
    let settings = Settings {
        gravity: Vec2::new(0.0, -9.8),
        damping: 1.0,
        ..Settings::default()
    };
    let m = Material {
        stiffness: 500.0,
        damping: 1.0,
    };
    let mut rope: Rope<Vec2<f32>, 4> =
        Rope::new(Vec2::new(-3.0, 0.0), Vec2::new(3.0, 0.0), 1.0, m, settings).unwrap();
    rope.set_inv_mass(3, 0.0).unwrap();
    for _ in 0..300 {
        let _ = rope.step(1.0 / 60.0).unwrap();
    }
    let (mut points, mut pieces) = ([Vec2::default(); 31], [Piece::EMPTY; 4]);
    rope.draw(Smoothing::NaturalSpline, &mut points, &mut pieces)
        .unwrap();
    // The drawn point halfway along the middle span, and a short swipe through it.
    let mid = points[15];
    let hit = rope
        .cut(
            &points,
            &pieces[..1],
            mid + Vec2::new(0.05, 0.1),
            mid - Vec2::new(0.05, 0.1),
        )
        .unwrap();
    assert_eq!(hit, Some(1));
}

#[test]
fn bad_input_is_an_error_and_changes_nothing() {
    let mut rope = hanging(1.0);
    assert!(matches!(
        rope.set_snap(Snap::Stretch(1.0)),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        rope.set_snap(Snap::Stretch(f64::NAN)),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        rope.set_snap(Snap::Tension(-1.0)),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(rope.set_spring_snap(99, Snap::Stretch(2.0)).is_err());
    let (mut points, mut pieces) = ([Vec2::default(); 16], [Piece::EMPTY; 1]);
    rope.draw(Smoothing::BSpline, &mut points, &mut pieces)
        .unwrap();
    let before = rope.clone();
    let nan = Vec2::new(f64::NAN, 0.0);
    assert!(rope.cut(&points, &pieces, nan, Vec2::default()).is_err());
    let wrong = [Piece {
        particles: 0..9,
        points: 0..16,
    }];
    assert!(matches!(
        rope.cut(&points, &wrong, Vec2::new(-1.0, -3.0), Vec2::new(1.0, -3.0)),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        rope.release(8, 1.0),
        Err(Error::IndexOutOfRange { .. })
    ));
    assert_eq!(rope.release(0, 1.0), Err(Error::Pinned { index: 0 }));
    assert!(matches!(
        rope.release(7, 5.0),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        rope.hang(3, f64::NAN),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        rope.move_pinned(0, Vec2::new(1.0, 0.0), 0.0),
        Err(Error::InvalidParameter { .. })
    ));
    assert_eq!(rope.positions(), before.positions());
    assert_eq!(rope.inv_masses(), before.inv_masses());
    assert_eq!(rope.topology().as_slice(), before.topology().as_slice());
    // Too small buffers.
    let mut few = [Vec2::default(); 4];
    assert!(matches!(
        rope.draw(Smoothing::BSpline, &mut few, &mut pieces),
        Err(Error::BufferTooSmall { .. })
    ));
}

/// A tiny deterministic generator (xorshift), so the soak needs no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// 10⁵ random swipes, snap limits, grabs and releases on a rope in the game loop: every
/// position stays finite, and no call panics.
#[test]
fn positions_stay_finite_through_random_cuts_and_breaks() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let settings = Settings {
        gravity: Vec2::new(0.0, -200.0),
        damping: 0.1,
        ..Settings::default()
    };
    let m = Material {
        stiffness: 300.0,
        damping: 0.5,
    };
    let fresh = || -> Rope<Vec2<f32>, 8> {
        Rope::new(Vec2::new(0.0, 0.0), Vec2::new(70.0, 0.0), 7.0, m, settings).unwrap()
    };
    let mut rope = fresh();
    let (mut points, mut pieces) = ([Vec2::default(); 40], [Piece::EMPTY; 8]);
    let (mut cuts, mut snaps) = (0, 0);
    for op in 0..100_000 {
        let r = |rng: &mut Rng, scale: f64| ((rng.next() - 0.5) * scale) as f32;
        let n = rope
            .draw(Smoothing::CatmullRom, &mut points, &mut pieces)
            .unwrap();
        match op % 5 {
            0 => {
                // Most swipes go through a drawn point; some are anywhere.
                let aim = points[(rng.next() * pieces[n - 1].points.end as f64) as usize];
                let reach = Vec2::new(r(&mut rng, 30.0), r(&mut rng, 30.0));
                let (from, to) = if rng.next() < 0.8 {
                    (aim + reach, aim - reach)
                } else {
                    (reach * 10.0, aim * 2.0)
                };
                cuts += usize::from(rope.cut(&points, &pieces[..n], from, to).unwrap().is_some());
            }
            1 => {
                let ratio = 1.0 + rng.next() as f32 * 0.5 + 1e-3;
                let spring = (rng.next() * 8.0) as usize;
                let _ = rope.set_spring_snap(spring, Snap::Stretch(ratio));
            }
            2 => {
                let hand = Vec2::new(r(&mut rng, 40.0), r(&mut rng, 40.0));
                rope.move_pinned(0, hand, 1.0 / 60.0).unwrap();
            }
            3 => {
                let i = 1 + (rng.next() * 7.0) as usize;
                if rng.next() < 0.5 {
                    let _ = rope.hang(i, rng.next() as f32 * 5.0);
                } else {
                    let _ = rope.release(i, rng.next() as f32 * 5.0);
                }
            }
            _ => {}
        }
        snaps += usize::from(rope.step(1.0 / 60.0).unwrap().snapped);
        assert!(
            rope.positions()
                .iter()
                .all(|p| p.x.is_finite() && p.y.is_finite()),
            "op {op}"
        );
        if rope.pieces().count() == 8 || op % 997 == 0 {
            rope = fresh();
        }
    }
    eprintln!("{cuts} cuts, {snaps} snaps");
    assert!(cuts > 5000 && snaps > 300, "{cuts} cuts, {snaps} snaps");
}

use crate::catapult;

/// The catapult example's penguin lands where the closed-form arc from its release point and
/// velocity lands (the flight is stepped frame by frame, the landing found on the last
/// frame's chord), within a centimetre over some 18 m.
#[test]
fn the_catapult_penguin_lands_on_its_closed_form_arc() {
    let mut game = catapult::Catapult::new();
    while !matches!(game.penguin, catapult::Penguin::Landed { .. }) {
        assert!(game.time() < 30.0, "the penguin never landed");
        game.step();
    }
    let catapult::Penguin::Landed { x, from, launch } = game.penguin else {
        unreachable!()
    };
    let exact = catapult::landing_x(from, launch, -9.81);
    assert!(
        launch.x > 1.0 && launch.y > 1.0,
        "thrown up and forward: {launch:?}"
    );
    assert!(
        (x - exact).abs() < 0.01,
        "landed at {x}, the arc lands at {exact}"
    );
    assert!(exact > 5.0, "the throw carried {exact} m");
}

/// A rope tied by its end to a corner of a cloth: the pair keeps its momentum at every weld,
/// and the tie holds (the two points coincide after every frame).
#[test]
fn a_rope_welded_to_a_cloth_keeps_momentum() {
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.2,
        ..Settings::default()
    };
    let m = Material {
        stiffness: 800.0,
        damping: 1.0,
    };
    let mut sheet: Cloth<Vec3<f64>, 5, 5> = Cloth::rectangle(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        1.0,
        [m, m, m],
        Settings {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            damping: 0.2,
            ..Settings::default()
        },
    )
    .unwrap();
    sheet.pin_row(0).unwrap();
    let mut rope: Rope<Vec3<f64>, 6> = Rope::new(
        Vec3::new(2.0, 0.0, 2.0),
        Vec3::new(2.0, -2.5, 2.0),
        0.5,
        m,
        settings,
    )
    .unwrap();
    // The rope hangs from the sheet's free corner (24), not from a pin.
    rope.let_go(0, 20.0).unwrap(); // its end's own 0.05 kg
    let momentum = |w: &[f64], v: &[Vec3<f64>], k: usize| {
        if w[k] > 0.0 {
            v[k] * (1.0 / w[k])
        } else {
            Vec3::default()
        }
    };
    for _ in 0..240 {
        let _ = sheet.step(1.0 / 60.0).unwrap();
        let _ = rope.step(1.0 / 60.0).unwrap();
        let before = momentum(sheet.inv_masses(), sheet.velocities(), 24)
            + momentum(rope.inv_masses(), rope.velocities(), 0);
        rope.weld(0, &mut sheet, 24).unwrap();
        let after = momentum(sheet.inv_masses(), sheet.velocities(), 24)
            + momentum(rope.inv_masses(), rope.velocities(), 0);
        assert!((after - before).length() <= 1e-12 * (1.0 + before.length()));
        assert_eq!(rope.positions()[0], sheet.positions()[24]);
    }
    // The corner carries the rope: it hangs lower than the sheet's other free corner.
    assert!(sheet.positions()[24].y < sheet.positions()[20].y - 0.05);
    assert!(rope.weld(6, &mut sheet, 0).is_err());
}

fn curtain() -> Cloth<Vec3<f64>, 6, 6> {
    let m = Material {
        stiffness: 600.0,
        damping: 0.5,
    };
    let settings = Settings {
        gravity: Vec3::new(0.0, -9.81, 0.0),
        damping: 0.5,
        ..Settings::default()
    };
    let mut c = Cloth::rectangle(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.5, 0.0, 0.0),
        Vec3::new(0.0, -2.5, 0.0),
        1.0,
        [m, m, m],
        settings,
    )
    .unwrap();
    c.pin_row(0).unwrap();
    c
}

/// A swipe across a hanging curtain tears every spring it crosses, and the part below falls.
#[test]
fn a_swipe_tears_a_cloth() {
    let mut c = curtain();
    // Between rows 2 and 3 (y = -1 and -1.5): every vertical, diagonal and bending spring
    // across the line y = -1.25, and nothing else.
    let torn = c
        .cut(Vec2::new(-1.0, -1.25), Vec2::new(3.5, -1.25))
        .unwrap();
    // 6 structural + 2·5 shear + 6 bending from row 1 and 6 from row 2.
    assert_eq!(torn, 6 + 10 + 12);
    for _ in 0..60 {
        let _ = c.step(1.0 / 60.0).unwrap();
    }
    assert!(
        c.positions()[3 * 6].y < -1.5 - 2.0,
        "the lower part fell: {:?}",
        c.positions()[18]
    );
    assert!(
        c.positions()[2 * 6].y > -1.2,
        "the upper part hangs: {:?}",
        c.positions()[12]
    );
    assert!(c.cut(Vec2::new(f64::NAN, 0.0), Vec2::default()).is_err());
}

/// A cloth weighed down past its structural springs' stretch limit tears, and keeps tearing
/// no further than its springs allow: a torn spring stays torn.
#[test]
fn an_overloaded_cloth_tears() {
    let mut c = curtain();
    c.set_snap([Snap::Stretch(1.2), Snap::Never, Snap::Never])
        .unwrap();
    let mut snapped = 0;
    for _ in 0..60 {
        snapped += c.step(1.0 / 60.0).unwrap().snapped;
    }
    assert_eq!(snapped, 0, "its own weight does not tear it");
    for i in 30..36 {
        c.hang(i, 20.0).unwrap();
    }
    for _ in 0..120 {
        snapped += c.step(1.0 / 60.0).unwrap().snapped;
    }
    assert!(snapped > 0);
    let torn = (0..6)
        .flat_map(|j| (0..6).map(move |i| (i, j)))
        .filter(|&(i, j)| c.topology().is_torn(1, i, j))
        .count();
    assert!(torn > 0 && torn <= 30);
    assert!(!c.topology().is_torn(9, 0, 0) && !c.topology().is_torn(0, 99, 0));
    assert!(matches!(
        c.set_snap([Snap::Stretch(0.5), Snap::Never, Snap::Never]),
        Err(Error::InvalidParameter { .. })
    ));
}
