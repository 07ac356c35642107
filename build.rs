//! Build script: the device linker script and the float-math backend.
//!
//! - The device's memory layout is copied to `OUT_DIR/memory.x` for cortex-m-rt's `link.x`:
//!   `memory-m4f.x` for a Cortex-M4F (`thumbv7em`), `memory-m0.x` (the micro:bit's) otherwise;
//!   no file in the package is named `memory.x`, which the linker would find first;
//!   `-Tlink.x` is passed to the examples only when building for a bare-metal target, so
//!   host builds and tests are untouched.
//! - The float backend is chosen once here: `std`'s math on hosted targets with the `std`
//!   feature, otherwise `libm` (always available on bare-metal targets, where `std` cannot
//!   exist, so the default features still build for a microcontroller).

use std::env;
use std::fs;
use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let target = env::var("TARGET").unwrap_or_default();
    let layout = if target.starts_with("thumbv7em") {
        "memory-m4f.x"
    } else {
        "memory-m0.x"
    };
    fs::copy(layout, out.join("memory.x")).expect("the memory layouts sit next to Cargo.toml");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory-m0.x");
    println!("cargo:rerun-if-changed=memory-m4f.x");
    println!("cargo:rerun-if-changed=build.rs");

    let bare_metal = env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("none");
    if bare_metal {
        println!("cargo:rustc-link-arg-examples=-Tlink.x");
    }

    let feature = |name: &str| env::var_os(format!("CARGO_FEATURE_{name}")).is_some();
    println!("cargo::rustc-check-cfg=cfg(dunas_std)");
    println!("cargo::rustc-check-cfg=cfg(dunas_floats)");
    let std_math = feature("STD") && !bare_metal;
    if std_math {
        println!("cargo:rustc-cfg=dunas_std");
    }
    if std_math || feature("LIBM") || bare_metal {
        println!("cargo:rustc-cfg=dunas_floats");
    }
}
