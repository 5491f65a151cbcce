//! Criterion benchmark of the free-body kernels, n = 2..6: one collision at a time over an
//! in-cache batch of `BATCH` valid cases, three variants side by side in one group per n:
//!
//! - `generated`: `collision_core::kernels::dN::free::<f64>`, the generated straight-line
//!   kernel, called directly (no dispatch, no validation);
//! - `handwritten`: `collision_core::literal`, the closed form of docs/derivation.md §7 written by hand in
//!   `f64` with fixed-size loops that LLVM unrolls completely (the baseline);
//! - `reference`: `collision_core::reference::collide` in `f64`: nalgebra, heap-allocating,
//!   Gram matrix and Gaussian elimination, and it validates its inputs (unit normal, ball
//!   parameters, finite values, approaching) first; that is part of its measured cost.
//!
//! Throughput is `Elements(BATCH)`, so criterion's time per element is the time per
//! collision. Run: `cargo bench -p collision-core --bench kernels` (see docs/benchmarks.md).
//!
//! Before any timing, every case is checked: handwritten and reference must agree with the
//! generated kernel (tolerances below); a benchmark of a wrong kernel is worthless.
//!
//! Black boxes: `std::hint::black_box` (stable since Rust 1.66; criterion 0.6 re-exports it
//! as `criterion::black_box`). Criterion 0.5's own `criterion::black_box`, without its
//! nightly-only `real_blackbox` feature, is a `read_volatile` copy of the value, which would
//! add a volatile reload of all `2 (N + S)` outputs to every collision of every variant and
//! dilute the ratios being measured.

#[path = "support/cases.rs"]
mod cases;
#[path = "support/timed.rs"]
mod timed;
use collision_core::literal as handwritten;

use cases::{batch, Case};
use collision_core::{kernels, reference, Ball, BodyState};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::time::Duration;
use timed::run_batch;

/// Cases per batch: `2 (N + S)` inputs of 8 bytes plus the balls, at most ~0.5 kB a case for
/// n = 6, so about 120 kB of input for 256 cases: L2-resident on any current core, most of it
/// in L1 for small n. The same batch is replayed every iteration.
const BATCH: usize = 256;

/// Fixed seed: the batch is the same on every run and machine.
const SEED: u64 = 0x6e6f_736c_6970; // "noslip"

/// Agreement check, per case, relative to the output scale (see [`rel_diff`]):
/// `|x - y| <= C eps (1 + A)`, `A = max_i 2 k_i / R_i = max_i 2 w_i / (g_i R_i)`.
///
/// Handwritten vs generated, `C = 16`: both evaluate the same rational map with O(100)
/// f64 operations (about 60 for n = 2 to 330 for n = 6) in different association. On these inputs
/// every quantity is O(1), the denominators `w_1 + w_2 >= 1` and `mu_t` (resp. `D`) are
/// sums of positive terms (no cancellation) and each output is a short sum of O(1) products,
/// so the forward error is a few ulps of the output scale, except for one amplification the
/// literal closed form has: the handwritten kernel wedges all of `P`, and
/// `nu ^ (p_n nu) = 0` leaves a rounding residue of about `eps |p_n|` per entry, multiplied
/// by `2 k_i / R_i`, which grows like `1 / g_i` (up to ~2.6e3 in this batch, `g` down to
/// ~5e-4). The generated kernel wedges `t` instead (`nu ^ P = p_t nu ^ t`) and has no such
/// term. Observed: at most 0.77 eps (1 + A), so C = 16 leaves a factor 20 and still catches
/// any wrong term, coefficient or sign (those give O(1) differences).
const C_HANDWRITTEN: f64 = 16.0;

/// Reference vs generated, `C = 64`: the reference assembles the n x n Gram matrix of the
/// impulse basis, whose condition number grows with the same `A`, and solves it by
/// Gaussian elimination with partial pivoting. Observed: at most 0.97 eps (1 + A).
const C_REFERENCE: f64 = 64.0;

/// Componentwise `max |x - y| / max(1, max |x|, max |y|)` over both bodies' outputs.
fn rel_diff<const N: usize, const S: usize>(
    x: &[BodyState<f64, N, S>; 2],
    y: &[BodyState<f64, N, S>; 2],
) -> f64 {
    let flat = |s: &[BodyState<f64, N, S>; 2]| -> Vec<f64> {
        s.iter()
            .flat_map(|b| b.spin.iter().chain(&b.velocity).copied())
            .collect()
    };
    let (x, y) = (flat(x), flat(y));
    let scale = x.iter().chain(&y).fold(1.0f64, |m, v| m.max(v.abs()));
    let diff = x
        .iter()
        .zip(&y)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    diff / scale
}

/// The kernel signature shared by `generated` and `handwritten`.
trait FreeKernel<const N: usize, const S: usize>:
    Fn(
        &[f64; N],
        &Ball<f64>,
        &Ball<f64>,
        &BodyState<f64, N, S>,
        &BodyState<f64, N, S>,
    ) -> [BodyState<f64, N, S>; 2]
    + Copy
{
}

impl<const N: usize, const S: usize, F> FreeKernel<N, S> for F where
    F: Fn(
            &[f64; N],
            &Ball<f64>,
            &Ball<f64>,
            &BodyState<f64, N, S>,
            &BodyState<f64, N, S>,
        ) -> [BodyState<f64, N, S>; 2]
        + Copy
{
}

fn run_reference<const N: usize, const S: usize>(case: &Case<N, S>) -> [BodyState<f64, N, S>; 2] {
    let [b1, b2] = &case.balls;
    let [s1, s2] = &case.states;
    reference::collide(&case.nu, [b1, b2], [s1, s2]).expect("valid case")
}

/// Check every case against the generated kernel; panics (aborting the bench) on a
/// disagreement. Prints the worst differences.
fn check<const N: usize, const S: usize>(cases: &[Case<N, S>], generated: impl FreeKernel<N, S>) {
    let (mut worst_h, mut worst_r) = (0.0f64, 0.0f64);
    for (k, case) in cases.iter().enumerate() {
        let [b1, b2] = &case.balls;
        let [s1, s2] = &case.states;
        let g = generated(&case.nu, b1, b2, s1, s2);
        let h = handwritten::free(&case.nu, b1, b2, s1, s2);
        let r = run_reference(case);
        let amp = 1.0
            + (2.0 * b1.inv_mass / (b1.gamma2 * b1.radius))
                .max(2.0 * b2.inv_mass / (b2.gamma2 * b2.radius));
        // In units of eps (1 + A).
        let unit = f64::EPSILON * amp;
        let (dh, dr) = (rel_diff(&g, &h) / unit, rel_diff(&g, &r) / unit);
        assert!(
            dh <= C_HANDWRITTEN,
            "n = {N}, case {k}: handwritten differs from generated by {dh:.2} eps (1 + A) > {C_HANDWRITTEN}"
        );
        assert!(
            dr <= C_REFERENCE,
            "n = {N}, case {k}: reference differs from generated by {dr:.2} eps (1 + A) > {C_REFERENCE}"
        );
        worst_h = worst_h.max(dh);
        worst_r = worst_r.max(dr);
    }
    eprintln!(
        "n = {N}: {} cases checked; max difference to generated in units of eps (1 + A): handwritten {worst_h:.2} (limit {C_HANDWRITTEN}), reference {worst_r:.2} (limit {C_REFERENCE})",
        cases.len()
    );
}

fn bench_dim<const N: usize, const S: usize>(c: &mut Criterion, generated: impl FreeKernel<N, S>) {
    let cases = batch::<N, S>(SEED ^ N as u64, BATCH);
    check(&cases, generated);

    let mut group = c.benchmark_group(format!("free_d{N}"));
    group
        .throughput(Throughput::Elements(BATCH as u64))
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(60);
    group.bench_function("generated", |b| {
        b.iter(|| {
            run_batch(&cases, |case| {
                let [b1, b2] = &case.balls;
                let [s1, s2] = &case.states;
                generated(&case.nu, b1, b2, s1, s2)
            })
        })
    });
    group.bench_function("handwritten", |b| {
        b.iter(|| {
            run_batch(&cases, |case| {
                let [b1, b2] = &case.balls;
                let [s1, s2] = &case.states;
                handwritten::free(&case.nu, b1, b2, s1, s2)
            })
        })
    });
    group.bench_function("reference", |b| b.iter(|| run_batch(&cases, run_reference)));
    group.finish();
}

fn kernels(c: &mut Criterion) {
    bench_dim::<2, 1>(c, kernels::d2::free::<f64>);
    bench_dim::<3, 3>(c, kernels::d3::free::<f64>);
    bench_dim::<4, 6>(c, kernels::d4::free::<f64>);
    bench_dim::<5, 10>(c, kernels::d5::free::<f64>);
    bench_dim::<6, 15>(c, kernels::d6::free::<f64>);
}

criterion_group!(benches, kernels);
criterion_main!(benches);
