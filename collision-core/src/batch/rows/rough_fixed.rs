//! [`Exec::rough_fixed_rows`]: the rough-ball family's `fixed` kernels (body 1 immovable: a
//! wall, an obstacle, a ball of infinite mass) on row-major arrays ([`FixedRows`]), under
//! laws given as columns ([`RestitutionRows`](super::RestitutionRows),
//! [`WaltonRows`](super::WaltonRows)): one law shared by every row, or one per row.
//!
//! Row `i` gives `kernels::dN::rough::fixed(nu, R_1, ball_2, law_i, state_1, state_2)` (or
//! `walton::fixed`), body 2's state after the contact, bit for bit: the rows are gathered a
//! chunk at a time straight into the lanes of a [`FixedBatch`] (or a [`FixedEachBatch`] with
//! the laws' lanes, `LawRows::gather_block`), the blocks reused from chunk to chunk, run
//! by [`Exec::rough_fixed`] (or [`Exec::fixed_each`]) and scattered back as
//! [`super::Exec::rough_free_rows`]'s outputs are (each compact state as its full skew
//! matrix).

use super::law::{LawRowError, LawRows};
use super::scatter::scatter_state;
use super::{pairs, BallRows, StateRows, StateRowsMut};
use crate::batch::each::{EachLawBatchKernel, FixedEachBatch};
use crate::batch::lanes::{Contact, FixedLanes, Lanewise, StateLanes, LANES};
use crate::batch::law_lanes::FamilyLaw;
use crate::batch::{Exec, FixedBatch, RoughBatchKernel, StateBatch};
use crate::kernels::Generated;
use crate::{Ball, BodyState, RefArith, Scalar};
use std::ops::Range;

/// Rows gathered and run at a time: a chunk's blocks (`8` contacts each) stay in the L2
/// cache (about 0.5-1.5 MB of inputs and outputs at n = 6 in f64).
pub(super) const CHUNK_ROWS: usize = 2048;

/// Contacts of a free ball (body 2) with an immovable body 1, one per row: what
/// [`Exec::rough_fixed_rows`] reads. The number of contacts is `nu.len() / n`.
#[derive(Clone, Copy, Debug)]
pub struct FixedRows<'a, T> {
    /// The unit normals `nu` (from body 1's centre, or from the wall, to body 2's centre),
    /// `n` entries per contact.
    pub nu: &'a [T],
    /// Body 1's (the immovable body's own motion, as the scalar `fixed` kernels take it)
    /// and body 2's states.
    pub states: [StateRows<'a, T>; 2],
    /// Body 1's radius `R_1` (0 for a wall), one per contact or one shared.
    pub radius1: &'a [T],
    /// Body 2's parameters.
    pub ball2: BallRows<'a, T>,
}

impl<T> FixedRows<'_, T> {
    /// The number of contacts, `nu.len() / n`, after checking every slice's length.
    ///
    /// # Panics
    /// If a length does not fit, as [`super::FreeRows::len`]: `nu.len()` not a multiple of
    /// `n`, a state slice not `n^2` or `n` entries per contact, `radius1` or a parameter
    /// slice neither one entry per contact nor a single one.
    pub fn len<const N: usize>(&self) -> usize {
        assert_eq!(self.nu.len() % N, 0, "nu: {N} entries per contact");
        let len = self.nu.len() / N;
        for (b, s) in self.states.iter().enumerate() {
            assert_eq!(s.spin.len(), len * N * N, "body {b}: spin: n^2 per contact");
            assert_eq!(
                s.velocity.len(),
                len * N,
                "body {b}: velocity: n per contact"
            );
        }
        let p = &self.ball2;
        for x in [self.radius1, p.inv_mass, p.radius, p.gamma2] {
            assert!(x.len() == len || x.len() == 1, "parameters");
        }
        len
    }

    /// Whether there are no contacts.
    pub fn is_empty(&self) -> bool {
        self.nu.is_empty()
    }
}

/// Contact `i` of `rows` as a [`FixedBatch`] item: `(contact, R_1, ball_2)` (the padding
/// lanes' first fill).
fn fixed_item<T: Clone, const N: usize, const S: usize>(
    rows: &FixedRows<'_, T>,
    i: usize,
) -> (Contact<T, N, S>, T, Ball<T>) {
    let pairs = const { pairs::<N, S>() };
    let state = |s: &StateRows<'_, T>| BodyState {
        spin: pairs.map(|(r, c)| s.spin[i * N * N + r * N + c].clone()),
        velocity: std::array::from_fn(|k| s.velocity[i * N + k].clone()),
    };
    let p = |x: &[T]| x[if x.len() == 1 { 0 } else { i }].clone();
    let b = &rows.ball2;
    (
        Contact {
            nu: std::array::from_fn(|k| rows.nu[i * N + k].clone()),
            states: [state(&rows.states[0]), state(&rows.states[1])],
        },
        p(rows.radius1),
        Ball {
            inv_mass: p(b.inv_mass),
            radius: p(b.radius),
            gamma2: p(b.gamma2),
        },
    )
}

/// Contact `i` of `rows` straight into lane `l` of `block` (no item in between): what
/// [`Batch::push`](crate::batch::Batch::push) of [`fixed_item`] writes there.
#[inline(always)]
fn fixed_lane<T: Clone, const N: usize, const S: usize>(
    rows: &FixedRows<'_, T>,
    i: usize,
    l: usize,
    block: &mut FixedLanes<T, N, S>,
) {
    let pairs = const { pairs::<N, S>() };
    for (k, x) in block.contact.nu.iter_mut().enumerate() {
        x[l] = rows.nu[i * N + k].clone();
    }
    for (lanes, s) in block.contact.states.iter_mut().zip(&rows.states) {
        for (x, &(r, c)) in lanes.spin.iter_mut().zip(&pairs) {
            x[l] = s.spin[i * N * N + r * N + c].clone();
        }
        for (k, x) in lanes.velocity.iter_mut().enumerate() {
            x[l] = s.velocity[i * N + k].clone();
        }
    }
    let p = |x: &[T]| x[if x.len() == 1 { 0 } else { i }].clone();
    block.radius1[l] = p(rows.radius1);
    let b = &rows.ball2;
    block.ball2.inv_mass[l] = p(b.inv_mass);
    block.ball2.radius[l] = p(b.radius);
    block.ball2.gamma2[l] = p(b.gamma2);
}

/// Rows `range` of `rows` into `blocks` (`range.len().div_ceil(8)` of them), lane by lane; the
/// last block's lanes past the range repeat its first row, as `push` leaves them.
fn gather_fixed<T: Clone, const N: usize, const S: usize, B: AsMut<FixedLanes<T, N, S>>>(
    rows: &FixedRows<'_, T>,
    range: Range<usize>,
    blocks: &mut [B],
) {
    for (b, block) in blocks.iter_mut().enumerate() {
        let start = range.start + b * LANES;
        let block = block.as_mut();
        for l in 0..LANES {
            let i = if start + l < range.end {
                start + l
            } else {
                start
            };
            fixed_lane(rows, i, l, block);
        }
    }
}

/// The blocks of `states` (rows `range` of the call) into `out`.
fn scatter_chunk<T: Scalar, const N: usize, const S: usize>(
    blocks: &[StateLanes<T, N, S>],
    out: &mut StateRowsMut<'_, T>,
    range: Range<usize>,
) {
    for (b, block) in blocks.iter().enumerate() {
        let start = range.start + b * LANES;
        let count = LANES.min(range.end - start);
        scatter_state::<T, N, S>(block, out, start, count);
    }
}

/// The law lanes of a column type's law.
type LanesOf<T, R> = <<R as LawRows<T>>::Law as FamilyLaw>::Lanes;

impl Exec {
    /// The `fixed` counterpart of [`Exec::rough_free_rows`]: row `i` collided by
    /// `kernels::dN::rough::fixed` (or `walton::fixed`) under row `i`'s law, body 2's state
    /// after the contact written into `out`, bit for bit. When every column of `laws` is a
    /// single value, the shared-law kernel runs ([`Exec::rough_fixed`]); else the `_each`
    /// kernel ([`Exec::fixed_each`]), with each row's law in its lane.
    ///
    /// The laws are checked first, as [`Exec::rough_free_rows`]'s ([`LawRows::check`]): a
    /// refused law is an error naming the field and the row, and nothing is written. The
    /// contacts are not checked.
    ///
    /// # Panics
    /// If the lengths of `rows` do not fit ([`FixedRows::len`]) or `out` does not hold
    /// `n^2` and `n` entries per contact.
    pub fn rough_fixed_rows<R, T, const N: usize, const S: usize>(
        &self,
        laws: &R,
        rows: &FixedRows<'_, T>,
        mut out: StateRowsMut<'_, T>,
    ) -> Result<(), LawRowError>
    where
        R: LawRows<T>,
        T: Scalar + Send + Sync + 'static,
        for<'a> &'a T: RefArith<T>,
        LanesOf<T, R>: 'static,
        Generated: RoughBatchKernel<R::Law, T, N, S> + EachLawBatchKernel<LanesOf<T, R>, T, N, S>,
    {
        let len = rows.len::<N>();
        assert_eq!(out.spin.len(), len * N * N, "out: spin: n^2 per contact");
        assert_eq!(out.velocity.len(), len * N, "out: velocity: n per contact");
        laws.check(len)?;
        let mut states = StateBatch::<T, N, S>::new();
        let chunks = (0..len)
            .step_by(CHUNK_ROWS)
            .map(|a| a..(a + CHUNK_ROWS).min(len));
        match laws.shared() {
            Some(law) => {
                let mut batch = FixedBatch::<T, N, S>::with_capacity(CHUNK_ROWS.min(len));
                for range in chunks {
                    let first = fixed_item(rows, range.start);
                    batch.resize_with(range.len(), || Lanewise::splat(&first));
                    gather_fixed(rows, range.clone(), batch.blocks_mut());
                    self.rough_fixed(&law, &batch, &mut states);
                    scatter_chunk(states.blocks(), &mut out, range);
                }
            }
            None => {
                let mut batch =
                    FixedEachBatch::<T, N, S, LanesOf<T, R>>::with_capacity(CHUNK_ROWS.min(len));
                for range in chunks {
                    let first = (fixed_item(rows, range.start), laws.law(range.start));
                    batch.resize_with(range.len(), || Lanewise::splat(&first));
                    gather_fixed(rows, range.clone(), batch.blocks_mut());
                    for (b, block) in batch.blocks_mut().iter_mut().enumerate() {
                        let start = range.start + b * LANES;
                        let end = (start + LANES).min(range.end);
                        laws.gather_block(start, end, &mut block.law);
                    }
                    self.fixed_each(&batch, &mut states);
                    scatter_chunk(states.blocks(), &mut out, range);
                }
            }
        }
        Ok(())
    }
}
