//! Shared by the back-end faithfulness tests (`c_backend.rs`, `opencl_backend.rs`,
//! `scene_backends.rs`): cases
//! drawn from the accuracy report's regimes, their binary records, the Rust kernels' results,
//! and the bitwise comparison.
//!
//! A record is the C ABI's parameters in a row (docs/backends.md): `nu[N]`, `ball1[3]`,
//! `ball2[3]`, `state1[S+N]`, `state2[S+N]`, with `ball = {inv_mass, radius, gamma2}` and
//! `state = {spin, velocity}`; `fixed` takes `radius1 = ball1[1]`. The results are
//! `out1[S+N], out2[S+N]` (free) or `out2[S+N]` (fixed).

#![allow(dead_code)]

pub mod companions;
pub mod conserve;
pub mod opencl;

use collision_core::rng::Rng;
use collision_core::{
    BodyState, Generated, Kernel, Restitution, RoughKernel, ScalarRoot, Walton, WaltonKernel,
};
use noslip_accuracy::case::Case;
use noslip_accuracy::regime::Regime;
use noslip_codegen::backend::{file_name, Lang};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The generated kernels of each dimension, as the harnesses name them.
pub const KERNELS: [&str; 4] = ["free", "fixed", "free_fma", "fixed_fma"];

/// A float format the kernels run in, seen through its bits (`Scalar::NAME` is `f64`, `f32`).
pub trait Float: ScalarRoot + Copy {
    /// Its bytes in native order.
    fn bytes(self) -> Vec<u8>;
    /// The values of a file of native-order bytes.
    fn from_bytes(bytes: &[u8]) -> Vec<Self>;
    /// Its bit pattern.
    fn bits(self) -> u64;
    /// Whether it is finite.
    fn finite(self) -> bool;
    /// Whether it is a NaN.
    fn nan(self) -> bool;
    /// The value of this format nearest to `x`.
    fn from_f64(x: f64) -> Self;
    /// Whether every result must be finite in `regime`: always in `f64` (the accuracy report
    /// fails the `f64` kernel on any NaN); in `f32` except at extreme scales, whose inputs up
    /// to `1e38` overflow `f32` products inside the kernel (Rust's `f32` kernel too: the
    /// comparison shows the same infinities).
    fn must_be_finite(regime: Regime) -> bool;
}

impl Float for f64 {
    fn bytes(self) -> Vec<u8> {
        self.to_ne_bytes().to_vec()
    }
    fn from_bytes(bytes: &[u8]) -> Vec<Self> {
        bytes
            .chunks_exact(8)
            .map(|c| f64::from_ne_bytes(c.try_into().unwrap()))
            .collect()
    }
    fn bits(self) -> u64 {
        self.to_bits()
    }
    fn finite(self) -> bool {
        self.is_finite()
    }
    fn nan(self) -> bool {
        self.is_nan()
    }
    fn from_f64(x: f64) -> Self {
        x
    }
    fn must_be_finite(_: Regime) -> bool {
        true
    }
}

impl Float for f32 {
    fn bytes(self) -> Vec<u8> {
        self.to_ne_bytes().to_vec()
    }
    fn from_bytes(bytes: &[u8]) -> Vec<Self> {
        bytes
            .chunks_exact(4)
            .map(|c| f32::from_ne_bytes(c.try_into().unwrap()))
            .collect()
    }
    fn bits(self) -> u64 {
        u64::from(self.to_bits())
    }
    fn finite(self) -> bool {
        self.is_finite()
    }
    fn nan(self) -> bool {
        self.is_nan()
    }
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    fn must_be_finite(regime: Regime) -> bool {
        regime != Regime::Scale
    }
}

/// `count` cases per format, cycling through every regime of the accuracy report
/// ([`Regime::ALL`], its own samplers): the `f64` cases, and the `f32` cases (the draws whose
/// inputs `f32` can hold, `Case::to_f32`; the extreme-scale regime mostly cannot), each with
/// its regime.
pub struct Cases<const N: usize, const S: usize> {
    /// `f64` cases.
    pub f64: Vec<(Regime, Case<f64, N, S>)>,
    /// `f32` cases.
    pub f32: Vec<(Regime, Case<f32, N, S>)>,
}

/// Draw [`Cases`] with a fixed seed.
pub fn draw<const N: usize, const S: usize>(count: usize, seed: u64) -> Cases<N, S> {
    let mut rng = Rng::new(seed);
    let (mut f64s, mut f32s) = (Vec::with_capacity(count), Vec::with_capacity(count));
    let mut i = 0;
    while f64s.len() < count || f32s.len() < count {
        let regime = Regime::ALL[i % Regime::ALL.len()];
        i += 1;
        let case = regime.sample::<N, S>(&mut rng);
        if f32s.len() < count {
            if let Ok(c32) = case.to_f32() {
                f32s.push((regime, c32));
            }
        }
        if f64s.len() < count {
            f64s.push((regime, case));
        }
    }
    Cases {
        f64: f64s,
        f32: f32s,
    }
}

/// A state's values in the records' order: the spin entries, then the velocity.
pub fn state<T: Copy, const N: usize, const S: usize>(
    s: &BodyState<T, N, S>,
) -> impl Iterator<Item = T> + '_ {
    s.spin.iter().chain(&s.velocity).copied()
}

/// The cases as one file of records.
pub fn records<T: Float, const N: usize, const S: usize>(
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<u8> {
    let mut out = Vec::new();
    for (_, c) in cases {
        let values =
            c.nu.iter()
                .copied()
                .chain(
                    c.balls
                        .iter()
                        .flat_map(|b| [b.inv_mass, b.radius, b.gamma2]),
                )
                .chain(state(&c.states[0]))
                .chain(state(&c.states[1]));
        for v in values {
            out.extend(v.bytes());
        }
    }
    out
}

/// The Rust kernel `kernel` (one of [`KERNELS`]) on every case, flattened as the harness
/// writes its results.
pub fn rust_results<T: Float, const N: usize, const S: usize>(
    kernel: &str,
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<T>
where
    Generated: Kernel<T, N, S>,
{
    let mut out = Vec::new();
    for (_, c) in cases {
        let (nu, [b1, b2], [s1, s2]) = (&c.nu, c.ball_refs(), c.state_refs());
        let bodies: Vec<BodyState<T, N, S>> = match kernel {
            "free" => Generated::free(nu, b1, b2, s1, s2).to_vec(),
            "free_fma" => Generated::free_fma(nu, b1, b2, s1, s2).to_vec(),
            "fixed" => vec![Generated::fixed(nu, &b1.radius, b2, s1, s2)],
            "fixed_fma" => vec![Generated::fixed_fma(nu, &b1.radius, b2, s1, s2)],
            _ => panic!("no kernel {kernel}"),
        };
        for b in &bodies {
            out.extend(state(b));
        }
    }
    out
}

/// The rough-ball kernels of each dimension, as the harnesses name them.
pub const ROUGH_KERNELS: [&str; 4] = [
    "rough_free",
    "rough_fixed",
    "rough_free_fma",
    "rough_fixed_fma",
];

/// The laws `(e, beta)` the rough kernels are compared under: inside the ranges, and the
/// ends (the smooth member `(1, -1)`, `e = 0`). Each is exact in `f32` and `f64` and prints
/// as a shortest round-trip decimal, so the harness's `strtod`/`strtof` reads the same value.
pub const LAWS: [(f64, f64); 3] = [(0.9, 0.4), (0.0, -1.0), (0.3, -0.7)];

/// The Rust rough kernel `kernel` (one of [`ROUGH_KERNELS`]) under `law` on every case,
/// flattened as the harness writes its results.
pub fn rust_rough_results<T: Float, const N: usize, const S: usize>(
    kernel: &str,
    law: &Restitution<T>,
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<T>
where
    Generated: RoughKernel<T, N, S>,
{
    let mut out = Vec::new();
    for (_, c) in cases {
        let (nu, [b1, b2], [s1, s2]) = (&c.nu, c.ball_refs(), c.state_refs());
        let bodies: Vec<BodyState<T, N, S>> = match kernel {
            "rough_free" => Generated::rough_free(nu, b1, b2, law, s1, s2).to_vec(),
            "rough_free_fma" => Generated::rough_free_fma(nu, b1, b2, law, s1, s2).to_vec(),
            "rough_fixed" => vec![Generated::rough_fixed(nu, &b1.radius, b2, law, s1, s2)],
            "rough_fixed_fma" => {
                vec![Generated::rough_fixed_fma(nu, &b1.radius, b2, law, s1, s2)]
            }
            _ => panic!("no kernel {kernel}"),
        };
        for b in &bodies {
            out.extend(state(b));
        }
    }
    out
}

/// The Walton kernels of each dimension, as the harnesses name them.
pub const WALTON_KERNELS: [&str; 4] = [
    "walton_free",
    "walton_fixed",
    "walton_free_fma",
    "walton_fixed_fma",
];

/// The laws `(e, mu, beta0)` the Walton kernels are compared under: inside the ranges, and
/// the ends (`mu = 0`, `beta0 = 1`, `e = 0`); over the regimes' contacts some stick and some
/// slide. Decimal as [`LAWS`].
pub const WALTON_LAWS: [[f64; 3]; 3] = [[0.9, 0.3, 0.5], [1.0, 0.0, 1.0], [0.0, 2.0, -0.2]];

/// The Rust Walton kernel `kernel` (one of [`WALTON_KERNELS`]) under `law` on every case,
/// flattened as the harness writes its results.
pub fn rust_walton_results<T: Float, const N: usize, const S: usize>(
    kernel: &str,
    law: &Walton<T>,
    cases: &[(Regime, Case<T, N, S>)],
) -> Vec<T>
where
    Generated: WaltonKernel<T, N, S>,
{
    let mut out = Vec::new();
    for (_, c) in cases {
        let (nu, [b1, b2], [s1, s2]) = (&c.nu, c.ball_refs(), c.state_refs());
        let bodies: Vec<BodyState<T, N, S>> = match kernel {
            "walton_free" => Generated::walton_free(nu, b1, b2, law, s1, s2).to_vec(),
            "walton_free_fma" => Generated::walton_free_fma(nu, b1, b2, law, s1, s2).to_vec(),
            "walton_fixed" => vec![Generated::walton_fixed(nu, &b1.radius, b2, law, s1, s2)],
            "walton_fixed_fma" => {
                vec![Generated::walton_fixed_fma(nu, &b1.radius, b2, law, s1, s2)]
            }
            _ => panic!("no kernel {kernel}"),
        };
        for b in &bodies {
            out.extend(state(b));
        }
    }
    out
}

/// Whether two results are the same: equal bit patterns, or both NaN (IEEE 754 leaves the sign
/// and payload of a NaN an operation returns unspecified; they arise only where `f32`
/// overflows, see [`Float::must_be_finite`]).
pub fn same<T: Float>(a: T, b: T) -> bool {
    a.bits() == b.bits() || (a.nan() && b.nan())
}

/// Compare a foreign kernel's results with Rust's bit for bit ([`same`]); each foreign result
/// must also be finite where [`Float::must_be_finite`] says so. `Err` names the count of
/// differing components and the first, with its regime.
pub fn compare<T: Float, const N: usize, const S: usize>(
    what: &str,
    cases: &[(Regime, Case<T, N, S>)],
    rust: &[T],
    foreign: &[T],
) -> Result<(), String> {
    if rust.len() != foreign.len() {
        return Err(format!(
            "{what}: {} results, expected {}",
            foreign.len(),
            rust.len()
        ));
    }
    let per_case = rust.len() / cases.len();
    let differ: Vec<usize> = (0..rust.len())
        .filter(|&k| !same(rust[k], foreign[k]))
        .collect();
    if let Some(&k) = differ.first() {
        let (regime, _) = &cases[k / per_case];
        return Err(format!(
            "{what}: {} of {} components differ from Rust's; the first, case {} ({}) component {}: \
             Rust {:?} (bits {:#x}), foreign {:?} (bits {:#x})",
            differ.len(),
            rust.len(),
            k / per_case,
            regime.name(),
            k % per_case,
            rust[k],
            rust[k].bits(),
            foreign[k],
            foreign[k].bits()
        ));
    }
    let must = |k: usize| T::must_be_finite(cases[k / per_case].0);
    if let Some(k) = (0..foreign.len()).find(|&k| must(k) && !foreign[k].finite()) {
        return Err(format!(
            "{what}: non-finite result {:?} in case {} ({})",
            foreign[k],
            k / per_case,
            cases[k / per_case].0.name()
        ));
    }
    Ok(())
}

/// Scratch directories removed when a test is done with them (shared with the command
/// line's tests).
#[path = "../scratch.rs"]
mod scratch;
pub use scratch::scratch;

/// The checked-in C sources of these tests (`tests/c/`).
pub fn c_source(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("c").join(name)
}

/// Run a command; panic with its stderr when it fails.
pub fn run(cmd: &mut Command) {
    let out = cmd.output().unwrap_or_else(|e| panic!("{cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{cmd:?} failed ({}):\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Write the C `header` into `dir` and compile the harness `harness` (of `tests/c/`) against
/// it with `compiler` and `flags` into `dir/exe`; warnings are errors, so the emitted C must
/// compile cleanly.
pub fn compile_harness(
    dir: &Path,
    header: &str,
    compiler: &str,
    flags: &[&str],
    harness: &str,
    exe: &str,
) -> PathBuf {
    std::fs::write(dir.join(file_name(Lang::C)), header).unwrap();
    let exe = dir.join(exe);
    run(Command::new(compiler)
        .args(["-Wall", "-Wextra", "-Werror"])
        .args(flags)
        .arg("-I")
        .arg(dir)
        .arg(c_source(harness))
        .arg("-o")
        .arg(&exe)
        .arg("-lm"));
    exe
}

/// The C compiler: `$CC`, else `cc`.
pub fn cc() -> String {
    std::env::var("CC").unwrap_or_else(|_| "cc".into())
}
