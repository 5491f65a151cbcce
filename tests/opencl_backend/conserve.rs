//! Part of `opencl_backend.rs`: the energy-conserving correction in OpenCL C
//! (`noslip_conserve_fixed_dN`, `noslip_conserve_free_dN` of `noslip_kernels.cl`, run through
//! their batch kernels; `noslip_codegen::backend`'s `conserve.rs`) returns the Rust
//! correction's bits (`collision_core::conserve`), every result finite ([`compare`]): the
//! whole shipped source (`generate`) built by the OpenCL implementation (PoCL on the CPU in
//! CI), on 20 000 contacts per dimension (n = 2..6) drawn from every regime of the accuracy
//! report, the Rust kernels' outputs corrected by both. The test counts that most of the
//! corrections change the kernel's outputs, so a correction that did nothing would fail; the
//! C test (`c_backend/conserve.rs`) shows on the same kind of contacts that round to nearest
//! in place of the stochastic rounding changes the bits.
//!
//! Without an OpenCL device (or headers, or clang) the test says so on stderr and passes,
//! unless `NOSLIP_REQUIRE_OPENCL` is set (CI sets it in `.ci/run`), when it fails.

use super::backend::conserve::{contacts, Drawn};
use super::backend::{compare, opencl, scratch, Float};
use collision_core::{Generated, Kernel};
use noslip_codegen::backend::{file_name, generate, Lang};
use std::fmt::Write;
use std::path::Path;

const CASES: usize = 20_000;

/// The two batch kernels' names in dimension `N`.
fn names<const N: usize>() -> [String; 2] {
    ["fixed", "free"].map(|k| format!("noslip_conserve_{k}_d{N}"))
}

/// Write dimension `N`'s input files and their lines of the host's list; return the cases
/// and the Rust results (fixed, then free).
fn prepare<const N: usize, const S: usize>(
    dir: &Path,
    list: &mut String,
) -> (Drawn<N, S>, [Vec<f64>; 2])
where
    Generated: Kernel<f64, N, S>,
{
    let (cases, contacts, changed) = contacts::<N, S>(CASES, 4300 + N as u64);
    // Most of the 2 x CASES corrections apply (the rest: immovable bodies, and the regimes
    // where the pair's centre of mass carries the energy or the energies leave the range).
    assert!(
        changed > CASES,
        "n = {N}: {changed} of {} corrected",
        2 * CASES
    );
    let (mut fixed, mut free) = (Vec::new(), Vec::new());
    let mut want: [Vec<f64>; 2] = Default::default();
    for c in &contacts {
        let f = c.balls[1].iter().chain(&c.before[1]).chain(&c.fixed);
        fixed.extend(f.flat_map(|&x| x.bytes()));
        let g = c.balls.iter().flatten().chain(c.before.iter().flatten());
        free.extend(g.chain(c.after.iter().flatten()).flat_map(|&x| x.bytes()));
        want[0].extend(&c.want_fixed);
        want[1].extend(c.want_free.iter().flatten());
    }
    let len = S + N;
    let [fixed_name, free_name] = names::<N>();
    std::fs::write(dir.join(format!("{fixed_name}.bin")), fixed).unwrap();
    std::fs::write(dir.join(format!("{free_name}.bin")), free).unwrap();
    let _ = writeln!(list, "f64 {fixed_name} 3,{len},{len} {len}");
    let _ = writeln!(
        list,
        "f64 {free_name} 3,3,{len},{len},{len},{len} {len},{len}"
    );
    (cases, want)
}

/// Compare dimension `N`'s OpenCL results with the Rust correction.
fn check<const N: usize, const S: usize>(
    dir: &Path,
    cases: &Drawn<N, S>,
    want: &[Vec<f64>; 2],
) -> Vec<String> {
    let mut failures = Vec::new();
    for (name, want) in names::<N>().iter().zip(want) {
        let out = dir.join(format!("{name}.out"));
        match std::fs::read(&out) {
            Ok(bytes) => {
                let got = f64::from_bytes(&bytes);
                failures.extend(compare(&format!("{name} (OpenCL)"), cases, want, &got).err());
            }
            Err(e) => failures.push(format!("{}: {e}", out.display())),
        }
    }
    failures
}

#[test]
fn the_opencl_correction_is_the_rust_correction_bit_for_bit() {
    const TEST: &str = "OpenCL correction test";
    let dir = scratch("opencl-conserve");
    let source = dir.join(file_name(Lang::OpenCl));
    std::fs::write(&source, generate(Lang::OpenCl, &[2, 3, 4, 5, 6])).unwrap();
    let Some(host) = opencl::host_for(TEST, &source, &dir) else {
        return;
    };
    let mut list = String::new();
    let d2 = prepare::<2, 1>(&dir, &mut list);
    let d3 = prepare::<3, 3>(&dir, &mut list);
    let d4 = prepare::<4, 6>(&dir, &mut list);
    let d5 = prepare::<5, 10>(&dir, &mut list);
    let d6 = prepare::<6, 15>(&dir, &mut list);
    let list_path = dir.join("conserve.list");
    std::fs::write(&list_path, list).unwrap();
    if let Err(why) = opencl::run_host(&host, &source, &dir, Some(&list_path)) {
        return opencl::skip(TEST, &why);
    }
    let mut failures = check::<2, 1>(&dir, &d2.0, &d2.1);
    failures.extend(check::<3, 3>(&dir, &d3.0, &d3.1));
    failures.extend(check::<4, 6>(&dir, &d4.0, &d4.1));
    failures.extend(check::<5, 10>(&dir, &d5.0, &d5.1));
    failures.extend(check::<6, 15>(&dir, &d6.0, &d6.1));
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
