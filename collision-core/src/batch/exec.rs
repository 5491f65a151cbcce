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

/// Batches at least this long run on rayon's thread pool (feature `parallel`).
pub const PARALLEL_FROM: usize = 1 << 15;

/// The most blocks per rayon task: 1024 contacts, 64 kB to 0.8 MB of input and output.
#[cfg(feature = "parallel")]
const CHUNK_BLOCKS: usize = 128;

/// Blocks per rayon task for `blocks` blocks on `threads` threads: an equal share per
/// thread (so that a short batch is split once per thread, not left on one), at most
/// [`CHUNK_BLOCKS`] (so that a long one balances the load between threads).
#[cfg(feature = "parallel")]
fn chunk_blocks(blocks: usize, threads: usize) -> usize {
    blocks.div_ceil(threads.max(1)).clamp(1, CHUNK_BLOCKS)
}

/// How batches run: the instruction set and, with the `parallel` feature, from which
/// length on they are split across rayon's thread pool. Every setting gives the same
/// result, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Exec {
    isa: Isa,
    parallel_from: Option<usize>,
}

impl Default for Exec {
    fn default() -> Self {
        Self::auto()
    }
}

impl Exec {
    /// The widest instruction set of this CPU ([`Isa::detect`]); with the `parallel`
    /// feature, threads for batches of at least [`PARALLEL_FROM`] contacts.
    pub fn auto() -> Self {
        Exec {
            isa: Isa::detect(),
            parallel_from: cfg!(feature = "parallel").then_some(PARALLEL_FROM),
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
            parallel_from: None,
            ..self
        }
    }

    /// The same, on rayon's thread pool for batches of at least `contacts` contacts.
    #[cfg(feature = "parallel")]
    pub fn parallel_from(self, contacts: usize) -> Self {
        Exec {
            parallel_from: Some(contacts),
            ..self
        }
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

    /// Run `job` on this instruction set, in chunks on rayon's pool when the batch is long
    /// enough.
    #[inline(always)]
    fn drive<B: Sync, O: Send>(&self, job: &(impl Job<B, O> + Sync), blocks: &[B], out: &mut [O]) {
        #[cfg(feature = "parallel")]
        if self
            .parallel_from
            .is_some_and(|from| blocks.len() * super::LANES >= from)
        {
            use rayon::prelude::*;
            let isa = self.isa;
            let chunk = chunk_blocks(blocks.len(), rayon::current_num_threads());
            blocks
                .par_chunks(chunk)
                .zip(out.par_chunks_mut(chunk))
                .for_each(|(b, o)| run_on(isa, job, b, o));
            return;
        }
        run_on(self.isa, job, blocks, out);
    }
}

fn pairs_for<T: Scalar, const N: usize, const S: usize>(out: &mut PairBatch<T, N, S>, len: usize) {
    let zero = [BodyState::zero(), BodyState::zero()];
    out.resize_with(len, || Lanewise::splat(&zero));
}

fn states_for<T: Scalar, const N: usize, const S: usize>(
    out: &mut StateBatch<T, N, S>,
    len: usize,
) {
    out.resize_with(len, || StateLanes::splat(&BodyState::zero()));
}

/// The jobs: one kernel each, with the parameters shared by the call.
struct Free;

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
