//! The proven rounding-error bound (`noslip_codegen::bound`, per case through
//! `noslip_accuracy::proven`) against the true error of the generated kernels (f64, f64 FMA,
//! f32), computed exactly: for every case and every output component,
//! `|computed - exact| <= bound`, compared in exact rationals; and per movable body, the
//! measured normwise error within the body's proven normwise bound (both in `f64`; the
//! measured figure's own rounding is below `2^-50` of itself, so the comparison allows a
//! relative `2^-40`).
//!
//! Cases: every regime of the report (typical, mass ratios to 1e15, an immovable body,
//! `gamma^2` to 1e-15 and 0, radius ratios to 1e6, scales 1e-100..1e100, spin-dominated,
//! near-grazing) and an adversarial mix that combines several extremes in one case. `cargo
//! test` runs a few per regime and n; the long run is the ignored test
//! `a_million_cases_per_dimension_and_precision` (`NOSLIP_BOUND_CASES` per n and precision,
//! default 10^6):
//!
//! ```sh
//! cargo test --release -p noslip-accuracy --test proven -- --ignored --nocapture
//! ```
//!
//! Every case is also run through the certified companions (`f64`, `f32`;
//! [`certified`]): outputs bit-identical to the plain kernel's, every bound at least the
//! true error; the long run prints how their bounds compare with the interpreter's. The FMA
//! kernels' companions are checked the same way against the FMA kernels, and the companions
//! with rounded inputs against the exact map at the intended inputs ([`rounded`]). The
//! static bounds over the regimes' boxes are checked against the exact error of the cases in
//! them ([`static_bound`]).

#[path = "proven/certified.rs"]
mod certified;
#[path = "proven/rounded.rs"]
mod rounded;
#[path = "proven/static_bound.rs"]
mod static_bound;
#[path = "proven/wide.rs"]
mod wide;

use certified::CertSeen;
use collision_core::certified::{CertifiedKernel, Companion};
use collision_core::rng::Rng;
use collision_core::{validate, Exact, Generated, Kernel};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::measure::{exact_result, lambda, normwise, Truth};
use noslip_accuracy::method::Outcome;
use noslip_accuracy::proven::ProvenBound;
use noslip_accuracy::{Method, Regime};
use num_traits::Signed;

/// What a run saw, per method.
#[derive(Clone, Debug, Default)]
struct Seen {
    cases: usize,
    skipped: usize,
    /// Largest measured / proven normwise error (must stay <= 1).
    worst_ratio: f64,
    /// Largest measured normwise error and largest proven bound, in eps.
    measured_max: f64,
    bound_max: f64,
}

/// A typical case with several extremes at once: a mass ratio to 1e15, a radius ratio to
/// 1e6, small or zero `gamma^2`, an immovable body, velocities and spins scaled
/// independently by up to 1e+-30 (each with probability 1/2, the last two 1/4).
fn adversarial<const N: usize, const S: usize>(rng: &mut Rng) -> Case<f64, N, S> {
    let mut case = Regime::Typical.sample::<N, S>(rng);
    let pow10 = |rng: &mut Rng, lo: f64, hi: f64| 10f64.powf(rng.uniform(lo, hi));
    if rng.coin() {
        case.balls[0].inv_mass = case.balls[1].inv_mass * pow10(rng, -15.0, 15.0);
    }
    if rng.coin() {
        case.balls[0].radius = case.balls[1].radius * pow10(rng, -6.0, 6.0);
    }
    if rng.coin() {
        for b in &mut case.balls {
            b.gamma2 /= pow10(rng, 0.0, 15.0);
        }
    }
    if rng.coin() && rng.coin() {
        case.balls[usize::from(rng.coin())].gamma2 = 0.0;
    }
    if rng.coin() && rng.coin() {
        let b = usize::from(rng.coin());
        case.balls[b].inv_mass = 0.0;
    }
    if rng.coin() {
        let (v, w) = (pow10(rng, -30.0, 30.0), pow10(rng, -30.0, 30.0));
        for s in &mut case.states {
            s.velocity.iter_mut().for_each(|x| *x *= v);
            s.spin.iter_mut().for_each(|x| *x *= w);
        }
    }
    let dn: f64 = (0..N)
        .map(|k| (case.states[1].velocity[k] - case.states[0].velocity[k]) * case.nu[k])
        .sum();
    if dn > 0.0 {
        case.nu = case.nu.map(|x| -x);
    }
    case
}

/// Check `method` on `case` (for `f32`, the inputs as rounded); `None` if the case is not
/// one the method runs on.
fn check_one<const N: usize, const S: usize>(
    method: Method,
    bound: &ProvenBound,
    case: &Case<f64, N, S>,
    exact_case: &Case<Exact, N, S>,
    seen: &mut Seen,
) where
    Generated: Kernel<f64, N, S>
        + Kernel<f32, N, S>
        + Kernel<collision_core::ExactRelaxed, N, S>
        + collision_core::batch::BatchKernel<f64, N, S>,
{
    let case32 = case.to_f32();
    let outcome = match method {
        Method::F32 => match &case32 {
            Ok(c) if validate(&c.nu, c.ball_refs(), c.state_refs()).is_ok() => {
                method.run(case, Ok(c))
            }
            _ => {
                seen.skipped += 1;
                return;
            }
        },
        _ => method.run(case, Err("not used")),
    };
    // The inputs the kernel ran on, and their exact result.
    let (ran_on, exact_in): (Case<f64, N, S>, Case<Exact, N, S>) = match method {
        Method::F32 => {
            let c = case32.expect("checked above").map(|&x| f64::from(x));
            let e = c.to_exact();
            (c, e)
        }
        _ => (case.clone(), exact_case.clone()),
    };
    let exact = exact_result(&exact_in);
    let components = bound.component_bounds(&ran_on);
    let computed = match outcome {
        Outcome::Done(r) => r,
        Outcome::NonFinite => {
            assert!(
                components.iter().any(|e| e.is_infinite()),
                "n = {N} {}: a non-finite result with a finite bound for {case:?}",
                method.name()
            );
            seen.skipped += 1;
            return;
        }
        Outcome::Unsupported(why) => panic!("{why}"),
    };
    seen.cases += 1;
    for (k, (c, y)) in computed.iter().zip(flatten(&exact)).enumerate() {
        let e = components[k];
        if e.is_infinite() {
            continue;
        }
        let err = (Exact::from_float(*c).expect("finite") - &y).abs();
        assert!(
            err <= Exact::from_float(e).expect("finite bound"),
            "n = {N} {}: component {k} computed {c:e}, exact {}, error above its bound {e:e} for {case:?}",
            method.name(),
            y.to_f64()
        );
    }
    let truth = Truth::of(&exact);
    let lambdas = [lambda(&exact_in.balls[0]), lambda(&exact_in.balls[1])];
    let bodies = bound.body_bounds(&ran_on, lambdas);
    for (b, proven) in bodies.iter().enumerate() {
        let Some(proven) = *proven else { continue };
        let measured = normwise(lambdas[b], S, N, b, &computed, &truth) / method.epsilon();
        assert!(
            measured <= proven * (1.0 + 2f64.powi(-40)),
            "n = {N} {}: body {} measured {measured} eps above its proven bound {proven} for {case:?}",
            method.name(),
            b + 1
        );
        if std::env::var_os("NOSLIP_BOUND_SHOW").is_some() && proven > 1e6 && seen.bound_max <= 1e6
        {
            println!(
                "n = {N} {}: body {} proven {proven:e} eps, measured {measured:e} eps, components {components:?}, exact {:?}, computed {computed:?}, case {ran_on:?}",
                method.name(),
                b + 1,
                truth.hi
            );
        }
        seen.measured_max = seen.measured_max.max(measured);
        if proven.is_finite() {
            seen.bound_max = seen.bound_max.max(proven);
        }
        if measured > 0.0 {
            seen.worst_ratio = seen.worst_ratio.max(measured / proven);
        }
    }
}

const METHODS: [Method; 3] = [Method::F64, Method::F64Fma, Method::F32];

/// The certified companions checked: running error analysis, then the fast ones, of the
/// plain kernels and (`true`) of the FMA kernels.
const COMPANIONS: [(Companion, bool); 4] = [
    (Companion::Running, false),
    (Companion::Fast, false),
    (Companion::Running, true),
    (Companion::Fast, true),
];

/// `per_source` cases from every regime and from the adversarial mix, each checked with
/// every method, and with the certified companions (per source, `f64` and `f32`).
fn run<const N: usize, const S: usize>(
    per_source: usize,
    seed: u64,
) -> ([Seen; 3], Vec<[[CertSeen; 2]; 4]>)
where
    Generated: Kernel<f64, N, S>
        + Kernel<f32, N, S>
        + Kernel<collision_core::ExactRelaxed, N, S>
        + collision_core::batch::BatchKernel<f64, N, S>
        + CertifiedKernel<f64, N, S>
        + CertifiedKernel<f32, N, S>,
{
    let bounds = METHODS.map(|m| ProvenBound::of(N, m).expect("a generated float method"));
    // The f32 FMA kernels' interpreter bound, which no report method runs: the companions'
    // "bound / interpreter" column for them.
    let f32_fma = ProvenBound::of_kernel(
        N,
        noslip_codegen::Arith::Fma,
        noslip_codegen::bound::Format::F32,
    );
    let mut seen: [Seen; 3] = Default::default();
    let mut cert: Vec<[[CertSeen; 2]; 4]> = Vec::new();
    let mut rng = Rng::new(seed ^ ((N as u64) << 40));
    let sources = Regime::ALL.len() + 1;
    for source in 0..sources {
        cert.push(Default::default());
        for _ in 0..per_source {
            let case = match Regime::ALL.get(source) {
                Some(r) => r.sample::<N, S>(&mut rng),
                None => adversarial::<N, S>(&mut rng),
            };
            if validate(&case.nu, case.ball_refs(), case.state_refs()).is_err() {
                continue;
            }
            let exact_case = case.to_exact();
            for (i, m) in METHODS.iter().enumerate() {
                check_one(*m, &bounds[i], &case, &exact_case, &mut seen[i]);
            }
            for (k, companion) in COMPANIONS.into_iter().enumerate() {
                // The interpreter's bounds of the same kernel.
                let (b64, b32) = match companion.1 {
                    false => (&bounds[0], Some(&bounds[2])),
                    true => (&bounds[1], Some(&f32_fma)),
                };
                certified::check(
                    companion,
                    b64,
                    b32,
                    &case,
                    &exact_case,
                    &mut cert[source][k],
                );
            }
        }
    }
    (seen, cert)
}

fn quick<const N: usize, const S: usize>()
where
    Generated: Kernel<f64, N, S>
        + Kernel<f32, N, S>
        + Kernel<collision_core::ExactRelaxed, N, S>
        + collision_core::batch::BatchKernel<f64, N, S>
        + CertifiedKernel<f64, N, S>
        + CertifiedKernel<f32, N, S>,
{
    let (seen, cert) = run::<N, S>(6, 0xB0D);
    for (m, s) in METHODS.iter().zip(&seen) {
        assert!(s.cases > 0, "n = {N} {}: no case checked", m.name());
        assert!(s.worst_ratio <= 1.0 + 2f64.powi(-40));
    }
    // Every source gave f64 cases whose components were checked against the exact error;
    // f32 in total (the extreme scales are beyond f32).
    for k in 0..COMPANIONS.len() {
        for (source, c) in cert.iter().map(|c| &c[k]).enumerate() {
            assert!(
                c[0].components > 0,
                "n = {N} {:?} source {source}: no f64 component checked",
                COMPANIONS[k]
            );
            assert!(c[0].worst <= 1.0 && c[1].worst <= 1.0);
        }
        assert!(cert.iter().map(|c| c[k][1].components).sum::<usize>() > 0);
    }
}

macro_rules! per_dim {
    ($(($name:ident $n:literal $s:literal))*) => {$(
        mod $name {
            #[test]
            fn the_proven_bound_holds_in_every_regime() {
                super::quick::<$n, $s>();
            }
        }
    )*};
}

collision_core::for_each_dim!(per_dim);

/// The count in the environment variable `name` (a long run's size), else `default`.
fn env_count(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// The long run: `NOSLIP_BOUND_CASES` (default 10^6) cases per n and precision, spread over
/// the nine regimes and the adversarial mix; prints what it saw.
#[test]
#[ignore = "long: about an hour in a release build"]
fn a_million_cases_per_dimension_and_precision() {
    let total = env_count("NOSLIP_BOUND_CASES", 1_000_000);
    let dims: Vec<usize> = std::env::var("NOSLIP_BOUND_DIMS")
        .ok()
        .map(|s| s.split(',').filter_map(|d| d.parse().ok()).collect())
        .unwrap_or_else(|| (2..=6).collect());
    let per_source = total.div_ceil(Regime::ALL.len() + 1);
    for n in dims {
        let start = std::time::Instant::now();
        let (seen, cert) =
            collision_core::with_dim!(n, |N, S| run::<N, S>(per_source, 0x1E6), panic!());
        for (m, s) in METHODS.iter().zip(&seen) {
            println!(
                "n = {n} {:<18} cases {:>8} skipped {:>6} measured max {:>8.3} eps, proven max {:>10.3} eps, worst measured/proven {:.4} ({:.0} s)",
                m.name(),
                s.cases,
                s.skipped,
                s.measured_max,
                s.bound_max,
                s.worst_ratio,
                start.elapsed().as_secs_f64()
            );
        }
        print_certified(n, &cert);
    }
}

/// Per source and format: the companion's bound over the interpreter's and over the
/// measured error (medians and extremes), and the infinite bounds of each.
fn print_certified(n: usize, cert: &[[[CertSeen; 2]; 4]]) {
    let names: Vec<String> = Regime::ALL
        .iter()
        .map(|r| r.name().to_string())
        .chain(std::iter::once("adversarial".to_string()))
        .collect();
    for (k, companion) in COMPANIONS.iter().enumerate() {
        for (source, c) in cert.iter().map(|c| &c[k]).enumerate() {
            for (f, s) in ["f64", "f32"].iter().zip(c) {
                let (im, ix) = CertSeen::median_max(&s.over_interpreter);
                let (mm, mx) = CertSeen::median_max(&s.over_measured);
                let (kind, fma) = companion;
                let kernel = if *fma { "fma" } else { "plain" };
                println!(
                "n = {n} certified {kind:?} {kernel} {f} {:<14} cases {:>7} components {:>8} inf {:>6} (interpreter inf {:>6}); bound/interpreter median {im:.3} min {:.3} max {ix:.3}; bound/measured median {mm:.1} min {:.2} max {mx:.3e}; worst measured/bound {:.4}",
                names[source],
                s.cases,
                s.components,
                s.infinite,
                s.infinite_interpreter,
                CertSeen::min(&s.over_interpreter),
                CertSeen::min(&s.over_measured),
                s.worst
            );
            }
        }
    }
}
