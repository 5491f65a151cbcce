//! Generates the kernels for n = 2..6 into OUT_DIR (see noslip-codegen).
use std::path::PathBuf;

fn main() {
    let out_dir = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    noslip_codegen::generate_into(&out_dir, noslip_codegen::DIMS, "crate")
        .expect("write generated kernels to OUT_DIR");
    // The generator is a build dependency: cargo rebuilds this script when it changes.
    // The script reads no other input.
    println!("cargo:rerun-if-changed=build.rs");
}
