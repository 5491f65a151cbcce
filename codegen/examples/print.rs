//! Print the generated module for one dimension: `cargo run -p noslip-codegen --example print -- 3`.
fn main() {
    let dim = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(2);
    print!("{}", noslip_codegen::generate(dim, "crate").source);
}
