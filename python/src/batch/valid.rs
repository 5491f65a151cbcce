//! The cheap validity test of `collide_batch`: which rows are *clearly* valid, so that only
//! the others need `collide`'s own checks (`collision_core::validate_parts`).
//!
//! The test runs on a chunk after it is gathered into the kernel's lane arrays (blocks of
//! [`LANES`] contacts, one contact per lane), so each condition is one comparison over eight
//! lanes at once; the skew-symmetry of `U`, which needs the entries below the diagonal the
//! lanes do not hold, is tested on the row-major arrays ([`skew`]). It accepts only rows
//! that `collide`'s checks accept (in its unbounded-exponent arithmetic, with the allowance
//! `8 eps s`); with `eps` the float type's epsilon, every input is finite with
//! `|x| <= max eps^2` (NaN fails every comparison), and
//! - `||nu|^2 - 1| <= 4 eps`, each nonzero `|nu_k| >= 2 sqrt(min_positive)`: the squares and
//!   their sums (in the order `k = 0, 1, ...`) are normal numbers, computed as `collide`
//!   computes them, bit for bit; so `|nu|^2` is `collide`'s, within half its allowance;
//! - `inv_mass >= 0`, `radius > 0`, `0 <= gamma2 <= 2/n` (`2/n` rounded as `collide` does),
//!   not both immovable, not two movable point masses: the balls' checks, without the
//!   allowance;
//! - `U_rr = 0` and `U_cr = -U_rc` exactly: skew with no allowance needed;
//! - approaching by a margin: `dn = sum_k nu_k (u_2k - u_1k) <= -(2n + 8) eps s` with
//!   `s = sum_k |nu_k| (|u_1k| + |u_2k|) >= min_positive / eps^2`, or `u_1 = u_2`
//!   (then `dn = 0` exactly). `collide` computes `dn` with `nu` renormalised (each `nu_k`
//!   moved by at most `4 eps |nu_k|`) and its own roundings (at most `(n + 1) eps/2 s`
//!   each way): its `dn` is at most `(n + 6) eps s` above this one, so still negative.

use collision_core::batch::{FreeLanes, Isa, StateRows, LANES};
use num_traits::Float;

/// Whether every row of each block of a chunk is clearly valid: `ok[k]` for the rows
/// `start + k LANES ..` of block `k` (padding lanes included: copies of a real row of the
/// block), `blocks` the chunk gathered from `rows`. Compiled for the instruction set `isa`
/// (`#[target_feature]` wrappers around the same code, as the batch kernels), so the lane
/// comparisons run 4 or 8 wide. A block that fails is looked at row by row ([`row`]).
pub(crate) fn chunk<T: Float, const N: usize, const S: usize>(
    isa: Isa,
    blocks: &[FreeLanes<T, N, S>],
    rows: [&StateRows<'_, T>; 2],
    start: usize,
    ok: &mut Vec<bool>,
) {
    ok.clear();
    ok.resize(blocks.len(), false);
    #[cfg(target_arch = "x86_64")]
    {
        if isa == Isa::Avx512 && Isa::Avx512.is_available() {
            // SAFETY: the CPU has AVX-512F (checked at run time just above).
            return unsafe { chunk_avx512(blocks, rows, start, ok) };
        }
        if isa == Isa::Avx2 && Isa::Avx2.is_available() {
            // SAFETY: the CPU has AVX2 and FMA (checked at run time just above).
            return unsafe { chunk_avx2(blocks, rows, start, ok) };
        }
    }
    let _ = isa;
    chunk_any(blocks, rows, start, ok);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn chunk_avx512<T: Float, const N: usize, const S: usize>(
    blocks: &[FreeLanes<T, N, S>],
    rows: [&StateRows<'_, T>; 2],
    start: usize,
    ok: &mut [bool],
) {
    chunk_any(blocks, rows, start, ok);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn chunk_avx2<T: Float, const N: usize, const S: usize>(
    blocks: &[FreeLanes<T, N, S>],
    rows: [&StateRows<'_, T>; 2],
    start: usize,
    ok: &mut [bool],
) {
    chunk_any(blocks, rows, start, ok);
}

/// [`chunk`]'s body: [`lanes`] per block, and [`skew`] of both bodies' `U` on the block's
/// rows (those before the end of `rows`).
#[inline(always)]
fn chunk_any<T: Float, const N: usize, const S: usize>(
    blocks: &[FreeLanes<T, N, S>],
    rows: [&StateRows<'_, T>; 2],
    start: usize,
    ok: &mut [bool],
) {
    let end = rows[0].velocity.len() / N;
    for (k, (block, ok)) in blocks.iter().zip(ok.iter_mut()).enumerate() {
        let first = start + k * LANES;
        let last = (first + LANES).min(end);
        let spins = rows.map(|r| &r.spin[first * N * N..last * N * N]);
        // Row by row with an early exit: vectorised across rows, the test compiled to
        // gathers, slower than the loads of one matrix at a time.
        let skew_all = spins
            .iter()
            .all(|spin| spin.chunks_exact(N * N).all(skew::<T, N>));
        *ok = skew_all && lanes(block).iter().all(|&b| b);
    }
}

/// Whether row `i` (lane `l` of `block`) is clearly valid: the row-by-row look at a block
/// that [`chunk`] did not pass.
pub(crate) fn row<T: Float, const N: usize, const S: usize>(
    block: &FreeLanes<T, N, S>,
    rows: [&StateRows<'_, T>; 2],
    i: usize,
    l: usize,
) -> bool {
    let spin = |b: usize| &rows[b].spin[i * N * N..(i + 1) * N * N];
    lanes(block)[l] && skew::<T, N>(spin(0)) && skew::<T, N>(spin(1))
}

/// Which lanes of `block` pass the test above, the skew-symmetry of `U` excepted.
///
/// One loop over the lanes whose body tests one contact with no branch (`&`, `|` on `bool`),
/// the form LLVM's loop vectoriser turns into 4- or 8-wide code, as the batch kernels' lane
/// loop (an unrolled test per field, or a `[bool; 8]` per comparison, came out as a mix
/// of 2- and 4-wide pieces and lane-by-lane mask moves: 3 to 5x slower).
// The lane loop indexes several lane arrays at once, `l` in `0..LANES`.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
pub(crate) fn lanes<T: Float, const N: usize, const S: usize>(
    block: &FreeLanes<T, N, S>,
) -> [bool; LANES] {
    let eps = T::epsilon();
    let huge = T::max_value() * eps * eps;
    let small = T::min_positive_value().sqrt() * (T::one() + T::one());
    let tiny = T::min_positive_value() / (eps * eps);
    let four = T::from(4).unwrap_or_else(T::one);
    let shell = (T::one() + T::one()) / T::from(N).unwrap_or_else(T::one);
    let margin = T::from(2 * N + 8).unwrap_or_else(T::one) * eps;
    let zero = T::zero();
    let finite = |x: T| x.abs() <= huge;
    let nu = &block.contact.nu;
    let [b1, b2] = &block.balls;
    let [s1, s2] = &block.contact.states;
    let mut ok = [false; LANES];
    for l in 0..LANES {
        let mut pass = true;
        let mut norm2 = zero;
        for x in nu.iter().map(|lanes| lanes[l]) {
            pass &= finite(x) & ((x == zero) | (x.abs() >= small));
            norm2 = norm2 + x * x;
        }
        // Every |nu_k| passed `<= huge` or the lane failed; an infinite norm2 fails here too.
        pass &= (norm2 - T::one()).abs() <= four * eps;
        for ball in [b1, b2] {
            let (w, r, g) = (ball.inv_mass[l], ball.radius[l], ball.gamma2[l]);
            pass &= (w >= zero) & (w <= huge) & (r > zero) & (r <= huge);
            pass &= (g >= zero) & (g <= shell);
        }
        let (w1, w2) = (b1.inv_mass[l], b2.inv_mass[l]);
        let both_immovable = (w1 == zero) & (w2 == zero);
        let point_masses = (b1.gamma2[l] == zero) & (b2.gamma2[l] == zero);
        pass &= !both_immovable & !((w1 != zero) & (w2 != zero) & point_masses);
        for state in [s1, s2] {
            for lanes in &state.spin {
                pass &= finite(lanes[l]);
            }
        }
        let (mut dn, mut scale, mut moving) = (zero, zero, false);
        for k in 0..N {
            let (u1, u2) = (s1.velocity[k][l], s2.velocity[k][l]);
            pass &= finite(u1) & finite(u2);
            moving |= u1 != u2;
            dn = dn + nu[k][l] * (u2 - u1);
            scale = scale + nu[k][l].abs() * (u1.abs() + u2.abs());
        }
        ok[l] = pass & (!moving | ((scale >= tiny) & (dn <= -(margin * scale))));
    }
    ok
}

/// Whether the `n x n` matrix `spin` (row-major) is exactly skew: `U_rr = 0`,
/// `U_cr = -U_rc` (no allowance needed; `collide` accepts such a matrix).
#[inline(always)]
pub(crate) fn skew<T: Float, const N: usize>(spin: &[T]) -> bool {
    let mut ok = true;
    for r in 0..N {
        ok &= spin[r * N + r] == T::zero();
        for c in r + 1..N {
            ok &= spin[c * N + r] == -spin[r * N + c];
        }
    }
    ok
}
