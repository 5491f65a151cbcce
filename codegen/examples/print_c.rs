//! Print the generated C (or, with `opencl`, OpenCL C) kernels of the given dimensions:
//! `cargo run -p noslip-codegen --example print_c -- c 2 3`.
use noslip_codegen::backend::{generate, Lang};

fn main() {
    let mut args = std::env::args().skip(1);
    let lang = match args.next().as_deref() {
        Some("opencl") => Lang::OpenCl,
        _ => Lang::C,
    };
    let dims: Vec<usize> = args.map(|a| a.parse().expect("a dimension")).collect();
    let dims = if dims.is_empty() { vec![2] } else { dims };
    print!("{}", generate(lang, &dims));
}
