//! What one pass of the row path runs on its blocks: the no-slip `free` kernel, a family
//! kernel under one law for the call, or the `_each` kernel under each row's law (the
//! block type then carries the law lanes, gathered beside the contacts).

use super::law::{gather_laws, LawRows};
use crate::batch::dispatch::{run_on, Isa};
use crate::batch::each::{EachLawBatchKernel, FreeEach};
use crate::batch::exec::Free;
use crate::batch::kernels::BatchKernel;
use crate::batch::lanes::{Contact, FreeLanes, Lanewise, StateLanes};
use crate::batch::law_lanes::{FamilyLaw, WithLaw};
use crate::batch::rough::RoughFree;
use crate::batch::RoughBatchKernel;
use crate::kernels::Generated;
use crate::Ball;
use std::ops::Range;

/// The kernel of a pass and its input block.
pub(crate) trait Pass<T, const N: usize, const S: usize>: Sync + Sized {
    /// The input block: [`FreeLanes`], or with the law lanes beside it.
    type Block: AsMut<FreeLanes<T, N, S>> + Clone + Send + 'static;

    /// A block whose every lane is `first` (the contact of row `row`): the pass's blocks
    /// before the first gather.
    fn splat(&self, first: &(Contact<T, N, S>, [Ball<T>; 2]), row: usize) -> Self::Block;

    /// These rows' part of the pass (the law of rows `range`).
    #[cfg_attr(not(feature = "parallel"), allow(dead_code))]
    fn slice(&self, range: Range<usize>) -> Self;

    /// What the gather of the contacts leaves: the law lanes of rows `range`.
    fn fill(&self, range: Range<usize>, blocks: &mut [Self::Block]);

    /// The kernel on `blocks` at `isa`.
    fn run(&self, isa: Isa, blocks: &[Self::Block], out: &mut [[StateLanes<T, N, S>; 2]]);
}

/// The no-slip `free` kernel.
pub(crate) struct NoSlip;

impl<T, const N: usize, const S: usize> Pass<T, N, S> for NoSlip
where
    T: Clone + Send + 'static,
    Generated: BatchKernel<T, N, S>,
{
    type Block = FreeLanes<T, N, S>;
    fn splat(&self, first: &(Contact<T, N, S>, [Ball<T>; 2]), _: usize) -> Self::Block {
        FreeLanes::splat(first)
    }
    fn slice(&self, _: Range<usize>) -> Self {
        NoSlip
    }
    fn fill(&self, _: Range<usize>, _: &mut [Self::Block]) {}
    fn run(&self, isa: Isa, blocks: &[Self::Block], out: &mut [[StateLanes<T, N, S>; 2]]) {
        run_on(isa, &Free, blocks, out)
    }
}

/// A family kernel (`rough_free`, `walton_free`) under one law for every row.
pub(crate) struct SharedLaw<'a, L>(pub(crate) &'a L);

impl<T, L, const N: usize, const S: usize> Pass<T, N, S> for SharedLaw<'_, L>
where
    T: Clone + Send + 'static,
    L: Sync,
    Generated: RoughBatchKernel<L, T, N, S>,
{
    type Block = FreeLanes<T, N, S>;
    fn splat(&self, first: &(Contact<T, N, S>, [Ball<T>; 2]), _: usize) -> Self::Block {
        FreeLanes::splat(first)
    }
    fn slice(&self, _: Range<usize>) -> Self {
        SharedLaw(self.0)
    }
    fn fill(&self, _: Range<usize>, _: &mut [Self::Block]) {}
    fn run(&self, isa: Isa, blocks: &[Self::Block], out: &mut [[StateLanes<T, N, S>; 2]]) {
        run_on(isa, &RoughFree { law: self.0 }, blocks, out)
    }
}

/// The `_each` kernel under each row's law.
pub(crate) struct EachLaw<R>(pub(crate) R);

type LanesOf<T, R> = <<R as LawRows<T>>::Law as FamilyLaw>::Lanes;

impl<T, R, const N: usize, const S: usize> Pass<T, N, S> for EachLaw<R>
where
    T: Clone + Send + 'static,
    R: LawRows<T>,
    LanesOf<T, R>: 'static,
    Generated: EachLawBatchKernel<LanesOf<T, R>, T, N, S>,
{
    type Block = WithLaw<FreeLanes<T, N, S>, LanesOf<T, R>>;
    fn splat(&self, first: &(Contact<T, N, S>, [Ball<T>; 2]), row: usize) -> Self::Block {
        WithLaw {
            block: FreeLanes::splat(first),
            law: Lanewise::splat(&self.0.law(row)),
        }
    }
    fn slice(&self, range: Range<usize>) -> Self {
        EachLaw(self.0.slice(range))
    }
    fn fill(&self, range: Range<usize>, blocks: &mut [Self::Block]) {
        gather_laws(&self.0, range, blocks)
    }
    fn run(&self, isa: Isa, blocks: &[Self::Block], out: &mut [[StateLanes<T, N, S>; 2]]) {
        run_on(isa, &FreeEach, blocks, out)
    }
}
