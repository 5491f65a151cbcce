//! The rough-ball law's batch kernels (`rough_free`, `rough_fixed`, `rough_free_shared`,
//! `rough_fixed_shared` of the generated `batch_{n}.rs`): the batch form of
//! `kernels::dN::rough`, the law `(e, beta)` shared by the whole call (`h_n = (1 + e)/2` and
//! `h_t = (1 + beta)/2` computed once), and [`Exec`]'s four operations for them.
//!
//! Each lane runs the scalar rough kernel's operations on the same operands, so a batch gives
//! `rough::free`'s / `rough::fixed`'s bits for every contact at every instruction set; at
//! `(e, beta) = (1, 1)` those are the no-slip kernels' (`docs/kernels.md`).

use super::dispatch::Job;
use super::exec::{pairs_for, states_for};
use super::lanes::{ContactLanes, FixedLanes, FreeLanes, StateLanes};
use super::{ContactBatch, Exec, FixedBatch, FreeBatch, PairBatch, StateBatch};
use crate::kernels::Generated;
use crate::{Ball, RefArith, Restitution, Scalar, ScalarRoot, Walton};

/// The generated batch kernels of one dimension under a law `L` of the rough-ball family
/// shared by every contact of the call (as [`super::BatchKernel`]): [`Restitution`]
/// (`rough_free`, ...) or [`Walton`] (`walton_free`, ...).
pub trait RoughBatchKernel<L, T, const N: usize, const S: usize> {
    /// Both bodies free, parameters per contact: `out[k]` = `[body 1+, body 2+]` lanes.
    fn rough_free_blocks<const W: usize>(
        law: &L,
        blocks: &[FreeLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    );
    /// Body 1 immovable, parameters per contact: `out[k]` = body 2+ lanes.
    fn rough_fixed_blocks<const W: usize>(
        law: &L,
        blocks: &[FixedLanes<T, N, S>],
        out: &mut [StateLanes<T, N, S>],
    );
    /// Both bodies free, one pair of balls for every contact.
    fn rough_free_shared_blocks<const W: usize>(
        balls: [&Ball<T>; 2],
        law: &L,
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    );
    /// Body 1 immovable, one `radius1` and `ball2` for every contact.
    fn rough_fixed_shared_blocks<const W: usize>(
        radius1: &T,
        ball2: &Ball<T>,
        law: &L,
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [StateLanes<T, N, S>],
    );
}

macro_rules! rough_batch {
    ($law:ident $bound:ident [$free:ident $fixed:ident $free_shared:ident $fixed_shared:ident] $($module:ident $feature:literal $n:literal $s:literal;)*) => {$(
        #[cfg(feature = $feature)]
        impl<T: $bound> RoughBatchKernel<$law<T>, T, $n, $s> for Generated
        where
            for<'a> &'a T: RefArith<T>,
        {
            #[inline(always)]
            fn rough_free_blocks<const W: usize>(
                law: &$law<T>,
                blocks: &[FreeLanes<T, $n, $s>],
                out: &mut [[StateLanes<T, $n, $s>; 2]],
            ) {
                super::kernels::$module::$free::<T, W>(law, blocks, out)
            }

            #[inline(always)]
            fn rough_fixed_blocks<const W: usize>(
                law: &$law<T>,
                blocks: &[FixedLanes<T, $n, $s>],
                out: &mut [StateLanes<T, $n, $s>],
            ) {
                super::kernels::$module::$fixed::<T, W>(law, blocks, out)
            }

            #[inline(always)]
            fn rough_free_shared_blocks<const W: usize>(
                balls: [&Ball<T>; 2],
                law: &$law<T>,
                blocks: &[ContactLanes<T, $n, $s>],
                out: &mut [[StateLanes<T, $n, $s>; 2]],
            ) {
                super::kernels::$module::$free_shared::<T, W>(balls[0], balls[1], law, blocks, out)
            }

            #[inline(always)]
            fn rough_fixed_shared_blocks<const W: usize>(
                radius1: &T,
                ball2: &Ball<T>,
                law: &$law<T>,
                blocks: &[ContactLanes<T, $n, $s>],
                out: &mut [StateLanes<T, $n, $s>],
            ) {
                super::kernels::$module::$fixed_shared::<T, W>(radius1, ball2, law, blocks, out)
            }
        }
    )*};
}

rough_batch! {
    Restitution Scalar [rough_free rough_fixed rough_free_shared rough_fixed_shared]
    d2 "d2" 2 1;
    d3 "d3" 3 3;
    d4 "d4" 4 6;
    d5 "d5" 5 10;
    d6 "d6" 6 15;
}

rough_batch! {
    Walton ScalarRoot [walton_free walton_fixed walton_free_shared walton_fixed_shared]
    d2 "d2" 2 1;
    d3 "d3" 3 3;
    d4 "d4" 4 6;
    d5 "d5" 5 10;
    d6 "d6" 6 15;
}

impl Exec {
    /// [`Exec::free`] under the rough-ball law `law` (`kernels::dN::rough::free` per contact).
    /// `law` is not checked: [`Restitution::new`] checks it.
    pub fn rough_free<L: Sync, T, const N: usize, const S: usize>(
        &self,
        law: &L,
        batch: &FreeBatch<T, N, S>,
        out: &mut PairBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: RoughBatchKernel<L, T, N, S>,
    {
        pairs_for(out, batch.len());
        self.drive(&RoughFree { law }, batch.blocks(), out.blocks_mut());
    }

    /// [`Exec::fixed`] under the rough-ball law `law` (`kernels::dN::rough::fixed`).
    pub fn rough_fixed<L: Sync, T, const N: usize, const S: usize>(
        &self,
        law: &L,
        batch: &FixedBatch<T, N, S>,
        out: &mut StateBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: RoughBatchKernel<L, T, N, S>,
    {
        states_for(out, batch.len());
        self.drive(&RoughFixed { law }, batch.blocks(), out.blocks_mut());
    }

    /// [`Exec::free_shared`] under the rough-ball law `law`.
    pub fn rough_free_shared<L: Sync, T, const N: usize, const S: usize>(
        &self,
        balls: [&Ball<T>; 2],
        law: &L,
        batch: &ContactBatch<T, N, S>,
        out: &mut PairBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: RoughBatchKernel<L, T, N, S>,
    {
        pairs_for(out, batch.len());
        let job = RoughFreeShared { balls, law };
        self.drive(&job, batch.blocks(), out.blocks_mut());
    }

    /// [`Exec::fixed_shared`] under the rough-ball law `law`.
    pub fn rough_fixed_shared<L: Sync, T, const N: usize, const S: usize>(
        &self,
        radius1: &T,
        ball2: &Ball<T>,
        law: &L,
        batch: &ContactBatch<T, N, S>,
        out: &mut StateBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: RoughBatchKernel<L, T, N, S>,
    {
        states_for(out, batch.len());
        let job = RoughFixedShared {
            radius1,
            ball2,
            law,
        };
        self.drive(&job, batch.blocks(), out.blocks_mut());
    }
}

/// The jobs: one kernel each, with the law (and the shared balls) of the call.
pub(crate) struct RoughFree<'a, L> {
    pub(crate) law: &'a L,
}

impl<L, T, const N: usize, const S: usize> Job<FreeLanes<T, N, S>, [StateLanes<T, N, S>; 2]>
    for RoughFree<'_, L>
where
    Generated: RoughBatchKernel<L, T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(
        &self,
        blocks: &[FreeLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    ) {
        Generated::rough_free_blocks::<W>(self.law, blocks, out)
    }
}

struct RoughFixed<'a, L> {
    law: &'a L,
}

impl<L, T, const N: usize, const S: usize> Job<FixedLanes<T, N, S>, StateLanes<T, N, S>>
    for RoughFixed<'_, L>
where
    Generated: RoughBatchKernel<L, T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(&self, blocks: &[FixedLanes<T, N, S>], out: &mut [StateLanes<T, N, S>]) {
        Generated::rough_fixed_blocks::<W>(self.law, blocks, out)
    }
}

struct RoughFreeShared<'a, L, T> {
    balls: [&'a Ball<T>; 2],
    law: &'a L,
}

impl<L, T, const N: usize, const S: usize> Job<ContactLanes<T, N, S>, [StateLanes<T, N, S>; 2]>
    for RoughFreeShared<'_, L, T>
where
    Generated: RoughBatchKernel<L, T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(
        &self,
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    ) {
        Generated::rough_free_shared_blocks::<W>(self.balls, self.law, blocks, out)
    }
}

struct RoughFixedShared<'a, L, T> {
    radius1: &'a T,
    ball2: &'a Ball<T>,
    law: &'a L,
}

impl<L, T, const N: usize, const S: usize> Job<ContactLanes<T, N, S>, StateLanes<T, N, S>>
    for RoughFixedShared<'_, L, T>
where
    Generated: RoughBatchKernel<L, T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(
        &self,
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [StateLanes<T, N, S>],
    ) {
        Generated::rough_fixed_shared_blocks::<W>(self.radius1, self.ball2, self.law, blocks, out)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{execs, float, same_state, sample, Item, LENGTHS};
    use super::super::Contact;
    use super::*;
    use crate::kernels::{RoughKernel, WaltonKernel};
    use crate::BodyState;

    /// A law's scalar kernels on one contact: `free`'s two bodies and `fixed`'s body 2.
    type Scalars<'a, const N: usize, const S: usize> =
        &'a dyn Fn(
            &Contact<f64, N, S>,
            [&Ball<f64>; 2],
        ) -> ([BodyState<f64, N, S>; 2], BodyState<f64, N, S>);

    /// The four batch kernels of a law on `items` against the law's scalar kernels, bit for
    /// bit, for every instruction set (and thread split) this CPU runs.
    fn check<L: Sync + std::fmt::Debug, const N: usize, const S: usize>(
        items: &[Item<f64, N, S>],
        law: &L,
        scalar: Scalars<N, S>,
    ) where
        Generated: RoughBatchKernel<L, f64, N, S>,
    {
        let Some((_, shared)) = items.first() else {
            return;
        };
        let free_batch: FreeBatch<f64, N, S> = items.iter().cloned().collect();
        let fixed_batch: FixedBatch<f64, N, S> = items
            .iter()
            .map(|(c, [b1, b2])| (c.clone(), b1.radius, b2.clone()))
            .collect();
        let contacts: ContactBatch<f64, N, S> = items.iter().map(|(c, _)| c.clone()).collect();
        for exec in execs() {
            let what = |kernel: &str, k: usize| {
                format!("n = {N}, {kernel}, {law:?}, {exec:?}, contact {k}")
            };
            let (mut pairs, mut states) = (PairBatch::new(), StateBatch::new());
            exec.rough_free(law, &free_batch, &mut pairs);
            exec.rough_fixed(law, &fixed_batch, &mut states);
            assert_eq!((pairs.len(), states.len()), (items.len(), items.len()));
            for (k, ((c, [b1, b2]), (got, got1))) in items
                .iter()
                .zip(pairs.iter().zip(states.iter()))
                .enumerate()
            {
                let (want, want1) = scalar(c, [b1, b2]);
                let free = same_state(&got[0], &want[0]) && same_state(&got[1], &want[1]);
                assert!(free, "{}", what("free", k));
                assert!(same_state(&got1, &want1), "{}", what("fixed", k));
            }
            let [b1, b2] = shared;
            exec.rough_free_shared([b1, b2], law, &contacts, &mut pairs);
            exec.rough_fixed_shared(&b1.radius, b2, law, &contacts, &mut states);
            for (k, ((c, _), (got, got1))) in items
                .iter()
                .zip(pairs.iter().zip(states.iter()))
                .enumerate()
            {
                let (want, want1) = scalar(c, [b1, b2]);
                let free = same_state(&got[0], &want[0]) && same_state(&got[1], &want[1]);
                assert!(free, "{}", what("free_shared", k));
                assert!(same_state(&got1, &want1), "{}", what("fixed_shared", k));
            }
        }
    }

    fn every_length<const N: usize, const S: usize>()
    where
        Generated: RoughBatchKernel<Restitution<f64>, f64, N, S>
            + RoughBatchKernel<Walton<f64>, f64, N, S>
            + RoughKernel<f64, N, S>
            + WaltonKernel<f64, N, S>,
    {
        // Inside the family, at its ends (smooth inelastic, smooth elastic) and no-slip.
        let laws = [
            (0.9, 0.4),
            (0.0, -1.0),
            (0.3, -0.7),
            (1.0, -1.0),
            (1.0, 1.0),
        ];
        // Walton: contacts that slide and contacts that stick among the samples, no friction,
        // a sticking restitution of -1 (docs/backends.md's laws, and one more).
        let waltons = [
            (0.9, 0.3, 0.5),
            (1.0, 0.0, 1.0),
            (0.0, 2.0, -0.2),
            (0.5, 0.1, -1.0),
        ];
        for (seed, &len) in LENGTHS.iter().enumerate() {
            let items = sample::<f64, N, S>(0x7006 + seed as u64, len, float);
            for (e, beta) in laws {
                let law = Restitution::new(e, beta).unwrap();
                check(&items, &law, &|c, [b1, b2]| {
                    let [s1, s2] = &c.states;
                    (
                        Generated::rough_free(&c.nu, b1, b2, &law, s1, s2),
                        Generated::rough_fixed(&c.nu, &b1.radius, b2, &law, s1, s2),
                    )
                });
            }
            for (e, mu, beta0) in waltons {
                let law = Walton::new(e, mu, beta0).unwrap();
                check(&items, &law, &|c, [b1, b2]| {
                    let [s1, s2] = &c.states;
                    (
                        Generated::walton_free(&c.nu, b1, b2, &law, s1, s2),
                        Generated::walton_fixed(&c.nu, &b1.radius, b2, &law, s1, s2),
                    )
                });
            }
        }
    }

    #[test]
    fn rough_and_walton_batches_give_the_scalar_kernels_bits() {
        every_length::<2, 1>();
        every_length::<3, 3>();
        every_length::<4, 6>();
        every_length::<5, 10>();
        every_length::<6, 15>();
    }
}
