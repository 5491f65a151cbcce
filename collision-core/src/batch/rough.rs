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
use crate::{Ball, RefArith, Restitution, Scalar};

/// The generated rough-ball batch kernels of one dimension (as [`super::BatchKernel`], with
/// the law `(e, beta)` of every contact of the call).
pub trait RoughBatchKernel<T, const N: usize, const S: usize> {
    /// Both bodies free, parameters per contact: `out[k]` = `[body 1+, body 2+]` lanes.
    fn rough_free_blocks<const W: usize>(
        law: &Restitution<T>,
        blocks: &[FreeLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    );
    /// Body 1 immovable, parameters per contact: `out[k]` = body 2+ lanes.
    fn rough_fixed_blocks<const W: usize>(
        law: &Restitution<T>,
        blocks: &[FixedLanes<T, N, S>],
        out: &mut [StateLanes<T, N, S>],
    );
    /// Both bodies free, one pair of balls for every contact.
    fn rough_free_shared_blocks<const W: usize>(
        balls: [&Ball<T>; 2],
        law: &Restitution<T>,
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    );
    /// Body 1 immovable, one `radius1` and `ball2` for every contact.
    fn rough_fixed_shared_blocks<const W: usize>(
        radius1: &T,
        ball2: &Ball<T>,
        law: &Restitution<T>,
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [StateLanes<T, N, S>],
    );
}

macro_rules! rough_batch {
    ($($module:ident $feature:literal $n:literal $s:literal;)*) => {$(
        #[cfg(feature = $feature)]
        impl<T: Scalar> RoughBatchKernel<T, $n, $s> for Generated
        where
            for<'a> &'a T: RefArith<T>,
        {
            #[inline(always)]
            fn rough_free_blocks<const W: usize>(
                law: &Restitution<T>,
                blocks: &[FreeLanes<T, $n, $s>],
                out: &mut [[StateLanes<T, $n, $s>; 2]],
            ) {
                super::kernels::$module::rough_free::<T, W>(law, blocks, out)
            }

            #[inline(always)]
            fn rough_fixed_blocks<const W: usize>(
                law: &Restitution<T>,
                blocks: &[FixedLanes<T, $n, $s>],
                out: &mut [StateLanes<T, $n, $s>],
            ) {
                super::kernels::$module::rough_fixed::<T, W>(law, blocks, out)
            }

            #[inline(always)]
            fn rough_free_shared_blocks<const W: usize>(
                balls: [&Ball<T>; 2],
                law: &Restitution<T>,
                blocks: &[ContactLanes<T, $n, $s>],
                out: &mut [[StateLanes<T, $n, $s>; 2]],
            ) {
                super::kernels::$module::rough_free_shared::<T, W>(balls[0], balls[1], law, blocks, out)
            }

            #[inline(always)]
            fn rough_fixed_shared_blocks<const W: usize>(
                radius1: &T,
                ball2: &Ball<T>,
                law: &Restitution<T>,
                blocks: &[ContactLanes<T, $n, $s>],
                out: &mut [StateLanes<T, $n, $s>],
            ) {
                super::kernels::$module::rough_fixed_shared::<T, W>(radius1, ball2, law, blocks, out)
            }
        }
    )*};
}

rough_batch! {
    d2 "d2" 2 1;
    d3 "d3" 3 3;
    d4 "d4" 4 6;
    d5 "d5" 5 10;
    d6 "d6" 6 15;
}

impl Exec {
    /// [`Exec::free`] under the rough-ball law `law` (`kernels::dN::rough::free` per contact).
    /// `law` is not checked: [`Restitution::new`] checks it.
    pub fn rough_free<T, const N: usize, const S: usize>(
        &self,
        law: &Restitution<T>,
        batch: &FreeBatch<T, N, S>,
        out: &mut PairBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: RoughBatchKernel<T, N, S>,
    {
        pairs_for(out, batch.len());
        self.drive(&RoughFree { law }, batch.blocks(), out.blocks_mut());
    }

    /// [`Exec::fixed`] under the rough-ball law `law` (`kernels::dN::rough::fixed`).
    pub fn rough_fixed<T, const N: usize, const S: usize>(
        &self,
        law: &Restitution<T>,
        batch: &FixedBatch<T, N, S>,
        out: &mut StateBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: RoughBatchKernel<T, N, S>,
    {
        states_for(out, batch.len());
        self.drive(&RoughFixed { law }, batch.blocks(), out.blocks_mut());
    }

    /// [`Exec::free_shared`] under the rough-ball law `law`.
    pub fn rough_free_shared<T, const N: usize, const S: usize>(
        &self,
        balls: [&Ball<T>; 2],
        law: &Restitution<T>,
        batch: &ContactBatch<T, N, S>,
        out: &mut PairBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: RoughBatchKernel<T, N, S>,
    {
        pairs_for(out, batch.len());
        let job = RoughFreeShared { balls, law };
        self.drive(&job, batch.blocks(), out.blocks_mut());
    }

    /// [`Exec::fixed_shared`] under the rough-ball law `law`.
    pub fn rough_fixed_shared<T, const N: usize, const S: usize>(
        &self,
        radius1: &T,
        ball2: &Ball<T>,
        law: &Restitution<T>,
        batch: &ContactBatch<T, N, S>,
        out: &mut StateBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: RoughBatchKernel<T, N, S>,
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
struct RoughFree<'a, T> {
    law: &'a Restitution<T>,
}

impl<T, const N: usize, const S: usize> Job<FreeLanes<T, N, S>, [StateLanes<T, N, S>; 2]>
    for RoughFree<'_, T>
where
    Generated: RoughBatchKernel<T, N, S>,
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

struct RoughFixed<'a, T> {
    law: &'a Restitution<T>,
}

impl<T, const N: usize, const S: usize> Job<FixedLanes<T, N, S>, StateLanes<T, N, S>>
    for RoughFixed<'_, T>
where
    Generated: RoughBatchKernel<T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(&self, blocks: &[FixedLanes<T, N, S>], out: &mut [StateLanes<T, N, S>]) {
        Generated::rough_fixed_blocks::<W>(self.law, blocks, out)
    }
}

struct RoughFreeShared<'a, T> {
    balls: [&'a Ball<T>; 2],
    law: &'a Restitution<T>,
}

impl<T, const N: usize, const S: usize> Job<ContactLanes<T, N, S>, [StateLanes<T, N, S>; 2]>
    for RoughFreeShared<'_, T>
where
    Generated: RoughBatchKernel<T, N, S>,
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

struct RoughFixedShared<'a, T> {
    radius1: &'a T,
    ball2: &'a Ball<T>,
    law: &'a Restitution<T>,
}

impl<T, const N: usize, const S: usize> Job<ContactLanes<T, N, S>, StateLanes<T, N, S>>
    for RoughFixedShared<'_, T>
where
    Generated: RoughBatchKernel<T, N, S>,
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
    use super::*;
    use crate::kernels::RoughKernel;

    /// The four rough batch kernels on `items` under `law` against the scalar rough kernels,
    /// bit for bit, for every instruction set (and thread split) this CPU runs.
    fn check<const N: usize, const S: usize>(items: &[Item<f64, N, S>], law: &Restitution<f64>)
    where
        Generated: RoughBatchKernel<f64, N, S> + RoughKernel<f64, N, S>,
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
                let [s1, s2] = &c.states;
                let want = Generated::rough_free(&c.nu, b1, b2, law, s1, s2);
                assert!(
                    same_state(&got[0], &want[0]) && same_state(&got[1], &want[1]),
                    "{}",
                    what("free", k)
                );
                let want = Generated::rough_fixed(&c.nu, &b1.radius, b2, law, s1, s2);
                assert!(same_state(&got1, &want), "{}", what("fixed", k));
            }
            let [b1, b2] = shared;
            exec.rough_free_shared([b1, b2], law, &contacts, &mut pairs);
            exec.rough_fixed_shared(&b1.radius, b2, law, &contacts, &mut states);
            for (k, ((c, _), (got, got1))) in items
                .iter()
                .zip(pairs.iter().zip(states.iter()))
                .enumerate()
            {
                let [s1, s2] = &c.states;
                let want = Generated::rough_free(&c.nu, b1, b2, law, s1, s2);
                assert!(
                    same_state(&got[0], &want[0]) && same_state(&got[1], &want[1]),
                    "{}",
                    what("free_shared", k)
                );
                let want = Generated::rough_fixed(&c.nu, &b1.radius, b2, law, s1, s2);
                assert!(same_state(&got1, &want), "{}", what("fixed_shared", k));
            }
        }
    }

    fn every_length<const N: usize, const S: usize>()
    where
        Generated: RoughBatchKernel<f64, N, S> + RoughKernel<f64, N, S>,
    {
        // Inside the family, at its ends (smooth inelastic, smooth elastic) and no-slip.
        let laws = [
            (0.9, 0.4),
            (0.0, -1.0),
            (0.3, -0.7),
            (1.0, -1.0),
            (1.0, 1.0),
        ];
        for (seed, &len) in LENGTHS.iter().enumerate() {
            let items = sample::<f64, N, S>(0x7006 + seed as u64, len, float);
            for (e, beta) in laws {
                check(&items, &Restitution::new(e, beta).unwrap());
            }
        }
    }

    #[test]
    fn rough_batches_give_the_scalar_rough_kernels_bits() {
        every_length::<2, 1>();
        every_length::<3, 3>();
        every_length::<4, 6>();
        every_length::<5, 10>();
        every_length::<6, 15>();
    }
}
