//! The scripted scene of `examples/common/golden.rs` in a `.wasm` that node runs directly
//! (`web/golden.mjs`): its 600 frames' state checksums folded into one, in Q16.16 and in
//! f32, which must equal `tests/golden.txt`'s, as on the host and the microcontrollers.
//!
//! `cargo build --release -p dunas-golden --target wasm32-unknown-unknown`, then
//! `node web/golden.mjs`. It also plays the scene a frame a call (`begin`, `advance`), so
//! that `web/devices.mjs` can time each frame in Chromium.

#[path = "../../../examples/common/golden.rs"]
mod golden;

/// The scene's folded checksums in Q16.16 (0 if it failed).
#[unsafe(no_mangle)]
pub extern "C" fn golden_q16() -> u64 {
    golden::hashes::<dunas::Q16>().unwrap_or(0)
}

/// The scene's folded checksums in f32 (0 if it failed).
#[unsafe(no_mangle)]
pub extern "C" fn golden_f32() -> u64 {
    golden::hashes::<f32>().unwrap_or(0)
}

use std::cell::RefCell;

/// The scene `begin` made, in the format it asked for.
enum Playing {
    Q16(golden::Scene<dunas::Q16>),
    F32(golden::Scene<f32>),
}

thread_local! {
    static PLAYING: RefCell<Option<Playing>> = const { RefCell::new(None) };
}

/// Starts the scene afresh: in Q16.16 for `format` 0, in f32 otherwise; 1 if it started.
#[unsafe(no_mangle)]
pub extern "C" fn begin(format: u32) -> u32 {
    let scene = if format == 0 {
        golden::Scene::new().map(Playing::Q16)
    } else {
        golden::Scene::new().map(Playing::F32)
    };
    let started = scene.is_ok();
    PLAYING.with(|p| *p.borrow_mut() = scene.ok());
    u32::from(started)
}

/// One frame of the scene `begin` started; 1 if it stepped.
#[unsafe(no_mangle)]
pub extern "C" fn advance() -> u32 {
    PLAYING.with(|p| {
        let stepped = match p.borrow_mut().as_mut() {
            Some(Playing::Q16(scene)) => scene.advance().is_ok(),
            Some(Playing::F32(scene)) => scene.advance().is_ok(),
            None => false,
        };
        u32::from(stepped)
    })
}
