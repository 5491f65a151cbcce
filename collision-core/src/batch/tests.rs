//! The batch kernels against the scalar kernels: bit for bit in `f64` and `f32`, exactly in
//! `Exact`, on seeded random contacts, for every instruction set this CPU runs, serial and
//! (feature `parallel`) threaded, with batch lengths that leave ragged last blocks.

use super::*;
use crate::kernels::Generated;
use crate::{collide_unchecked, Ball, BodyState, Exact, Kernel, RefArith, Scalar};
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub(super) type Item<T, const N: usize, const S: usize> = (Contact<T, N, S>, [Ball<T>; 2]);

/// Lengths around the block size: empty, one lane, ragged, full, and several blocks.
pub(super) const LENGTHS: [usize; 6] = [0, 1, 7, 8, 9, 37];

/// `len` contacts with masses and radii in [1/2, 2), `gamma2` in [1/(5n), 2/n), spins and
/// velocities in [-1, 1), normals unit in floats (in `Exact` not: the kernels are rational
/// functions, and equality with the scalar kernel holds for any inputs); each number drawn
/// by `num(rng, lo, hi)`. Contact `k` has body 1 immovable (`inv_mass = 0`) when
/// `k % 4 == 1`, body 2 immovable when `k % 4 == 2`, and one point mass (`gamma2 = 0`) when
/// `k % 4 == 3`: `free` takes every one of them (its preconditions hold).
pub(super) fn sample<T: Scalar, const N: usize, const S: usize>(
    seed: u64,
    len: usize,
    num: impl Fn(&mut ChaCha8Rng, f64, f64) -> T,
) -> Vec<Item<T, N, S>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = N as f64;
    (0..len)
        .map(|k| {
            let raw: [T; N] = std::array::from_fn(|_| num(&mut rng, -1.0, 1.0));
            let norm2 = raw.iter().fold(T::zero(), |s, x| s + x.clone() * x.clone());
            let nu = if T::EXACT {
                raw
            } else {
                let norm = T::one() / from_f64::<T>(norm2.to_f64().sqrt());
                raw.map(|x| x * norm.clone())
            };
            let mut ball = || Ball {
                inv_mass: num(&mut rng, 0.5, 2.0),
                radius: num(&mut rng, 0.5, 2.0),
                gamma2: num(&mut rng, 0.2 / n, 2.0 / n),
            };
            let mut balls = [ball(), ball()];
            match k % 4 {
                1 => balls[0].inv_mass = T::zero(),
                2 => balls[1].inv_mass = T::zero(),
                3 => balls[k / 4 % 2].gamma2 = T::zero(),
                _ => {}
            }
            let mut state = || BodyState {
                spin: std::array::from_fn(|_| num(&mut rng, -1.0, 1.0)),
                velocity: std::array::from_fn(|_| num(&mut rng, -1.0, 1.0)),
            };
            let states = [state(), state()];
            (Contact { nu, states }, balls)
        })
        .collect()
}

/// `x` rounded to a multiple of `2^-40`, in `T` (for the float samples).
fn from_f64<T: Scalar>(x: f64) -> T {
    let scale = 1i64 << 40;
    T::from_ratio((x * scale as f64).round() as i64, scale)
}

pub(super) fn float<T: Scalar>(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> T {
    from_f64(rng.random_range(lo..hi))
}

/// A multiple of 1/64 in `[lo, hi]`.
fn rational(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> Exact {
    let (lo, hi) = ((lo * 64.0).ceil() as i64, (hi * 64.0).floor() as i64);
    Exact::from_ratio(rng.random_range(lo..=hi), 64)
}

/// Equal values with equal bits (through `f64`, exact from `f32`): tells `-0.0` from `0.0`.
fn same<T: Scalar>(a: &T, b: &T) -> bool {
    a == b && a.to_f64().to_bits() == b.to_f64().to_bits()
}

pub(super) fn same_state<T: Scalar, const N: usize, const S: usize>(
    a: &BodyState<T, N, S>,
    b: &BodyState<T, N, S>,
) -> bool {
    a.spin.iter().zip(&b.spin).all(|(x, y)| same(x, y))
        && a.velocity.iter().zip(&b.velocity).all(|(x, y)| same(x, y))
}

/// Every instruction set this CPU runs, serial and (feature `parallel`) threaded from the
/// first contact on.
pub(super) fn execs() -> Vec<Exec> {
    let mut out = Vec::new();
    for isa in Isa::available() {
        let exec = Exec::auto().with_isa(isa).expect("available").serial();
        out.push(exec);
        #[cfg(feature = "parallel")]
        out.push(exec.parallel_from(1));
    }
    out
}

/// All four batch kernels on `items` against the scalar kernels, for every [`execs`].
fn check<T, const N: usize, const S: usize>(items: &[Item<T, N, S>])
where
    T: Scalar + Send + Sync,
    for<'a> &'a T: RefArith<T>,
    Generated: BatchKernel<T, N, S> + Kernel<T, N, S>,
{
    let free_batch: FreeBatch<T, N, S> = items.iter().cloned().collect();
    let fixed_batch: FixedBatch<T, N, S> = items
        .iter()
        .map(|(c, [b1, b2])| (c.clone(), b1.radius.clone(), b2.clone()))
        .collect();
    let contacts: ContactBatch<T, N, S> = items.iter().map(|(c, _)| c.clone()).collect();
    let shared = match items.first() {
        Some((_, balls)) => balls.clone(),
        None => return check_empty(&free_batch, &fixed_batch, &contacts),
    };
    for exec in execs() {
        let what = |kernel: &str, k: usize| {
            format!(
                "{} n = {N}, {kernel}, {exec:?}, contact {k} of {}",
                T::NAME,
                items.len()
            )
        };
        let (mut pairs, mut states) = (PairBatch::new(), StateBatch::new());
        exec.free(&free_batch, &mut pairs);
        assert_eq!(pairs.len(), items.len());
        for (k, ((c, [b1, b2]), got)) in items.iter().zip(pairs.iter()).enumerate() {
            let want =
                <Generated as Kernel<T, N, S>>::free(&c.nu, b1, b2, &c.states[0], &c.states[1]);
            assert!(
                same_state(&got[0], &want[0]) && same_state(&got[1], &want[1]),
                "{}",
                what("free", k)
            );
        }
        exec.fixed(&fixed_batch, &mut states);
        assert_eq!(states.len(), items.len());
        for (k, ((c, [b1, b2]), got)) in items.iter().zip(states.iter()).enumerate() {
            let want = <Generated as Kernel<T, N, S>>::fixed(
                &c.nu,
                &b1.radius,
                b2,
                &c.states[0],
                &c.states[1],
            );
            assert!(same_state(&got, &want), "{}", what("fixed", k));
        }
        let [s1, s2] = &shared;
        exec.free_shared([s1, s2], &contacts, &mut pairs);
        for (k, ((c, _), got)) in items.iter().zip(pairs.iter()).enumerate() {
            let want =
                <Generated as Kernel<T, N, S>>::free(&c.nu, s1, s2, &c.states[0], &c.states[1]);
            assert!(
                same_state(&got[0], &want[0]) && same_state(&got[1], &want[1]),
                "{}",
                what("free_shared", k)
            );
        }
        exec.fixed_shared(&s1.radius, s2, &contacts, &mut states);
        for (k, ((c, _), got)) in items.iter().zip(states.iter()).enumerate() {
            let want = <Generated as Kernel<T, N, S>>::fixed(
                &c.nu,
                &s1.radius,
                s2,
                &c.states[0],
                &c.states[1],
            );
            assert!(same_state(&got, &want), "{}", what("fixed_shared", k));
        }
    }
}

/// The block kernels called directly at every lane width `W` (1, 2, 4, 8; on the default
/// target) against the scalar kernels: `free` with per-contact parameters and
/// `fixed_shared`, the two parameter modes.
fn check_widths<T, const N: usize, const S: usize>(items: &[Item<T, N, S>])
where
    T: Scalar + Send + Sync,
    for<'a> &'a T: RefArith<T>,
    Generated: BatchKernel<T, N, S> + Kernel<T, N, S>,
{
    let Some((_, [s1, s2])) = items.first() else {
        return;
    };
    let free_batch: FreeBatch<T, N, S> = items.iter().cloned().collect();
    let contacts: ContactBatch<T, N, S> = items.iter().map(|(c, _)| c.clone()).collect();
    let (mut pairs, mut states) = (PairBatch::new(), StateBatch::new());
    // Sized (and filled) by the default exec, then overwritten at each width.
    Exec::auto().serial().free(&free_batch, &mut pairs);
    Exec::auto()
        .serial()
        .fixed_shared(&s1.radius, s2, &contacts, &mut states);
    for w in [1, 2, 4, 8] {
        let run_free = match w {
            1 => <Generated as BatchKernel<T, N, S>>::free_blocks::<1>,
            2 => <Generated as BatchKernel<T, N, S>>::free_blocks::<2>,
            4 => <Generated as BatchKernel<T, N, S>>::free_blocks::<4>,
            _ => <Generated as BatchKernel<T, N, S>>::free_blocks::<8>,
        };
        let run_fixed = match w {
            1 => <Generated as BatchKernel<T, N, S>>::fixed_shared_blocks::<1>,
            2 => <Generated as BatchKernel<T, N, S>>::fixed_shared_blocks::<2>,
            4 => <Generated as BatchKernel<T, N, S>>::fixed_shared_blocks::<4>,
            _ => <Generated as BatchKernel<T, N, S>>::fixed_shared_blocks::<8>,
        };
        // Outputs cleared to zeros first, so that a lane the width skipped would show.
        for block in pairs.blocks_mut() {
            *block = Lanewise::splat(&[BodyState::zero(), BodyState::zero()]);
        }
        for block in states.blocks_mut() {
            *block = StateLanes::splat(&BodyState::zero());
        }
        run_free(free_batch.blocks(), pairs.blocks_mut());
        run_fixed(&s1.radius, s2, contacts.blocks(), states.blocks_mut());
        for (k, ((c, [b1, b2]), (got, got_fixed))) in items
            .iter()
            .zip(pairs.iter().zip(states.iter()))
            .enumerate()
        {
            let want =
                <Generated as Kernel<T, N, S>>::free(&c.nu, b1, b2, &c.states[0], &c.states[1]);
            assert!(
                same_state(&got[0], &want[0]) && same_state(&got[1], &want[1]),
                "{} n = {N}, free, W = {w}, contact {k}",
                T::NAME
            );
            let want = <Generated as Kernel<T, N, S>>::fixed(
                &c.nu,
                &s1.radius,
                s2,
                &c.states[0],
                &c.states[1],
            );
            assert!(
                same_state(&got_fixed, &want),
                "{} n = {N}, fixed_shared, W = {w}, contact {k}",
                T::NAME
            );
        }
    }
}

/// An empty batch gives empty outputs (and an output that held results is emptied).
fn check_empty<T, const N: usize, const S: usize>(
    free_batch: &FreeBatch<T, N, S>,
    fixed_batch: &FixedBatch<T, N, S>,
    contacts: &ContactBatch<T, N, S>,
) where
    T: Scalar + Send + Sync,
    for<'a> &'a T: RefArith<T>,
    Generated: BatchKernel<T, N, S>,
{
    let ball = Ball::immovable(N, T::one());
    for exec in execs() {
        let mut pairs: PairBatch<T, N, S> =
            std::iter::once([BodyState::zero(), BodyState::zero()]).collect();
        exec.free(free_batch, &mut pairs);
        assert!(pairs.is_empty() && pairs.blocks().is_empty());
        exec.free_shared([&ball, &ball], contacts, &mut pairs);
        assert!(pairs.is_empty());
        let mut states: StateBatch<T, N, S> = std::iter::once(BodyState::zero()).collect();
        exec.fixed(fixed_batch, &mut states);
        assert!(states.is_empty() && states.blocks().is_empty());
        exec.fixed_shared(&ball.radius, &ball, contacts, &mut states);
        assert!(states.is_empty());
    }
}

macro_rules! per_dim {
    ($(($name:ident $n:literal $s:literal))*) => {$(
        mod $name {
            use super::*;

            #[test]
            fn f64_bit_for_bit() {
                for (i, len) in LENGTHS.into_iter().enumerate() {
                    check::<f64, $n, $s>(&sample(0xb17 ^ (100 * $n + i as u64), len, float));
                }
            }

            #[test]
            fn f32_bit_for_bit() {
                for (i, len) in LENGTHS.into_iter().enumerate() {
                    check::<f32, $n, $s>(&sample(0xf32 ^ (100 * $n + i as u64), len, float));
                }
            }

            #[test]
            fn every_lane_width_bit_for_bit() {
                check_widths::<f64, $n, $s>(&sample(0x3d ^ $n, 37, float));
                check_widths::<f32, $n, $s>(&sample(0x3e ^ $n, 37, float));
            }

            #[test]
            fn exact() {
                check::<Exact, $n, $s>(&sample(0xe ^ $n, 11, rational));
            }
        }
    )*};
}

for_each_dim!(per_dim);

fn to_exact(x: f64) -> Exact {
    Exact::from_float(x).expect("finite")
}

fn exact_state<const N: usize, const S: usize>(s: &BodyState<f64, N, S>) -> BodyState<Exact, N, S> {
    BodyState {
        spin: s.spin.map(to_exact),
        velocity: s.velocity.map(to_exact),
    }
}

/// A body's state error against the exact state, relative, in the body's energy norm
/// `|u|^2 + g R^2 sum U_ij^2` (the mass cancels), in eps.
fn normwise_eps<const N: usize, const S: usize>(
    ball: &Ball<f64>,
    got: &BodyState<f64, N, S>,
    exact: &BodyState<Exact, N, S>,
) -> f64 {
    let weight = to_exact(ball.gamma2) * to_exact(ball.radius) * to_exact(ball.radius);
    let norm2 = |d: &dyn Fn(usize, bool) -> Exact| {
        let spin = (0..S).map(|k| d(k, true) * d(k, true)).sum::<Exact>();
        let velocity = (0..N).map(|k| d(k, false) * d(k, false)).sum::<Exact>();
        (velocity + &weight * spin).to_f64()
    };
    let pick = |s: &BodyState<Exact, N, S>, k: usize, spin: bool| {
        if spin {
            s.spin[k].clone()
        } else {
            s.velocity[k].clone()
        }
    };
    let got = exact_state(got);
    let error = norm2(&|k, spin| pick(&got, k, spin) - pick(exact, k, spin));
    let size = norm2(&|k, spin| pick(exact, k, spin));
    (error / size).sqrt() / f64::EPSILON
}

/// `collide` does not run `free` for an immovable body: it runs `fixed` (with the bodies
/// swapped and `nu` negated when body 2 is immovable). The batch `free` with `inv_mass = 0`
/// is the same rational map (`dN_exact`), rounded differently. On these contacts its results
/// differ from `collide_unchecked`'s in some bits (as docs/batch.md states); both are within
/// 16 eps of the exact result in the moving body's energy norm (the report's bound for
/// typical inputs, which these are; docs/accuracy.md), and both return the immovable body
/// unchanged.
fn immovable_in_free_is_collide_up_to_rounding<const N: usize, const S: usize>()
where
    Generated: BatchKernel<f64, N, S> + Kernel<f64, N, S> + Kernel<Exact, N, S>,
{
    let items: Vec<Item<f64, N, S>> = sample(0x1330 ^ N as u64, 80, float)
        .into_iter()
        .enumerate()
        .filter(|(k, _)| matches!(k % 4, 1 | 2))
        .map(|(_, item)| item)
        .collect();
    let batch: FreeBatch<f64, N, S> = items.iter().cloned().collect();
    let mut out = PairBatch::new();
    Exec::auto().free(&batch, &mut out);
    let mut differ = 0;
    for (k, ((c, [b1, b2]), got)) in items.iter().zip(out.iter()).enumerate() {
        let scalar = collide_unchecked(&c.nu, [b1, b2], [&c.states[0], &c.states[1]]);
        let nu = c.nu.map(to_exact);
        let balls = [b1, b2].map(|b| Ball {
            inv_mass: to_exact(b.inv_mass),
            radius: to_exact(b.radius),
            gamma2: to_exact(b.gamma2),
        });
        let states = [exact_state(&c.states[0]), exact_state(&c.states[1])];
        let exact = collide_unchecked(&nu, [&balls[0], &balls[1]], [&states[0], &states[1]]);
        for (body, ball) in [b1, b2].into_iter().enumerate() {
            if ball.inv_mass == 0.0 {
                assert!(got[body] == c.states[body] && scalar[body] == c.states[body]);
                continue;
            }
            let (e_batch, e_scalar) = (
                normwise_eps(ball, &got[body], &exact[body]),
                normwise_eps(ball, &scalar[body], &exact[body]),
            );
            assert!(
                e_batch <= 16.0 && e_scalar <= 16.0,
                "n = {N}, contact {k}: free {e_batch:.2} eps, collide {e_scalar:.2} eps"
            );
        }
        differ +=
            usize::from(!(same_state(&got[0], &scalar[0]) && same_state(&got[1], &scalar[1])));
    }
    assert!(
        differ > 0,
        "n = {N}: free with inv_mass = 0 matched collide on every contact"
    );
}

#[test]
fn free_with_an_immovable_body_is_collide_up_to_rounding() {
    immovable_in_free_is_collide_up_to_rounding::<2, 1>();
    immovable_in_free_is_collide_up_to_rounding::<3, 3>();
    immovable_in_free_is_collide_up_to_rounding::<4, 6>();
    immovable_in_free_is_collide_up_to_rounding::<5, 10>();
    immovable_in_free_is_collide_up_to_rounding::<6, 15>();
}

#[test]
fn batches_round_trip_the_per_collision_types() {
    for len in LENGTHS {
        let items = sample::<f64, 3, 3>(7 + len as u64, len, float);
        let batch: FreeBatch<f64, 3, 3> = items.iter().cloned().collect();
        assert_eq!(batch.len(), len);
        assert_eq!(batch.blocks().len(), len.div_ceil(LANES));
        assert_eq!(batch.iter().collect::<Vec<_>>(), items);
        for (i, item) in items.iter().enumerate() {
            assert_eq!(batch.get(i).as_ref(), Some(item));
        }
        assert_eq!(batch.get(len), None);
        // Cleared and refilled (a reused scratch batch), it is the fresh batch again.
        let mut refilled = batch.clone();
        refilled.clear();
        assert!(refilled.is_empty() && refilled.blocks().is_empty());
        refilled.extend(items.iter().cloned());
        assert_eq!(refilled, batch);
        // Padding lanes repeat the last block's first contact.
        if let Some(last) = batch.blocks().last() {
            let first = &items[(len - 1) / LANES * LANES];
            for l in Lane::all().skip((len - 1) % LANES + 1) {
                assert_eq!(&last.lane(l), first);
            }
        }
    }
}

#[test]
fn lanes_are_checked_and_isas_reported_as_available() {
    assert_eq!(Lane::new(LANES), None);
    assert_eq!(Lane::new(LANES - 1).map(Lane::index), Some(LANES - 1));
    assert_eq!(Lane::all().count(), LANES);
    for isa in Isa::ALL {
        match Exec::auto().with_isa(isa) {
            Ok(exec) => assert!(isa.is_available() && exec.isa() == isa),
            Err(e) => {
                assert!(!isa.is_available());
                assert_eq!(e, BatchError::UnavailableIsa(isa));
            }
        }
    }
    assert!(Isa::Baseline.is_available());
    assert_eq!(Exec::auto().isa(), Isa::detect());
}

#[test]
fn blocks_are_cache_line_aligned_without_padding_in_f64() {
    // Alignment: an `f64` lane array is one cache line, so a vector load of it touches one.
    assert_eq!(std::mem::align_of::<FreeLanes<f64, 6, 15>>(), BLOCK_ALIGN);
    assert_eq!(std::mem::align_of::<FixedLanes<f32, 2, 1>>(), BLOCK_ALIGN);
    assert_eq!(std::mem::align_of::<ContactLanes<f64, 3, 3>>(), BLOCK_ALIGN);
    assert_eq!(std::mem::align_of::<StateLanes<f64, 5, 10>>(), BLOCK_ALIGN);
    // No padding in f64: every block is its lane arrays, 64 bytes each.
    let lane = std::mem::size_of::<Lanes<f64>>();
    assert_eq!(std::mem::size_of::<StateLanes<f64, 2, 1>>(), 3 * lane);
    assert_eq!(
        std::mem::size_of::<FreeLanes<f64, 6, 15>>(),
        (6 + 2 * 21 + 6) * lane
    );
    assert_eq!(
        std::mem::size_of::<FixedLanes<f64, 4, 6>>(),
        (4 + 2 * 10 + 4) * lane
    );
    // And the blocks of a batch start on a cache line, whatever `malloc` would give.
    for len in [1, 9, 1000] {
        let batch: FreeBatch<f64, 3, 3> =
            sample::<f64, 3, 3>(len as u64, len, |r, lo, hi| r.random_range(lo..hi))
                .into_iter()
                .collect();
        assert_eq!(batch.blocks().as_ptr() as usize % BLOCK_ALIGN, 0);
    }
}
