//! The rounded-input companions (`..._certified_rounded_{f64|f32}`, plain and FMA), the
//! `float` kernels' companions with the bound in `double` (`..._certified_f32_wide`) and the
//! rough-ball and Walton kernels' (`noslip_dN_{rough|walton}_..._certified_...`) against
//! their Rust forms (`kernels::dN::certified::{free,fixed}{,_fma}_rounded{,_f32}`,
//! `..._f32_wide`, `rough_free`, `walton_fixed_fma_f32`, ...), through the harness compiled
//! for the other companions; the rough-family ones under each law of [`ROUGH_LAWS`] and
//! [`WALTON_LAWS`], passed to the harness for every record.

use super::backend::companions::{
    Extra, LawFixed, LawFree, RoundedFixed, RoundedFree, WideFixed, WideFree,
};
use super::{compare, Job, Results};
use collision_core::certified::InputRounding;
use collision_core::{Restitution, Walton};
use noslip_accuracy::case::Case;
use noslip_accuracy::regime::Regime;
use std::path::{Path, PathBuf};

/// `(rho_nu, rho_gamma2)` tried, each exact in `f32` (so the harness's `strtod` of the
/// shortest decimal restores it in both formats): a normal normalised in `f64` with
/// `gamma2` rounded once (`6 2^-52`, `2^-53`), larger input errors (`2^-20`, `2^-30`), and
/// `rho_gamma2` past the rule's limit `2^-10` (`+inf` bounds wherever `gamma2` reaches).
pub const RHOS: &[(f32, f32)] = &[
    (6.0 / (1u64 << 52) as f32, 1.0 / (1u64 << 53) as f32),
    (1.0 / (1u32 << 20) as f32, 1.0 / (1u32 << 30) as f32),
    (1.0 / (1u32 << 12) as f32, 1.0 / (1u32 << 9) as f32),
];

/// `(variant, fma)` of the four companions of a kind, by harness name.
const NAMES: [(&str, usize); 4] = [("free", 0), ("fixed", 0), ("free_fma", 1), ("fixed_fma", 1)];

/// A rounded-input pair on every case (the harness's convention: `free` on both balls,
/// `fixed` with `radius1 = ball1.radius`).
fn rounded<T: Copy, const N: usize, const S: usize>(
    (free, fixed): (RoundedFree<T, N, S>, RoundedFixed<T, N, S>),
    is_free: bool,
    rho: &InputRounding<T>,
    cases: &[(Regime, Case<T, N, S>)],
) -> Results<T, T> {
    let mut out = Results::new();
    for (_, c) in cases {
        let ([b1, b2], [s1, s2]) = (&c.balls, &c.states);
        if is_free {
            let (o, e) = free(&c.nu, b1, b2, s1, s2, rho);
            out.push(&o, &e);
        } else {
            let (o, e) = fixed(&c.nu, &b1.radius, b2, s1, s2, rho);
            out.push(&[o], &[e]);
        }
    }
    out
}

/// `(e, beta)` of the rough companions' comparisons, exact in `f32`.
pub const ROUGH_LAWS: &[[f32; 2]] = &[[0.75, 0.5], [0.25, -0.375]];

/// `(e, mu, beta0)` of the Walton companions' comparisons, exact in `f32`: a small `mu`
/// (mostly sliding), a large one (mostly sticking), and `mu = 0`.
pub const WALTON_LAWS: &[[f32; 3]] = &[[0.75, 0.125, 0.5], [0.5, 2.0, -0.25], [1.0, 0.0, 1.0]];

/// A rough-family pair on every case, under `law`.
fn family<T: Copy, L, const N: usize, const S: usize>(
    (free, fixed): (LawFree<T, L, N, S>, LawFixed<T, L, N, S>),
    is_free: bool,
    law: &L,
    cases: &[(Regime, Case<T, N, S>)],
) -> Results<T, T> {
    let mut out = Results::new();
    for (_, c) in cases {
        let ([b1, b2], [s1, s2]) = (&c.balls, &c.states);
        if is_free {
            let (o, e) = free(&c.nu, b1, b2, law, s1, s2);
            out.push(&o, &e);
        } else {
            let (o, e) = fixed(&c.nu, &b1.radius, b2, law, s1, s2);
            out.push(&[o], &[e]);
        }
    }
    out
}

/// A wide pair on every case.
fn wide<const N: usize, const S: usize>(
    (free, fixed): (WideFree<N, S>, WideFixed<N, S>),
    is_free: bool,
    cases: &[(Regime, Case<f32, N, S>)],
) -> Results<f32, f64> {
    let mut out = Results::new();
    for (_, c) in cases {
        let ([b1, b2], [s1, s2]) = (&c.balls, &c.states);
        if is_free {
            let (o, e) = free(&c.nu, b1, b2, s1, s2);
            out.push(&o, &e);
        } else {
            let (o, e) = fixed(&c.nu, &b1.radius, b2, s1, s2);
            out.push(&[o], &[e]);
        }
    }
    out
}

impl<const N: usize, const S: usize> Extra<N, S> {
    /// Compare the C forms with these Rust companions on `cases`, the rounded-input ones
    /// under each pair of `rhos`; one message per difference.
    pub fn check(
        &self,
        dir: &Path,
        exes: &[(&str, PathBuf)],
        cases: &super::backend::Cases<N, S>,
        rhos: &[(f32, f32)],
        laws: Laws,
    ) -> Vec<String> {
        let mut failures = Vec::new();
        let in64 = dir.join(format!("extra_{N}_f64.bin"));
        let in32 = dir.join(format!("extra_{N}_f32.bin"));
        std::fs::write(&in64, super::records(&cases.f64)).unwrap();
        std::fs::write(&in32, super::records(&cases.f32)).unwrap();
        for (name, fma) in NAMES {
            let is_free = name.starts_with("free");
            for &(rho_nu, rho_gamma2) in rhos {
                let args = |p: &str| {
                    vec![
                        format!("{name}_rounded"),
                        p.to_string(),
                        // The `f64` value's shortest decimal: `strtod` restores it exactly.
                        format!("{:e}", f64::from(rho_nu)),
                        format!("{:e}", f64::from(rho_gamma2)),
                    ]
                };
                let what = |p: &str| {
                    format!(
                        "n = {N}, {name}_rounded_certified {p} (rho {rho_nu:e}, {rho_gamma2:e})"
                    )
                };
                let rho64 = InputRounding {
                    nu: f64::from(rho_nu),
                    gamma2: f64::from(rho_gamma2),
                };
                let job = Job {
                    what: what("f64"),
                    args: args("f64"),
                    rust: rounded(self.rounded64[fma], is_free, &rho64, &cases.f64),
                };
                failures.extend(compare::<f64, f64, N>(exes, &in64, &job));
                let rho32 = InputRounding {
                    nu: rho_nu,
                    gamma2: rho_gamma2,
                };
                let job = Job {
                    what: what("f32"),
                    args: args("f32"),
                    rust: rounded(self.rounded32[fma], is_free, &rho32, &cases.f32),
                };
                failures.extend(compare::<f32, f32, N>(exes, &in32, &job));
            }
            let job = Job {
                what: format!("n = {N}, {name}_certified f32_wide"),
                args: vec![name.to_string(), "f32_wide".to_string()],
                rust: wide(self.wide[fma], is_free, &cases.f32),
            };
            failures.extend(compare::<f32, f64, N>(exes, &in32, &job));
            for law in laws.rough {
                let (l64, l32) = (
                    Restitution {
                        e: f64::from(law[0]),
                        beta: f64::from(law[1]),
                    },
                    Restitution {
                        e: law[0],
                        beta: law[1],
                    },
                );
                failures.extend(self.compare_family(
                    exes,
                    (&in64, &in32),
                    (&format!("rough_{name}"), &law[..]),
                    (&self.rough.f64[fma], &self.rough.f32[fma]),
                    (&l64, &l32),
                    is_free,
                    cases,
                ));
            }
            for law in laws.walton {
                let l64 = Walton {
                    e: f64::from(law[0]),
                    mu: f64::from(law[1]),
                    beta0: f64::from(law[2]),
                };
                let l32 = Walton {
                    e: law[0],
                    mu: law[1],
                    beta0: law[2],
                };
                failures.extend(self.compare_family(
                    exes,
                    (&in64, &in32),
                    (&format!("walton_{name}"), &law[..]),
                    (&self.walton.f64[fma], &self.walton.f32[fma]),
                    (&l64, &l32),
                    is_free,
                    cases,
                ));
            }
        }
        std::fs::remove_file(&in64).unwrap();
        std::fs::remove_file(&in32).unwrap();
        failures
    }
}

/// The laws the rough-family comparisons run under.
#[derive(Clone, Copy)]
pub struct Laws {
    /// `(e, beta)` pairs.
    pub rough: &'static [[f32; 2]],
    /// `(e, mu, beta0)` triples.
    pub walton: &'static [[f32; 3]],
}

/// Every law of [`ROUGH_LAWS`] and [`WALTON_LAWS`].
pub const LAWS: Laws = Laws {
    rough: ROUGH_LAWS,
    walton: WALTON_LAWS,
};

impl<const N: usize, const S: usize> Extra<N, S> {
    /// One rough-family companion (`kernel`, e.g. `walton_free_fma`) under one law, in
    /// both formats.
    #[allow(clippy::too_many_arguments, clippy::type_complexity)]
    fn compare_family<L64, L32>(
        &self,
        exes: &[(&str, PathBuf)],
        (in64, in32): (&Path, &Path),
        (kernel, law): (&str, &[f32]),
        (k64, k32): (
            &(LawFree<f64, L64, N, S>, LawFixed<f64, L64, N, S>),
            &(LawFree<f32, L32, N, S>, LawFixed<f32, L32, N, S>),
        ),
        (l64, l32): (&L64, &L32),
        is_free: bool,
        cases: &super::backend::Cases<N, S>,
    ) -> Vec<String> {
        // The f64 value's shortest decimal: `strtod` restores it exactly.
        let law_args: Vec<String> = law.iter().map(|x| format!("{:e}", f64::from(*x))).collect();
        let mut failures = Vec::new();
        for (p, input) in [("f64", in64), ("f32", in32)] {
            let what = format!("n = {N}, {kernel}_certified {p} (law {law:?})");
            let args: Vec<String> = [kernel.to_string(), p.to_string()]
                .into_iter()
                .chain(law_args.iter().cloned())
                .collect();
            if p == "f64" {
                let rust = family(*k64, is_free, l64, &cases.f64);
                failures.extend(compare::<f64, f64, N>(
                    exes,
                    input,
                    &Job { what, args, rust },
                ));
            } else {
                let rust = family(*k32, is_free, l32, &cases.f32);
                failures.extend(compare::<f32, f32, N>(
                    exes,
                    input,
                    &Job { what, args, rust },
                ));
            }
        }
        failures
    }
}
