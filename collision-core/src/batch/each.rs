//! The rough-ball family's batch kernels with a law per contact (`rough_free_each`,
//! `rough_fixed_each`, `walton_free_each`, `walton_fixed_each` of the generated
//! `batch_{n}.rs`): each block carries its contacts' laws ([`WithLaw`]), lane `l` runs
//! `kernels::dN::rough::free` (or `walton::free`, ...) under its own law, and [`Exec`]'s two
//! operations for them.
//!
//! Each lane runs the scalar kernel's operations on the same operands, its law's `h_n =
//! (1 + e)/2` and `h_t = (1 + beta)/2` included (computed in the lane loop, where the
//! shared-law kernels compute them once per call), so a lane gives the scalar family
//! kernel's bits for its contact and law at every instruction set.

use super::dispatch::Job;
use super::exec::{pairs_for, states_for};
use super::lanes::{FixedLanes, FreeLanes, Lanewise, StateLanes};
use super::law_lanes::{RestitutionLanes, WaltonLanes, WithLaw};
use super::{Batch, Exec, PairBatch, StateBatch};
use crate::kernels::Generated;
use crate::{RefArith, Scalar, ScalarRoot};

/// Contacts of two free balls, each with its own law (lanes `Q`: [`RestitutionLanes`] or
/// [`WaltonLanes`]); built with `push` / `collect` from `((Contact, [Ball; 2]), law)`.
pub type FreeEachBatch<T, const N: usize, const S: usize, Q> =
    Batch<WithLaw<FreeLanes<T, N, S>, Q>>;

/// Contacts of a ball with an immovable body, each with its own law; built from
/// `((Contact, radius1, Ball), law)`.
pub type FixedEachBatch<T, const N: usize, const S: usize, Q> =
    Batch<WithLaw<FixedLanes<T, N, S>, Q>>;

/// The generated batch kernels of one dimension with a law of the rough-ball family per
/// contact, its lanes `Q` ([`RestitutionLanes`]: `rough_*_each`; [`WaltonLanes`]:
/// `walton_*_each`).
pub trait EachLawBatchKernel<Q, T, const N: usize, const S: usize> {
    /// Both bodies free: `out[k]` = `[body 1+, body 2+]` lanes of block `k`.
    fn free_each_blocks<const W: usize>(
        blocks: &[WithLaw<FreeLanes<T, N, S>, Q>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    );
    /// Body 1 immovable: `out[k]` = body 2+ lanes of block `k`.
    fn fixed_each_blocks<const W: usize>(
        blocks: &[WithLaw<FixedLanes<T, N, S>, Q>],
        out: &mut [StateLanes<T, N, S>],
    );
}

macro_rules! each_batch {
    ($lanes:ident $bound:ident [$free:ident $fixed:ident] $($module:ident $feature:literal $n:literal $s:literal;)*) => {$(
        #[cfg(feature = $feature)]
        impl<T: $bound> EachLawBatchKernel<$lanes<T>, T, $n, $s> for Generated
        where
            for<'a> &'a T: RefArith<T>,
        {
            #[inline(always)]
            fn free_each_blocks<const W: usize>(
                blocks: &[WithLaw<FreeLanes<T, $n, $s>, $lanes<T>>],
                out: &mut [[StateLanes<T, $n, $s>; 2]],
            ) {
                super::kernels::$module::$free::<T, W>(blocks, out)
            }

            #[inline(always)]
            fn fixed_each_blocks<const W: usize>(
                blocks: &[WithLaw<FixedLanes<T, $n, $s>, $lanes<T>>],
                out: &mut [StateLanes<T, $n, $s>],
            ) {
                super::kernels::$module::$fixed::<T, W>(blocks, out)
            }
        }
    )*};
}

each_batch! {
    RestitutionLanes Scalar [rough_free_each rough_fixed_each]
    d2 "d2" 2 1;
    d3 "d3" 3 3;
    d4 "d4" 4 6;
    d5 "d5" 5 10;
    d6 "d6" 6 15;
}

each_batch! {
    WaltonLanes ScalarRoot [walton_free_each walton_fixed_each]
    d2 "d2" 2 1;
    d3 "d3" 3 3;
    d4 "d4" 4 6;
    d5 "d5" 5 10;
    d6 "d6" 6 15;
}

impl Exec {
    /// [`Exec::free`] with a law of the rough-ball family per contact: contact `i` with law
    /// `L_i` gives `kernels::dN::rough::free` (or `walton::free`) under `L_i`, bit for bit.
    /// The laws are not checked: build them with [`Restitution::new`](crate::Restitution::new)
    /// / [`Walton::new`](crate::Walton::new), or check row-major ones with
    /// [`LawRows::check`](super::LawRows::check).
    pub fn free_each<Q: Lanewise + Sync, T, const N: usize, const S: usize>(
        &self,
        batch: &FreeEachBatch<T, N, S, Q>,
        out: &mut PairBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: EachLawBatchKernel<Q, T, N, S>,
    {
        pairs_for(out, batch.len());
        self.drive(&FreeEach, batch.blocks(), out.blocks_mut());
    }

    /// [`Exec::fixed`] with a law per contact (`kernels::dN::rough::fixed` per contact).
    pub fn fixed_each<Q: Lanewise + Sync, T, const N: usize, const S: usize>(
        &self,
        batch: &FixedEachBatch<T, N, S, Q>,
        out: &mut StateBatch<T, N, S>,
    ) where
        T: Scalar + Send + Sync,
        for<'a> &'a T: RefArith<T>,
        Generated: EachLawBatchKernel<Q, T, N, S>,
    {
        states_for(out, batch.len());
        self.drive(&FixedEach, batch.blocks(), out.blocks_mut());
    }
}

/// The `free_each` kernel as a job (`rows/exec.rs` runs it on a pass of blocks too).
pub(crate) struct FreeEach;

impl<Q, T, const N: usize, const S: usize>
    Job<WithLaw<FreeLanes<T, N, S>, Q>, [StateLanes<T, N, S>; 2]> for FreeEach
where
    Generated: EachLawBatchKernel<Q, T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(
        &self,
        blocks: &[WithLaw<FreeLanes<T, N, S>, Q>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    ) {
        Generated::free_each_blocks::<W>(blocks, out)
    }
}

struct FixedEach;

impl<Q, T, const N: usize, const S: usize> Job<WithLaw<FixedLanes<T, N, S>, Q>, StateLanes<T, N, S>>
    for FixedEach
where
    Generated: EachLawBatchKernel<Q, T, N, S>,
{
    #[inline(always)]
    fn run<const W: usize>(
        &self,
        blocks: &[WithLaw<FixedLanes<T, N, S>, Q>],
        out: &mut [StateLanes<T, N, S>],
    ) {
        Generated::fixed_each_blocks::<W>(blocks, out)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::super::tests::{execs, float, same_state, sample, LENGTHS};
    use super::super::FreeBatch;
    use super::*;
    use crate::kernels::{RoughKernel, WaltonKernel};
    use crate::{Restitution, Walton};
    use rand::{Rng as _, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `len` laws `(e, beta)`: the family's ends and no-slip among values drawn in
    /// `[0, 1] x [-1, 1]`, in turn.
    pub(crate) fn restitutions(seed: u64, len: usize) -> Vec<Restitution<f64>> {
        let ends = [(1.0, 1.0), (1.0, -1.0), (0.0, -1.0), (0.0, 1.0), (0.9, 0.4)];
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..len)
            .map(|k| {
                let (e, beta) = match ends.get(k % 8) {
                    Some(&law) => law,
                    None => (float(&mut rng, 0.0, 1.0), float(&mut rng, -1.0, 1.0)),
                };
                Restitution::new(e, beta).unwrap()
            })
            .collect()
    }

    /// `len` Walton laws: no friction, large friction and a sticking `beta0 = -1` among
    /// values drawn in `[0, 1] x [0, 2] x [-1, 1]` (sliding and sticking contacts).
    pub(crate) fn waltons(seed: u64, len: usize) -> Vec<Walton<f64>> {
        let ends = [
            (0.9, 0.3, 0.5),
            (1.0, 0.0, 1.0),
            (0.0, 2.0, -0.2),
            (0.5, 0.1, -1.0),
        ];
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..len)
            .map(|k| {
                let (e, mu, beta0) = match ends.get(k % 7) {
                    Some(&law) => law,
                    None => (
                        float(&mut rng, 0.0, 1.0),
                        float::<f64>(&mut rng, 0.0, 2.0) * rng.random_range(0..2) as f64,
                        float(&mut rng, -1.0, 1.0),
                    ),
                };
                Walton::new(e, mu, beta0).unwrap()
            })
            .collect()
    }

    /// Both `_each` kernels of one law family on `items`, contact `k` under `laws[k]`,
    /// against `scalar` (the law's scalar `free` and `fixed`), bit for bit, at every
    /// instruction set and thread split of this CPU.
    #[allow(clippy::type_complexity)]
    fn check<L: Clone + std::fmt::Debug, Q, const N: usize, const S: usize>(
        items: &[super::super::tests::Item<f64, N, S>],
        laws: &[L],
        scalar: &dyn Fn(
            &super::super::Contact<f64, N, S>,
            [&crate::Ball<f64>; 2],
            &L,
        ) -> (
            [crate::BodyState<f64, N, S>; 2],
            crate::BodyState<f64, N, S>,
        ),
    ) where
        Q: Lanewise<Item = L> + Sync + Clone,
        Generated: EachLawBatchKernel<Q, f64, N, S>,
    {
        let free: FreeEachBatch<f64, N, S, Q> =
            items.iter().cloned().zip(laws.iter().cloned()).collect();
        let fixed: FixedEachBatch<f64, N, S, Q> = items
            .iter()
            .zip(laws)
            .map(|((c, [b1, b2]), law)| ((c.clone(), b1.radius, b2.clone()), law.clone()))
            .collect();
        for exec in execs() {
            let (mut pairs, mut states) = (PairBatch::new(), StateBatch::new());
            exec.free_each(&free, &mut pairs);
            exec.fixed_each(&fixed, &mut states);
            assert_eq!((pairs.len(), states.len()), (items.len(), items.len()));
            for (k, (((c, [b1, b2]), law), (got, got1))) in items
                .iter()
                .zip(laws)
                .zip(pairs.iter().zip(states.iter()))
                .enumerate()
            {
                let (want, want1) = scalar(c, [b1, b2], law);
                let what = format!("n = {N}, {law:?}, {exec:?}, contact {k}");
                assert!(same_state(&got[0], &want[0]), "free: {what}");
                assert!(same_state(&got[1], &want[1]), "free: {what}");
                assert!(same_state(&got1, &want1), "fixed: {what}");
            }
        }
    }

    fn every_length<const N: usize, const S: usize>()
    where
        Generated: EachLawBatchKernel<RestitutionLanes<f64>, f64, N, S>
            + EachLawBatchKernel<WaltonLanes<f64>, f64, N, S>
            + RoughKernel<f64, N, S>
            + WaltonKernel<f64, N, S>,
    {
        for (seed, &len) in LENGTHS.iter().enumerate() {
            let seed = 0x7e4c + seed as u64;
            let items = sample::<f64, N, S>(seed, len, float);
            check::<_, RestitutionLanes<f64>, N, S>(
                &items,
                &restitutions(seed, len),
                &|c, [b1, b2], law| {
                    let [s1, s2] = &c.states;
                    (
                        Generated::rough_free(&c.nu, b1, b2, law, s1, s2),
                        Generated::rough_fixed(&c.nu, &b1.radius, b2, law, s1, s2),
                    )
                },
            );
            check::<_, WaltonLanes<f64>, N, S>(&items, &waltons(seed, len), &|c, [b1, b2], law| {
                let [s1, s2] = &c.states;
                (
                    Generated::walton_free(&c.nu, b1, b2, law, s1, s2),
                    Generated::walton_fixed(&c.nu, &b1.radius, b2, law, s1, s2),
                )
            });
        }
    }

    #[test]
    fn each_lane_gives_the_scalar_family_kernels_bits_under_its_own_law() {
        every_length::<2, 1>();
        every_length::<3, 3>();
        every_length::<4, 6>();
        every_length::<5, 10>();
        every_length::<6, 15>();
    }

    /// At `(e, beta) = (1, 1)` in every lane the `_each` kernel gives the no-slip batch
    /// kernel's bits, and at `(1, -1)` the smooth map's (the rough kernel's, which the
    /// scalar tests tie to the smooth map).
    #[test]
    fn no_slip_in_every_lane_is_the_no_slip_batch() {
        let items = sample::<f64, 3, 3>(0x7e4d, 37, float);
        let free: FreeBatch<f64, 3, 3> = items.iter().cloned().collect();
        let each: FreeEachBatch<f64, 3, 3, RestitutionLanes<f64>> = items
            .iter()
            .cloned()
            .map(|i| (i, Restitution::no_slip()))
            .collect();
        for exec in execs() {
            let (mut want, mut got) = (PairBatch::new(), PairBatch::new());
            exec.free(&free, &mut want);
            exec.free_each(&each, &mut got);
            for (k, (w, g)) in want.iter().zip(got.iter()).enumerate() {
                let same = same_state(&w[0], &g[0]) && same_state(&w[1], &g[1]);
                assert!(same, "{exec:?}, contact {k}");
            }
        }
    }
}
