//! The full blocks' gather and scatter in `f64` with AVX-512 two-source permutes
//! (`vpermt2pd`, planned in `plan.rs` and unrolled at compile time).
//!
//! Per full block of 8 rows, a field of row width `m` is `m` vectors of 8 values in and its
//! lane arrays out (or the reverse): at n = 2 a lane array of `nu` is one permute of two
//! vectors, where the portable transpose moves its 8 values one by one (8 loads, 8 stores).
//! Every value is moved, or negated as `0 - x`
//! (`vsubpd`, the scalar `0.0 - x` lane by lane), so the bits are the portable transposes'
//! (`every_level_gathers_and_scatters_as_the_baseline`, `rows/tests.rs`).

use super::plan::{self, Plan};
use super::{BallRows, FreeRows, StateRowsMut};
use crate::batch::lanes::{BallLanes, FreeLanes, StateLanes, LANES};
use core::arch::x86_64::{
    _mm512_castpd512_pd128, _mm512_castpd_ps, _mm512_cvtepu8_epi64, _mm512_extractf32x4_ps,
    _mm512_loadu_pd, _mm512_mask_mov_pd, _mm512_mask_sub_pd, _mm512_permutex2var_pd,
    _mm512_setzero_pd, _mm512_storeu_pd, _mm_castps_pd, _mm_loadl_epi64, _mm_sfence, _mm_stream_pd,
};

/// The largest n whose full blocks are gathered and scattered here. From n = 5 on, a
/// spin's lane array or a piece of 8 values of the rows' matrices draws on 8 vectors or
/// lane arrays (4 to 5 permutes of two 256-bit halves each on Zen 4 for 8 values), and the
/// portable transposes were faster: in cache (512 contacts, 4 December 2026)
/// `Exec::free_rows` took 1.02x (n = 5) and 1.07-1.11x (n = 6) its time with them when
/// only the gather ran here, 1.09x and 1.27x when both did. At n = 4 the permutes took 0.98x
/// in cache and 1.04x (0.99-1.14) out of cache, and `collide_batch` `out=` 1.04x (1.03-1.22)
/// at 10^6 rows (docs/batch.md): n = 4 keeps the portable transposes too.
pub(super) const PERMUTES_UP_TO: usize = 3;

/// A plan known at compile time, so that [`run`] unrolls it into straight-line permutes
/// with constant indices and masks.
trait Planned {
    /// The plan.
    const PLAN: Plan;
}

/// [`plan::gather_vectors`].
struct GatherVectors<const N: usize>;
/// [`plan::gather_spins`].
struct GatherSpins<const N: usize, const S: usize>;
/// [`plan::scatter_vectors`].
struct ScatterVectors<const N: usize>;
/// [`plan::scatter_spins`].
struct ScatterSpins<const N: usize, const S: usize>;

impl<const N: usize> Planned for GatherVectors<N> {
    const PLAN: Plan = plan::gather_vectors::<N>();
}
impl<const N: usize, const S: usize> Planned for GatherSpins<N, S> {
    const PLAN: Plan = plan::gather_spins::<N, S>();
}
impl<const N: usize> Planned for ScatterVectors<N> {
    const PLAN: Plan = plan::scatter_vectors::<N>();
}
impl<const N: usize, const S: usize> Planned for ScatterSpins<N, S> {
    const PLAN: Plan = plan::scatter_spins::<N, S>();
}

/// Destination `D` of `P`'s plan: `dst[8 D .. 8 D + 8]` from the sources `src[8 j .. 8 j +
/// 8]`, `+0` first, then each step's values (`0 - ` them for a negated step); with
/// `STREAM`, written as four 16-byte non-temporal stores (`movntpd`), which need `dst` at a
/// multiple of 16 bytes only (a 64-byte one needs 64).
///
/// # Safety
/// As [`run`].
#[target_feature(enable = "avx512f")]
#[inline]
unsafe fn destination<P: Planned, const D: usize, const STREAM: bool>(
    src: *const f64,
    dst: *mut f64,
) {
    if D >= P::PLAN.destinations {
        return;
    }
    let (first, end) = (P::PLAN.starts[D] as usize, P::PLAN.starts[D + 1] as usize);
    // SAFETY (every block below): the caller's; the plan's loads and stores are within.
    unsafe {
        let zero = _mm512_setzero_pd();
        let mut acc = zero;
        // At most 5 steps a destination (`plan.rs`): a constant trip count, unrolled.
        for j in 0..5 {
            if first + j >= end {
                break;
            }
            let s = &P::PLAN.steps[first + j];
            let idx = _mm512_cvtepu8_epi64(_mm_loadl_epi64(s.idx.as_ptr().cast()));
            let a = _mm512_loadu_pd(src.add(8 * s.a as usize));
            let b = _mm512_loadu_pd(src.add(8 * s.b as usize));
            let r = _mm512_permutex2var_pd(a, idx, b);
            acc = if s.neg {
                _mm512_mask_sub_pd(acc, s.mask, zero, r)
            } else {
                _mm512_mask_mov_pd(acc, s.mask, r)
            };
        }
        let q = dst.add(8 * D);
        if STREAM {
            let all = _mm512_castpd_ps(acc);
            _mm_stream_pd(q, _mm512_castpd512_pd128(acc));
            _mm_stream_pd(q.add(2), _mm_castps_pd(_mm512_extractf32x4_ps::<1>(all)));
            _mm_stream_pd(q.add(4), _mm_castps_pd(_mm512_extractf32x4_ps::<2>(all)));
            _mm_stream_pd(q.add(6), _mm_castps_pd(_mm512_extractf32x4_ps::<3>(all)));
        } else {
            _mm512_storeu_pd(q, acc);
        }
    }
}

/// `dst[8 d .. 8 d + 8]` for every destination `d` of `P`'s plan, from the sources
/// `src[8 j .. 8 j + 8]`: one call per destination, each a constant, so the whole plan is
/// straight-line code; with `STREAM`, by non-temporal stores ([`destination`]).
///
/// # Safety
/// The CPU has AVX-512F; `src` is valid for reads of `8 j + 8` values for every source `j`
/// of the plan, `dst` for writes of `8 destinations` values; with `STREAM`, `dst` is at a
/// multiple of 16 bytes.
#[target_feature(enable = "avx512f")]
#[inline]
unsafe fn run<P: Planned, const STREAM: bool>(src: *const f64, dst: *mut f64) {
    macro_rules! each {
        ($($d:literal)*) => {
            // SAFETY: the caller's.
            $(unsafe { destination::<P, $d, STREAM>(src, dst) };)*
        };
    }
    const _: () = assert!(plan::MAX_DESTINATIONS == 36);
    each!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31 32 33 34 35);
}

/// Contacts `start..start + 8 blocks.len()` of `rows` into `blocks` (all full), block by
/// block.
///
/// # Safety
/// The CPU has AVX-512F.
///
/// # Panics
/// If the rows end before `start + 8 blocks.len()`.
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn gather<const N: usize, const S: usize>(
    rows: &FreeRows<'_, f64>,
    start: usize,
    blocks: &mut [FreeLanes<f64, N, S>],
) {
    let end = start + LANES * blocks.len();
    let nu = &rows.nu[start * N..end * N];
    let spins = rows
        .states
        .each_ref()
        .map(|s| &s.spin[start * N * N..end * N * N]);
    let velocities = rows
        .states
        .each_ref()
        .map(|s| &s.velocity[start * N..end * N]);
    for (b, block) in blocks.iter_mut().enumerate() {
        let vectors = |x: &[f64]| x[b * LANES * N..(b + 1) * LANES * N].as_ptr();
        // SAFETY: AVX-512F (the caller's); the block's 8 rows of `n` values (`n` sources)
        // into its `n` lane arrays.
        unsafe {
            run::<GatherVectors<N>, false>(vectors(nu), block.contact.nu.as_mut_ptr().cast())
        };
        for k in 0..2 {
            let state = &mut block.contact.states[k];
            let spin = spins[k][b * LANES * N * N..(b + 1) * LANES * N * N].as_ptr();
            // SAFETY: as above, `n^2` sources of 8 rows of matrices, `S` lane arrays.
            unsafe { run::<GatherSpins<N, S>, false>(spin, state.spin.as_mut_ptr().cast()) };
            let velocity = vectors(velocities[k]);
            // SAFETY: as for `nu`.
            unsafe { run::<GatherVectors<N>, false>(velocity, state.velocity.as_mut_ptr().cast()) };
            balls(&rows.balls[k], start + b * LANES, &mut block.balls[k]);
        }
    }
}

/// One body's parameters of 8 rows (from `at`): 8 consecutive values, or a shared one.
#[inline(always)]
fn balls(p: &BallRows<'_, f64>, at: usize, lanes: &mut BallLanes<f64>) {
    for (lane, x) in [
        (&mut lanes.inv_mass, p.inv_mass),
        (&mut lanes.radius, p.radius),
        (&mut lanes.gamma2, p.gamma2),
    ] {
        if x.len() == 1 {
            *lane = [x[0]; LANES];
        } else {
            lane.copy_from_slice(&x[at..at + LANES]);
        }
    }
}

/// The blocks' contacts (all full) into rows `0..8 blocks.len()` of `out`, body `k` of
/// each block into `out[k]`, block by block.
///
/// # Safety
/// The CPU has AVX-512F.
///
/// # Panics
/// If `out[k]` holds fewer than `8 blocks.len()` contacts.
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn scatter<const N: usize, const S: usize>(
    blocks: &[[StateLanes<f64, N, S>; 2]],
    out: &mut [StateRowsMut<'_, f64>; 2],
) {
    // SAFETY: the caller's.
    unsafe { scatter_with::<N, S, false>(blocks, out) }
}

/// [`scatter`] by non-temporal stores ([`crate::batch::Exec::streamed_results`]), then a
/// store fence, so that the rows are written, in order, before anything after it.
///
/// # Safety
/// The CPU has AVX-512F; each of the four arrays of `out` starts at a multiple of 16
/// bytes.
///
/// # Panics
/// As [`scatter`].
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn scatter_streamed<const N: usize, const S: usize>(
    blocks: &[[StateLanes<f64, N, S>; 2]],
    out: &mut [StateRowsMut<'_, f64>; 2],
) {
    // SAFETY: the caller's; every destination is 8 rows of `n` or `n^2` values (a multiple
    // of 16 bytes) past the array's start.
    unsafe { scatter_with::<N, S, true>(blocks, out) };
    _mm_sfence();
}

/// [`scatter`], by non-temporal stores if `STREAM`.
///
/// # Safety
/// As [`scatter`]; with `STREAM`, as [`scatter_streamed`].
#[target_feature(enable = "avx512f")]
unsafe fn scatter_with<const N: usize, const S: usize, const STREAM: bool>(
    blocks: &[[StateLanes<f64, N, S>; 2]],
    out: &mut [StateRowsMut<'_, f64>; 2],
) {
    let len = LANES * blocks.len();
    let [o1, o2] = out;
    let spins = [&mut o1.spin[..len * N * N], &mut o2.spin[..len * N * N]];
    let velocities = [&mut o1.velocity[..len * N], &mut o2.velocity[..len * N]];
    for (b, block) in blocks.iter().enumerate() {
        for k in 0..2 {
            let spin = &mut spins[k][b * LANES * N * N..(b + 1) * LANES * N * N];
            // SAFETY: AVX-512F (the caller's); `S` lane arrays in, 8 rows of `n^2` values
            // (`n^2` destinations) out.
            unsafe {
                run::<ScatterSpins<N, S>, STREAM>(block[k].spin.as_ptr().cast(), spin.as_mut_ptr())
            };
            let velocity = &mut velocities[k][b * LANES * N..(b + 1) * LANES * N];
            // SAFETY: as above, `n` lane arrays in, 8 rows of `n` values out.
            unsafe {
                run::<ScatterVectors<N>, STREAM>(
                    block[k].velocity.as_ptr().cast(),
                    velocity.as_mut_ptr(),
                )
            };
        }
    }
}
