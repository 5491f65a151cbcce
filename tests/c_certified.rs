//! The certified companions of the C header (`noslip_d{n}_{free|fixed}_certified_{f64|f32}`,
//! the fast ones `..._certified_fast_...`, and those of the FMA kernels
//! `noslip_d{n}_{free|fixed}_fma_certified_...`, which call `fma`/`fmaf`) are faithful: compiled by the system C compiler at `-O2 -ffp-contract=off` and at
//! `-O3 -march=native -ffp-contract=off`, they return bit for bit the Rust companions'
//! outputs and bounds (`collision_core::kernels::dN::certified`), and so the plain Rust
//! kernels' outputs (accuracy/tests/proven.rs checks the Rust companions against those and
//! against exact truth), on [`CASES`] cases per dimension (n = 2..6), kernel (`free`, `fixed`)
//! and format, drawn from every regime of the accuracy report.

mod backend;

use backend::{cc, compile_harness, draw, records, run, same, scratch, Float};
use collision_core::certified::{CertifiedKernel, Companion};
use collision_core::{BodyState, Generated, Scalar};
use noslip_accuracy::case::Case;
use noslip_accuracy::regime::Regime;
use noslip_codegen::backend::{generate, Lang};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Cases per dimension, kernel and format.
const CASES: usize = 5_000;

/// The companions compared: of the plain kernels, then of the FMA kernels.
const KERNELS: [&str; 8] = [
    "free",
    "fixed",
    "free_fast",
    "fixed_fast",
    "free_fma",
    "fixed_fma",
    "free_fma_fast",
    "fixed_fma_fast",
];

const CONFIGS: [(&str, &[&str]); 2] = [
    ("-O2", &["-O2", "-ffp-contract=off"]),
    (
        "-O3 -march=native",
        &["-O3", "-march=native", "-ffp-contract=off"],
    ),
];

fn state<T: Copy, const N: usize, const S: usize>(b: &BodyState<T, N, S>) -> Vec<T> {
    b.spin.iter().chain(&b.velocity).copied().collect()
}

/// The Rust companion `kernel` on every case, as the harness writes its results.
fn rust_results<T: Float, const N: usize, const S: usize>(
    kernel: &str,
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<T>
where
    Generated: CertifiedKernel<T, N, S>,
{
    let mut out = Vec::new();
    for (_, c) in cases {
        let (nu, [b1, b2], [s1, s2]) = (&c.nu, c.ball_refs(), c.state_refs());
        let (variant, companion) = match kernel.strip_suffix("_fast") {
            Some(v) => (v, Companion::Fast),
            None => (kernel, Companion::Running),
        };
        let bodies: Vec<BodyState<T, N, S>> = match variant {
            "free" => {
                let ([o1, o2], [e1, e2]) = Generated::free(companion, nu, b1, b2, s1, s2);
                vec![o1, o2, e1, e2]
            }
            "fixed" => {
                let (o, e) = Generated::fixed(companion, nu, &b1.radius, b2, s1, s2);
                vec![o, e]
            }
            "free_fma" => {
                let ([o1, o2], [e1, e2]) = Generated::free_fma(companion, nu, b1, b2, s1, s2);
                vec![o1, o2, e1, e2]
            }
            "fixed_fma" => {
                let (o, e) = Generated::fixed_fma(companion, nu, &b1.radius, b2, s1, s2);
                vec![o, e]
            }
            _ => panic!("no kernel {kernel}"),
        };
        for b in &bodies {
            out.extend(state(b));
        }
    }
    out
}

fn check_format<T: Float, const N: usize, const S: usize>(
    dir: &Path,
    exes: &[(&str, PathBuf)],
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<String>
where
    Generated: CertifiedKernel<T, N, S>,
{
    let input = dir.join(format!("cases_{N}_{}.bin", <T as Scalar>::NAME));
    std::fs::write(&input, records(cases)).unwrap();
    let mut failures = Vec::new();
    for kernel in KERNELS {
        let rust = rust_results(kernel, cases);
        assert!(rust.iter().any(|x| x.finite()), "no finite result");
        for (config, exe) in exes {
            let output = input.with_extension("out");
            run(Command::new(exe)
                .arg(N.to_string())
                .arg(kernel)
                .arg(<T as Scalar>::NAME)
                .arg(&input)
                .arg(&output));
            let c = T::from_bytes(&std::fs::read(&output).unwrap());
            let what = format!(
                "n = {N}, {kernel}_certified {} (cc {config})",
                <T as Scalar>::NAME
            );
            if c.len() != rust.len() {
                failures.push(format!(
                    "{what}: {} results, expected {}",
                    c.len(),
                    rust.len()
                ));
                continue;
            }
            let differ = (0..c.len()).filter(|&k| !same(c[k], rust[k])).count();
            if differ > 0 {
                let k = (0..c.len()).find(|&k| !same(c[k], rust[k])).unwrap();
                failures.push(format!(
                    "{what}: {differ} of {} values differ; the first at {k}: Rust {:?}, C {:?}",
                    c.len(),
                    rust[k],
                    c[k]
                ));
            }
        }
    }
    std::fs::remove_file(&input).unwrap();
    failures
}

/// Compile the companions' harness (`tests/c/certified_harness.c`) against `header` as C99
/// with `flags` (warnings are errors).
fn build(dir: &Path, header: &str, flags: &[&str], exe: &str) -> PathBuf {
    let mut all = vec!["-std=c99"];
    all.extend(flags);
    compile_harness(dir, header, &cc(), &all, "certified_harness.c", exe)
}

#[test]
fn c_certified_companions_are_bit_identical_to_the_rust_ones() {
    let dir = scratch("c-certified");
    let header = generate(Lang::C, &[2, 3, 4, 5, 6]);
    let exes: Vec<(&str, PathBuf)> = CONFIGS
        .iter()
        .enumerate()
        .map(|(k, (name, flags))| (*name, build(&dir, &header, flags, &format!("certified{k}"))))
        .collect();
    let mut failures = Vec::new();
    for n in collision_core::DIMS.iter().copied() {
        failures.extend(collision_core::with_dim!(
            n,
            |N, S| {
                let cases = draw::<N, S>(CASES, 28 + N as u64);
                let mut f = check_format(&dir, &exes, &cases.f64);
                f.extend(check_format(&dir, &exes, &cases.f32));
                f
            },
            unreachable!("DIMS lists the compiled dimensions")
        ));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `header` with the first sum `+ {prefix}` of a `const double {prefix}` line in `function`
/// made a difference, and the line altered.
fn with_first_sum_negated(header: &str, function: &str, prefix: &str) -> (String, String) {
    let start = header
        .find(&format!("void {function}("))
        .expect("the companion is in the header");
    let body = &header[start..];
    let line = body
        .lines()
        .find(|l| {
            l.trim_start()
                .starts_with(&format!("const double {prefix}"))
                && l.contains(&format!(" + {prefix}"))
        })
        .expect("a sum of two bound terms");
    let at = start + body.find(line).unwrap();
    let mut mutated = header.to_string();
    let altered = line.replacen(&format!(" + {prefix}"), &format!(" - {prefix}"), 1);
    mutated.replace_range(at..at + line.len(), &altered);
    (mutated, line.trim().to_string())
}

/// One bound operation altered (the first sum of two bound terms of the running companion,
/// then the first sum of two magnitudes of the fast one, then the first sum of bound terms
/// of the FMA kernel's running companion, made a difference) makes the
/// comparison fail: the test above compares the bounds, not only the outputs.
#[test]
fn one_altered_bound_operation_fails_the_comparison() {
    let dir = scratch("c-certified-mutation");
    let header = generate(Lang::C, &[2, 3, 4, 5, 6]);
    let cases = draw::<3, 3>(1000, 3).f64;
    let good = [("good", build(&dir, &header, CONFIGS[0].1, "good"))];
    let good = check_format(&dir, &good, &cases);
    assert!(good.is_empty(), "{good:?}");
    for (function, prefix, kernel) in [
        ("noslip_d3_free_certified_f64", "cert", "free_certified"),
        (
            "noslip_d3_free_certified_fast_f64",
            "mag",
            "free_fast_certified",
        ),
        (
            "noslip_d3_free_fma_certified_f64",
            "cert",
            "free_fma_certified",
        ),
    ] {
        let (mutated, line) = with_first_sum_negated(&header, function, prefix);
        let bad = [(
            "bad",
            build(&dir, &mutated, CONFIGS[0].1, &format!("bad_{prefix}")),
        )];
        let bad = check_format(&dir, &bad, &cases);
        assert!(
            bad.iter().any(|f| f.contains(kernel)),
            "altering `{line}` went unnoticed: {bad:?}"
        );
    }
}
