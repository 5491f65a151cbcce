//! Blocks into rows: lane `l` of block `b` of a [`PairBatch`] into row `8 b + l` of
//! row-major arrays, each compact state as its full skew matrix (`U_rr = +0`, `U_rc` for
//! `r < c`, `U_cr = 0 - U_rc`) and its velocity; compiled for each instruction-set level
//! (`dispatch::at_level`).

use super::{pairs, StateRowsMut};
use crate::batch::dispatch::{at_level, AtLevel, Isa};
use crate::batch::lanes::{StateLanes, LANES};
use crate::batch::PairBatch;
use crate::Scalar;

/// Lanes `0..count` of one body's state block into rows `start..start + count` of `out`.
#[inline(always)]
pub(super) fn scatter_state<T: Scalar, const N: usize, const S: usize>(
    lanes: &StateLanes<T, N, S>,
    out: &mut StateRowsMut<'_, T>,
    start: usize,
    count: usize,
) {
    let pairs = const { pairs::<N, S>() };
    let spin = &mut out.spin[start * N * N..(start + count) * N * N];
    let velocity = &mut out.velocity[start * N..(start + count) * N];
    if count == LANES && N <= INTERLEAVED_UP_TO {
        // A full block: every entry of 8 rows written in one iteration per lane (one
        // interleaved group of stores per array, which the vectoriser turns into shuffles).
        let (spin, velocity) = (&mut spin[..LANES * N * N], &mut velocity[..LANES * N]);
        let sign = const { signs::<N, S>() };
        for l in 0..LANES {
            for (e, &(k, negate)) in sign[..N * N].iter().enumerate() {
                let x = if k == S {
                    T::zero()
                } else {
                    lanes.spin[k][l].clone()
                };
                spin[l * N * N + e] = if negate { T::zero() - x } else { x };
            }
            for k in 0..N {
                velocity[l * N + k] = lanes.velocity[k][l].clone();
            }
        }
        return;
    }
    for (l, (m, v)) in spin
        .chunks_exact_mut(N * N)
        .zip(velocity.chunks_exact_mut(N))
        .enumerate()
    {
        for r in 0..N {
            m[r * N + r] = T::zero();
        }
        for (lane, &(r, c)) in lanes.spin.iter().zip(&pairs) {
            let x = &lane[l];
            m[r * N + c] = x.clone();
            m[c * N + r] = T::zero() - x.clone();
        }
        for (x, lane) in v.iter_mut().zip(&lanes.velocity) {
            *x = lane[l].clone();
        }
    }
}

/// For each entry `r n + c` of an `n x n` skew matrix, the compact entry it holds and
/// whether negated: `(k, false)` above the diagonal (`U_rc`, the `k`-th of
/// [`BodyState::spin`](crate::BodyState::spin)), `(k, true)` below it (`0 - U_cr`), `(S,
/// false)` on the diagonal (`+0`).
/// Room for n <= 6 (the first `n^2` entries are used).
const fn signs<const N: usize, const S: usize>() -> [(usize, bool); MAX_ENTRIES] {
    assert!(N * N <= MAX_ENTRIES, "n <= 6");
    let pairs = pairs::<N, S>();
    let mut out = [(S, false); MAX_ENTRIES];
    let mut k = 0;
    while k < S {
        let (r, c) = pairs[k];
        out[r * N + c] = (k, false);
        out[c * N + r] = (k, true);
        k += 1;
    }
    out
}

/// The largest n whose full blocks are scattered as interleaved groups: in cache (512
/// contacts, AVX-512, docs/batch.md) that form took 0.48x the row-by-row form's time at
/// n = 2, 0.79x at n = 3 and 0.9x at n = 4, but 1.4-2x at n = 6.
const INTERLEAVED_UP_TO: usize = 4;

/// The most entries of a matrix [`signs`] describes: 36, n = 6.
const MAX_ENTRIES: usize = 36;

/// Contacts `0..len` of `blocks` (`[body 1, body 2]` per block) into rows `0..len` of
/// `out[0]` and `out[1]`.
#[inline(always)]
pub(super) fn scatter<T: Scalar, const N: usize, const S: usize>(
    blocks: &[[StateLanes<T, N, S>; 2]],
    len: usize,
    out: &mut [StateRowsMut<'_, T>; 2],
) {
    for (b, block) in blocks.iter().enumerate() {
        let start = b * LANES;
        if start >= len {
            break;
        }
        let count = (len - start).min(LANES);
        for (lanes, o) in block.iter().zip(out.iter_mut()) {
            scatter_state(lanes, o, start, count);
        }
    }
}

/// [`scatter`] as work compiled per level.
pub(super) struct Scatter<'b, 'o, 'x, T, const N: usize, const S: usize> {
    pub(super) blocks: &'b [[StateLanes<T, N, S>; 2]],
    pub(super) len: usize,
    pub(super) out: &'x mut [StateRowsMut<'o, T>; 2],
    /// Non-temporal stores where the level and the alignment allow
    /// ([`crate::batch::Exec::streamed_results`]).
    pub(super) stream: bool,
}

impl<T: Scalar + 'static, const N: usize, const S: usize> AtLevel for Scatter<'_, '_, '_, T, N, S> {
    type Output = ();
    #[inline(always)]
    fn run<const W: usize>(self) {
        #[cfg(all(target_arch = "x86_64", noslip_avx512_intrinsics))]
        if W == crate::batch::dispatch::AVX512_WIDTH
            && N <= super::avx512::PERMUTES_UP_TO
            && std::any::TypeId::of::<T>() == std::any::TypeId::of::<f64>()
            && Isa::Avx512.is_available()
        {
            let full = self.len / LANES;
            // SAFETY: `T` is `f64` (same type id), so the casts change no type.
            let (blocks, out) = unsafe {
                (
                    std::slice::from_raw_parts(
                        self.blocks.as_ptr().cast::<[StateLanes<f64, N, S>; 2]>(),
                        full,
                    ),
                    &mut *(self.out as *mut [StateRowsMut<'_, T>; 2])
                        .cast::<[StateRowsMut<'_, f64>; 2]>(),
                )
            };
            // Every full block writes whole 16-byte pieces of each array from its start
            // (8 rows of `n` and of `n^2` values), so the arrays' starts decide.
            let at16 = |p: *const f64| (p as usize) % 16 == 0;
            let aligned = out
                .iter()
                .all(|o| at16(o.spin.as_ptr()) && at16(o.velocity.as_ptr()));
            if self.stream && aligned {
                // SAFETY: the CPU has AVX-512F (checked just now); the arrays start at
                // multiples of 16 bytes.
                unsafe { super::avx512::scatter_streamed(blocks, out) };
            } else {
                // SAFETY: the CPU has AVX-512F (checked just now).
                unsafe { super::avx512::scatter(blocks, out) };
            }
            let start = full * LANES;
            if start < self.len {
                for (lanes, o) in self.blocks[full].iter().zip(self.out.iter_mut()) {
                    scatter_state(lanes, o, start, self.len - start);
                }
            }
            return;
        }
        scatter(self.blocks, self.len, self.out)
    }
}

impl<T: Scalar + 'static, const N: usize, const S: usize> PairBatch<T, N, S> {
    /// Write every item `[body 1, body 2]` of the batch into contact rows `0..len` of `out`
    /// (body `b` into `out[b]`): the compact entries as the full skew matrix
    /// (`U_rr = +0`, `U_rc` for `r < c`, `U_cr = 0 - U_rc`) and the velocity, as
    /// [`Batch::get`](crate::batch::Batch::get) returns them. Compiled for each
    /// instruction-set level; runs on [`Isa::detect`]'s.
    ///
    /// # Panics
    /// If `out[b]` does not hold exactly `len` contacts (`n^2` and `n` entries each).
    pub fn write_rows(&self, out: [StateRowsMut<'_, T>; 2]) {
        self.write_rows_on(Isa::detect(), out)
    }

    /// [`write_rows`](Self::write_rows) compiled for `isa` (the baseline when this CPU
    /// lacks it): every level writes the same rows.
    pub fn write_rows_on(&self, isa: Isa, mut out: [StateRowsMut<'_, T>; 2]) {
        let len = self.len();
        for o in &out {
            assert_eq!(o.spin.len(), len * N * N, "spin: n^2 per contact");
            assert_eq!(o.velocity.len(), len * N, "velocity: n per contact");
        }
        at_level(
            isa,
            Scatter {
                blocks: self.blocks(),
                len,
                out: &mut out,
                stream: false,
            },
        );
    }
}
