//! Criterion benchmark of the rough-ball kernel against the no-slip kernel, n = 2..6: one
//! collision at a time over the same in-cache batch of `BATCH` valid cases as the `kernels`
//! bench, in one group per n:
//!
//! - `no_slip`: `collision_core::kernels::dN::free::<f64>`;
//! - `rough`: `collision_core::kernels::dN::rough::free::<f64>` with `(e, beta) = (0.9, 0.4)`
//!   passed at run time through `black_box` (so the compiler cannot fold the law in);
//! - `walton`: `collision_core::kernels::dN::walton::free::<f64>` with `(e, mu, beta0) =
//!   (0.9, 0.2, 0.4)`, likewise (its select between sticking and sliding is branch-free:
//!   both are computed).
//!
//! Target (issue 27): `rough` within 1.2x of `no_slip`. Run:
//! `cargo bench -p collision-core --bench rough` (figures in docs/benchmarks.md).
//!
//! Before any timing, the rough kernel at `(1, 1)` must return the no-slip kernel's bits on
//! every case of the batch (docs/kernels.md): the benchmarked function is the right one.

#[path = "support/cases.rs"]
mod cases;
#[path = "support/timed.rs"]
mod timed;

use cases::{batch, Case};
use collision_core::{kernels, Ball, BodyState, Restitution, Walton};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use timed::run_batch;

/// Cases per batch, as in the `kernels` bench.
const BATCH: usize = 256;

/// Fixed seed, as in the `kernels` bench: the same batch.
const SEED: u64 = 0x6e6f_736c_6970;

// The kernels are passed as function items (zero-sized, one type each), not function
// pointers, so that each is called directly and may be inlined as in a caller's loop.

fn bits<const N: usize, const S: usize>(s: &[BodyState<f64, N, S>; 2]) -> Vec<u64> {
    s.iter()
        .flat_map(|b| b.spin.iter().chain(&b.velocity).map(|x| x.to_bits()))
        .collect()
}

fn bench_dim<const N: usize, const S: usize>(
    c: &mut Criterion,
    no_slip: impl Fn(
            &[f64; N],
            &Ball<f64>,
            &Ball<f64>,
            &BodyState<f64, N, S>,
            &BodyState<f64, N, S>,
        ) -> [BodyState<f64, N, S>; 2]
        + Copy,
    rough: impl Fn(
            &[f64; N],
            &Ball<f64>,
            &Ball<f64>,
            &Restitution<f64>,
            &BodyState<f64, N, S>,
            &BodyState<f64, N, S>,
        ) -> [BodyState<f64, N, S>; 2]
        + Copy,
    walton: impl Fn(
            &[f64; N],
            &Ball<f64>,
            &Ball<f64>,
            &Walton<f64>,
            &BodyState<f64, N, S>,
            &BodyState<f64, N, S>,
        ) -> [BodyState<f64, N, S>; 2]
        + Copy,
) {
    let cases: Vec<Case<N, S>> = batch::<N, S>(SEED ^ N as u64, BATCH);
    let one = Restitution::no_slip();
    for (k, case) in cases.iter().enumerate() {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        assert_eq!(
            bits(&rough(&case.nu, b1, b2, &one, s1, s2)),
            bits(&no_slip(&case.nu, b1, b2, s1, s2)),
            "n = {N}, case {k}: the rough kernel at (1, 1) is not the no-slip kernel"
        );
    }
    let law = Restitution::new(0.9, 0.4).expect("in range");
    let friction = Walton::new(0.9, 0.2, 0.4).expect("in range");
    for case in &cases {
        let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
        let out = walton(&case.nu, b1, b2, &friction, s1, s2);
        assert!(bits(&out).iter().all(|b| f64::from_bits(*b).is_finite()));
    }

    let mut group = c.benchmark_group(format!("rough_d{N}"));
    group
        .throughput(Throughput::Elements(BATCH as u64))
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(60);
    group.bench_function("no_slip", |b| {
        b.iter(|| {
            run_batch(&cases, |case| {
                let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
                no_slip(&case.nu, b1, b2, s1, s2)
            })
        })
    });
    group.bench_function("rough", |b| {
        b.iter(|| {
            let law = black_box(&law);
            run_batch(&cases, |case| {
                let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
                rough(&case.nu, b1, b2, law, s1, s2)
            })
        })
    });
    group.bench_function("walton", |b| {
        b.iter(|| {
            let law = black_box(&friction);
            run_batch(&cases, |case| {
                let ([b1, b2], [s1, s2]) = (&case.balls, &case.states);
                walton(&case.nu, b1, b2, law, s1, s2)
            })
        })
    });
    group.finish();
}

fn rough_against_no_slip(c: &mut Criterion) {
    bench_dim::<2, 1>(
        c,
        kernels::d2::free::<f64>,
        kernels::d2::rough::free::<f64>,
        kernels::d2::walton::free::<f64>,
    );
    bench_dim::<3, 3>(
        c,
        kernels::d3::free::<f64>,
        kernels::d3::rough::free::<f64>,
        kernels::d3::walton::free::<f64>,
    );
    bench_dim::<4, 6>(
        c,
        kernels::d4::free::<f64>,
        kernels::d4::rough::free::<f64>,
        kernels::d4::walton::free::<f64>,
    );
    bench_dim::<5, 10>(
        c,
        kernels::d5::free::<f64>,
        kernels::d5::rough::free::<f64>,
        kernels::d5::walton::free::<f64>,
    );
    bench_dim::<6, 15>(
        c,
        kernels::d6::free::<f64>,
        kernels::d6::rough::free::<f64>,
        kernels::d6::walton::free::<f64>,
    );
}

criterion_group!(benches, rough_against_no_slip);
criterion_main!(benches);
