//! Criterion benchmark of the batch kernels (`collision_core::batch`), `free` with per-contact
//! parameters, n = 2..6, against the memory floor and the scalar kernel, side by side in one
//! run. Groups per n:
//!
//! - `batch_in_dN`: an in-cache batch of [`IN_CACHE`] contacts (at most 0.4 MB with its
//!   output: within the 1 MB L2 of the machine in docs/batch.md);
//! - `batch_out_dN`: an out-of-cache batch of about [`OUT_OF_CACHE_BYTES`] of input and
//!   output (8 times the 32 MB L3);
//! - with `--features parallel`, `batch_l2_dN`: `SHARED_L2` contacts, within the L2 caches of
//!   two cores together, and `batch_l3_dN`: `IN_L3_BYTES` of input and output, within a
//!   quarter of the L3; each on one thread (`batch_serial`), split on rayon (`batch_rayon`)
//!   and as `Exec::auto()` decides (`batch_auto`: split from `PARALLEL_FROM_BYTES` on).
//!
//! Variants, each over the same contacts, reading the same input bytes and writing the same
//! output bytes:
//!
//! - `floor`: the memory floor. One pass over the blocked batch that reads every input lane
//!   and writes every output lane, with one addition per input word (each output is its
//!   input state plus the sum of the contact's other inputs), compiled for the widest
//!   instruction set this CPU has;
//! - `scalar`: the generated scalar kernel, one contact at a time, over the per-collision
//!   (array of structs) layout, results stored into a preallocated vector;
//! - `batch_baseline`, `batch_avx2`, `batch_avx512`: the batch kernel on one thread, at each
//!   instruction set this CPU runs, at that level's lane width (`collision_core::batch`'s
//!   `BASELINE_WIDTH`, `AVX2_WIDTH`, `AVX512_WIDTH`);
//! - `batch_baseline_w2`, `batch_baseline_w8`, `batch_avx2_w8`: the same kernel at other lane
//!   widths (8 at every level was the code before issue 15);
//! - with `--features parallel`: `batch_rayon` (widest instruction set, all threads, split
//!   from the first contact on) and, out of cache, `floor_rayon` (the floor split the same
//!   way).
//!
//! Group `batch_family_dN` (in cache, widest instruction set, one thread): `no_slip`
//! (`Exec::free`), `rough` (`Exec::rough_free` under `(e, beta) = (0.9, 0.4)`) and `walton`
//! (`Exec::rough_free` under the Walton law `(0.9, 0.2, 0.4)`), the laws through
//! `black_box`, over the same batch.
//!
//! Throughput is `Elements(len)`: criterion's time per element is the time per collision.
//! Before timing, the batch kernel's results on the in-cache batch are checked bit for bit
//! against the scalar kernel's.
//!
//! Run: `cargo bench -p collision-core --bench batch --features parallel` (docs/batch.md).

#[path = "support/cases.rs"]
mod cases;

use cases::{batch, Case};
use collision_core::batch::RoughBatchKernel;
use collision_core::batch::{
    BatchKernel, Contact, Exec, FreeBatch, FreeLanes, Isa, Lane, Lanewise, PairBatch, StateLanes,
    LANES,
};
use collision_core::{BodyState, Generated, Kernel, Restitution, Walton};
use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;

/// Contacts of the in-cache batch.
const IN_CACHE: usize = 512;

/// Contacts of the batch split across threads in cache: 0.5 MB (n = 2) to 2.4 MB (n = 6)
/// of input and output, within the two cores' L2 caches together.
#[cfg(feature = "parallel")]
const SHARED_L2: usize = 3072;

/// Input plus output bytes of the batch split across threads within the L3: a quarter of the
/// 32 MB L3 (about 52000 contacts at n = 2, 11000 at n = 6).
#[cfg(feature = "parallel")]
const IN_L3_BYTES: usize = 8 << 20;

/// Input plus output bytes of the out-of-cache batch.
const OUT_OF_CACHE_BYTES: usize = 256 << 20;

const SEED: u64 = 0x6e6f_736c_6970; // "noslip"

/// Bytes read and written per contact: normal, two balls, two states in; two states out.
fn bytes_per_contact(n: usize, s: usize) -> usize {
    8 * (n + 6 + 2 * (n + s) + 2 * (n + s))
}

fn to_batch<const N: usize, const S: usize>(cases: &[Case<N, S>]) -> FreeBatch<f64, N, S> {
    cases
        .iter()
        .map(|c| {
            let contact = Contact {
                nu: c.nu,
                states: c.states.clone(),
            };
            (contact, c.balls.clone())
        })
        .collect()
}

/// The floor's work on one block: every input lane read, every output lane written.
#[inline(always)]
fn floor_block<const N: usize, const S: usize>(
    b: &FreeLanes<f64, N, S>,
    o: &mut [StateLanes<f64, N, S>; 2],
) {
    for l in 0..LANES {
        let mut x = 0.0;
        for nu in &b.contact.nu {
            x += nu[l];
        }
        for ball in &b.balls {
            x += ball.inv_mass[l] + ball.radius[l] + ball.gamma2[l];
        }
        for (state, out) in b.contact.states.iter().zip(o.iter_mut()) {
            for (a, y) in state.spin.iter().zip(out.spin.iter_mut()) {
                y[l] = a[l] + x;
            }
            for (a, y) in state.velocity.iter().zip(out.velocity.iter_mut()) {
                y[l] = a[l] + x;
            }
        }
    }
}

#[inline(always)]
fn floor_blocks<const N: usize, const S: usize>(
    blocks: &[FreeLanes<f64, N, S>],
    out: &mut [[StateLanes<f64, N, S>; 2]],
) {
    for (b, o) in blocks.iter().zip(out.iter_mut()) {
        floor_block(b, o);
    }
}

/// # Safety
/// The CPU must have AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx2,fma")]
unsafe fn floor_avx512<const N: usize, const S: usize>(
    blocks: &[FreeLanes<f64, N, S>],
    out: &mut [[StateLanes<f64, N, S>; 2]],
) {
    floor_blocks(blocks, out)
}

/// The floor loop on the widest instruction set available (the loads and stores are the
/// widest there).
#[inline(never)]
fn floor<const N: usize, const S: usize>(
    blocks: &[FreeLanes<f64, N, S>],
    out: &mut [[StateLanes<f64, N, S>; 2]],
) {
    #[cfg(target_arch = "x86_64")]
    if Isa::Avx512.is_available() {
        // SAFETY: AVX-512F was detected just now.
        return unsafe { floor_avx512(black_box(blocks), out) };
    }
    floor_blocks(black_box(blocks), out)
}

/// The block kernel at lane width `W` on the default target (x86-64: SSE2).
#[inline(never)]
fn width_baseline<const N: usize, const S: usize, const W: usize>(
    blocks: &[FreeLanes<f64, N, S>],
    out: &mut [[StateLanes<f64, N, S>; 2]],
) where
    Generated: BatchKernel<f64, N, S>,
{
    <Generated as BatchKernel<f64, N, S>>::free_blocks::<W>(black_box(blocks), out)
}

/// The scalar kernel on each lane in turn (gathered from the block, scattered back), on the
/// default target.
#[inline(never)]
fn scalar_lanes<const N: usize, const S: usize>(
    blocks: &[FreeLanes<f64, N, S>],
    out: &mut [[StateLanes<f64, N, S>; 2]],
) where
    Generated: Kernel<f64, N, S>,
{
    for (block, post) in black_box(blocks).iter().zip(out.iter_mut()) {
        for l in Lane::all() {
            let (c, [b1, b2]) = block.lane(l);
            post.set_lane(
                l,
                Generated::free(&c.nu, &b1, &b2, &c.states[0], &c.states[1]),
            );
        }
    }
}

/// # Safety
/// The CPU must have AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn width_avx2_unchecked<const N: usize, const S: usize, const W: usize>(
    blocks: &[FreeLanes<f64, N, S>],
    out: &mut [[StateLanes<f64, N, S>; 2]],
) where
    Generated: BatchKernel<f64, N, S>,
{
    <Generated as BatchKernel<f64, N, S>>::free_blocks::<W>(blocks, out)
}

/// The block kernel at lane width `W`, compiled for AVX2 + FMA (the CPU must have them).
#[cfg(target_arch = "x86_64")]
#[inline(never)]
fn width_avx2<const N: usize, const S: usize, const W: usize>(
    blocks: &[FreeLanes<f64, N, S>],
    out: &mut [[StateLanes<f64, N, S>; 2]],
) where
    Generated: BatchKernel<f64, N, S>,
{
    assert!(Isa::Avx2.is_available());
    // SAFETY: AVX2 and FMA were detected just now.
    unsafe { width_avx2_unchecked::<N, S, W>(black_box(blocks), out) }
}

/// The scalar kernel over the per-collision layout, results stored.
#[inline(never)]
fn scalar<const N: usize, const S: usize>(
    cases: &[Case<N, S>],
    out: &mut [[BodyState<f64, N, S>; 2]],
) where
    Generated: Kernel<f64, N, S> + BatchKernel<f64, N, S>,
{
    for (c, o) in black_box(cases).iter().zip(out.iter_mut()) {
        let [b1, b2] = &c.balls;
        let [s1, s2] = &c.states;
        *o = Generated::free(&c.nu, b1, b2, s1, s2);
    }
}

fn check<const N: usize, const S: usize>(cases: &[Case<N, S>], batch: &FreeBatch<f64, N, S>)
where
    Generated: Kernel<f64, N, S> + BatchKernel<f64, N, S>,
{
    let mut want = vec![[BodyState::zero(), BodyState::zero()]; cases.len()];
    scalar(cases, &mut want);
    for isa in Isa::available() {
        let mut out = PairBatch::new();
        Exec::auto()
            .with_isa(isa)
            .expect("available")
            .serial()
            .free(batch, &mut out);
        let bits = |s: &[BodyState<f64, N, S>; 2]| -> Vec<u64> {
            s.iter()
                .flat_map(|b| b.spin.iter().chain(&b.velocity).map(|x| x.to_bits()))
                .collect()
        };
        for (k, (got, want)) in out.iter().zip(&want).enumerate() {
            assert_eq!(
                bits(&got),
                bits(want),
                "n = {N}, {isa}, contact {k}: batch != scalar"
            );
        }
    }
    eprintln!(
        "n = {N}: batch kernel == scalar kernel bit for bit on {} contacts",
        cases.len()
    );
}

fn bench_group<const N: usize, const S: usize>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    cases: &[Case<N, S>],
    parallel: bool,
) where
    Generated: Kernel<f64, N, S> + BatchKernel<f64, N, S>,
{
    let len = cases.len();
    group.throughput(Throughput::Elements(len as u64));
    let batch = to_batch(cases);
    let mut out: PairBatch<f64, N, S> = PairBatch::new();
    Exec::auto().serial().free(&batch, &mut out); // sizes `out` once
    group.bench_function("floor", |b| {
        b.iter(|| floor(batch.blocks(), out.blocks_mut()))
    });
    let mut scalar_out = vec![[BodyState::zero(), BodyState::zero()]; len];
    group.bench_function("scalar", |b| b.iter(|| scalar(cases, &mut scalar_out)));
    drop(scalar_out);
    for isa in Isa::available() {
        let exec = Exec::auto().with_isa(isa).expect("available").serial();
        group.bench_function(format!("batch_{isa}"), |b| {
            b.iter(|| exec.free(black_box(&batch), &mut out))
        });
    }
    // Other lane widths than the levels' own (docs/batch.md: the widths of before issue 15
    // were 8 lanes at a time at every level).
    group.bench_function("scalar_lanes", |b| {
        b.iter(|| scalar_lanes::<N, S>(batch.blocks(), out.blocks_mut()))
    });
    group.bench_function("batch_baseline_w1", |b| {
        b.iter(|| width_baseline::<N, S, 1>(batch.blocks(), out.blocks_mut()))
    });
    group.bench_function("batch_baseline_w2", |b| {
        b.iter(|| width_baseline::<N, S, 2>(batch.blocks(), out.blocks_mut()))
    });
    group.bench_function("batch_baseline_w8", |b| {
        b.iter(|| width_baseline::<N, S, 8>(batch.blocks(), out.blocks_mut()))
    });
    #[cfg(target_arch = "x86_64")]
    if Isa::Avx2.is_available() {
        group.bench_function("batch_avx2_w8", |b| {
            b.iter(|| width_avx2::<N, S, 8>(batch.blocks(), out.blocks_mut()))
        });
    }
    #[cfg(feature = "parallel")]
    {
        let exec = Exec::auto().parallel_from(0);
        group.bench_function("batch_rayon", |b| {
            b.iter(|| exec.free(black_box(&batch), &mut out))
        });
    }
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        group.bench_function("floor_rayon", |b| {
            b.iter(|| {
                batch
                    .blocks()
                    .par_chunks(128)
                    .zip(out.blocks_mut().par_chunks_mut(128))
                    .for_each(|(b, o)| floor(b, o))
            })
        });
    }
    #[cfg(not(feature = "parallel"))]
    let _ = parallel;
}

fn bench_dim<const N: usize, const S: usize>(c: &mut Criterion)
where
    Generated: Kernel<f64, N, S>
        + BatchKernel<f64, N, S>
        + RoughBatchKernel<Restitution<f64>, f64, N, S>
        + RoughBatchKernel<Walton<f64>, f64, N, S>,
{
    let cases = batch::<N, S>(SEED ^ N as u64, IN_CACHE);
    check(&cases, &to_batch(&cases));
    let mut group = c.benchmark_group(format!("batch_in_d{N}"));
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(30);
    bench_group(&mut group, &cases, false);
    group.finish();

    // The rough-ball family's batch kernels beside the no-slip one (the law a run-time value).
    let blocks = to_batch(&cases);
    let mut out: PairBatch<f64, N, S> = PairBatch::new();
    let exec = Exec::auto().serial();
    let mut group = c.benchmark_group(format!("batch_family_d{N}"));
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(30)
        .throughput(Throughput::Elements(cases.len() as u64));
    group.bench_function("no_slip", |b| {
        b.iter(|| exec.free(black_box(&blocks), &mut out))
    });
    let rough = Restitution::new(0.9, 0.4).expect("in range");
    group.bench_function("rough", |b| {
        b.iter(|| exec.rough_free(black_box(&rough), black_box(&blocks), &mut out))
    });
    let walton = Walton::new(0.9, 0.2, 0.4).expect("in range");
    group.bench_function("walton", |b| {
        b.iter(|| exec.rough_free(black_box(&walton), black_box(&blocks), &mut out))
    });
    group.finish();

    // Threads on work that fits the two cores' L2 caches (1 MB each), and on work that fits
    // a quarter of the L3.
    #[cfg(feature = "parallel")]
    {
        let in_l3 = (IN_L3_BYTES / bytes_per_contact(N, S)).next_multiple_of(LANES);
        threads_group::<N, S>(c, "l2", SHARED_L2);
        threads_group::<N, S>(c, "l3", in_l3);
    }

    let len = (OUT_OF_CACHE_BYTES / bytes_per_contact(N, S)).next_multiple_of(LANES);
    let cases = batch::<N, S>(SEED ^ (N as u64) << 8, len);
    let mut group = c.benchmark_group(format!("batch_out_d{N}"));
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    bench_group(&mut group, &cases, true);
    group.finish();
}

/// Group `batch_{name}_dN`: `len` contacts on one thread and split on rayon.
#[cfg(feature = "parallel")]
fn threads_group<const N: usize, const S: usize>(c: &mut Criterion, name: &str, len: usize)
where
    Generated: Kernel<f64, N, S> + BatchKernel<f64, N, S>,
{
    let cases = batch::<N, S>(SEED ^ (N as u64) << 4 ^ len as u64, len);
    let batch = to_batch(&cases);
    let mut out: PairBatch<f64, N, S> = PairBatch::new();
    let mut group = c.benchmark_group(format!("batch_{name}_d{N}"));
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(30)
        .throughput(Throughput::Elements(len as u64));
    let serial = Exec::auto().serial();
    group.bench_function("batch_serial", |b| {
        b.iter(|| serial.free(black_box(&batch), &mut out))
    });
    let threads = Exec::auto().parallel_from(0);
    group.bench_function("batch_rayon", |b| {
        b.iter(|| threads.free(black_box(&batch), &mut out))
    });
    let auto = Exec::auto();
    group.bench_function("batch_auto", |b| {
        b.iter(|| auto.free(black_box(&batch), &mut out))
    });
    group.finish();
}

macro_rules! benches {
    ($(($name:ident $n:literal $s:literal))*) => {
        fn benches(c: &mut Criterion) {
            $(bench_dim::<$n, $s>(c);)*
        }
    };
}
collision_core::for_each_dim!(benches);

criterion_group!(batch_benches, benches);
criterion_main!(batch_benches);
