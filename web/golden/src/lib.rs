//! The scripted scene of `examples/common/golden.rs` in a `.wasm` that node runs directly
//! (`web/golden.mjs`): its 600 frames' state checksums folded into one, in Q16.16 and in
//! f32, which must equal `tests/golden.txt`'s, as on the host and the microcontrollers.
//!
//! `cargo build --release -p dunas-golden --target wasm32-unknown-unknown`, then
//! `node web/golden.mjs`.

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
