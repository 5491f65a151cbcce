//! Part of `c_backend.rs`: the energy-conserving correction in C (`noslip_conserve_fixed_dN`,
//! `noslip_conserve_free_dN` of the C header; `noslip_codegen::backend`'s `conserve.rs`)
//! returns the Rust correction's bits (`collision_core::conserve`), every result finite
//! ([`compare`]): on 20 000 cases per dimension (n = 2..6) drawn from every regime of the
//! accuracy report (mass ratios, immovable bodies, `gamma^2` to 0, radius ratios, scales
//! `10^-100..10^100`, spin-dominated, near-grazing), the Rust kernels' outputs corrected by
//! both, the C compiled at `-O2 -ffp-contract=off` and at `-O3 -march=native`. The cases
//! include those the correction leaves alone (an immovable body, `E > 16 E_rel`, energies out
//! of range), and the test counts that most are corrected. A mutation check: the C built with
//! round to nearest in place of the stochastic rounding differs.

use super::backend::conserve::{contacts, Drawn};
use super::backend::{cc, compare, compile_harness, run, scratch, Float};
use collision_core::{Generated, Kernel};
use noslip_codegen::backend::{generate, Lang};
use std::path::Path;
use std::process::Command;

const CASES: usize = 20_000;

/// The cases, the records of `conserve_harness.c` (ball1, ball2, before1, before2, after1,
/// after2, fixed2), the Rust results (fixed2, after1, after2 corrected) and the number of
/// corrections that changed something.
fn records<const N: usize, const S: usize>() -> (Drawn<N, S>, Vec<u8>, Vec<f64>, usize)
where
    Generated: Kernel<f64, N, S>,
{
    let (cases, contacts, changed) = contacts::<N, S>(CASES, 4200 + N as u64);
    let (mut bytes, mut want) = (Vec::new(), Vec::new());
    for c in &contacts {
        let record = c.balls.iter().flatten().chain(c.before.iter().flatten());
        let record = record.chain(c.after.iter().flatten()).chain(&c.fixed);
        bytes.extend(record.flat_map(|&x| x.bytes()));
        want.extend(c.want_fixed.iter().chain(c.want_free.iter().flatten()));
    }
    (cases, bytes, want, changed)
}

fn run_c(exe: &Path, n: usize, input: &Path) -> Vec<f64> {
    let output = input.with_extension("out");
    run(Command::new(exe).arg(n.to_string()).arg(input).arg(&output));
    f64::from_bytes(&std::fs::read(&output).unwrap())
}

fn check<const N: usize, const S: usize>(
    dir: &Path,
    exes: &[(&str, std::path::PathBuf)],
    mutant: &Path,
) where
    Generated: Kernel<f64, N, S>,
{
    let (cases, bytes, want, changed) = records::<N, S>();
    // Most of the 2 x CASES corrections apply (the rest: immovable bodies, and the regimes
    // where the pair's centre of mass carries the energy or the energies leave the range).
    assert!(
        changed > CASES,
        "n = {N}: {changed} of {} corrected",
        2 * CASES
    );
    let input = dir.join(format!("conserve_d{N}.bin"));
    std::fs::write(&input, bytes).unwrap();
    for (name, exe) in exes {
        let got = run_c(exe, N, &input);
        if let Err(e) = compare(&format!("n = {N}, {name}"), &cases, &want, &got) {
            panic!("{e}");
        }
    }
    let got = run_c(mutant, N, &input);
    assert!(
        compare("mutant", &cases, &want, &got).is_err(),
        "n = {N}: the mutant (round to nearest) gives the same bits: the comparison sees nothing"
    );
}

#[test]
fn the_c_correction_is_the_rust_correction_bit_for_bit() {
    let dir = scratch("c-conserve");
    let header = generate(Lang::C, &[2, 3, 4, 5, 6]);
    let build = |flags: &[&str], exe: &str, header: &str| {
        let mut all = vec!["-std=c99"];
        all.extend(flags);
        compile_harness(&dir, header, &cc(), &all, "conserve_harness.c", exe)
    };
    let exes = [
        (
            "-O2",
            build(&["-O2", "-ffp-contract=off"], "conserve_o2", &header),
        ),
        (
            "-O3 -march=native",
            build(
                &["-O3", "-march=native", "-ffp-contract=off"],
                "conserve_o3",
                &header,
            ),
        ),
    ];
    let stochastic = "return r < chance ? next : hi;";
    assert!(header.contains(stochastic), "the rounding's line moved");
    let mutant = build(
        &["-O2", "-ffp-contract=off"],
        "conserve_mutant",
        &header.replace(stochastic, "return (void)r, (void)chance, (void)next, hi;"),
    );
    check::<2, 1>(&dir, &exes, &mutant);
    check::<3, 3>(&dir, &exes, &mutant);
    check::<4, 6>(&dir, &exes, &mutant);
    check::<5, 10>(&dir, &exes, &mutant);
    check::<6, 15>(&dir, &exes, &mutant);
    let _ = std::fs::remove_dir_all(&dir);
}
