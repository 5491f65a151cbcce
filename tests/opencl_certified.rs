//! The certified companions of the OpenCL source (`noslip_kernels.cl`: the functions of
//! `noslip_codegen::certify::c::functions` spelled in OpenCL C, each with its batch kernel
//! `NAME_batch`) are faithful: built by the OpenCL implementation (PoCL on the CPU in CI)
//! with `-cl-fp32-correctly-rounded-divide-sqrt`, the companions return, bit for bit, the Rust
//! companions' outputs and bounds (`collision_core::kernels::dN::certified`) on
//! [`PER_REGIME`] cases from each regime of the accuracy report; so every bound is finite
//! exactly where the Rust bound is (the test also asserts that some are). The quick test runs
//! the 12 kinds of [`PAIRWISE`] (a pairwise covering of the 44 kinds: running, fast and
//! rounded-input companions of `free`, `fixed` and their FMA forms in `f64` and `f32`, the
//! `float` kernels' with the bound in `double`, the rough-ball and Walton kernels'); the
//! ignored one every companion of n = 2..6 (220).
//!
//! A companion is a straight-line program: the same IEEE operations on any input, with no
//! branch but selects. A spelling difference (another operation, a contraction into an FMA,
//! a `float` division or square root not correctly rounded, a literal read back otherwise)
//! changes the last bits of nearly every case, not of rare ones; so a few cases per regime
//! (each regime selects its own side of the selects) suffice, where the kernels' test draws
//! 10^5 per kernel. PoCL's build of each batch kernel is the test's main cost.
//!
//! Without an OpenCL device (or headers, or clang) the test says so on stderr and passes,
//! unless `NOSLIP_REQUIRE_OPENCL` is set (CI sets it in `.ci/run`), when it fails.

use crate::backend;

use backend::companions::{of, Extra, LawFixed, LawFree, RoundedFixed, RoundedFree};
use backend::{draw, opencl, same, scratch, Float};
use collision_core::certified::{CertifiedKernel, Companion, InputRounding};
use collision_core::{Ball, BodyState, Generated, Restitution, Scalar, Walton};
use noslip_accuracy::case::Case;
use noslip_accuracy::regime::Regime;
use noslip_codegen::backend::{source_with, OpenCl};
use noslip_codegen::certify::c::{companions, functions_of, name_of};
use noslip_codegen::certify::Certified;
use std::path::Path;

/// Cases per regime of the accuracy report, per companion.
const PER_REGIME: usize = 5;

/// `(rho_nu, rho_gamma2)` of the rounded-input companions: a normal normalised in `f64`,
/// `gamma2` rounded once; exact in `f32`.
const RHO: [f32; 2] = [6.0 / (1u64 << 52) as f32, 1.0 / (1u64 << 53) as f32];

/// The rough companions' law `(e, beta)`, exact in `f32`.
const ROUGH_LAW: [f32; 2] = [0.75, 0.5];

/// The Walton companions' law `(e, mu, beta0)`, exact in `f32`; mostly sticking (`mu`
/// large) in odd dimensions, mostly sliding in even ones.
const WALTON_LAWS: [[f32; 3]; 2] = [[0.75, 0.125, 0.5], [0.5, 2.0, -0.25]];

/// One result value as the host writes it.
#[derive(Clone, Copy, Debug)]
enum Value {
    F64(f64),
    F32(f32),
}

impl Value {
    fn size(self) -> usize {
        match self {
            Value::F64(_) => 8,
            Value::F32(_) => 4,
        }
    }

    /// The value of the same format in `bytes`, and whether it is [`same`] as `self`.
    fn read(self, bytes: &[u8]) -> (Value, bool) {
        match self {
            Value::F64(x) => {
                let y = f64::from_bytes(bytes)[0];
                (Value::F64(y), same(x, y))
            }
            Value::F32(x) => {
                let y = f32::from_bytes(bytes)[0];
                (Value::F32(y), same(x, y))
            }
        }
    }

    fn finite(self) -> bool {
        match self {
            Value::F64(x) => x.is_finite(),
            Value::F32(x) => x.is_finite(),
        }
    }
}

/// A format of the companions: its tables of Rust companions in an
/// [`Extra`].
trait Format<const N: usize, const S: usize>: Float
where
    Generated: CertifiedKernel<Self, N, S>,
{
    fn rounded(e: &Extra<N, S>) -> [(RoundedFree<Self, N, S>, RoundedFixed<Self, N, S>); 2];
    #[allow(clippy::type_complexity)]
    fn rough(
        e: &Extra<N, S>,
    ) -> [(
        LawFree<Self, Restitution<Self>, N, S>,
        LawFixed<Self, Restitution<Self>, N, S>,
    ); 2];
    #[allow(clippy::type_complexity)]
    fn walton(
        e: &Extra<N, S>,
    ) -> [(
        LawFree<Self, Walton<Self>, N, S>,
        LawFixed<Self, Walton<Self>, N, S>,
    ); 2];
}

/// [`Format`] for `$t`, its tables the fields `$rounded` and `$f` of an [`Extra`].
macro_rules! format_tables {
    ($t:ty, $rounded:ident, $f:ident) => {
        impl<const N: usize, const S: usize> Format<N, S> for $t
        where
            Generated: CertifiedKernel<$t, N, S>,
        {
            fn rounded(
                e: &Extra<N, S>,
            ) -> [(RoundedFree<Self, N, S>, RoundedFixed<Self, N, S>); 2] {
                e.$rounded
            }
            fn rough(
                e: &Extra<N, S>,
            ) -> [(
                LawFree<Self, Restitution<Self>, N, S>,
                LawFixed<Self, Restitution<Self>, N, S>,
            ); 2] {
                e.rough.$f
            }
            fn walton(
                e: &Extra<N, S>,
            ) -> [(
                LawFree<Self, Walton<Self>, N, S>,
                LawFixed<Self, Walton<Self>, N, S>,
            ); 2] {
                e.walton.$f
            }
        }
    };
}

format_tables!(f64, rounded64, f64);
format_tables!(f32, rounded32, f32);

/// A Rust companion on one case: per body returned, its output and its bound.
type Run<'a, T, B, const N: usize, const S: usize> =
    Box<dyn Fn(&Case<T, N, S>) -> (Vec<BodyState<T, N, S>>, Vec<BodyState<B, N, S>>) + 'a>;

/// The `free` companion `f` or the `fixed` one `g` as a [`Run`] (`fixed` with
/// `radius1 = ball1.radius`).
#[allow(clippy::type_complexity)]
fn either<'a, T: Copy + 'a, B: 'a, const N: usize, const S: usize>(
    free: bool,
    f: impl Fn(
            &[T; N],
            &Ball<T>,
            &Ball<T>,
            &BodyState<T, N, S>,
            &BodyState<T, N, S>,
        ) -> ([BodyState<T, N, S>; 2], [BodyState<B, N, S>; 2])
        + 'a,
    g: impl Fn(
            &[T; N],
            &T,
            &Ball<T>,
            &BodyState<T, N, S>,
            &BodyState<T, N, S>,
        ) -> (BodyState<T, N, S>, BodyState<B, N, S>)
        + 'a,
) -> Run<'a, T, B, N, S> {
    if free {
        Box::new(move |c| {
            let (o, e) = f(&c.nu, &c.balls[0], &c.balls[1], &c.states[0], &c.states[1]);
            (o.into(), e.into())
        })
    } else {
        Box::new(move |c| {
            let (o, e) = g(
                &c.nu,
                &c.balls[0].radius,
                &c.balls[1],
                &c.states[0],
                &c.states[1],
            );
            (vec![o], vec![e])
        })
    }
}

/// What a companion's name says: `(family, variant, fma, kind, format)`, e.g.
/// `noslip_d3_walton_fixed_fma_certified_f32` is `("walton_", "fixed", true, "", "f32")`.
fn parse(name: &str) -> (&str, &str, bool, &str, &str) {
    let (kernel, rest) = name.split_once("_certified_").expect("a companion");
    let kernel = kernel.splitn(3, '_').nth(2).expect("noslip_dN_...");
    let family = ["rough_", "walton_"]
        .into_iter()
        .find(|f| kernel.starts_with(f))
        .unwrap_or("");
    let kernel = &kernel[family.len()..];
    let (variant, fma) = match kernel.strip_suffix("_fma") {
        Some(v) => (v, true),
        None => (kernel, false),
    };
    let (kind, format) = ["fast_", "rounded_"]
        .into_iter()
        .find_map(|k| rest.strip_prefix(k).map(|f| (k, f)))
        .unwrap_or(("", rest));
    (family, variant, fma, kind, format)
}

/// The Rust companion of the OpenCL function `name` in format `T` (bound in `T`), and the
/// values its record carries after the balls (`law`) and after the states (`rho`).
fn rust_of<'a, T: Format<N, S>, const N: usize, const S: usize>(
    name: &str,
    extra: &'a Extra<N, S>,
) -> (Run<'a, T, T, N, S>, Vec<T>, Vec<T>)
where
    Generated: CertifiedKernel<T, N, S>,
{
    let (family, variant, fma, kind, _) = parse(name);
    let (free, k) = (variant == "free", usize::from(fma));
    let of = |x: &[f32]| {
        x.iter()
            .map(|&x| T::from_f64(f64::from(x)))
            .collect::<Vec<T>>()
    };
    match (family, kind) {
        ("", "rounded_") => {
            let rho = InputRounding {
                nu: T::from_f64(f64::from(RHO[0])),
                gamma2: T::from_f64(f64::from(RHO[1])),
            };
            let (f, g) = T::rounded(extra)[k];
            let run = either(
                free,
                move |nu, b1, b2, s1, s2| f(nu, b1, b2, s1, s2, &rho),
                move |nu, r1, b2, s1, s2| g(nu, r1, b2, s1, s2, &rho),
            );
            (run, Vec::new(), of(&RHO))
        }
        ("", _) => {
            let c = match kind {
                "fast_" => Companion::Fast,
                _ => Companion::Running,
            };
            let run = if fma {
                either(
                    free,
                    move |nu, b1, b2, s1, s2| Generated::free_fma(c, nu, b1, b2, s1, s2),
                    move |nu, r1, b2, s1, s2| Generated::fixed_fma(c, nu, r1, b2, s1, s2),
                )
            } else {
                either(
                    free,
                    move |nu, b1, b2, s1, s2| Generated::free(c, nu, b1, b2, s1, s2),
                    move |nu, r1, b2, s1, s2| Generated::fixed(c, nu, r1, b2, s1, s2),
                )
            };
            (run, Vec::new(), Vec::new())
        }
        ("rough_", _) => {
            let [e, beta] = ROUGH_LAW.map(|x| T::from_f64(f64::from(x)));
            let (law, law2) = (Restitution { e, beta }, Restitution { e, beta });
            let (f, g) = T::rough(extra)[k];
            let run = either(
                free,
                move |nu, b1, b2, s1, s2| f(nu, b1, b2, &law, s1, s2),
                move |nu, r1, b2, s1, s2| g(nu, r1, b2, &law2, s1, s2),
            );
            (run, of(&ROUGH_LAW), Vec::new())
        }
        _ => {
            let l = WALTON_LAWS[N % 2];
            let [e, mu, beta0] = l.map(|x| T::from_f64(f64::from(x)));
            let (law, law2) = (Walton { e, mu, beta0 }, Walton { e, mu, beta0 });
            let (f, g) = T::walton(extra)[k];
            let run = either(
                free,
                move |nu, b1, b2, s1, s2| f(nu, b1, b2, &law, s1, s2),
                move |nu, r1, b2, s1, s2| g(nu, r1, b2, &law2, s1, s2),
            );
            (run, of(&l), Vec::new())
        }
    }
}

/// How the outputs (`T`) and the bounds (`B`) of a companion become [`Value`]s.
type Values<T, B> = (fn(T) -> Value, fn(B) -> Value);

/// One companion's comparison: the host's list line, the input records, the Rust results.
struct Job {
    /// The OpenCL function.
    name: String,
    /// The host's list line.
    line: String,
    /// The input records.
    input: Vec<u8>,
    /// Per record: the outputs, then the bounds, as the host writes them.
    rust: Vec<Value>,
    /// Values per record.
    per_record: usize,
    /// The regime of each record.
    regimes: Vec<Regime>,
    /// The bounds the Rust companion gives finite.
    finite_bounds: usize,
}

/// The [`Job`] of the OpenCL function `name` on `cases`: records `nu, ball1 | radius1,
/// ball2, law.., state1, state2, rho..` (the batch kernel's parameters), results of `run`.
fn job<T: Float, B: Copy, const N: usize, const S: usize>(
    name: &str,
    cases: &[(Regime, Case<T, N, S>)],
    (run, law, rho): (Run<'_, T, B, N, S>, Vec<T>, Vec<T>),
    value: Values<T, B>,
    wide: bool,
) -> Job {
    let free = parse(name).1 == "free";
    let state = S + N;
    let (mut input, mut rust, mut finite_bounds) = (Vec::new(), Vec::new(), 0);
    for (_, c) in cases {
        let ball = |b: &Ball<T>| vec![b.inv_mass, b.radius, b.gamma2];
        let first = if free {
            ball(&c.balls[0])
        } else {
            vec![c.balls[0].radius]
        };
        let flat = |b: &BodyState<T, N, S>| {
            b.spin
                .iter()
                .chain(&b.velocity)
                .copied()
                .collect::<Vec<T>>()
        };
        let record =
            c.nu.iter()
                .copied()
                .chain(first)
                .chain(ball(&c.balls[1]))
                .chain(law.iter().copied())
                .chain(flat(&c.states[0]))
                .chain(flat(&c.states[1]))
                .chain(rho.iter().copied());
        for x in record {
            input.extend(x.bytes());
        }
        let (outs, bounds) = run(c);
        for o in &outs {
            rust.extend(o.spin.iter().chain(&o.velocity).map(|&x| value.0(x)));
        }
        for b in &bounds {
            let b: Vec<Value> = b
                .spin
                .iter()
                .chain(&b.velocity)
                .map(|&x| value.1(x))
                .collect();
            finite_bounds += b.iter().filter(|v| v.finite()).count();
            rust.extend(b);
        }
    }
    let bodies = if free { 2 } else { 1 };
    let mut ins = vec![N, if free { 3 } else { 1 }, 3];
    ins.extend((!law.is_empty()).then_some(law.len()));
    ins.extend([state, state]);
    ins.extend(rho.iter().map(|_| 1));
    let ins: Vec<String> = ins.iter().map(usize::to_string).collect();
    let bound_width = format!("{state}{}", if wide { "d" } else { "" });
    let outs: Vec<String> = std::iter::repeat_n(state.to_string(), bodies)
        .chain(std::iter::repeat_n(bound_width, bodies))
        .collect();
    Job {
        name: name.to_string(),
        line: format!(
            "{} {name} {} {}\n",
            <T as Scalar>::NAME,
            ins.join(","),
            outs.join(",")
        ),
        input,
        per_record: rust.len() / cases.len(),
        rust,
        regimes: cases.iter().map(|(r, _)| *r).collect(),
        finite_bounds,
    }
}

/// The kinds the quick test runs, `(family, format, fma, variant, n)`: every pair of values
/// of two of the first four factors meets at least once (a pairwise covering of the 44
/// kinds), in dimensions taken in turn. Each choice the emitter makes depends on one or two
/// of these factors (`fma` or `fmaf` on format and kernel, `fabs`/`sqrt` of the bound on the
/// format, the scalar `radius1` on the variant, the `rho` scalars and the `law` array on the
/// family, `(double)` conversions on the wide format), so each is exercised.
const PAIRWISE: [(&str, &str, bool, &str, usize); 12] = [
    ("running", "f64", false, "free", 2),
    ("running", "f32", true, "fixed", 3),
    ("fast", "f64", true, "fixed", 4),
    ("fast", "f32", false, "free", 5),
    ("rounded", "f64", false, "fixed", 6),
    ("rounded", "f32", true, "free", 2),
    ("wide", "f32_wide", false, "free", 3),
    ("wide", "f32_wide", true, "fixed", 4),
    ("rough", "f64", true, "free", 5),
    ("rough", "f32", false, "fixed", 6),
    ("walton", "f64", false, "fixed", 2),
    ("walton", "f32", true, "free", 3),
];

/// The kind of the companion `name`, as [`PAIRWISE`] lists it (without the dimension).
fn kind_of(name: &str) -> (&str, &str, bool, &str) {
    let (family, variant, fma, kind, format) = parse(name);
    let family = match (family, kind, format) {
        ("rough_", ..) => "rough",
        ("walton_", ..) => "walton",
        (_, "fast_", _) => "fast",
        (_, "rounded_", _) => "rounded",
        (_, _, "f32_wide") => "wide",
        _ => "running",
    };
    (family, format, fma, variant)
}

/// The companions of dimension `N` ([`companions`]) the test runs, each with its [`Job`]:
/// with `all` every one, otherwise those of [`PAIRWISE`] in dimension `N`.
fn dim_jobs<const N: usize, const S: usize>(extra: &Extra<N, S>, all: bool) -> Vec<(Certified, Job)>
where
    Generated: CertifiedKernel<f64, N, S> + CertifiedKernel<f32, N, S>,
{
    let cases = draw::<N, S>(PER_REGIME * Regime::ALL.len(), 2800 + N as u64);
    companions(&[N])
        .into_iter()
        .filter(|c| {
            let name = name_of(c);
            let (family, format, fma, variant) = kind_of(&name);
            all || PAIRWISE.contains(&(family, format, fma, variant, N))
        })
        .map(|c| {
            let name = name_of(&c);
            let f64v = |x: f64| Value::F64(x);
            let f32v = |x: f32| Value::F32(x);
            let (_, variant, fma, _, format) = parse(&name);
            let job = match format {
                "f64" => job(
                    &name,
                    &cases.f64,
                    rust_of::<f64, N, S>(&name, extra),
                    (f64v, f64v),
                    false,
                ),
                "f32" => job(
                    &name,
                    &cases.f32,
                    rust_of::<f32, N, S>(&name, extra),
                    (f32v, f32v),
                    false,
                ),
                _ => {
                    let (f, g) = extra.wide[usize::from(fma)];
                    let run = either(variant == "free", f, g);
                    job(
                        &name,
                        &cases.f32,
                        (run, Vec::new(), Vec::new()),
                        (f32v, f64v),
                        true,
                    )
                }
            };
            (c, job)
        })
        .collect()
}

/// Compare the host's results in `dir` with the Rust ones; one message per difference.
fn compare(dir: &Path, job: &Job) -> Option<String> {
    let out = dir.join(format!("{}.out", job.name));
    let bytes = match std::fs::read(&out) {
        Ok(b) => b,
        Err(e) => return Some(format!("{}: {e}", out.display())),
    };
    let expected: usize = job.rust.iter().map(|v| v.size()).sum();
    if bytes.len() != expected {
        return Some(format!(
            "{}: {} bytes of results, expected {expected}",
            job.name,
            bytes.len()
        ));
    }
    let (mut at, mut bad, mut first) = (0, 0, None);
    for (k, v) in job.rust.iter().enumerate() {
        let (cl, ok) = v.read(&bytes[at..at + v.size()]);
        at += v.size();
        if !ok {
            bad += 1;
            first.get_or_insert((k, *v, cl));
        }
    }
    first.map(|(k, rust, cl)| {
        let (record, slot) = (k / job.per_record, k % job.per_record);
        format!(
            "{} (OpenCL): {bad} of {} values differ; the first, record {record} ({:?}) slot {slot} \
             (outputs, then bounds): Rust {rust:?}, OpenCL {cl:?}",
            job.name,
            job.rust.len(),
            job.regimes[record]
        )
    })
}

macro_rules! every_dim {
    ($all:expr, $(($m:ident $n:literal $s:literal))*) => {{
        let mut jobs = Vec::new();
        $(jobs.extend(dim_jobs::<$n, $s>(&of!($m), $all));)*
        jobs
    }};
}

/// Build the chosen companions ([`dim_jobs`]) with the OpenCL implementation, run each batch
/// kernel on its records, compare with Rust.
fn check(all: bool) {
    let dir = scratch(if all {
        "opencl-certified-all"
    } else {
        "opencl-certified"
    });
    const TEST: &str = "OpenCL certified-companion faithfulness test";
    let (chosen, jobs): (Vec<Certified>, Vec<Job>) =
        every_dim!(all, (d2 2 1) (d3 3 3) (d4 4 6) (d5 5 10) (d6 6 15))
            .into_iter()
            .unzip();
    let every = 5 * companions(&[2]).len();
    assert_eq!(jobs.len(), if all { every } else { PAIRWISE.len() });
    let source = dir.join("noslip_certified.cl");
    std::fs::write(
        &source,
        source_with(
            &OpenCl,
            "NOSLIP_KERNELS",
            "Certified companions of noslip_kernels.cl (its functions, as they are there)",
            &[],
            &functions_of(&OpenCl, &chosen),
        ),
    )
    .unwrap();
    let Some(host) = opencl::host_for(TEST, &source, &dir) else {
        return;
    };
    let mut list = String::new();
    for j in &jobs {
        std::fs::write(dir.join(format!("{}.bin", j.name)), &j.input).unwrap();
        list.push_str(&j.line);
    }
    let list_file = dir.join("certified.txt");
    std::fs::write(&list_file, list).unwrap();
    if let Err(why) = opencl::run_host(&host, &source, &dir, Some(&list_file)) {
        return opencl::skip(TEST, &why);
    }
    let mut failures: Vec<String> = jobs.iter().filter_map(|j| compare(&dir, j)).collect();
    for j in &jobs {
        if j.finite_bounds == 0 {
            failures.push(format!("{}: no finite Rust bound among the cases", j.name));
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The [`PAIRWISE`] companions.
#[test]
fn opencl_certified_companions_are_bit_identical_to_the_rust_ones() {
    check(false);
}

/// Every companion of every dimension (220; about a minute to build cold):
/// `NOSLIP_REQUIRE_OPENCL=1 cargo test -p noslip-tests --test all opencl_certified:: -- --ignored`.
#[test]
#[ignore = "every companion in every dimension: about a minute of OpenCL build"]
fn every_opencl_certified_companion_is_bit_identical_to_the_rust_one() {
    check(true);
}
