//! Build script: the device linker script and the float-math backend.
//!
//! - `-Tlink.x` (cortex-m-rt's linker script, which includes the package's `memory.x`) is
//!   passed to the examples only when building for a bare-metal target, so host builds,
//!   tests and a user's own firmware are untouched.
//! - The float backend is chosen once here: `std`'s math on hosted targets with the `std`
//!   feature, otherwise `libm` (always available on bare-metal targets, where `std` cannot
//!   exist, so the default features still build for a microcontroller).

use std::env;

fn main() {
    println!("cargo:rerun-if-changed=memory.x");
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
