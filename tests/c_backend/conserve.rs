//! Part of `c_backend.rs`: the energy-conserving correction in C (`noslip_conserve_fixed_dN`, `noslip_conserve_free_dN`
//! of the C header; `noslip_codegen::backend`'s `conserve.rs`) returns the Rust correction's
//! bits (`collision_core::conserve`): on 20 000 cases per dimension (n = 2..6) drawn from every
//! regime of the accuracy report (mass ratios, immovable bodies, `gamma^2` to 0, radius ratios,
//! scales `10^-100..10^100`, spin-dominated, near-grazing), the Rust kernels' outputs corrected
//! by both, the C compiled at `-O2 -ffp-contract=off` and at `-O3 -march=native`. The cases
//! include those the correction leaves alone (an immovable body, `E > 16 E_rel`, energies out
//! of range), and the test counts that most are corrected. A mutation check: the C built with
//! round to nearest in place of the stochastic rounding differs.

use super::backend::{cc, compile_harness, draw, run, scratch};
use collision_core::{conserve, BodyState, Generated, Kernel};
use noslip_codegen::backend::{generate, Lang};
use std::path::Path;
use std::process::Command;

const CASES: usize = 20_000;

/// The records of `conserve_harness.c` and the Rust results (fixed2, after1, after2 corrected),
/// with the number of cases the correction changed.
fn records<const N: usize, const S: usize>() -> (Vec<u8>, Vec<f64>, usize)
where
    Generated: Kernel<f64, N, S>,
{
    let cases = draw::<N, S>(CASES, 4200 + N as u64).f64;
    let (mut bytes, mut want, mut changed) = (Vec::new(), Vec::new(), 0);
    let flat = |s: &BodyState<f64, N, S>| {
        s.spin
            .iter()
            .chain(&s.velocity)
            .copied()
            .collect::<Vec<_>>()
    };
    for (_, c) in &cases {
        let [b1, b2] = &c.balls;
        let [s1, s2] = &c.states;
        let [o1, o2] = Generated::free(&c.nu, b1, b2, s1, s2);
        let fixed2 = Generated::fixed(&c.nu, &b1.radius, b2, &BodyState::zero(), s2);
        let mut values: Vec<f64> = [b1, b2]
            .iter()
            .flat_map(|b| [b.inv_mass, b.radius, b.gamma2])
            .collect();
        for s in [s1, s2, &o1, &o2, &fixed2] {
            values.extend(flat(s));
        }
        bytes.extend(values.iter().flat_map(|v| v.to_ne_bytes()));
        let f = conserve::fixed(b2, s2, &fixed2);
        let [c1, c2] = conserve::free(b1, b2, [s1, s2], [&o1, &o2]);
        changed += usize::from(f != fixed2) + usize::from(c1 != o1 || c2 != o2);
        for s in [&f, &c1, &c2] {
            want.extend(flat(s));
        }
    }
    (bytes, want, changed)
}

fn run_c(exe: &Path, n: usize, input: &Path) -> Vec<f64> {
    let output = input.with_extension("out");
    run(Command::new(exe).arg(n.to_string()).arg(input).arg(&output));
    let bytes = std::fs::read(&output).unwrap();
    bytes
        .chunks_exact(8)
        .map(|c| f64::from_ne_bytes(c.try_into().unwrap()))
        .collect()
}

/// The first differing value's index, if any (bits; NaNs of any payload alike).
fn first_difference(got: &[f64], want: &[f64]) -> Option<usize> {
    assert_eq!(got.len(), want.len());
    (0..got.len())
        .find(|&i| got[i].to_bits() != want[i].to_bits() && !(got[i].is_nan() && want[i].is_nan()))
}

fn check<const N: usize, const S: usize>(
    dir: &Path,
    exes: &[(&str, std::path::PathBuf)],
    mutant: &Path,
) where
    Generated: Kernel<f64, N, S>,
{
    let (bytes, want, changed) = records::<N, S>();
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
        if let Some(i) = first_difference(&got, &want) {
            panic!(
                "n = {N}, {name}: value {i} is {:e} in C, {:e} in Rust",
                got[i], want[i]
            );
        }
    }
    let got = run_c(mutant, N, &input);
    assert!(
        first_difference(&got, &want).is_some(),
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
