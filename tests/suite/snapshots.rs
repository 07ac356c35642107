//! Snapshot tests: the rope demo's frames, drawn from a deterministic scene, against text
//! checked in under `tests/snapshots/`. Run with `UPDATE_SNAPSHOTS=1` to rewrite them after a
//! deliberate change, and review the diff.
#![cfg(feature = "std")]

use std::path::Path;

use crate::rope_scene;

use dunas::{Point, Vec2};

fn check(name: &str, actual: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/snapshots")
        .join(name);
    if std::env::var_os("UPDATE_SNAPSHOTS").is_some() {
        std::fs::write(&path, actual).expect("write snapshot");
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e} (run with UPDATE_SNAPSHOTS=1 to create it)",
            path.display()
        )
    });
    if expected != actual {
        panic!("{name} differs from its snapshot.\n--- expected\n{expected}\n--- actual\n{actual}");
    }
}

#[test]
fn rope_demo_frames_match_their_snapshots() {
    let mut scene = rope_scene::Scene::new();
    for (at, name) in [
        (0.4f32, "rope_0.4s.txt"),
        (1.6, "rope_1.6s.txt"),
        (2.3, "rope_2.3s.txt"),
    ] {
        while scene.time() < at - 1e-3 {
            scene.step(1.0 / 60.0);
        }
        let frame: String = scene
            .render(false)
            .iter()
            .map(|l| format!("{}\n", l.trim_end()))
            .collect();
        check(name, &frame);
        eprintln!("{name}: drawn lengths {:?}", scene.drawn().map(length));
        holds_its_properties(&scene);
    }
}

fn length(line: &[Vec2<f32>]) -> f32 {
    line.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// What every frame must show, whatever its snapshot: the smoothed rope is outside the pegs
/// (radius 1.5), each drawn rope starts at the hand,
/// and is as long as the rope (70 units) stretched by at most 3% under the swinging weight
/// (tension up to 3·m·g on a whole-rope stiffness of 1500 per unit: about 2%), and at least
/// as long as the straight line from its first point to its last.
fn holds_its_properties(scene: &rope_scene::Scene) {
    // The smoothed rope touches the pegs with its drawn curve: no drawn point is inside one.
    for (x, y) in rope_scene::PEGS {
        let peg = dunas::Vec2::new(x, y);
        for p in scene.drawn()[0] {
            assert!(p.distance(peg) >= 1.5, "{p:?} inside the peg at {peg:?}");
        }
    }
    let hand = scene.held_at();
    for line in scene.drawn() {
        assert_eq!(line[0], hand, "the pinned end is where the hand is");
        let (len, chord) = (length(line), line[0].distance(line[line.len() - 1]));
        assert!(
            len <= 70.0 * 1.03 && len >= chord,
            "drawn length {len}, chord {chord}"
        );
    }
}
