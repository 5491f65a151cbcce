//! [`Exec::free_rows`]: the `free` kernel from row-major arrays into row-major arrays, a
//! pass of a few blocks at a time (gather, kernel, scatter), each step compiled for the
//! `Exec`'s instruction set.

use super::gather::{item, Gather};
use super::pass::{NoSlip, Pass};
use super::scatter::Scatter;
use super::{FreeRows, StateRowsMut};
use crate::batch::dispatch::at_level;
use crate::batch::kept::Kept;
use crate::batch::kernels::BatchKernel;
use crate::batch::lanes::{Lanewise, StateLanes, LANES};
use crate::batch::Exec;
use crate::kernels::Generated;
use crate::{BodyState, RefArith, Scalar};

/// Input and output bytes of the blocks of one pass of [`Exec::free_rows`] when the call's
/// arrays fit the L2 cache ([`ROWS_IN_CACHE_BYTES`]): 16 KiB, half the 32 KiB L1 data cache
/// of the machine in docs/batch.md, so that the blocks gathered stay in L1 while the kernel
/// reads them and the results stay there until they are scattered. Measured there on 512
/// contacts: 1.1x (n = 2) to 1.8x (n = 3, 6) faster than passes of 512 contacts.
pub const ROWS_PASS_BYTES: usize = 16 << 10;

/// The same for larger calls: 256 KiB, a quarter of the 1 MiB L2. Out of cache the short
/// passes ran up to 1.5x slower than passes of 512 contacts (n = 6, 10^6 contacts: the row
/// arrays are read and written in short bursts between the kernel's runs, and the memory
/// streams stall); passes of this size ran as fast as them (docs/batch.md).
pub const ROWS_PASS_BYTES_OUT_OF_CACHE: usize = 256 << 10;

/// Row-major bytes (inputs and outputs) up to which a call of [`Exec::free_rows`] takes
/// passes of [`ROWS_PASS_BYTES`], and beyond which [`ROWS_PASS_BYTES_OUT_OF_CACHE`]: 1 MiB,
/// the L2 cache of one core of the machine in docs/batch.md.
pub const ROWS_IN_CACHE_BYTES: usize = 1 << 20;

/// Contacts per pass of `bytes` of blocks in and out: whole blocks, at least one.
pub(crate) const fn pass_rows<B, O>(bytes: usize) -> usize {
    let block = std::mem::size_of::<B>() + std::mem::size_of::<O>();
    let blocks = match bytes.checked_div(block) {
        Some(0) | None => 1,
        Some(blocks) => blocks,
    };
    blocks * LANES
}

/// The pass of a call on `len` contacts of `N`-dimensional rows of `T` (row-major bytes in
/// and out: `nu`, parameters and two states in, two states out).
fn pass_for<T, const N: usize, const S: usize, B>(len: usize) -> usize {
    let row = std::mem::size_of::<T>() * (N + 6 + 4 * (N * N + N));
    let bytes = if len * row <= ROWS_IN_CACHE_BYTES {
        ROWS_PASS_BYTES
    } else {
        ROWS_PASS_BYTES_OUT_OF_CACHE
    };
    pass_rows::<B, [StateLanes<T, N, S>; 2]>(bytes)
}

/// Contacts per run of rows shared between threads: about 8 runs per thread (as
/// `Exec::free` splits its blocks), at least a pass and at most 128 blocks, whole passes.
#[cfg(feature = "parallel")]
fn run_rows(len: usize, threads: usize, pass: usize) -> usize {
    len.div_ceil(threads.max(1) * 8)
        .clamp(pass, 128 * LANES)
        .next_multiple_of(pass)
}

impl Exec {
    /// Both bodies free, parameters per row: every contact of `rows` collided by the `free`
    /// kernel into the same row of `out` (body `b` into `out[b]`, the full skew matrix and
    /// the velocity, as [`PairBatch::write_rows`](crate::batch::PairBatch::write_rows)
    /// writes them). The result is, bit for bit, [`FreeBatch::fill_from_rows`], then
    /// [`Exec::free`], then `write_rows`; but it runs a pass of a few blocks at a time
    /// ([`ROWS_PASS_BYTES`]), so that the blocks never leave the L1 cache and the arrays are
    /// read and written once, in address order; and the gather and scatter are compiled,
    /// like the kernel, for this `Exec`'s instruction set. Split across rayon's threads as
    /// `Exec::free` is (by runs of rows, feature `parallel`).
    ///
    /// The preconditions are the kernel's: nothing is validated.
    ///
    /// [`FreeBatch::fill_from_rows`]: crate::batch::FreeBatch::fill_from_rows
    ///
    /// # Panics
    /// If the lengths of `rows` do not fit ([`FreeRows::len`]) or `out[b]` does not hold as
    /// many contacts (`n^2` and `n` entries each).
    pub fn free_rows<T, const N: usize, const S: usize>(
        &self,
        rows: &FreeRows<'_, T>,
        out: [StateRowsMut<'_, T>; 2],
    ) where
        T: Scalar + Send + Sync + 'static,
        for<'a> &'a T: RefArith<T>,
        Generated: BatchKernel<T, N, S>,
    {
        self.rows_in_passes::<T, N, S, _>(&NoSlip, rows, out)
    }

    /// The row path with the kernel `pass` ([`Pass`]): the checks of the lengths, the
    /// split across threads, then [`Exec::rows_here`] on each part.
    pub(crate) fn rows_in_passes<T, const N: usize, const S: usize, K>(
        &self,
        kernel: &K,
        rows: &FreeRows<'_, T>,
        out: [StateRowsMut<'_, T>; 2],
    ) where
        T: Scalar + Send + Sync + 'static,
        K: Pass<T, N, S>,
    {
        let len = rows.len::<N>();
        for o in &out {
            assert_eq!(o.spin.len(), len * N * N, "spin: n^2 per contact");
            assert_eq!(o.velocity.len(), len * N, "velocity: n per contact");
        }
        #[cfg(feature = "parallel")]
        if self.splits::<K::Block, [StateLanes<T, N, S>; 2]>(len.div_ceil(LANES)) {
            let pass = pass_for::<T, N, S, K::Block>(len.div_ceil(rayon::current_num_threads()));
            let chunk = run_rows(len, rayon::current_num_threads(), pass);
            let [StateRowsMut {
                spin: s1,
                velocity: v1,
            }, StateRowsMut {
                spin: s2,
                velocity: v2,
            }] = out;
            crate::batch::share_rows(
                [s1, v1, s2, v2],
                [N * N, N, N * N, N],
                chunk,
                &|first, [s1, v1, s2, v2]| {
                    let range = first..first + v1.len() / N;
                    let part = rows.slice::<N>(range.clone());
                    let out = [
                        StateRowsMut {
                            spin: s1,
                            velocity: v1,
                        },
                        StateRowsMut {
                            spin: s2,
                            velocity: v2,
                        },
                    ];
                    self.rows_here(&kernel.slice(range), &part, out, pass);
                },
            );
            return;
        }
        self.rows_here(kernel, rows, out, pass_for::<T, N, S, K::Block>(len));
    }

    /// The row path on the calling thread, `pass` contacts at a time.
    fn rows_here<T, const N: usize, const S: usize, K>(
        &self,
        kernel: &K,
        rows: &FreeRows<'_, T>,
        mut out: [StateRowsMut<'_, T>; 2],
        pass: usize,
    ) where
        T: Scalar + Send + Sync + 'static,
        K: Pass<T, N, S>,
    {
        let len = rows.len::<N>();
        if len == 0 {
            return;
        }
        let pass = pass.min(len);
        let blocks_per_pass = pass.div_ceil(LANES);
        // The pass's blocks, kept by this thread between calls (`kept.rs`); the gather
        // overwrites every lane of the blocks a pass uses.
        let mut kept = Kept::<(Vec<K::Block>, Vec<[StateLanes<T, N, S>; 2]>)>::take();
        let (blocks, pairs) = &mut *kept;
        if blocks.len() < blocks_per_pass {
            let first = kernel.splat(&item(rows, 0), 0);
            blocks.resize(blocks_per_pass, first);
            let zero = [BodyState::zero(), BodyState::zero()];
            pairs.resize(blocks_per_pass, Lanewise::splat(&zero));
        }
        let isa = self.isa();
        let passes = len.div_ceil(pass);
        for p in 0..passes {
            // From the last pass to the first, for new memory (`Exec::last_rows_first`).
            let k = if self.is_backward() {
                passes - 1 - p
            } else {
                p
            };
            let start = pass * k;
            let end = (start + pass).min(len);
            let used = (end - start).div_ceil(LANES);
            let (blocks, pairs) = (&mut blocks[..used], &mut pairs[..used]);
            at_level(
                isa,
                Gather::<T, K::Block, N, S> {
                    rows,
                    range: start..end,
                    blocks,
                },
            );
            kernel.fill(start..end, blocks);
            kernel.run(isa, blocks, pairs);
            let [o1, o2] = &mut out;
            let (k, range) = (end - start, start..end);
            let out = &mut [o1.slice::<N>(range.clone()), o2.slice::<N>(range)];
            at_level(
                isa,
                Scatter {
                    blocks: pairs,
                    len: k,
                    out,
                    stream: self.is_streamed(),
                },
            );
        }
    }
}
