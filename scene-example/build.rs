//! The build-script API: kernels specialised to three shipped 2D scenes.
fn main() {
    noslip_codegen::specialise::Config::new()
        .compile_scenes(&[
            "../scenes/disk_between_walls.toml",
            "../scenes/gas2d.toml",
            "../scenes/sinai.toml",
        ])
        .expect("generate the scene kernels");
    println!("cargo:rerun-if-changed=build.rs");
}
