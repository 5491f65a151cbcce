//! The timed loop the per-collision benchmarks share (`kernels`, `fma`).

use crate::cases::Case;
use std::hint::black_box;

/// The timed loop: one collision at a time over the batch. Not inlined, so that each
/// variant's loop is one symbol in the assembly (`kernels::timed::run_batch::<..>`); whether the
/// kernel is inlined into it is LLVM's usual `#[inline]` decision, as in a caller's loop.
/// Inputs are opaque through `black_box(cases)`; each result is consumed by
/// `black_box(&result)`, which makes it live in memory (as a caller storing it would)
/// without the extra copy of `black_box(result)` (a 336-byte `memcpy` call per collision
/// for n = 6).
#[inline(never)]
pub fn run_batch<const N: usize, const S: usize, R>(
    cases: &[Case<N, S>],
    f: impl Fn(&Case<N, S>) -> R,
) {
    for case in black_box(cases) {
        let result = f(case);
        black_box(&result);
    }
}
