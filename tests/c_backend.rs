//! The C back end is faithful: the emitted header, compiled by the system C compiler at
//! `-O2 -ffp-contract=off` and at `-O3 -march=native -ffp-contract=off`, returns bit for bit
//! the Rust kernels' results (`collision_core::kernels`, through `Generated`) on 10^5 cases
//! per dimension (n = 2..6), kernel (`free`, `fixed`, `free_fma`, `fixed_fma`) and format
//! (`f64`, `f32`), drawn from every regime of the accuracy report (its own samplers, so the
//! extremes included: mass ratios to 1e15, immovable bodies, gamma^2 to 1e-15 and 0, radius
//! ratios to 1e6, scales 1e-100..1e100, spin-dominated, near-grazing), and every result is
//! finite. A mutation check shows the comparison catches one altered operation. Without
//! `-ffp-contract=off` (GCC in GNU C modes and C++, clang) the header's own guards keep the
//! results identical; a control shows GCC contracts, and differs, without them.

use crate::backend;
#[path = "c_backend/conserve.rs"]
mod conserve;

use backend::{
    cc, compare, compile_harness, draw, records, run, rust_results, rust_rough_results,
    rust_walton_results, scratch, Float, KERNELS, LAWS, ROUGH_KERNELS, WALTON_KERNELS, WALTON_LAWS,
};
use collision_core::{Generated, Kernel, Restitution, RoughKernel, Scalar, Walton, WaltonKernel};
use noslip_accuracy::case::Case;
use noslip_accuracy::regime::Regime;
use noslip_codegen::backend::{file_name, generate, Lang};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// Cases per dimension, kernel and format.
const CASES: usize = 100_000;

/// The compiler configurations the issue names.
const CONFIGS: [(&str, &[&str]); 2] = [
    ("-O2", &["-O2", "-ffp-contract=off"]),
    (
        "-O3 -march=native",
        &["-O3", "-march=native", "-ffp-contract=off"],
    ),
];

/// The harness compiled against the whole header once per configuration of [`CONFIGS`],
/// shared by the tests that run it unaltered (a compile takes about 6 s): `(name, executable)`,
/// in cargo's temporary directory for integration tests.
fn harnesses() -> &'static [(&'static str, PathBuf)] {
    static EXES: OnceLock<Vec<(&'static str, PathBuf)>> = OnceLock::new();
    EXES.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("c-backend-harness");
        std::fs::create_dir_all(&dir).unwrap();
        let header = generate(Lang::C, &[2, 3, 4, 5, 6]);
        CONFIGS
            .iter()
            .enumerate()
            .map(|(k, (name, flags))| (*name, build(&dir, &header, flags, &format!("harness{k}"))))
            .collect()
    })
}

/// Write `header` into `dir` and compile the harness against it as C99 with `flags`.
fn build(dir: &Path, header: &str, flags: &[&str], exe: &str) -> PathBuf {
    let mut all = vec!["-std=c99"];
    all.extend(flags);
    build_with(dir, header, &cc(), &all, exe)
}

/// Compile the harness (`tests/c/harness.c`) against `header` with `compiler` and `flags`.
fn build_with(dir: &Path, header: &str, compiler: &str, flags: &[&str], exe: &str) -> PathBuf {
    compile_harness(dir, header, compiler, flags, "harness.c", exe)
}

fn run_c<T: Float>(exe: &Path, n: usize, kernel: &str, input: &Path) -> Vec<T> {
    let output = input.with_extension(format!("{kernel}.out"));
    run(Command::new(exe)
        .arg(n.to_string())
        .arg(kernel)
        .arg(<T as Scalar>::NAME)
        .arg(input)
        .arg(&output));
    let values = T::from_bytes(&std::fs::read(&output).unwrap());
    std::fs::remove_file(&output).unwrap();
    values
}

/// Run rough or Walton kernel `kernel` of dimension `n` in format `T` under `law`
/// (`(e, beta)` or `(e, mu, beta0)`) on `input`.
fn run_c_rough<T: Float>(exe: &Path, n: usize, kernel: &str, law: &[f64], input: &Path) -> Vec<T> {
    let output = input.with_extension(format!("{kernel}.out"));
    run(Command::new(exe)
        .arg(n.to_string())
        .arg(kernel)
        .arg(<T as Scalar>::NAME)
        .arg(input)
        .arg(&output)
        .args(law.iter().map(f64::to_string)));
    let values = T::from_bytes(&std::fs::read(&output).unwrap());
    std::fs::remove_file(&output).unwrap();
    values
}

/// Compare every rough kernel in format `T` under each of [`LAWS`] on `cases`; the failures.
fn check_rough_format<T: Float, const N: usize, const S: usize>(
    dir: &Path,
    exes: &[(&str, PathBuf)],
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<String>
where
    Generated: RoughKernel<T, N, S>,
{
    let input = dir.join(format!("rough_{N}_{}.bin", <T as Scalar>::NAME));
    std::fs::write(&input, records(cases)).unwrap();
    let mut failures = Vec::new();
    for law in LAWS {
        let exact = Restitution::new(T::from_f64(law.0), T::from_f64(law.1)).expect("in range");
        for kernel in ROUGH_KERNELS {
            let rust = rust_rough_results(kernel, &exact, cases);
            for (config, exe) in exes {
                let c = run_c_rough::<T>(exe, N, kernel, &[law.0, law.1], &input);
                let what = format!(
                    "n = {N}, {kernel} {} (e, beta) = {law:?} (cc {config})",
                    <T as Scalar>::NAME
                );
                if let Err(e) = compare(&what, cases, &rust, &c) {
                    failures.push(e);
                }
            }
        }
    }
    std::fs::remove_file(&input).unwrap();
    failures
}

/// Compare every Walton kernel in format `T` under each of [`WALTON_LAWS`] on `cases`; the
/// failures.
fn check_walton_format<T: Float, const N: usize, const S: usize>(
    dir: &Path,
    exes: &[(&str, PathBuf)],
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<String>
where
    Generated: WaltonKernel<T, N, S>,
{
    let input = dir.join(format!("walton_{N}_{}.bin", <T as Scalar>::NAME));
    std::fs::write(&input, records(cases)).unwrap();
    let mut failures = Vec::new();
    for law in WALTON_LAWS {
        let [e, mu, beta0] = law.map(T::from_f64);
        let typed = Walton::new(e, mu, beta0).expect("in range");
        for kernel in WALTON_KERNELS {
            let rust = rust_walton_results(kernel, &typed, cases);
            for (config, exe) in exes {
                let c = run_c_rough::<T>(exe, N, kernel, &law, &input);
                let what = format!(
                    "n = {N}, {kernel} {} (e, mu, beta0) = {law:?} (cc {config})",
                    <T as Scalar>::NAME
                );
                if let Err(e) = compare(&what, cases, &rust, &c) {
                    failures.push(e);
                }
            }
        }
    }
    std::fs::remove_file(&input).unwrap();
    failures
}

/// Compare every kernel in format `T` on `cases` for each compiled harness; the failures.
fn check_format<T: Float, const N: usize, const S: usize>(
    dir: &Path,
    exes: &[(&str, PathBuf)],
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<String>
where
    Generated: Kernel<T, N, S>,
{
    let input = dir.join(format!("cases_{N}_{}.bin", <T as Scalar>::NAME));
    std::fs::write(&input, records(cases)).unwrap();
    let mut failures = Vec::new();
    for kernel in KERNELS {
        let rust = rust_results(kernel, cases);
        for (config, exe) in exes {
            let c = run_c::<T>(exe, N, kernel, &input);
            let what = format!("n = {N}, {kernel} {} (cc {config})", <T as Scalar>::NAME);
            if let Err(e) = compare(&what, cases, &rust, &c) {
                failures.push(e);
            }
        }
    }
    std::fs::remove_file(&input).unwrap();
    failures
}

fn check_dim<const N: usize, const S: usize>(
    dir: &Path,
    exes: &[(&str, PathBuf)],
    count: usize,
) -> Vec<String>
where
    Generated: Kernel<f64, N, S> + Kernel<f32, N, S>,
{
    let cases = draw::<N, S>(count, 14 + N as u64);
    let mut failures = check_format(dir, exes, &cases.f64);
    failures.extend(check_format(dir, exes, &cases.f32));
    failures
}

#[test]
fn c_kernels_are_bit_identical_to_the_rust_kernels_and_finite() {
    let dir = scratch("c-backend");
    let exes = harnesses();
    let mut failures = Vec::new();
    for n in collision_core::DIMS.iter().copied() {
        failures.extend(collision_core::with_dim!(
            n,
            |N, S| check_dim::<N, S>(&dir, exes, CASES),
            unreachable!("DIMS lists the compiled dimensions")
        ));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Cases per dimension, rough kernel, law and format.
const ROUGH_CASES: usize = 20_000;

/// The rough-ball kernels of the C header return the Rust rough kernels' bits, under each of
/// [`LAWS`], on the same regimes, in both compiler configurations.
#[test]
fn c_rough_kernels_are_bit_identical_to_the_rust_kernels_and_finite() {
    let dir = scratch("c-backend-rough");
    let exes = harnesses();
    let mut failures = Vec::new();
    for n in collision_core::DIMS.iter().copied() {
        failures.extend(collision_core::with_dim!(
            n,
            |N, S| {
                let cases = draw::<N, S>(ROUGH_CASES, 24 + N as u64);
                let mut f = check_rough_format(&dir, exes, &cases.f64);
                f.extend(check_rough_format(&dir, exes, &cases.f32));
                f
            },
            unreachable!("DIMS lists the compiled dimensions")
        ));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The Walton kernels of the C header (a square root and two selects each) return the Rust
/// Walton kernels' bits, under each of [`WALTON_LAWS`], on the same regimes, in both
/// compiler configurations.
#[test]
fn c_walton_kernels_are_bit_identical_to_the_rust_kernels_and_finite() {
    // Half the rough test's cases: the comparison's cost, not its reach, differs (the same
    // regimes, every law, both configurations).
    const WALTON_CASES: usize = ROUGH_CASES / 2;
    let dir = scratch("c-backend-walton");
    let exes = harnesses();
    let mut failures = Vec::new();
    for n in collision_core::DIMS.iter().copied() {
        failures.extend(collision_core::with_dim!(
            n,
            |N, S| {
                let cases = draw::<N, S>(WALTON_CASES, 44 + N as u64);
                let mut f = check_walton_format(&dir, exes, &cases.f64);
                f.extend(check_walton_format(&dir, exes, &cases.f32));
                f
            },
            unreachable!("DIMS lists the compiled dimensions")
        ));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every kernel of every dimension in both formats on `count` cases per harness: the failures.
fn check_all(dir: &Path, exes: &[(&str, PathBuf)], count: usize) -> Vec<String> {
    let mut failures = Vec::new();
    for n in collision_core::DIMS.iter().copied() {
        failures.extend(collision_core::with_dim!(
            n,
            |N, S| check_dim::<N, S>(dir, exes, count),
            unreachable!("DIMS lists the compiled dimensions")
        ));
    }
    failures
}

/// Whether this CPU has FMA instructions (x86 `/proc/cpuinfo` flag `fma`), so that a compiler
/// targeting it (`-march=native`) can contract `a * b + c`.
fn cpu_has_fma() -> bool {
    std::fs::read_to_string("/proc/cpuinfo")
        .map(|s| {
            s.lines()
                .filter(|l| l.starts_with("flags"))
                .any(|l| l.split_whitespace().any(|f| f == "fma"))
        })
        .unwrap_or(false)
}

/// Cases per dimension, kernel and format in the contraction tests.
const CONTRACTION_CASES: usize = 20_000;

/// The header is faithful without `-ffp-contract=off`: GCC in a GNU C mode and as C++ (both
/// contract by default) and clang in a GNU C mode, each at `-O3 -march=native` and no
/// contraction flag, return the Rust kernels' bits. The header's own guards do it: GCC's
/// `optimize("fp-contract=off")` attribute on each function, clang's `STDC FP_CONTRACT OFF`.
/// The control below shows GCC does contract here when the attribute is disabled.
#[test]
fn gnu_modes_without_a_contraction_flag_are_bit_identical() {
    let dir = scratch("c-no-flag");
    let header = generate(Lang::C, &[2, 3, 4, 5, 6]);
    let native = ["-O3", "-march=native"];
    let mut exes = vec![
        (
            "gcc -std=gnu99 -O3 -march=native",
            build_with(
                &dir,
                &header,
                "gcc",
                &[&["-std=gnu99"][..], &native].concat(),
                "gcc",
            ),
        ),
        (
            "g++ -x c++ -std=c++11 -O3 -march=native",
            build_with(
                &dir,
                &header,
                "g++",
                &[&["-x", "c++", "-std=c++11"][..], &native].concat(),
                "gxx",
            ),
        ),
    ];
    if Command::new("clang").arg("--version").output().is_ok() {
        exes.push((
            "clang -std=gnu99 -O3 -march=native",
            build_with(
                &dir,
                &header,
                "clang",
                &[&["-std=gnu99"][..], &native].concat(),
                "clang",
            ),
        ));
    } else {
        eprintln!("clang not installed: only GCC checked without a contraction flag");
    }
    let failures = check_all(&dir, &exes, CONTRACTION_CASES);
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The control of the test above: with the attribute disabled (`-DNOSLIP_NO_CONTRACT=`), GCC
/// in a GNU mode at `-O3 -march=native` contracts products into FMAs on this CPU and the
/// plain kernels' results differ from Rust's, so the test above checks something, and the
/// requirement docs/backends.md states for other compilers (no contraction) is real.
#[test]
fn without_the_attribute_gcc_contracts_and_differs() {
    if !cpu_has_fma() {
        eprintln!("SKIPPED: this CPU has no FMA instructions, so nothing can be contracted");
        return;
    }
    let dir = scratch("c-contracted");
    let header = generate(Lang::C, &[2, 3, 4, 5, 6]);
    let flags = [
        "-std=gnu99",
        "-O3",
        "-march=native",
        "-DNOSLIP_NO_CONTRACT=",
    ];
    let exes = vec![(
        "gcc -std=gnu99 -O3 -march=native -DNOSLIP_NO_CONTRACT=",
        build_with(&dir, &header, "gcc", &flags, "contracted"),
    )];
    let failures = check_all(&dir, &exes, CONTRACTION_CASES);
    std::fs::remove_dir_all(&dir).unwrap();
    let plain = |f: &&String| f.contains(" free f") || f.contains(" fixed f");
    let differ = failures.iter().filter(plain).count();
    assert!(
        differ > 0,
        "GCC without the attribute gave the Rust bits on every plain kernel: contraction untested"
    );
    assert!(
        failures.iter().all(|f| f.contains("components differ")),
        "{}",
        failures.join("\n")
    );
    eprintln!(
        "{differ} of 20 plain kernels (n, format) differ when contracted; the first:\n{}",
        failures[0]
    );
}

/// The line of the first `+` step in `function`'s body, with the `+` made a `-`.
fn mutate_first_addition(header: &str, function: &str) -> (String, String) {
    let start = header
        .find(&format!("void {function}("))
        .expect("the function is in the header");
    let body = &header[start..];
    let line = body
        .lines()
        .find(|l| l.trim_start().starts_with("const double ") && l.contains(" + "))
        .expect("an addition step");
    let mutated = line.replacen(" + ", " - ", 1);
    let at = start + body.find(line).unwrap();
    let mut out = header.to_string();
    out.replace_range(at..at + line.len(), &mutated);
    (out, mutated)
}

/// One emitted operation altered (`+` made `-`) makes the comparison fail: the test above can
/// fail, and only for the alteration (the same cases pass unaltered).
#[test]
fn one_altered_operation_fails_the_comparison() {
    let dir = scratch("c-mutation");
    let header = generate(Lang::C, &[2, 3, 4, 5, 6]);
    let (mutated, line) = mutate_first_addition(&header, "noslip_d3_free_f64");
    let cases = draw::<3, 3>(10_000, 3).f64;
    let input = dir.join("cases.bin");
    std::fs::write(&input, records(&cases)).unwrap();
    let rust = rust_results("free", &cases);
    let good = &harnesses()[0].1;
    let c = run_c::<f64>(good, 3, "free", &input);
    assert_eq!(compare("unaltered", &cases, &rust, &c), Ok(()));
    let bad = build(&dir, &mutated, CONFIGS[0].1, "bad");
    let c = run_c::<f64>(&bad, 3, "free", &input);
    let err = compare("altered", &cases, &rust, &c)
        .expect_err(&format!("altering `{}` went unnoticed", line.trim()));
    assert!(err.contains("components differ from Rust's"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The values `examples/c/collide.c` prints after `label`.
fn printed(stdout: &str, label: &str) -> Vec<f64> {
    let line = stdout
        .lines()
        .find_map(|l| l.strip_prefix(label))
        .unwrap_or_else(|| panic!("no line {label:?} in:\n{stdout}"));
    line.split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect()
}

/// `examples/c/collide.c` builds with the one command of docs/backends.md (and as C++11), and
/// prints the Rust kernels' results for its cases (17 significant digits read back exactly).
#[test]
fn the_c_example_builds_as_c_and_cpp_and_prints_the_rust_results() {
    use collision_core::{kernels::d3, Ball, BodyState};
    let dir = scratch("c-example");
    std::fs::write(dir.join(file_name(Lang::C)), generate(Lang::C, &[3])).unwrap();
    let example = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/c/collide.c");
    let ball1 = Ball {
        inv_mass: 0.5,
        radius: 1.0,
        gamma2: 0.4,
    };
    let ball2 = Ball {
        inv_mass: 1.0,
        radius: 1.5,
        gamma2: 0.4,
    };
    let state1 = BodyState {
        spin: [1.0, -2.0, 3.0],
        velocity: [1.0, 0.0, 0.5],
    };
    let state2 = BodyState::zero();
    let nu = [0.0, 0.6, 0.8];
    let wall = d3::fixed(&[-0.0, -0.6, -0.8], &1.5, &ball1, &state2, &state1);
    let [free1, free2] = d3::free(&nu, &ball1, &ball2, &state1, &state2);
    let flat = |s: &BodyState<f64, 3, 3>| {
        s.spin
            .iter()
            .chain(&s.velocity)
            .map(|x| x.to_bits())
            .collect::<Vec<_>>()
    };
    for (compiler, std) in [(cc(), "-std=c99"), ("c++".to_string(), "-std=c++11")] {
        let exe = dir.join(format!("collide-{}", std.trim_start_matches("-std=")));
        let mut cmd = Command::new(&compiler);
        if compiler == "c++" {
            cmd.args(["-x", "c++"]);
        }
        run(cmd
            .args([
                std,
                "-O2",
                "-ffp-contract=off",
                "-Wall",
                "-Wextra",
                "-Werror",
                "-I",
            ])
            .arg(&dir)
            .arg(&example)
            .arg("-o")
            .arg(&exe)
            .arg("-lm"));
        let out = Command::new(&exe).output().unwrap();
        assert!(out.status.success());
        let stdout = String::from_utf8(out.stdout).unwrap();
        let bits = |label| {
            printed(&stdout, label)
                .iter()
                .map(|x| x.to_bits())
                .collect::<Vec<_>>()
        };
        assert_eq!(bits("wall: body 1+"), flat(&wall), "{compiler}");
        assert_eq!(bits("free: body 1+"), flat(&free1), "{compiler}");
        assert_eq!(bits("free: body 2+"), flat(&free2), "{compiler}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
