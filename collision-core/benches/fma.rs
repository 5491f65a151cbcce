//! Criterion benchmark of the FMA entry point against the plain one, n = 2..6: one collision
//! at a time over an in-cache batch of `BATCH` cases, side by side in one group per n and
//! kernel:
//!
//! - `plain`: `collision_core::collide_unchecked::<f64>` (`free` or `fixed`);
//! - `fma`: `collision_core::collide_unchecked_fma::<f64>`, which runs the FMA kernels on FMA
//!   instructions where the CPU has them (run-time dispatch);
//! - `fma_libm`: the same FMA kernels (`kernels::dN::free_fma`, `fixed_fma`) called from
//!   this crate's default-target code, where every `mul_add` is a libm call: what
//!   `collide_unchecked_fma` cost before the dispatch, and what it costs on a CPU without FMA.
//!
//! Groups `fma_free_dN` (both bodies free: the cases of `support/cases.rs`) and
//! `fma_fixed_dN` (the same cases with body 1 immovable: `fixed`, `fixed_fma`). Before any
//! timing, `fma` and `fma_libm` are checked equal bit for bit on every case.
//!
//! Run: `cargo bench -p collision-core --bench fma` (figures in docs/accuracy.md).

#[path = "support/cases.rs"]
mod cases;
#[path = "support/timed.rs"]
mod timed;

use cases::{batch, Case};
use collision_core::{collide_unchecked, collide_unchecked_fma, BodyState, Generated, Kernel};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::time::Duration;
use timed::run_batch;

const BATCH: usize = 256;
const SEED: u64 = 0x6e6f_736c_6970; // "noslip"

fn plain<const N: usize, const S: usize>(c: &Case<N, S>) -> [BodyState<f64, N, S>; 2]
where
    Generated: Kernel<f64, N, S>,
{
    let [b1, b2] = &c.balls;
    let [s1, s2] = &c.states;
    collide_unchecked(&c.nu, [b1, b2], [s1, s2])
}

fn fma<const N: usize, const S: usize>(c: &Case<N, S>) -> [BodyState<f64, N, S>; 2]
where
    Generated: Kernel<f64, N, S>,
{
    let [b1, b2] = &c.balls;
    let [s1, s2] = &c.states;
    collide_unchecked_fma(&c.nu, [b1, b2], [s1, s2])
}

/// The FMA kernel of the case's kind (body 1 immovable or both free), compiled here.
fn fma_libm<const N: usize, const S: usize>(c: &Case<N, S>) -> [BodyState<f64, N, S>; 2]
where
    Generated: Kernel<f64, N, S>,
{
    let [b1, b2] = &c.balls;
    let [s1, s2] = &c.states;
    if b1.inv_mass == 0.0 {
        [
            s1.clone(),
            Generated::fixed_fma(&c.nu, &b1.radius, b2, s1, s2),
        ]
    } else {
        Generated::free_fma(&c.nu, b1, b2, s1, s2)
    }
}

fn bits<const N: usize, const S: usize>(s: &[BodyState<f64, N, S>; 2]) -> Vec<u64> {
    s.iter()
        .flat_map(|b| b.spin.iter().chain(&b.velocity))
        .map(|x| x.to_bits())
        .collect()
}

fn bench_kernel<const N: usize, const S: usize>(c: &mut Criterion, kind: &str, cases: &[Case<N, S>])
where
    Generated: Kernel<f64, N, S>,
{
    for (k, case) in cases.iter().enumerate() {
        assert_eq!(
            bits(&fma(case)),
            bits(&fma_libm(case)),
            "n = {N} {kind}, case {k}: dispatched and libm FMA kernels differ"
        );
    }
    let mut group = c.benchmark_group(format!("fma_{kind}_d{N}"));
    group
        .throughput(Throughput::Elements(cases.len() as u64))
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
        .sample_size(40);
    group.bench_function("plain", |b| b.iter(|| run_batch(cases, plain)));
    group.bench_function("fma", |b| b.iter(|| run_batch(cases, fma)));
    group.bench_function("fma_libm", |b| b.iter(|| run_batch(cases, fma_libm)));
    group.finish();
}

fn bench_dim<const N: usize, const S: usize>(c: &mut Criterion)
where
    Generated: Kernel<f64, N, S>,
{
    let free = batch::<N, S>(SEED ^ N as u64, BATCH);
    bench_kernel(c, "free", &free);
    let mut fixed = free;
    for case in &mut fixed {
        case.balls[0].inv_mass = 0.0;
    }
    bench_kernel(c, "fixed", &fixed);
}

macro_rules! benches {
    ($(($name:ident $n:literal $s:literal))*) => {
        fn benches(c: &mut Criterion) {
            $(bench_dim::<$n, $s>(c);)*
        }
    };
}
collision_core::for_each_dim!(benches);

criterion_group!(fma_benches, benches);
criterion_main!(fma_benches);
