//! The OpenCL back end is faithful where it runs: the emitted OpenCL C, built once by the
//! OpenCL implementation (PoCL on the CPU in CI) with `-cl-fp32-correctly-rounded-divide-sqrt`,
//! its batch kernels run on 10^5 cases per dimension (n = 2..6), kernel (`free`, `fixed`,
//! `free_fma`, `fixed_fma`) and format (`f64`, `f32`) from every regime of the accuracy
//! report, return bit for bit the Rust kernels' results (`tests/backend`), and every `f64`
//! result is finite. The source is also compiled by clang's OpenCL front end.
//!
//! Without an OpenCL device (or headers, or clang) the test says so on stderr and passes, unless
//! `NOSLIP_REQUIRE_OPENCL` is set (CI sets it in `.ci/run`), when it fails.

mod backend;

use backend::{compare, draw, opencl, records, rust_results, scratch, Float, KERNELS};
use collision_core::{Generated, Kernel, Scalar};
use noslip_accuracy::case::Case;
use noslip_accuracy::regime::Regime;
use noslip_codegen::backend::{file_name, generate, Lang};
use std::path::Path;

const CASES: usize = 100_000;

fn write_cases<T: Float, const N: usize, const S: usize>(
    dir: &Path,
    cases: &[(Regime, Case<T, N, S>)],
) {
    let input = dir.join(format!("cases_{N}_{}.bin", <T as Scalar>::NAME));
    std::fs::write(input, records(cases)).unwrap();
}

fn compare_format<T: Float, const N: usize, const S: usize>(
    dir: &Path,
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<String>
where
    Generated: Kernel<T, N, S>,
{
    let mut failures = Vec::new();
    for kernel in KERNELS {
        let name = <T as Scalar>::NAME;
        let out = dir.join(format!("{N}_{kernel}_{name}.out"));
        let bytes = match std::fs::read(&out) {
            Ok(b) => b,
            Err(e) => {
                failures.push(format!("{}: {e}", out.display()));
                continue;
            }
        };
        let what = format!("n = {N}, {kernel} {name} (OpenCL)");
        if let Err(e) = compare(
            &what,
            cases,
            &rust_results(kernel, cases),
            &T::from_bytes(&bytes),
        ) {
            failures.push(e);
        }
    }
    failures
}

/// Write dimension `N`'s case files (seeded: [`check`] draws the same cases again).
fn prepare<const N: usize, const S: usize>(dir: &Path) {
    let cases = draw::<N, S>(CASES, 140 + N as u64);
    write_cases(dir, &cases.f64);
    write_cases(dir, &cases.f32);
}

/// Compare dimension `N`'s OpenCL results with the Rust kernels on the cases of [`prepare`].
fn check<const N: usize, const S: usize>(dir: &Path) -> Vec<String>
where
    Generated: Kernel<f64, N, S> + Kernel<f32, N, S>,
{
    let cases = draw::<N, S>(CASES, 140 + N as u64);
    let mut failures = compare_format(dir, &cases.f64);
    failures.extend(compare_format(dir, &cases.f32));
    failures
}

#[test]
fn opencl_kernels_are_bit_identical_to_the_rust_kernels() {
    let dir = scratch("opencl-backend");
    let source = dir.join(file_name(Lang::OpenCl));
    std::fs::write(&source, generate(Lang::OpenCl, &[2, 3, 4, 5, 6])).unwrap();

    const TEST: &str = "OpenCL faithfulness test";
    if let Err(why) = opencl::clang_check(&source) {
        return opencl::skip(TEST, &why);
    }
    let host = match opencl::build_host(&dir) {
        Ok(host) => host,
        Err(why) => return opencl::skip(TEST, &why),
    };
    for n in collision_core::DIMS.iter().copied() {
        collision_core::with_dim!(
            n,
            |N, S| prepare::<N, S>(&dir),
            unreachable!("a compiled dimension")
        );
    }
    if let Err(why) = opencl::run_host(&host, &source, &dir, None) {
        return opencl::skip(TEST, &why);
    }
    let mut failures = Vec::new();
    for n in collision_core::DIMS.iter().copied() {
        failures.extend(collision_core::with_dim!(
            n,
            |N, S| check::<N, S>(&dir),
            unreachable!("a compiled dimension")
        ));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
