//! [`Exec`]: how a batch runs (instruction set, threads) and the four batch operations.

use super::dispatch::{run_on, Isa, Job};
use super::kernels::BatchKernel;
use super::lanes::{ContactLanes, FixedLanes, FreeLanes, Lanewise, StateLanes};
use super::{ContactBatch, FixedBatch, FreeBatch, PairBatch, StateBatch};
use crate::kernels::Generated;
use crate::{Ball, BodyState, RefArith, Scalar};
use std::fmt;

/// Why an [`Exec`] could not be set up as asked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BatchError {
    /// This CPU does not run the requested instruction set.
    UnavailableIsa(Isa),
}

impl fmt::Display for BatchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BatchError::UnavailableIsa(isa) => {
                write!(f, "this CPU does not support the {isa} instruction set")
            }
        }
    }
}

impl std::error::Error for BatchError {}

/// Batches of at least this many bytes of input and output are shared with rayon's workers
/// (feature `parallel`, [`Exec::auto`]): 384 KiB, about 2460 contacts of `free` at n = 2
/// (160 bytes each) and 512 at n = 6 (768 bytes), 3-5 µs on one thread. The calling thread
/// works from the start and a worker joins when it wakes (`share.rs`), so a split costs the
/// caller about 0.4 µs more than one thread when no worker comes in time. On the 2-core VM
/// of docs/batch.md two threads were faster from about this size on (1.13x at 384 KiB, n =
/// 6), slower below it (0.58-0.90x at 82-290 KiB).
pub const PARALLEL_FROM_BYTES: usize = 384 << 10;

/// The most blocks per chunk: 1024 contacts, 64 kB to 0.8 MB of input and output.
#[cfg(feature = "parallel")]
const CHUNK_BLOCKS: usize = 128;

/// Chunks per thread: a helper that starts late still finds some left.
#[cfg(feature = "parallel")]
const CHUNKS_PER_THREAD: usize = 8;

/// Blocks per chunk for `blocks` blocks on `threads` threads: [`CHUNKS_PER_THREAD`] chunks
/// per thread (so that the threads share a short batch evenly, whenever each starts), at
/// most [`CHUNK_BLOCKS`].
#[cfg(feature = "parallel")]
fn chunk_blocks(blocks: usize, threads: usize) -> usize {
    blocks
        .div_ceil(threads.max(1) * CHUNKS_PER_THREAD)
        .clamp(1, CHUNK_BLOCKS)
}

/// `out`'s start, shared by the chunks of a split batch (each writes its own run).
#[cfg(feature = "parallel")]
struct OutPtr<O>(*mut O);

// SAFETY: the chunks write disjoint runs of `out` (`share`'s contract), each from one thread,
// and `O: Send` lets each run be written from another thread.
#[cfg(feature = "parallel")]
unsafe impl<O: Send> Sync for OutPtr<O> {}

/// How batches run: the instruction set and, with the `parallel` feature, from which
/// length on they are split across rayon's thread pool. Every setting gives the same
/// result, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Exec {
    isa: Isa,
    split: Option<Split>,
    /// Whether the row path runs its passes from the last rows to the first
    /// ([`Exec::last_rows_first`]).
    backward: bool,
    /// Whether the row path writes its results past the caches where it can
    /// ([`Exec::streamed_results`]).
    streamed: bool,
}

/// From which size on a batch is split across rayon's pool.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Split {
    /// At least this many contacts ([`Exec::parallel_from`], feature `parallel`).
    #[cfg_attr(not(feature = "parallel"), allow(dead_code))]
    Contacts(usize),
    /// At least this many bytes of input and output ([`PARALLEL_FROM_BYTES`]).
    Bytes(usize),
}

impl Default for Exec {
    fn default() -> Self {
        Self::auto()
    }
}

impl Exec {
    /// The widest instruction set of this CPU ([`Isa::detect`]); with the `parallel`
    /// feature, threads for batches of at least [`PARALLEL_FROM_BYTES`] of input and output.
    pub fn auto() -> Self {
        Exec {
            isa: Isa::detect(),
            split: cfg!(feature = "parallel").then_some(Split::Bytes(PARALLEL_FROM_BYTES)),
            backward: false,
            streamed: false,
        }
    }

    /// The same, on instruction set `isa`; an error if this CPU does not run it.
    pub fn with_isa(self, isa: Isa) -> Result<Self, BatchError> {
        if isa.is_available() {
            Ok(Exec { isa, ..self })
        } else {
            Err(BatchError::UnavailableIsa(isa))
        }
    }

    /// The same, on the calling thread only.
    pub fn serial(self) -> Self {
        Exec {
            split: None,
            ..self
        }
    }

    /// The same, on rayon's thread pool for batches of at least `contacts` contacts.
    #[cfg(feature = "parallel")]
    pub fn parallel_from(self, contacts: usize) -> Self {
        Exec {
            split: Some(Split::Contacts(contacts)),
            ..self
        }
    }

    /// The same, with the row path ([`Exec::free_rows`] and the family kernels' row paths)
    /// running its passes from the last rows to the first: the same results, bit for bit
    /// (every row is its own contact). For outputs in memory never written before (new
    /// arrays): the kernel zeroes a huge page when it is first written, from its start to
    /// its end, so its end is what the cache holds; written from the end down, each page is
    /// written where it is still in cache. Out of cache at n = 3 (10^6 rows, four new output
    /// arrays, 192 MB), writing backward into new memory cost 19-21 ms against 27-28 forward,
    /// and 12.8-15.2 ms into memory already written (docs/benchmarks.md, session 52): for new
    /// memory only.
    pub fn last_rows_first(self) -> Self {
        Exec {
            backward: true,
            ..self
        }
    }

    /// Whether the row path runs its passes from the last rows to the first.
    pub fn is_backward(&self) -> bool {
        self.backward
    }

    /// The same, with [`Exec::free_rows`] writing its results with non-temporal stores
    /// where it can: the same results, bit for bit. Ordinary stores read each output line
    /// before writing it; these do not, and leave nothing in the caches. For outputs far
    /// larger than the caches that the caller does not read again at once; it combines with
    /// [`Exec::last_rows_first`] for new memory (0.93-0.96x the time of the backward passes
    /// alone into new NumPy arrays, Zen 4, docs/python.md). Where: the AVX-512 scatter of
    /// full blocks at n = 2 and 3 (`rows/avx512.rs`), when each output array starts at a
    /// multiple of 16 bytes (as NumPy's do); elsewhere the ordinary stores. Out of cache
    /// (256 MB of rows, Zen 4) `free_rows` then took 0.93x its time at n = 2 and 0.94x at
    /// n = 3 (docs/batch.md).
    pub fn streamed_results(self) -> Self {
        Exec {
            streamed: true,
            ..self
        }
    }

    /// Whether the row path writes its results with non-temporal stores where it can.
    pub fn is_streamed(&self) -> bool {
        self.streamed
    }

    /// The instruction set the batch kernels run on.
    pub fn isa(&self) -> Isa {
        self.isa
    }

    /// Both bodies free, parameters per contact: `out` becomes the `[body 1+, body 2+]` of
    /// every contact of `batch` (resized to its length, its blocks reused).
    pub fn free<T, const N: usize, const S: usize>(
        &self,
        batch: &FreeBatch<T, N, S>,
        out: &mut PairBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: BatchKernel<T, N, S>,
    {
        pairs_for(out, batch.len());
        self.drive(&Free, batch.blocks(), out.blocks_mut());
    }

    /// Body 1 immovable, parameters per contact: `out` becomes body 2+ of every contact.
    pub fn fixed<T, const N: usize, const S: usize>(
        &self,
        batch: &FixedBatch<T, N, S>,
        out: &mut StateBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: BatchKernel<T, N, S>,
    {
        states_for(out, batch.len());
        self.drive(&Fixed, batch.blocks(), out.blocks_mut());
    }

    /// Both bodies free, the same two balls in every contact.
    pub fn free_shared<T, const N: usize, const S: usize>(
        &self,
        balls: [&Ball<T>; 2],
        batch: &ContactBatch<T, N, S>,
        out: &mut PairBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: BatchKernel<T, N, S>,
    {
        pairs_for(out, batch.len());
        self.drive(&FreeShared { balls }, batch.blocks(), out.blocks_mut());
    }

    /// Body 1 immovable, the same `radius1` and `ball2` in every contact.
    pub fn fixed_shared<T, const N: usize, const S: usize>(
        &self,
        radius1: &T,
        ball2: &Ball<T>,
        batch: &ContactBatch<T, N, S>,
        out: &mut StateBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: BatchKernel<T, N, S>,
    {
        states_for(out, batch.len());
        let job = FixedShared { radius1, ball2 };
        self.drive(&job, batch.blocks(), out.blocks_mut());
    }

    /// Whether a batch of `blocks` blocks of inputs `B` and outputs `O` is split.
    #[cfg_attr(not(feature = "parallel"), allow(dead_code))]
    pub(super) fn splits<B, O>(&self, blocks: usize) -> bool {
        match self.split {
            None => false,
            Some(Split::Contacts(from)) => blocks * super::LANES >= from,
            Some(Split::Bytes(from)) => {
                blocks * (std::mem::size_of::<B>() + std::mem::size_of::<O>()) >= from
            }
        }
    }

    /// Run `job` on this instruction set, shared with rayon's workers in chunks when the
    /// batch is long enough (`share.rs`).
    #[inline(always)]
    pub(super) fn drive<B: Sync, O: Send>(
        &self,
        job: &(impl Job<B, O> + Sync),
        blocks: &[B],
        out: &mut [O],
    ) {
        #[cfg(feature = "parallel")]
        if self.splits::<B, O>(blocks.len()) {
            let (isa, len) = (self.isa, blocks.len().min(out.len()));
            let threads = rayon::current_num_threads();
            let start = OutPtr(out.as_mut_ptr());
            let start = &start;
            super::share::share(
                len,
                chunk_blocks(len, threads),
                threads - 1,
                &|first, count| {
                    // SAFETY: `[first, first + count)` is within `out` (`len <= out.len()`) and
                    // no other chunk writes it; `out` is borrowed until `share` returns.
                    let out = unsafe { std::slice::from_raw_parts_mut(start.0.add(first), count) };
                    run_on(isa, job, &blocks[first..first + count], out);
                },
            );
            return;
        }
        run_on(self.isa, job, blocks, out);
    }
}

pub(super) fn pairs_for<T: Scalar, const N: usize, const S: usize>(
    out: &mut PairBatch<T, N, S>,
    len: usize,
) {
    let zero = [BodyState::zero(), BodyState::zero()];
    out.resize_with(len, || Lanewise::splat(&zero));
}

pub(super) fn states_for<T: Scalar, const N: usize, const S: usize>(
    out: &mut StateBatch<T, N, S>,
    len: usize,
) {
    out.resize_with(len, || StateLanes::splat(&BodyState::zero()));
}

/// The jobs: one kernel each, with the parameters shared by the call.
pub(super) struct Free;

impl<T, const N: usize, const S: usize> Job<FreeLanes<T, N, S>, [StateLanes<T, N, S>; 2]> for Free
where
    Generated: BatchKernel<T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(
        &self,
        blocks: &[FreeLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    ) {
        Generated::free_blocks::<W>(blocks, out)
    }
}

struct Fixed;

impl<T, const N: usize, const S: usize> Job<FixedLanes<T, N, S>, StateLanes<T, N, S>> for Fixed
where
    Generated: BatchKernel<T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(&self, blocks: &[FixedLanes<T, N, S>], out: &mut [StateLanes<T, N, S>]) {
        Generated::fixed_blocks::<W>(blocks, out)
    }
}

struct FreeShared<'a, T> {
    balls: [&'a Ball<T>; 2],
}

impl<T, const N: usize, const S: usize> Job<ContactLanes<T, N, S>, [StateLanes<T, N, S>; 2]>
    for FreeShared<'_, T>
where
    Generated: BatchKernel<T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(
        &self,
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    ) {
        Generated::free_shared_blocks::<W>(self.balls, blocks, out)
    }
}

struct FixedShared<'a, T> {
    radius1: &'a T,
    ball2: &'a Ball<T>,
}

impl<T, const N: usize, const S: usize> Job<ContactLanes<T, N, S>, StateLanes<T, N, S>>
    for FixedShared<'_, T>
where
    Generated: BatchKernel<T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(
        &self,
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [StateLanes<T, N, S>],
    ) {
        Generated::fixed_shared_blocks::<W>(self.radius1, self.ball2, blocks, out)
    }
}

#[cfg(test)]
mod split_tests {
    use super::*;

    #[test]
    fn a_batch_is_split_by_its_bytes_unless_told_a_length() {
        // `free` at n = 2: 160 bytes a contact (8 (n + 6 + 4 (n + s))), 1280 a block of 8.
        type In = FreeLanes<f64, 2, 1>;
        type Out = [StateLanes<f64, 2, 1>; 2];
        let block = std::mem::size_of::<In>() + std::mem::size_of::<Out>();
        assert_eq!(block, 8 * 160);
        let auto = Exec {
            isa: Isa::Baseline,
            split: Some(Split::Bytes(PARALLEL_FROM_BYTES)),
            backward: false,
            streamed: false,
        };
        let from = PARALLEL_FROM_BYTES.div_ceil(block);
        assert!(!auto.splits::<In, Out>(from - 1));
        assert!(auto.splits::<In, Out>(from));
        // n = 6 moves 768 bytes a contact: split from 4.8 times fewer contacts.
        type In6 = FreeLanes<f64, 6, 15>;
        type Out6 = [StateLanes<f64, 6, 15>; 2];
        let block6 = std::mem::size_of::<In6>() + std::mem::size_of::<Out6>();
        assert_eq!(block6, 8 * 768);
        let from6 = PARALLEL_FROM_BYTES.div_ceil(block6);
        assert!(!auto.splits::<In6, Out6>(from6 - 1));
        assert!(auto.splits::<In6, Out6>(from6));
        // A length given (`parallel_from`) counts contacts; `serial` never splits.
        let by_length = Exec {
            split: Some(Split::Contacts(64)),
            ..auto
        };
        assert!(!by_length.splits::<In6, Out6>(7));
        assert!(by_length.splits::<In6, Out6>(8));
        assert!(!auto.serial().splits::<In, Out>(usize::MAX / block));
    }
}
