//! Print the generated module for one dimension: `cargo run -p noslip-codegen --example print -- 3`
//! (the scalar kernels) or `... -- 3 batch` (the batch kernels).
fn main() {
    let mut args = std::env::args().skip(1);
    let dim = args.next().and_then(|a| a.parse().ok()).unwrap_or(2);
    if args.next().as_deref() == Some("batch") {
        print!("{}", noslip_codegen::batch::generate(dim, "crate").source);
    } else {
        print!("{}", noslip_codegen::generate(dim, "crate").source);
    }
}
