use dunas::prelude::*;

#[test]
fn yank() {
    let q = Q16::from_f64;
    let settings = Settings {
        gravity: Vec2::new(q(0.0), q(-150.0)),
        damping: q(0.3),
        ..Settings::default()
    };
    let material = Material {
        stiffness: q(300.0),
        damping: q(1.0),
    };
    let mut rope: Rope<Vec2<Q16>, 10> = Rope::new(
        Vec2::new(q(0.0), q(0.0)),
        Vec2::new(q(90.0), q(0.0)),
        q(2.0),
        material,
        settings,
    )
    .unwrap();
    let dt = Q16::ratio(1, 60);
    let hand = Vec2::new(q(1500.0), q(-1500.0));
    let (mut sat, mut div) = (0, 0);
    for f in 0..600 {
        rope.set_position(0, hand).unwrap();
        match rope.step(dt) {
            Ok(i) => {
                if i.saturated {
                    sat += 1
                }
            }
            Err(_) => div += 1,
        }
        if f % 100 == 0 {
            println!(
                "f{f} {:?}",
                rope.positions()
                    .iter()
                    .map(|p| (p.x.to_f64() as i32, p.y.to_f64() as i32))
                    .collect::<Vec<_>>()
            );
        }
    }
    println!("sat {sat} div {div}");
    let (mut sat, mut div) = (0, 0);
    for f in 0..3600 {
        rope.set_position(0, Vec2::new(q(0.0), q(0.0))).unwrap();
        match rope.step(dt) {
            Ok(i) => {
                if i.saturated {
                    sat += 1
                }
            }
            Err(_) => div += 1,
        }
        if f % 300 == 0 {
            println!(
                "back f{f} {:?} v {:?}",
                rope.positions()
                    .iter()
                    .map(|p| (p.x.to_f64() as i32, p.y.to_f64() as i32))
                    .collect::<Vec<_>>(),
                rope.velocities()
                    .iter()
                    .map(|p| (p.x.to_f64() as i32, p.y.to_f64() as i32))
                    .collect::<Vec<_>>()
            );
        }
    }
    println!("sat {sat} div {div}");
}
