//! The generated C kernels against the Rust kernels on the same cases, in one run:
//! `cargo run --release -p noslip-tests --example c_vs_rust` (figures in docs/backends.md).
//!
//! For n = 2..6 it draws 4096 cases of the accuracy report's typical regime, writes them as
//! records, runs `examples/c/bench.c` (compiled against the generated header with `cc -O2
//! -ffp-contract=off`, the baseline target as the Rust release build; with `-O3
//! -march=native`; with `-O3 -march=native -fno-tree-slp-vectorize -fno-tree-loop-vectorize`,
//! the options under which GCC inlines the kernels (`NOSLIP_NO_CONTRACT`); and, when `clang`
//! is installed, with `clang -O2` and `clang -O3 -march=native`) and times the Rust kernels (`Generated::free`, `fixed`, f64) on the same
//! cases with `noslip_accuracy::timing`: the median nanoseconds per collision over 21 samples
//! each, and the ratio C / Rust.

use collision_core::rng::Rng;
use collision_core::{Generated, Kernel};
use noslip_accuracy::regime::Regime;
use noslip_accuracy::timing::{pass_over, time};
use noslip_codegen::backend::{file_name, generate, Lang};
use std::path::Path;
use std::process::Command;

const BATCH: usize = 4096;
const SAMPLES: usize = 21;

fn run_c(exe: &Path, n: usize, cases: &Path) -> (f64, f64) {
    let out = Command::new(exe)
        .arg(n.to_string())
        .arg(cases)
        .arg(SAMPLES.to_string())
        .output()
        .expect("run the C benchmark");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let get = |name: &str| -> f64 {
        text.lines()
            .find_map(|l| l.strip_prefix(name)?.trim().parse().ok())
            .unwrap_or_else(|| panic!("no {name} in {text}"))
    };
    (get("free "), get("fixed "))
}

fn rust<const N: usize, const S: usize>(dir: &Path) -> (std::path::PathBuf, f64, f64)
where
    Generated: Kernel<f64, N, S>,
{
    let mut rng = Rng::new(2026);
    let cases: Vec<_> = (0..BATCH)
        .map(|_| (Regime::Typical, Regime::Typical.sample::<N, S>(&mut rng)))
        .collect();
    let path = dir.join(format!("cases_{N}.bin"));
    let mut bytes = Vec::new();
    for (_, c) in &cases {
        let values =
            c.nu.iter()
                .chain(
                    c.balls
                        .iter()
                        .flat_map(|b| [&b.inv_mass, &b.radius, &b.gamma2]),
                )
                .chain(
                    c.states
                        .iter()
                        .flat_map(|s| s.spin.iter().chain(&s.velocity)),
                );
        for v in values {
            bytes.extend(v.to_ne_bytes());
        }
    }
    std::fs::write(&path, bytes).unwrap();
    let cases: Vec<_> = cases.into_iter().map(|(_, c)| c).collect();
    let free = time(BATCH, SAMPLES, || {
        pass_over(&cases, |c| {
            Generated::free(&c.nu, &c.balls[0], &c.balls[1], &c.states[0], &c.states[1])
        })
    });
    let fixed = time(BATCH, SAMPLES, || {
        pass_over(&cases, |c| {
            Generated::fixed(
                &c.nu,
                &c.balls[0].radius,
                &c.balls[1],
                &c.states[0],
                &c.states[1],
            )
        })
    });
    (path, free.median_ns, fixed.median_ns)
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/c-bench");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join(file_name(Lang::C)),
        generate(Lang::C, &[2, 3, 4, 5, 6]),
    )
    .unwrap();
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/c/bench.c");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let mut configs: Vec<(String, &str, &[&str])> = vec![
        (
            format!("{cc} -O2"),
            cc.as_str(),
            &["-O2", "-ffp-contract=off"],
        ),
        (
            format!("{cc} -O3 -march=native"),
            cc.as_str(),
            &["-O3", "-march=native", "-ffp-contract=off"],
        ),
        (
            format!("{cc} -O3 -march=native, no vectorising"),
            cc.as_str(),
            &[
                "-O3",
                "-march=native",
                "-ffp-contract=off",
                "-fno-tree-slp-vectorize",
                "-fno-tree-loop-vectorize",
            ],
        ),
    ];
    if Command::new("clang").arg("--version").output().is_ok() {
        configs.push(("clang -O2".into(), "clang", &["-O2", "-ffp-contract=off"]));
        configs.push((
            "clang -O3 -march=native".into(),
            "clang",
            &["-O3", "-march=native", "-ffp-contract=off"],
        ));
    } else {
        eprintln!("no clang: its columns are left out");
    }
    let exes: Vec<_> = configs
        .iter()
        .enumerate()
        .map(|(k, (_, compiler, flags))| {
            let exe = dir.join(format!("bench{k}"));
            let status = Command::new(compiler)
                .arg("-std=c99")
                .args(*flags)
                .arg("-I")
                .arg(&dir)
                .arg(&source)
                .arg("-o")
                .arg(&exe)
                .arg("-lm")
                .status()
                .expect("run the C compiler");
            assert!(status.success(), "compiling {}", source.display());
            exe
        })
        .collect();
    println!("median ns per collision, f64, {BATCH} typical cases, {SAMPLES} samples; (C / Rust)");
    let names: Vec<&str> = configs.iter().map(|(name, ..)| name.as_str()).collect();
    println!("| n | kernel | Rust (release) | {} |", names.join(" | "));
    println!("|---|---|---:|{}", "---:|".repeat(names.len()));
    for n in collision_core::DIMS.iter().copied() {
        let (path, rust_free, rust_fixed) = collision_core::with_dim!(
            n,
            |N, S| rust::<N, S>(&dir),
            unreachable!("a compiled dimension")
        );
        let c: Vec<(f64, f64)> = exes.iter().map(|exe| run_c(exe, n, &path)).collect();
        for (kernel, r, pick) in [("free", rust_free, 0), ("fixed", rust_fixed, 1)] {
            let cells: Vec<String> = c
                .iter()
                .map(|&(free, fixed)| {
                    let t = if pick == 0 { free } else { fixed };
                    format!("{t:.1} ({:.2})", t / r)
                })
                .collect();
            println!("| {n} | {kernel} | {r:.1} | {} |", cells.join(" | "));
        }
    }
}
