//! The cross-crate tests, one module a file, compiled as one test binary:
//! `cargo test -p noslip-tests --test all MODULE::` runs one file's tests (the C and OpenCL
//! back ends' tests need a C compiler, clang and an OpenCL implementation: docs/backends.md).

mod backend;

mod c_backend;
mod c_certified;
mod exact_backends;
mod kernels_exact;
mod kernels_f64;
mod opencl_backend;
mod opencl_certified;
mod rough;
mod scene_backends;
mod walton;
