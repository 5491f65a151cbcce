//! The OpenCL back end is faithful where it runs: the emitted OpenCL C kernels
//! (`kernels_source`: `noslip_kernels.cl` without its certified companions, which
//! `opencl_certified.rs` builds and runs), built once by the
//! OpenCL implementation (PoCL on the CPU in CI) with `-cl-fp32-correctly-rounded-divide-sqrt`,
//! its batch kernels run on 10^5 cases per dimension (n = 2..6), kernel (`free`, `fixed`,
//! `free_fma`, `fixed_fma`) and format (`f64`, `f32`) from every regime of the accuracy
//! report, return bit for bit the Rust kernels' results (`tests/backend`), and every `f64`
//! result is finite. The source is also compiled by clang's OpenCL front end.
//!
//! Without an OpenCL device (or headers, or clang) the test says so on stderr and passes, unless
//! `NOSLIP_REQUIRE_OPENCL` is set (CI sets it in `.ci/run`), when it fails.

use crate::backend;
#[path = "opencl_backend/conserve.rs"]
mod conserve;

use backend::{
    compare, draw, opencl, records, rust_results, scratch, Float, KERNELS, LAWS, WALTON_LAWS,
};
use collision_core::{
    BodyState, Generated, Kernel, Restitution, RoughKernel, Scalar, Walton, WaltonKernel,
};
use noslip_accuracy::case::Case;
use noslip_accuracy::regime::Regime;
use noslip_codegen::backend::{file_name, kernels_source, Lang};
use std::fmt::Write;
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
    std::fs::write(&source, kernels_source(Lang::OpenCl, &[2, 3, 4, 5, 6])).unwrap();

    const TEST: &str = "OpenCL faithfulness test";
    let Some(host) = opencl::host_for(TEST, &source, &dir) else {
        return;
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

/// Cases per dimension, rough kernel and format.
const ROUGH_CASES: usize = 20_000;

/// The law of case `k`: the [`LAWS`] in turn, so every law meets every regime.
fn law_of<T: Float>(k: usize) -> Restitution<T> {
    let (e, beta) = LAWS[k % LAWS.len()];
    Restitution::new(T::from_f64(e), T::from_f64(beta)).expect("in range")
}

/// The law of case `k` for the Walton kernels: the [`WALTON_LAWS`] in turn.
fn walton_law_of<T: Float>(k: usize) -> Walton<T> {
    let [e, mu, beta0] = WALTON_LAWS[k % WALTON_LAWS.len()].map(T::from_f64);
    Walton::new(e, mu, beta0).expect("in range")
}

/// The flattened state `(U, u)`.
fn flat<T: Float, const N: usize, const S: usize>(s: &BodyState<T, N, S>) -> Vec<T> {
    s.spin
        .iter()
        .chain(&s.velocity)
        .copied()
        .collect::<Vec<T>>()
}

/// One kernel of dimension `N` in format `T` with a per-contact law: its input records (the
/// batch kernel's parameters in order, `law(k)` for record `k`) and the Rust results
/// (`run(k, case)`), as the host's list mode reads and writes them.
fn law_records<T: Float, const N: usize, const S: usize>(
    kernel: &str,
    cases: &[(Regime, Case<T, N, S>)],
    law: impl Fn(usize) -> Vec<T>,
    run: impl Fn(usize, &Case<T, N, S>) -> Vec<BodyState<T, N, S>>,
) -> (Vec<u8>, Vec<T>) {
    let (mut bytes, mut rust) = (Vec::new(), Vec::new());
    for (k, (_, c)) in cases.iter().enumerate() {
        let (nu, [b1, b2], [s1, s2]) = (&c.nu, c.ball_refs(), c.state_refs());
        let ball = |b: &collision_core::Ball<T>| vec![b.inv_mass, b.radius, b.gamma2];
        let first: Vec<T> = if kernel.contains("fixed") {
            vec![b1.radius]
        } else {
            ball(b1)
        };
        let values = nu
            .iter()
            .copied()
            .chain(first)
            .chain(ball(b2))
            .chain(law(k))
            .chain(flat(s1))
            .chain(flat(s2));
        for v in values {
            bytes.extend(v.bytes());
        }
        for b in &run(k, c) {
            rust.extend(flat(b));
        }
    }
    (bytes, rust)
}

/// One rough kernel: [`law_records`] under [`law_of`].
fn rough_records<T: Float, const N: usize, const S: usize>(
    kernel: &str,
    cases: &[(Regime, Case<T, N, S>)],
) -> (Vec<u8>, Vec<T>)
where
    Generated: RoughKernel<T, N, S>,
{
    let law = |k: usize| {
        let l = law_of::<T>(k);
        vec![l.e, l.beta]
    };
    law_records(kernel, cases, law, |k, c| {
        let law = law_of::<T>(k);
        let (nu, [b1, b2], [s1, s2]) = (&c.nu, c.ball_refs(), c.state_refs());
        match kernel {
            "rough_free" => Generated::rough_free(nu, b1, b2, &law, s1, s2).to_vec(),
            "rough_free_fma" => Generated::rough_free_fma(nu, b1, b2, &law, s1, s2).to_vec(),
            "rough_fixed" => vec![Generated::rough_fixed(nu, &b1.radius, b2, &law, s1, s2)],
            _ => vec![Generated::rough_fixed_fma(nu, &b1.radius, b2, &law, s1, s2)],
        }
    })
}

/// One Walton kernel: [`law_records`] under [`walton_law_of`].
fn walton_records<T: Float, const N: usize, const S: usize>(
    kernel: &str,
    cases: &[(Regime, Case<T, N, S>)],
) -> (Vec<u8>, Vec<T>)
where
    Generated: WaltonKernel<T, N, S>,
{
    let law = |k: usize| {
        let l = walton_law_of::<T>(k);
        vec![l.e, l.mu, l.beta0]
    };
    law_records(kernel, cases, law, |k, c| {
        let law = walton_law_of::<T>(k);
        let (nu, [b1, b2], [s1, s2]) = (&c.nu, c.ball_refs(), c.state_refs());
        match kernel {
            "walton_free" => Generated::walton_free(nu, b1, b2, &law, s1, s2).to_vec(),
            "walton_free_fma" => Generated::walton_free_fma(nu, b1, b2, &law, s1, s2).to_vec(),
            "walton_fixed" => vec![Generated::walton_fixed(nu, &b1.radius, b2, &law, s1, s2)],
            _ => vec![Generated::walton_fixed_fma(
                nu, &b1.radius, b2, &law, s1, s2,
            )],
        }
    })
}

/// The host's list lines (written with the case files) or the comparison, for dimension `N`:
/// every rough and Walton kernel in both formats.
fn rough_dim<const N: usize, const S: usize>(dir: &Path, list: Option<&mut String>) -> Vec<String>
where
    Generated: RoughKernel<f64, N, S>
        + RoughKernel<f32, N, S>
        + WaltonKernel<f64, N, S>
        + WaltonKernel<f32, N, S>,
{
    let cases = draw::<N, S>(ROUGH_CASES, 240 + N as u64);
    let mut failures = Vec::new();
    let mut list = list;
    for kernel in backend::ROUGH_KERNELS {
        let (f64s, f32s) = (&cases.f64, &cases.f32);
        let r64 = rough_records(kernel, f64s);
        let r32 = rough_records(kernel, f32s);
        let laws = format!("laws {LAWS:?}");
        failures.extend(law_format(
            dir,
            kernel,
            f64s,
            r64,
            2,
            &laws,
            list.as_deref_mut(),
        ));
        failures.extend(law_format(
            dir,
            kernel,
            f32s,
            r32,
            2,
            &laws,
            list.as_deref_mut(),
        ));
    }
    for kernel in backend::WALTON_KERNELS {
        let (f64s, f32s) = (&cases.f64, &cases.f32);
        let r64 = walton_records(kernel, f64s);
        let r32 = walton_records(kernel, f32s);
        let laws = format!("laws {WALTON_LAWS:?}");
        failures.extend(law_format(
            dir,
            kernel,
            f64s,
            r64,
            3,
            &laws,
            list.as_deref_mut(),
        ));
        failures.extend(law_format(
            dir,
            kernel,
            f32s,
            r32,
            3,
            &laws,
            list.as_deref_mut(),
        ));
    }
    failures
}

/// Write one kernel's records and its list line (`list` given), or compare the host's
/// results with `records`' Rust ones; `law_len` is the law's length, `laws` says which.
fn law_format<T: Float, const N: usize, const S: usize>(
    dir: &Path,
    kernel: &str,
    cases: &[(Regime, Case<T, N, S>)],
    (bytes, rust): (Vec<u8>, Vec<T>),
    law_len: usize,
    laws: &str,
    list: Option<&mut String>,
) -> Vec<String> {
    let format = <T as Scalar>::NAME;
    let name = format!("noslip_d{N}_{kernel}_{format}");
    let state = S + N;
    match list {
        Some(list) => {
            std::fs::write(dir.join(format!("{name}.bin")), bytes).unwrap();
            let (first, outs) = if kernel.contains("fixed") {
                (1, format!("{state}"))
            } else {
                (3, format!("{state},{state}"))
            };
            let _ = writeln!(
                list,
                "{format} {name} {N},{first},3,{law_len},{state},{state} {outs}"
            );
            Vec::new()
        }
        None => {
            let out = dir.join(format!("{name}.out"));
            let cl = match std::fs::read(&out) {
                Ok(b) => T::from_bytes(&b),
                Err(e) => return vec![format!("{}: {e}", out.display())],
            };
            let what = format!("n = {N}, {kernel} {format} (OpenCL, {laws})");
            compare(&what, cases, &rust, &cl)
                .err()
                .into_iter()
                .collect()
        }
    }
}

/// The rough-ball and Walton batch kernels return the Rust kernels' bits, each record under
/// one of [`LAWS`] or [`WALTON_LAWS`] (the law is a per-contact array of the batch kernel).
#[test]
fn opencl_rough_kernels_are_bit_identical_to_the_rust_kernels() {
    let dir = scratch("opencl-backend-rough");
    let source = dir.join(file_name(Lang::OpenCl));
    std::fs::write(&source, kernels_source(Lang::OpenCl, &[2, 3, 4, 5, 6])).unwrap();
    const TEST: &str = "OpenCL rough-kernel faithfulness test";
    let Some(host) = opencl::host_for(TEST, &source, &dir) else {
        return;
    };
    let mut list = String::new();
    for n in collision_core::DIMS.iter().copied() {
        collision_core::with_dim!(
            n,
            |N, S| rough_dim::<N, S>(&dir, Some(&mut list)),
            unreachable!("a compiled dimension")
        );
    }
    let list_file = dir.join("rough.txt");
    std::fs::write(&list_file, list).unwrap();
    if let Err(why) = opencl::run_host(&host, &source, &dir, Some(&list_file)) {
        return opencl::skip(TEST, &why);
    }
    let mut failures = Vec::new();
    for n in collision_core::DIMS.iter().copied() {
        failures.extend(collision_core::with_dim!(
            n,
            |N, S| rough_dim::<N, S>(&dir, None),
            unreachable!("a compiled dimension")
        ));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
