//! Snapshot tests: the rope demo's frames, drawn from a deterministic scene, against text
//! checked in under `tests/snapshots/`. Run with `UPDATE_SNAPSHOTS=1` to rewrite them after a
//! deliberate change, and review the diff.
#![cfg(feature = "std")]

#[path = "../examples/common/rope_scene.rs"]
mod rope_scene;

use std::path::Path;

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
    }
}
