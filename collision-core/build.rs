//! Generates the kernels of the enabled dimensions (features `d2`..`d6`) into OUT_DIR (see
//! noslip-codegen): the scalar `kernels_{n}.rs` and the batch `batch_{n}.rs`.
use std::path::PathBuf;

fn main() {
    let out_dir = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let dims =
        noslip_codegen::DIMS.filter(|d| std::env::var_os(format!("CARGO_FEATURE_D{d}")).is_some());
    let dims: Vec<usize> = dims.collect();
    noslip_codegen::generate_into(&out_dir, dims.iter().copied(), "crate")
        .expect("write generated kernels to OUT_DIR");
    for dim in dims {
        let module = noslip_codegen::batch::generate(dim, "crate");
        let path = out_dir.join(noslip_codegen::batch::file_name(dim));
        noslip_codegen::write_if_changed(&path, &module.source)
            .expect("write generated batch kernels to OUT_DIR");
    }
    // The generator is a build dependency: cargo rebuilds this script when it changes.
    // The script reads no other input.
    println!("cargo:rerun-if-changed=build.rs");
}
