//! The build-script API: kernels specialised to three shipped 2D scenes, and to a Walton box
//! (`walton_box.toml`, for the tests).
fn main() {
    noslip_codegen::specialise::Config::new()
        .compile_scenes(&[
            "../scenes/disk_between_walls.toml",
            "../scenes/gas2d.toml",
            "../scenes/sinai.toml",
            "walton_box.toml",
        ])
        .expect("generate the scene kernels");
    println!("cargo:rerun-if-changed=build.rs");
}
