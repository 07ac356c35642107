//! Build script: the device linker script and the float-math backend.
//!
//! - `-Tlink.x` (cortex-m-rt's linker script, which includes the package's `memory.x`) is
//!   passed to the examples only when building for a bare-metal target, so host builds,
//!   tests and a user's own firmware are untouched.
//! - The float backend is chosen once here: `std`'s math on hosted targets with the `std`
//!   feature, otherwise `libm` (always available on bare-metal targets, where `std` cannot
//!   exist, so the default features still build for a microcontroller).
//! - `Q16`'s product is the 64-bit one (`dunas_wide_mul`) where the core multiplies into 64
//!   bits in an instruction or two: a 64-bit target, or RISC-V with its `M` extension
//!   (`mul` and `mulh`: the RISC-V rope's frame 4.8% and the coil's 9.6% cheaper than in
//!   16-bit halves, bit for bit the same); elsewhere (a Cortex-M0) 16-bit halves.

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
    println!("cargo::rustc-check-cfg=cfg(dunas_wide_mul)");
    let target = |key: &str| env::var(format!("CARGO_CFG_{key}")).unwrap_or_default();
    let riscv_m =
        target("TARGET_ARCH") == "riscv32" && target("TARGET_FEATURE").split(',').any(|f| f == "m");
    if target("TARGET_POINTER_WIDTH") == "64" || riscv_m {
        println!("cargo:rustc-cfg=dunas_wide_mul");
    }
    let std_math = feature("STD") && !bare_metal;
    if std_math {
        println!("cargo:rustc-cfg=dunas_std");
    }
    if std_math || feature("LIBM") || bare_metal {
        println!("cargo:rustc-cfg=dunas_floats");
    }
}
