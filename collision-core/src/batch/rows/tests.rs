//! The row-major gather and scatter against the per-collision types, and every
//! instruction-set level's gather, scatter and `Exec::free_rows` against the baseline's and
//! against `fill_from_rows`, `Exec::free`, `write_rows`, bit for bit.

use super::*;
use crate::batch::lanes::{Contact, StateLanes};
use crate::batch::{Batch, Exec, FreeBatch, Isa, PairBatch};
use crate::{skew_pairs, Ball, BodyState, Generated, Kernel};
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Random row-major arrays of `len` contacts (not physical: any numbers are moved
/// alike); `shared[b]`: body `b`'s parameters one value for all.
pub(super) struct Arrays {
    pub(super) nu: Vec<f64>,
    pub(super) spin: [Vec<f64>; 2],
    pub(super) velocity: [Vec<f64>; 2],
    pub(super) params: [[Vec<f64>; 3]; 2],
}

pub(super) fn arrays<const N: usize>(seed: u64, len: usize, shared: [bool; 2]) -> Arrays {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut v = |k: usize| -> Vec<f64> { (0..k).map(|_| rng.random_range(-1.0..1.0)).collect() };
    let nu = v(len * N);
    let spin = [v(len * N * N), v(len * N * N)];
    let velocity = [v(len * N), v(len * N)];
    let params = shared.map(|s| {
        let k = if s { 1 } else { len };
        [v(k), v(k), v(k)]
    });
    Arrays {
        nu,
        spin,
        velocity,
        params,
    }
}

pub(super) fn rows(a: &Arrays) -> FreeRows<'_, f64> {
    FreeRows {
        nu: &a.nu,
        states: [0, 1].map(|b| StateRows {
            spin: &a.spin[b],
            velocity: &a.velocity[b],
        }),
        balls: [0, 1].map(|b| BallRows {
            inv_mass: &a.params[b][0],
            radius: &a.params[b][1],
            gamma2: &a.params[b][2],
        }),
    }
}

/// Contact `i` built by hand from the arrays, field by field.
pub(super) fn by_hand<const N: usize, const S: usize>(
    a: &Arrays,
    i: usize,
) -> (Contact<f64, N, S>, [Ball<f64>; 2]) {
    let state = |b: usize| BodyState {
        spin: {
            let mut s = [0.0; S];
            for (x, (r, c)) in s.iter_mut().zip(skew_pairs(N)) {
                *x = a.spin[b][i * N * N + r * N + c];
            }
            s
        },
        velocity: std::array::from_fn(|k| a.velocity[b][i * N + k]),
    };
    let ball = |b: usize| {
        let p = |k: usize| {
            let x = &a.params[b][k];
            if x.len() == 1 {
                x[0]
            } else {
                x[i]
            }
        };
        Ball {
            inv_mass: p(0),
            radius: p(1),
            gamma2: p(2),
        }
    };
    let nu = std::array::from_fn(|k| a.nu[i * N + k]);
    (
        Contact {
            nu,
            states: [state(0), state(1)],
        },
        [ball(0), ball(1)],
    )
}

fn fill_is_push<const N: usize, const S: usize>() {
    for (len, range, shared) in [
        (37, 0..37, [false, false]),
        (37, 5..22, [true, false]),
        (9, 3..4, [false, true]),
        (16, 8..16, [true, true]),
        (1, 0..1, [true, true]),
        (5, 2..2, [false, false]),
    ] {
        let a = arrays::<N>(len as u64 * 7 + N as u64, len, shared);
        let want: FreeBatch<f64, N, S> = range.clone().map(|i| by_hand(&a, i)).collect();
        // A fresh batch, and one reused after holding more and fewer contacts.
        let mut fresh = FreeBatch::new();
        fresh.fill_from_rows(&rows(&a), range.clone());
        assert_eq!(fresh, want, "n = {N}, {len} rows, {range:?}");
        let mut reused = FreeBatch::new();
        let big = arrays::<N>(99, 50, [false, false]);
        reused.fill_from_rows(&rows(&big), 0..50);
        reused.fill_from_rows(&rows(&a), range.clone());
        assert_eq!(reused, want, "n = {N}, reused, {range:?}");
        let small = arrays::<N>(98, 3, [false, false]);
        reused.fill_from_rows(&rows(&small), 0..3);
        reused.fill_from_rows(&rows(&a), range.clone());
        assert_eq!(reused, want, "n = {N}, reused after 3, {range:?}");
    }
}

#[test]
fn filling_from_rows_builds_the_batch_push_builds() {
    fill_is_push::<2, 1>();
    fill_is_push::<3, 3>();
    fill_is_push::<4, 6>();
    fill_is_push::<5, 10>();
    fill_is_push::<6, 15>();
}

fn write_is_get<const N: usize, const S: usize>() {
    for len in [0, 1, 7, 8, 9, 37] {
        let mut a = arrays::<N>(len as u64 + 3, len, [false, false]);
        if len > 0 {
            // A zero entry (0,1): both sides come back +0.
            a.spin[0][1] = 0.0;
        }
        let pairs: Batch<[StateLanes<f64, N, S>; 2]> =
            (0..len).map(|i| by_hand::<N, S>(&a, i).0.states).collect();
        // Start from NaN so that an entry left unwritten shows.
        let mut spin = [vec![f64::NAN; len * N * N], vec![f64::NAN; len * N * N]];
        let mut velocity = [vec![f64::NAN; len * N], vec![f64::NAN; len * N]];
        let [s1, s2] = &mut spin;
        let [v1, v2] = &mut velocity;
        pairs.write_rows([
            StateRowsMut {
                spin: s1,
                velocity: v1,
            },
            StateRowsMut {
                spin: s2,
                velocity: v2,
            },
        ]);
        for i in 0..len {
            let got = pairs.get(i).expect("i < len");
            for b in 0..2 {
                let mut m = [[0.0f64; N]; N];
                for (&x, (r, c)) in got[b].spin.iter().zip(skew_pairs(N)) {
                    (m[r][c], m[c][r]) = (x, 0.0 - x);
                }
                for r in 0..N {
                    for c in 0..N {
                        let x = spin[b][i * N * N + r * N + c];
                        // Same bits: +0 on the diagonal and for a zero entry.
                        assert_eq!(x.to_bits(), m[r][c].to_bits(), "n = {N} ({r},{c})");
                    }
                }
                assert_eq!(m[0][1].to_bits(), got[b].spin[0].to_bits());
                assert_eq!(velocity[b][i * N..(i + 1) * N], got[b].velocity);
            }
        }
    }
}

#[test]
fn writing_rows_gives_what_get_returns_as_full_skew_matrices() {
    write_is_get::<2, 1>();
    write_is_get::<3, 3>();
    write_is_get::<4, 6>();
    write_is_get::<5, 10>();
    write_is_get::<6, 15>();
}

#[test]
#[should_panic(expected = "velocity: n per contact")]
fn rows_of_the_wrong_length_panic() {
    let mut a = arrays::<3>(1, 4, [false, false]);
    a.velocity[1].pop();
    FreeBatch::<f64, 3, 3>::new().fill_from_rows(&rows(&a), 0..4);
}

/// `a` with every parameter made positive (`|x| + 0.1`), so that the kernel's results are
/// finite numbers (NaN payloads are not compared bit for bit across instruction sets).
pub(super) fn physical(mut a: Arrays) -> Arrays {
    for p in a.params.iter_mut().flatten().flatten() {
        *p = p.abs() + 0.1;
    }
    a
}

/// Row-major outputs of `len` contacts, every entry NaN, so that one left unwritten shows.
pub(super) fn nan_rows<const N: usize>(len: usize) -> [[Vec<f64>; 2]; 2] {
    [0, 1].map(|_| [vec![f64::NAN; len * N * N], vec![f64::NAN; len * N]])
}

pub(super) fn rows_mut(o: &mut [[Vec<f64>; 2]; 2]) -> [StateRowsMut<'_, f64>; 2] {
    let [[s1, v1], [s2, v2]] = o;
    [
        StateRowsMut {
            spin: s1,
            velocity: v1,
        },
        StateRowsMut {
            spin: s2,
            velocity: v2,
        },
    ]
}

pub(super) fn bits(o: &[[Vec<f64>; 2]; 2]) -> Vec<u64> {
    o.iter().flatten().flatten().map(|x| x.to_bits()).collect()
}

/// Every level this CPU runs gathers the batch and scatters the rows the baseline does.
fn levels_gather_and_scatter_alike<const N: usize, const S: usize>() {
    for (len, shared) in [
        (37, [false, true]),
        (64, [true, false]),
        (5, [false, false]),
    ] {
        let a = arrays::<N>(len as u64 + 11, len, shared);
        let mut want = FreeBatch::<f64, N, S>::new();
        want.fill_from_rows_on(Isa::Baseline, &rows(&a), 0..len);
        let pairs: PairBatch<f64, N, S> =
            (0..len).map(|i| by_hand::<N, S>(&a, i).0.states).collect();
        let mut want_rows = nan_rows::<N>(len);
        pairs.write_rows_on(Isa::Baseline, rows_mut(&mut want_rows));
        for isa in Isa::available() {
            let mut got = FreeBatch::new();
            got.fill_from_rows_on(isa, &rows(&a), 0..len);
            assert_eq!(got, want, "n = {N}, {isa}, {len} rows: gather");
            let mut got_rows = nan_rows::<N>(len);
            pairs.write_rows_on(isa, rows_mut(&mut got_rows));
            assert_eq!(bits(&got_rows), bits(&want_rows), "n = {N}, {isa}: scatter");
        }
    }
}

#[test]
fn every_level_gathers_and_scatters_as_the_baseline() {
    levels_gather_and_scatter_alike::<2, 1>();
    levels_gather_and_scatter_alike::<3, 3>();
    levels_gather_and_scatter_alike::<4, 6>();
    levels_gather_and_scatter_alike::<5, 10>();
    levels_gather_and_scatter_alike::<6, 15>();
}

/// The `Exec`s the row paths are tested with at `isa`: serial and, with feature
/// `parallel`, split from the first contact on; each with its passes in address order and
/// from the last rows to the first (`Exec::last_rows_first`, for new outputs), with its
/// results streamed (`Exec::streamed_results`), and with both (large new outputs).
pub(super) fn row_execs(isa: Isa) -> Vec<Exec> {
    let serial = Exec::auto().with_isa(isa).expect("available").serial();
    let backward = serial.last_rows_first();
    let streamed = serial.streamed_results();
    let both = backward.streamed_results();
    #[cfg_attr(not(feature = "parallel"), allow(unused_mut))]
    let mut execs = vec![serial, backward, streamed, both];
    #[cfg(feature = "parallel")]
    execs.extend([
        serial.parallel_from(0),
        backward.parallel_from(0),
        streamed.parallel_from(0),
        both.parallel_from(0),
    ]);
    execs
}

/// `Exec::streamed_results` writes the bits of ordinary stores into outputs at a multiple
/// of 16 bytes (the non-temporal stores, on AVX-512 at n = 2 and 3) and into outputs that
/// are not (the ordinary stores then), at every level, with its passes in address order and
/// from the last rows to the first; lengths around a block and a pass.
fn streamed_rows_are_the_same_bits<const N: usize, const S: usize>()
where
    Generated: crate::batch::BatchKernel<f64, N, S>,
{
    for len in [8, 13, 1100, 5000] {
        let a = physical(arrays::<N>(len as u64 + 3 * N as u64, len, [false, true]));
        let mut want = nan_rows::<N>(len);
        Exec::auto()
            .serial()
            .free_rows::<f64, N, S>(&rows(&a), rows_mut(&mut want));
        for isa in Isa::available() {
            let exec = Exec::auto().with_isa(isa).expect("available").serial();
            let streamed = [exec, exec.last_rows_first()].map(Exec::streamed_results);
            for (exec, offset) in streamed.into_iter().flat_map(|e| [(e, 0), (e, 1)]) {
                // Each array one value longer, the rows from `offset` on: at a multiple of
                // 16 bytes (glibc's `malloc` gives 16) for 0, not for 1.
                let mut got =
                    [0, 1].map(|_| [vec![f64::NAN; len * N * N + 1], vec![f64::NAN; len * N + 1]]);
                let aligned = got
                    .iter()
                    .flatten()
                    .all(|x| (x[offset..].as_ptr() as usize) % 16 == 0);
                assert_eq!(
                    aligned,
                    offset == 0,
                    "the test's premise: malloc's alignment"
                );
                let [[s1, v1], [s2, v2]] = &mut got;
                let out = [
                    StateRowsMut {
                        spin: &mut s1[offset..offset + len * N * N],
                        velocity: &mut v1[offset..offset + len * N],
                    },
                    StateRowsMut {
                        spin: &mut s2[offset..offset + len * N * N],
                        velocity: &mut v2[offset..offset + len * N],
                    },
                ];
                exec.free_rows::<f64, N, S>(&rows(&a), out);
                let got: Vec<u64> = got
                    .iter()
                    .flatten()
                    .flat_map(|x| {
                        let rows = x.len() - 1;
                        x[offset..offset + rows].iter().map(|v| v.to_bits())
                    })
                    .collect();
                assert_eq!(
                    got,
                    bits(&want),
                    "n = {N}, {isa}, {len} rows, offset {offset}, backward {}",
                    exec.is_backward()
                );
            }
        }
    }
}

#[test]
fn streamed_results_are_the_same_bits_aligned_or_not() {
    streamed_rows_are_the_same_bits::<2, 1>();
    streamed_rows_are_the_same_bits::<3, 3>();
    streamed_rows_are_the_same_bits::<4, 6>();
}

/// `Exec::free_rows` at every level (serial, and split from the first contact on with
/// feature `parallel`; passes in address order and from the last rows to the first,
/// `Exec::last_rows_first`) against the scalar kernel `free` on each row and against
/// `fill_from_rows`, `Exec::free`, `write_rows`, bit for bit; lengths around a block, a
/// pass and a run of a split.
fn free_rows_is_the_scalar_kernel<const N: usize, const S: usize>()
where
    Generated: crate::batch::BatchKernel<f64, N, S> + Kernel<f64, N, S>,
{
    // Passes in cache and out of it (`ROWS_IN_CACHE_BYTES`): 1100 contacts are 0.3 MB
    // (n = 2) to 1.6 MB (n = 6) of rows, 5000 contacts 1.3 to 7.2 MB.
    let pass = super::exec::pass_rows::<
        crate::batch::FreeLanes<f64, N, S>,
        [StateLanes<f64, N, S>; 2],
    >(super::ROWS_PASS_BYTES);
    for (len, shared) in [
        (0, [false, false]),
        (1, [true, true]),
        (7, [false, false]),
        (9, [true, false]),
        (pass + 3, [false, true]),
        (3 * pass, [false, false]),
        (1100, [false, false]),
        (5000, [true, false]),
    ] {
        let a = physical(arrays::<N>(len as u64 * 5 + N as u64, len, shared));
        // The scalar kernel on each row, as `write_rows` writes a state.
        let mut want = nan_rows::<N>(len);
        let scalar: PairBatch<f64, N, S> = (0..len)
            .map(|i| {
                let (c, [b1, b2]) = by_hand::<N, S>(&a, i);
                <Generated as Kernel<f64, N, S>>::free(&c.nu, &b1, &b2, &c.states[0], &c.states[1])
            })
            .collect();
        scalar.write_rows_on(Isa::Baseline, rows_mut(&mut want));
        // The three steps, as a caller without `free_rows` runs them.
        let mut batch = FreeBatch::<f64, N, S>::new();
        batch.fill_from_rows(&rows(&a), 0..len);
        let mut pairs = PairBatch::new();
        Exec::auto().serial().free(&batch, &mut pairs);
        let mut steps = nan_rows::<N>(len);
        pairs.write_rows(rows_mut(&mut steps));
        assert_eq!(bits(&steps), bits(&want), "n = {N}, {len} rows: steps");
        for isa in Isa::available() {
            for exec in row_execs(isa) {
                let mut got = nan_rows::<N>(len);
                exec.free_rows::<f64, N, S>(&rows(&a), rows_mut(&mut got));
                assert_eq!(
                    bits(&got),
                    bits(&want),
                    "n = {N}, {isa}, {exec:?}, {len} rows"
                );
            }
        }
    }
}

#[test]
fn free_rows_gives_the_scalar_kernels_bits_at_every_level() {
    free_rows_is_the_scalar_kernel::<2, 1>();
    free_rows_is_the_scalar_kernel::<3, 3>();
    free_rows_is_the_scalar_kernel::<4, 6>();
    free_rows_is_the_scalar_kernel::<5, 10>();
    free_rows_is_the_scalar_kernel::<6, 15>();
}

#[test]
fn slices_of_rows_keep_shared_parameters() {
    let a = arrays::<3>(7, 20, [true, false]);
    let r = rows(&a);
    let part = r.slice::<3>(4..9);
    assert_eq!(part.len::<3>(), 5);
    assert_eq!(part.nu, &a.nu[12..27]);
    assert_eq!(part.balls[0].radius.len(), 1);
    assert_eq!(part.balls[1].radius, &a.params[1][1][4..9]);
    assert_eq!(part.states[1].spin, &a.spin[1][36..81]);
}

/// Row-major arrays of any bits: random words and, among them, `+0`, `-0`, infinities,
/// quiet and signalling NaNs with payloads of either sign, subnormals.
fn any_bits<const N: usize>(seed: u64, len: usize) -> Arrays {
    let mut a = arrays::<N>(seed, len, [false, false]);
    let special = [
        0.0,
        -0.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::from_bits(0x7ff8_0000_dead_beef),
        f64::from_bits(0xfff0_0000_0000_0001),
        f64::MIN_POSITIVE / 3.0,
        -f64::MIN_POSITIVE / 7.0,
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let fields = a.spin.iter_mut().chain(&mut a.velocity);
    for x in a.nu.iter_mut().chain(fields.flatten()) {
        *x = if rng.random_bool(0.3) {
            special[rng.random_range(0..special.len())]
        } else {
            f64::from_bits(rng.random())
        };
    }
    for p in a.params.iter_mut().flatten().flatten() {
        *p = f64::from_bits(rng.random());
    }
    a
}

/// The words of `f64` blocks (lane arrays only: no padding in `f64`,
/// `blocks_are_cache_line_aligned_without_padding_in_f64`), so that NaNs compare by bits.
fn block_words<B>(blocks: &[B]) -> Vec<u64> {
    let words = std::mem::size_of_val(blocks) / 8;
    // SAFETY: the blocks are `f64` lane arrays without padding, 64-byte aligned: `words`
    // initialised `u64`s.
    unsafe { std::slice::from_raw_parts(blocks.as_ptr().cast::<u64>(), words) }.to_vec()
}

/// Every level (the AVX-512 permutes of `avx512.rs` where this CPU has them) gathers and
/// scatters any bits as the baseline does: every start of a range within a block, every
/// tail of 0 to 7 rows after whole blocks; a scattered `0 - x` (below the diagonal) of
/// `-0`, NaNs and infinities included.
fn levels_move_any_bits<const N: usize, const S: usize>() {
    let a = any_bits::<N>(N as u64, 8 * 5 + 7 + 3);
    for start in 0..3 {
        for len in (0..=23).chain([40, 47]) {
            let range = start..start + len;
            let mut want = FreeBatch::<f64, N, S>::new();
            want.fill_from_rows_on(Isa::Baseline, &rows(&a), range.clone());
            let pairs: PairBatch<f64, N, S> = (range.clone())
                .map(|i| by_hand::<N, S>(&a, i).0.states)
                .collect();
            let mut want_rows = nan_rows::<N>(len);
            pairs.write_rows_on(Isa::Baseline, rows_mut(&mut want_rows));
            for isa in Isa::available() {
                let mut got = FreeBatch::<f64, N, S>::new();
                got.fill_from_rows_on(isa, &rows(&a), range.clone());
                let at = format!("n = {N}, {isa}, rows {range:?}");
                assert_eq!(got.len(), want.len(), "{at}");
                assert_eq!(
                    block_words(got.blocks()),
                    block_words(want.blocks()),
                    "{at}"
                );
                let mut got_rows = nan_rows::<N>(len);
                pairs.write_rows_on(isa, rows_mut(&mut got_rows));
                assert_eq!(bits(&got_rows), bits(&want_rows), "{at}: scatter");
            }
        }
    }
}

#[test]
fn every_level_moves_any_bits_as_the_baseline() {
    levels_move_any_bits::<2, 1>();
    levels_move_any_bits::<3, 3>();
    levels_move_any_bits::<4, 6>();
    levels_move_any_bits::<5, 10>();
    levels_move_any_bits::<6, 15>();
}
