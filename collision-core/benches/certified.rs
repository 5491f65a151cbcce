//! Criterion benchmark of the certified companions against the plain kernels (`free` and
//! `fixed`, `f64`, n = 2..6), one collision at a time over the in-cache batch the `kernels`
//! bench uses (`fixed` on the same cases, body 1 taken as immovable), in alternated rounds:
//! each round benchmarks `plain`, `certified`, `fast`, `plain_fma`, `certified_fma`,
//! `fast_fma` (the FMA kernels and their companions, through `collide_unchecked_fma` and
//! `collide_certified_fma_by`, so on FMA instructions), `plain_fixed`, `certified_fixed`,
//! `fast_fixed`, and the rough-ball family's kernels beside their running companions
//! (`plain_rough`, `certified_rough`: `kernels::dN::rough::free` and
//! `kernels::dN::certified::rough_free` under `(e, beta) = (0.9, 0.4)`; `plain_walton`,
//! `certified_walton`: the Walton kernel and its companion under `(e, mu, beta0) = (0.9, 0.2,
//! 0.4)`, as the `rough` bench) for every n, so a change
//! of the shared machine's load hits both alike. Per round and variant the figure is
//! criterion's samples' median time per collision (recorded through `iter_custom`); the
//! summary printed at the end gives per n the median (min-max) over the rounds of each
//! variant and of the ratio certified / plain.
//!
//! ```sh
//! NOSLIP_ROUNDS=3 cargo bench -p collision-core --bench certified
//! ```
//!
//! Before any timing every case is checked: the companion's outputs equal the plain
//! kernel's bit for bit, and every bound is finite.

#[path = "support/cases.rs"]
mod cases;
#[path = "support/timed.rs"]
mod timed;

use cases::{batch, Case};
use collision_core::certified::{collide_certified_fma_by, CertifiedKernel, Companion};
use collision_core::{
    collide_unchecked_fma, kernels, Ball, BodyState, Generated, Kernel, Restitution, Walton,
};
use criterion::{Criterion, Throughput};
use std::hint::black_box;
use std::sync::Mutex;
use std::time::{Duration, Instant};
use timed::run_batch;

const BATCH: usize = 256;
const SEED: u64 = 0x6e6f_736c_6970; // "noslip", as the kernels bench

/// Per (n, round, variant): the per-collision times of criterion's samples, in ns.
static SAMPLES: Mutex<Vec<(usize, usize, &'static str, f64)>> = Mutex::new(Vec::new());

type Plain<const N: usize, const S: usize> = fn(
    &[f64; N],
    &Ball<f64>,
    &Ball<f64>,
    &BodyState<f64, N, S>,
    &BodyState<f64, N, S>,
) -> [BodyState<f64, N, S>; 2];

type PlainFixed<const N: usize, const S: usize> = fn(
    &[f64; N],
    &f64,
    &Ball<f64>,
    &BodyState<f64, N, S>,
    &BodyState<f64, N, S>,
) -> BodyState<f64, N, S>;

type CertifiedFixed<const N: usize, const S: usize> =
    fn(
        &[f64; N],
        &f64,
        &Ball<f64>,
        &BodyState<f64, N, S>,
        &BodyState<f64, N, S>,
    ) -> (BodyState<f64, N, S>, BodyState<f64, N, S>);

type Certified<const N: usize, const S: usize> =
    fn(
        &[f64; N],
        &Ball<f64>,
        &Ball<f64>,
        &BodyState<f64, N, S>,
        &BodyState<f64, N, S>,
    ) -> ([BodyState<f64, N, S>; 2], [BodyState<f64, N, S>; 2]);

/// A family kernel under its law `L` (`Restitution` or `Walton`).
type Family<const N: usize, const S: usize, L> = fn(
    &[f64; N],
    &Ball<f64>,
    &Ball<f64>,
    &L,
    &BodyState<f64, N, S>,
    &BodyState<f64, N, S>,
) -> [BodyState<f64, N, S>; 2];

/// A family kernel's running companion under its law `L`.
type FamilyCertified<const N: usize, const S: usize, L> =
    fn(
        &[f64; N],
        &Ball<f64>,
        &Ball<f64>,
        &L,
        &BodyState<f64, N, S>,
        &BodyState<f64, N, S>,
    ) -> ([BodyState<f64, N, S>; 2], [BodyState<f64, N, S>; 2]);

/// The rough and Walton kernels of one n, each with its running companion.
type Families<const N: usize, const S: usize> = (
    (
        Family<N, S, Restitution<f64>>,
        FamilyCertified<N, S, Restitution<f64>>,
    ),
    (
        Family<N, S, Walton<f64>>,
        FamilyCertified<N, S, Walton<f64>>,
    ),
);

fn flat<const N: usize, const S: usize>(s: &[BodyState<f64, N, S>; 2]) -> Vec<f64> {
    s.iter()
        .flat_map(|b| b.spin.iter().chain(&b.velocity).copied())
        .collect()
}

fn check<const N: usize, const S: usize>(
    cases: &[Case<N, S>],
    plain: impl Fn(
        &[f64; N],
        &Ball<f64>,
        &Ball<f64>,
        &BodyState<f64, N, S>,
        &BodyState<f64, N, S>,
    ) -> [BodyState<f64, N, S>; 2],
    certified: impl Fn(
        &[f64; N],
        &Ball<f64>,
        &Ball<f64>,
        &BodyState<f64, N, S>,
        &BodyState<f64, N, S>,
    ) -> ([BodyState<f64, N, S>; 2], [BodyState<f64, N, S>; 2]),
) {
    let mut worst = 0.0f64;
    for (k, case) in cases.iter().enumerate() {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        let p = flat(&plain(&case.nu, b1, b2, s1, s2));
        let (out, bound) = certified(&case.nu, b1, b2, s1, s2);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(
            bits(&flat(&out)),
            bits(&p),
            "n = {N}, case {k}: outputs differ"
        );
        for (x, e) in p.iter().zip(flat(&bound)) {
            assert!(e.is_finite(), "n = {N}, case {k}: infinite bound");
            worst = worst.max(e / (f64::EPSILON * x.abs().max(1.0)));
        }
    }
    eprintln!(
        "n = {N}: {} cases checked (bit-identical outputs, finite bounds; largest bound {worst:.1} eps max(1, |x|))",
        cases.len()
    );
}

fn timed<const N: usize, const S: usize, R>(
    c: &mut Criterion,
    round: usize,
    name: &'static str,
    cases: &[Case<N, S>],
    f: impl Fn(&Case<N, S>) -> R + Copy,
) {
    let mut group = c.benchmark_group(format!("certified_d{N}_round{round}"));
    group
        .throughput(Throughput::Elements(BATCH as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(30);
    group.bench_function(name, |b| {
        b.iter_custom(|iters| {
            let start = Instant::now();
            for _ in 0..iters {
                run_batch(cases, f);
            }
            let elapsed = start.elapsed();
            let ns = elapsed.as_nanos() as f64 / (iters as f64 * BATCH as f64);
            SAMPLES.lock().unwrap().push((N, round, name, ns));
            elapsed
        })
    });
    group.finish();
}

fn round_dim<const N: usize, const S: usize>(
    c: &mut Criterion,
    round: usize,
    (plain, certified): (Plain<N, S>, Certified<N, S>),
    (plain_fixed, certified_fixed): (PlainFixed<N, S>, CertifiedFixed<N, S>),
    (fast, fast_fixed): (Certified<N, S>, CertifiedFixed<N, S>),
    ((rough, rough_certified), (walton, walton_certified)): Families<N, S>,
) where
    Generated: Kernel<f64, N, S> + CertifiedKernel<f64, N, S>,
{
    let cases = batch::<N, S>(SEED ^ N as u64, BATCH);
    let law = Restitution::new(0.9, 0.4).expect("in range");
    let friction = Walton::new(0.9, 0.2, 0.4).expect("in range");
    if round == 0 {
        check(&cases, plain, certified);
        check(&cases, plain, fast);
        check(
            &cases,
            |nu, b1, b2, s1, s2| rough(nu, b1, b2, &law, s1, s2),
            |nu, b1, b2, s1, s2| rough_certified(nu, b1, b2, &law, s1, s2),
        );
        check(
            &cases,
            |nu, b1, b2, s1, s2| walton(nu, b1, b2, &friction, s1, s2),
            |nu, b1, b2, s1, s2| walton_certified(nu, b1, b2, &friction, s1, s2),
        );
        for companion in [Companion::Running, Companion::Fast] {
            for (k, case) in cases.iter().enumerate() {
                let (b, s) = (&case.balls, &case.states);
                let p = collide_unchecked_fma(&case.nu, [&b[0], &b[1]], [&s[0], &s[1]]);
                let (out, bound) =
                    collide_certified_fma_by(companion, &case.nu, [&b[0], &b[1]], [&s[0], &s[1]]);
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&flat(&out)),
                    bits(&flat(&p)),
                    "n = {N}, case {k}: FMA outputs differ"
                );
                assert!(flat(&bound).iter().all(|e| e.is_finite()));
            }
        }
        for (k, case) in cases.iter().enumerate() {
            let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
            let p = plain_fixed(&case.nu, &b1.radius, b2, s1, s2);
            for companion in [certified_fixed, fast_fixed] {
                let (out, bound) = companion(&case.nu, &b1.radius, b2, s1, s2);
                let bits = |s: &BodyState<f64, N, S>| -> Vec<u64> {
                    s.spin
                        .iter()
                        .chain(&s.velocity)
                        .map(|x| x.to_bits())
                        .collect()
                };
                assert_eq!(
                    bits(&out),
                    bits(&p),
                    "n = {N}, case {k}: fixed outputs differ"
                );
                assert!(bound
                    .velocity
                    .iter()
                    .chain(&bound.spin)
                    .all(|e| e.is_finite()));
            }
        }
    }
    timed(c, round, "plain", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        plain(&case.nu, b1, b2, s1, s2)
    });
    timed(c, round, "certified", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        certified(&case.nu, b1, b2, s1, s2)
    });
    timed(c, round, "fast", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        fast(&case.nu, b1, b2, s1, s2)
    });
    // The FMA kernels and their companions through the entry points that run them on FMA
    // instructions (run-time detection on x86-64): the same dispatch on both sides.
    timed(c, round, "plain_fma", &cases, |case| {
        let (b, s) = (&case.balls, &case.states);
        collide_unchecked_fma(&case.nu, [&b[0], &b[1]], [&s[0], &s[1]])
    });
    timed(c, round, "certified_fma", &cases, |case| {
        let (b, s) = (&case.balls, &case.states);
        collide_certified_fma_by(Companion::Running, &case.nu, [&b[0], &b[1]], [&s[0], &s[1]])
    });
    timed(c, round, "fast_fma", &cases, |case| {
        let (b, s) = (&case.balls, &case.states);
        collide_certified_fma_by(Companion::Fast, &case.nu, [&b[0], &b[1]], [&s[0], &s[1]])
    });
    timed(c, round, "plain_fixed", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        plain_fixed(&case.nu, &b1.radius, b2, s1, s2)
    });
    timed(c, round, "certified_fixed", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        certified_fixed(&case.nu, &b1.radius, b2, s1, s2)
    });
    timed(c, round, "fast_fixed", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        fast_fixed(&case.nu, &b1.radius, b2, s1, s2)
    });
    // The law through `black_box`, as the `rough` bench passes it: not folded in.
    let (law, friction) = (black_box(law), black_box(friction));
    timed(c, round, "plain_rough", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        rough(&case.nu, b1, b2, &law, s1, s2)
    });
    timed(c, round, "certified_rough", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        rough_certified(&case.nu, b1, b2, &law, s1, s2)
    });
    timed(c, round, "plain_walton", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        walton(&case.nu, b1, b2, &friction, s1, s2)
    });
    timed(c, round, "certified_walton", &cases, |case| {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        walton_certified(&case.nu, b1, b2, &friction, s1, s2)
    });
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn summary(rounds: usize) {
    for (plain, certified) in [
        ("plain", "certified"),
        ("plain_fixed", "certified_fixed"),
        ("plain", "fast"),
        ("plain_fixed", "fast_fixed"),
        ("plain_fma", "certified_fma"),
        ("plain_fma", "fast_fma"),
        ("plain_rough", "certified_rough"),
        ("plain_walton", "certified_walton"),
    ] {
        summary_of(rounds, plain, certified);
    }
}

fn summary_of(rounds: usize, plain: &str, certified: &str) {
    let samples = SAMPLES.lock().unwrap();
    println!("\n{certified} against {plain}");
    println!("n  plain ns (median, min-max over rounds)  certified ns  certified/plain");
    for n in 2..=6 {
        let per_round = |name: &str| -> Vec<f64> {
            (0..rounds)
                .map(|r| {
                    median(
                        samples
                            .iter()
                            .filter(|s| s.0 == n && s.1 == r && s.2 == name)
                            .map(|s| s.3)
                            .collect(),
                    )
                })
                .collect()
        };
        let (p, c) = (per_round(plain), per_round(certified));
        let ratio: Vec<f64> = p.iter().zip(&c).map(|(p, c)| c / p).collect();
        let mm = |v: &[f64]| {
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(0.0, f64::max);
            format!("{:.1} ({:.1}-{:.1})", median(v.to_vec()), lo, hi)
        };
        let rr = {
            let lo = ratio.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = ratio.iter().copied().fold(0.0, f64::max);
            format!("{:.2} ({:.2}-{:.2})", median(ratio.clone()), lo, hi)
        };
        println!("{n}  {:<36} {:<22} {rr}", mm(&p), mm(&c));
    }
}

fn main() {
    let rounds: usize = std::env::var("NOSLIP_ROUNDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let mut c = Criterion::default().configure_from_args();
    for round in 0..rounds {
        macro_rules! dim {
            ($m:ident $n:literal $s:literal) => {
                round_dim::<$n, $s>(
                    &mut c,
                    round,
                    (kernels::$m::free::<f64>, kernels::$m::certified::free),
                    (kernels::$m::fixed::<f64>, kernels::$m::certified::fixed),
                    (
                        kernels::$m::certified::free_fast,
                        kernels::$m::certified::fixed_fast,
                    ),
                    (
                        (
                            kernels::$m::rough::free::<f64>,
                            kernels::$m::certified::rough_free,
                        ),
                        (
                            kernels::$m::walton::free::<f64>,
                            kernels::$m::certified::walton_free,
                        ),
                    ),
                )
            };
        }
        dim!(d2 2 1);
        dim!(d3 3 3);
        dim!(d4 4 6);
        dim!(d5 5 10);
        dim!(d6 6 15);
    }
    c.final_summary();
    summary(rounds);
}
