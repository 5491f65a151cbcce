//! The certified companions of the C header (`noslip_d{n}_{free|fixed}_certified_{f64|f32}`,
//! the fast ones `..._certified_fast_...`, those of the FMA kernels
//! `noslip_d{n}_{free|fixed}_fma_certified_...`, which call `fma`/`fmaf`, the rounded-input
//! ones `..._certified_rounded_{f64|f32}`, the `float` kernels' with the bound in `double`,
//! `..._certified_f32_wide`, and the rough-ball and Walton kernels',
//! `noslip_d{n}_{rough|walton}_..._certified_...`) are faithful: compiled by the system C compiler at
//! `-O2 -ffp-contract=off` and at `-O3 -march=native -ffp-contract=off`, they return bit for
//! bit the Rust companions' outputs and bounds (`collision_core::kernels::dN::certified`),
//! and so the plain Rust kernels' outputs (accuracy/tests/proven.rs checks the Rust
//! companions against those and against exact truth), on [`CASES`] cases per dimension
//! (n = 2..6), kernel (`free`, `fixed`) and format, drawn from every regime of the accuracy
//! report ([`EXTRA_CASES`] for the rounded-input, wide and rough-family companions, each
//! rounded-input one under three pairs `(rho_nu, rho_gamma2)`, the rough ones under two laws,
//! the Walton ones under three). The two executables are compiled once and
//! serve every comparison.

use crate::backend;
#[path = "c_certified/extra.rs"]
mod extra;

use backend::companions::{of, Extra};
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

/// Cases per dimension and format for the rounded-input and wide companions.
const EXTRA_CASES: usize = 1_000;

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

/// A companion's results on every case as the harness writes them: every case's outputs
/// (`out1, out2` or `out2`), then every case's bounds in the same layout.
pub struct Results<T, B> {
    /// The outputs.
    pub values: Vec<T>,
    /// The bounds.
    pub bounds: Vec<B>,
}

impl<T: Copy, B: Copy> Results<T, B> {
    fn new() -> Self {
        Results {
            values: Vec::new(),
            bounds: Vec::new(),
        }
    }

    /// Append one case's bodies: `values[k]` with its bound `bounds[k]`.
    pub fn push<const N: usize, const S: usize>(
        &mut self,
        values: &[BodyState<T, N, S>],
        bounds: &[BodyState<B, N, S>],
    ) {
        for b in values {
            self.values.extend(state(b));
        }
        for b in bounds {
            self.bounds.extend(state(b));
        }
    }
}

/// The Rust companion `kernel` on every case.
fn rust_results<T: Float, const N: usize, const S: usize>(
    kernel: &str,
    cases: &[(Regime, Case<T, N, S>)],
) -> Results<T, T>
where
    Generated: CertifiedKernel<T, N, S>,
{
    let mut out = Results::new();
    for (_, c) in cases {
        let (nu, [b1, b2], [s1, s2]) = (&c.nu, c.ball_refs(), c.state_refs());
        let (variant, companion) = match kernel.strip_suffix("_fast") {
            Some(v) => (v, Companion::Fast),
            None => (kernel, Companion::Running),
        };
        match variant {
            "free" => {
                let (o, e) = Generated::free(companion, nu, b1, b2, s1, s2);
                out.push(&o, &e);
            }
            "fixed" => {
                let (o, e) = Generated::fixed(companion, nu, &b1.radius, b2, s1, s2);
                out.push(&[o], &[e]);
            }
            "free_fma" => {
                let (o, e) = Generated::free_fma(companion, nu, b1, b2, s1, s2);
                out.push(&o, &e);
            }
            "fixed_fma" => {
                let (o, e) = Generated::fixed_fma(companion, nu, &b1.radius, b2, s1, s2);
                out.push(&[o], &[e]);
            }
            _ => panic!("no kernel {kernel}"),
        }
    }
    out
}

/// One comparison: the harness's command line after `N` (kernel, precision, then the
/// `rho` arguments of a rounded-input companion) and the Rust results.
pub struct Job<T, B> {
    /// What is compared, for the failure messages.
    pub what: String,
    /// `KERNEL PRECISION [RHO_NU RHO_GAMMA2]`.
    pub args: Vec<String>,
    /// The Rust companion's results.
    pub rust: Results<T, B>,
}

/// Run every executable of `exes` on `input` for `job`; one message per difference.
pub fn compare<T: Float, B: Float, const N: usize>(
    exes: &[(&str, PathBuf)],
    input: &Path,
    job: &Job<T, B>,
) -> Vec<String> {
    let mut failures = Vec::new();
    let rust = &job.rust;
    assert!(rust.values.iter().any(|x| x.finite()), "no finite result");
    for (config, exe) in exes {
        let output = input.with_extension("out");
        let mut cmd = Command::new(exe);
        cmd.arg(N.to_string())
            .arg(&job.args[0])
            .arg(&job.args[1])
            .arg(input)
            .arg(&output)
            .args(&job.args[2..]);
        run(&mut cmd);
        let bytes = std::fs::read(&output).unwrap();
        let what = format!("{} (cc {config})", job.what);
        let split = rust.values.len() * std::mem::size_of::<T>();
        let expected = split + rust.bounds.len() * std::mem::size_of::<B>();
        if bytes.len() != expected {
            failures.push(format!(
                "{what}: {} bytes of results, expected {expected}",
                bytes.len()
            ));
            continue;
        }
        let values = T::from_bytes(&bytes[..split]);
        let bounds = B::from_bytes(&bytes[split..]);
        let differ = |c: &[T], r: &[T], part: &str, failures: &mut Vec<String>| {
            let bad: Vec<usize> = (0..c.len()).filter(|&k| !same(c[k], r[k])).collect();
            if let Some(&k) = bad.first() {
                failures.push(format!(
                    "{what}: {} of {} {part} differ; the first at {k}: Rust {:?}, C {:?}",
                    bad.len(),
                    c.len(),
                    r[k],
                    c[k]
                ));
            }
        };
        differ(&values, &rust.values, "outputs", &mut failures);
        let bad: Vec<usize> = (0..bounds.len())
            .filter(|&k| !same(bounds[k], rust.bounds[k]))
            .collect();
        if let Some(&k) = bad.first() {
            failures.push(format!(
                "{what}: {} of {} bounds differ; the first at {k}: Rust {:?}, C {:?}",
                bad.len(),
                bounds.len(),
                rust.bounds[k],
                bounds[k]
            ));
        }
    }
    failures
}

/// The running, fast and FMA companions of one format on `cases`.
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
        let job = Job {
            what: format!("n = {N}, {kernel}_certified {}", <T as Scalar>::NAME),
            args: vec![kernel.to_string(), <T as Scalar>::NAME.to_string()],
            rust: rust_results(kernel, cases),
        };
        failures.extend(compare::<T, T, N>(exes, &input, &job));
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

/// Every check of dimension `N`: the running, fast and FMA companions on [`CASES`] cases
/// per format, the rounded-input and wide ones on [`EXTRA_CASES`].
fn check_dim<const N: usize, const S: usize>(
    dir: &Path,
    exes: &[(&str, PathBuf)],
    extra: &Extra<N, S>,
) -> Vec<String>
where
    Generated: CertifiedKernel<f64, N, S> + CertifiedKernel<f32, N, S>,
{
    let cases = draw::<N, S>(CASES, 28 + N as u64);
    let mut f = check_format(dir, exes, &cases.f64);
    f.extend(check_format(dir, exes, &cases.f32));
    let cases = draw::<N, S>(EXTRA_CASES, 280 + N as u64);
    f.extend(extra.check(dir, exes, &cases, extra::RHOS, extra::LAWS));
    f
}

macro_rules! every_dim {
    ($dir:expr, $exes:expr, $(($m:ident $n:literal $s:literal))*) => {{
        let mut failures = Vec::new();
        $(failures.extend(check_dim::<$n, $s>($dir, $exes, &of!($m)));)*
        failures
    }};
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
    let failures = every_dim!(&dir, &exes, (d2 2 1) (d3 3 3) (d4 4 6) (d5 5 10) (d6 6 15));
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

/// The first law of each rough family: enough for the mutation test.
const FIRST_LAWS: extra::Laws = extra::Laws {
    rough: &[extra::ROUGH_LAWS[0]],
    walton: &[extra::WALTON_LAWS[0]],
};

/// One bound operation altered in each of six companions (the first sum of two bound terms
/// of the running companion, of the FMA kernel's, of the rounded-input one, of the wide one
/// and of the Walton kernel's, and the first sum of two magnitudes of the fast one, each made
/// a difference) makes
/// that companion's comparison fail: the test above compares the bounds, not only the
/// outputs. Cheap: a header of n = 3 alone, the six alterations in one build.
#[test]
fn one_altered_bound_operation_fails_the_comparison() {
    let dir = scratch("c-certified-mutation");
    let header = generate(Lang::C, &[3]);
    let flags: Vec<&str> = CONFIGS[0]
        .1
        .iter()
        .copied()
        .chain(["-DNOSLIP_ONLY_N=3"])
        .collect();
    let cases = draw::<3, 3>(300, 3);
    let extra = of!(d3);
    let good = [("good", build(&dir, &header, &flags, "good"))];
    let mut seen = check_format(&dir, &good, &cases.f64);
    seen.extend(extra.check(&dir, &good, &cases, &extra::RHOS[..1], FIRST_LAWS));
    assert!(seen.is_empty(), "{seen:?}");
    let mutations = [
        ("noslip_d3_free_certified_f64", "cert", "free_certified f64"),
        (
            "noslip_d3_free_certified_fast_f64",
            "mag",
            "free_fast_certified f64",
        ),
        (
            "noslip_d3_free_fma_certified_f64",
            "cert",
            "free_fma_certified f64",
        ),
        (
            "noslip_d3_fixed_certified_rounded_f64",
            "cert",
            "fixed_rounded_certified f64",
        ),
        (
            "noslip_d3_free_fma_certified_f32_wide",
            "cert",
            "free_fma_certified f32_wide",
        ),
        (
            "noslip_d3_walton_free_certified_f64",
            "cert",
            "walton_free_certified f64",
        ),
    ];
    let mut mutated = header.clone();
    let mut lines = Vec::new();
    for (function, prefix, _) in mutations {
        let (m, line) = with_first_sum_negated(&mutated, function, prefix);
        mutated = m;
        lines.push(line);
    }
    let bad = [("bad", build(&dir, &mutated, &flags, "bad"))];
    let mut seen = check_format(&dir, &bad, &cases.f64);
    seen.extend(extra.check(&dir, &bad, &cases, &extra::RHOS[..1], FIRST_LAWS));
    std::fs::remove_dir_all(&dir).unwrap();
    for ((_, _, kernel), line) in mutations.iter().zip(&lines) {
        assert!(
            seen.iter()
                .any(|f| f.contains(&format!("{kernel} ")) && f.contains("bounds differ")),
            "altering `{line}` in {kernel} went unnoticed: {seen:?}"
        );
    }
    // Only the altered companions differ, in their bounds only.
    assert!(
        seen.iter().all(|f| mutations
            .iter()
            .any(|(_, _, k)| f.contains(&format!("{k} ")))
            && f.contains("bounds differ")),
        "{seen:?}"
    );
}
