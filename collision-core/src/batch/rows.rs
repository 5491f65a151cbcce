//! Row-major arrays in and out of the blocked layout: contacts gathered from the arrays of
//! NumPy or C (one contact per row: `nu` `(len, n)`, angular velocities `(len, n, n)`,
//! velocities `(len, n)`, ball parameters `(len,)` or one shared value) straight into the
//! lane arrays of a [`FreeBatch`], and results scattered from a [`PairBatch`] straight into
//! such arrays, with no per-contact [`Contact`](super::Contact) or
//! [`BodyState`](crate::BodyState) in between.
//!
//! The result is the same batch as [`Batch::push`](super::Batch::push) of each row's item would build (padding
//! lanes included: copies of their block's first contact), and the rows written are what
//! [`Batch::get`](super::Batch::get) returns, each compact state as its full skew matrix (`+0` on the diagonal,
//! `U_cr = 0 - U_rc`: a zero entry is `+0` on both sides).

use super::lanes::{BallLanes, Contact, ContactLanes, FreeLanes, Lanewise, StateLanes, LANES};
use super::{FreeBatch, PairBatch};
use crate::{skew_pairs, Ball, BodyState, Scalar};
use std::ops::Range;

/// One body's states, one contact per row: contact `i`'s angular velocity `U` is the full
/// `n x n` matrix `spin[i n^2 .. (i + 1) n^2]`, row-major (entry `U_rc` at `r n + c`), and
/// its velocity `u` is `velocity[i n .. (i + 1) n]`. Gathering reads the entries above the
/// diagonal, `U_rc` with `r < c` (the compact state); it does not check that `U` is skew.
#[derive(Clone, Copy, Debug)]
pub struct StateRows<'a, T> {
    /// The angular velocities, `n^2` entries per contact.
    pub spin: &'a [T],
    /// The velocities, `n` entries per contact.
    pub velocity: &'a [T],
}

/// [`StateRows`] to write into.
#[derive(Debug)]
pub struct StateRowsMut<'a, T> {
    /// The angular velocities, `n^2` entries per contact.
    pub spin: &'a mut [T],
    /// The velocities, `n` entries per contact.
    pub velocity: &'a mut [T],
}

/// One body's parameters ([`Ball`](crate::Ball)'s fields): each slice holds one value per
/// contact, or a single value shared by every contact.
#[derive(Clone, Copy, Debug)]
pub struct BallRows<'a, T> {
    /// Inverse masses `w = 1/m`.
    pub inv_mass: &'a [T],
    /// Radii `R`.
    pub radius: &'a [T],
    /// `gamma^2 = 2 lambda / R^2`.
    pub gamma2: &'a [T],
}

/// Contacts of two balls with their own parameters, one per row: what
/// [`FreeBatch::fill_from_rows`] reads. The number of contacts is `nu.len() / n`.
#[derive(Clone, Copy, Debug)]
pub struct FreeRows<'a, T> {
    /// The unit normals `nu` (from body 1's centre to body 2's), `n` entries per contact.
    pub nu: &'a [T],
    /// Body 1's and body 2's states.
    pub states: [StateRows<'a, T>; 2],
    /// Body 1's and body 2's parameters.
    pub balls: [BallRows<'a, T>; 2],
}

impl<T> FreeRows<'_, T> {
    /// The number of contacts, `nu.len() / n`, after checking every slice's length.
    ///
    /// # Panics
    /// If a length does not fit: `nu.len()` not a multiple of `n`, a state slice not `n^2`
    /// (angular velocity) or `n` (velocity) entries per contact, a parameter slice neither
    /// one entry per contact nor a single one.
    pub fn len<const N: usize>(&self) -> usize {
        assert_eq!(self.nu.len() % N, 0, "nu: {N} entries per contact");
        let len = self.nu.len() / N;
        for (b, (s, p)) in self.states.iter().zip(&self.balls).enumerate() {
            assert_eq!(s.spin.len(), len * N * N, "body {b}: spin: n^2 per contact");
            assert_eq!(
                s.velocity.len(),
                len * N,
                "body {b}: velocity: n per contact"
            );
            for x in [p.inv_mass, p.radius, p.gamma2] {
                assert!(x.len() == len || x.len() == 1, "body {b}: parameters");
            }
        }
        len
    }

    /// Whether there are no contacts.
    pub fn is_empty(&self) -> bool {
        self.nu.is_empty()
    }
}

/// Offsets `r n + c` of the compact entries `U_rc`, `r < c`, in the order of
/// [`BodyState::spin`](crate::BodyState::spin) ([`skew_pairs`]).
fn offsets<const N: usize, const S: usize>() -> [usize; S] {
    let mut out = [0; S];
    for (o, (r, c)) in out.iter_mut().zip(skew_pairs(N)) {
        *o = r * N + c;
    }
    out
}

/// Contact `i`'s row of a parameter slice (one shared value: `stride = 0`).
#[inline(always)]
fn at<T: Clone>(p: &[T], stride: usize, i: usize) -> T {
    p[i * stride].clone()
}

/// Gather one body's state of contact `i` into lane `l`.
#[inline(always)]
fn gather_state<T: Clone, const N: usize, const S: usize>(
    lanes: &mut StateLanes<T, N, S>,
    rows: &StateRows<'_, T>,
    offsets: &[usize; S],
    i: usize,
    l: usize,
) {
    let spin = &rows.spin[i * N * N..(i + 1) * N * N];
    for (lane, &o) in lanes.spin.iter_mut().zip(offsets) {
        lane[l] = spin[o].clone();
    }
    let velocity = &rows.velocity[i * N..(i + 1) * N];
    for (lane, x) in lanes.velocity.iter_mut().zip(velocity) {
        lane[l] = x.clone();
    }
}

/// Gather one body's parameters of contact `i` into lane `l`.
#[inline(always)]
fn gather_ball<T: Clone>(
    lanes: &mut BallLanes<T>,
    rows: &BallRows<'_, T>,
    strides: [usize; 3],
    i: usize,
    l: usize,
) {
    lanes.inv_mass[l] = at(rows.inv_mass, strides[0], i);
    lanes.radius[l] = at(rows.radius, strides[1], i);
    lanes.gamma2[l] = at(rows.gamma2, strides[2], i);
}

/// Scatter lane `l` of one body's states into contact `j` of `out`, as a full skew matrix.
#[inline(always)]
fn scatter_state<T: Scalar, const N: usize, const S: usize>(
    lanes: &StateLanes<T, N, S>,
    out: &mut StateRowsMut<'_, T>,
    pairs: &[(usize, usize); S],
    j: usize,
    l: usize,
) {
    let spin = &mut out.spin[j * N * N..(j + 1) * N * N];
    for r in 0..N {
        spin[r * N + r] = T::zero();
    }
    for (lane, &(r, c)) in lanes.spin.iter().zip(pairs) {
        let x = &lane[l];
        spin[r * N + c] = x.clone();
        spin[c * N + r] = T::zero() - x.clone();
    }
    let velocity = &mut out.velocity[j * N..(j + 1) * N];
    for (x, lane) in velocity.iter_mut().zip(&lanes.velocity) {
        *x = lane[l].clone();
    }
}

impl<T: Clone, const N: usize, const S: usize> FreeBatch<T, N, S> {
    /// Replace the batch's contacts by contacts `range` of `rows`, in order, reusing the
    /// blocks already allocated: the batch that [`Batch::push`](super::Batch::push) of each
    /// row's `(Contact, [Ball; 2])` would build (`Contact::states[b].spin` the entries
    /// `U_rc`, `r < c`, of body `b`'s matrix row), padding lanes included.
    ///
    /// # Panics
    /// If the lengths of `rows` do not fit ([`FreeRows::len`]) or `range` is not within
    /// `0..rows.len()`.
    pub fn fill_from_rows(&mut self, rows: &FreeRows<'_, T>, range: Range<usize>) {
        let total = rows.len::<N>();
        assert!(
            range.start <= range.end && range.end <= total,
            "range {range:?} of {total} contacts"
        );
        let len = range.len();
        if len == 0 {
            self.clear();
            return;
        }
        let offsets = offsets::<N, S>();
        let strides = rows
            .balls
            .each_ref()
            .map(|b| [b.inv_mass, b.radius, b.gamma2].map(|p| usize::from(p.len() != 1)));
        let first = range.start;
        let fill = |block: &mut FreeLanes<T, N, S>, b: usize| {
            let start = first + b * LANES;
            let count = (range.end - start).min(LANES);
            for l in 0..LANES {
                // Lanes past the end repeat the block's first contact, as `push` pads.
                let i = if l < count { start + l } else { start };
                let ContactLanes { nu, states } = &mut block.contact;
                for (lane, x) in nu.iter_mut().zip(&rows.nu[i * N..(i + 1) * N]) {
                    lane[l] = x.clone();
                }
                for k in 0..2 {
                    gather_state(&mut states[k], &rows.states[k], &offsets, i, l);
                    gather_ball(&mut block.balls[k], &rows.balls[k], strides[k], i, l);
                }
            }
        };
        // New blocks start as copies of contact `first` (every lane is overwritten below).
        self.resize_with(len, || FreeLanes::splat(&item(rows, first, &offsets)));
        for (b, block) in self.blocks_mut().iter_mut().enumerate() {
            fill(block, b);
        }
    }
}

/// Contact `i` of `rows` as a batch item.
fn item<T: Clone, const N: usize, const S: usize>(
    rows: &FreeRows<'_, T>,
    i: usize,
    offsets: &[usize; S],
) -> (Contact<T, N, S>, [Ball<T>; 2]) {
    let state = |s: &StateRows<'_, T>| BodyState {
        spin: offsets.map(|o| s.spin[i * N * N + o].clone()),
        velocity: std::array::from_fn(|k| s.velocity[i * N + k].clone()),
    };
    let ball = |b: &BallRows<'_, T>| {
        let p = |x: &[T]| x[if x.len() == 1 { 0 } else { i }].clone();
        Ball {
            inv_mass: p(b.inv_mass),
            radius: p(b.radius),
            gamma2: p(b.gamma2),
        }
    };
    (
        Contact {
            nu: std::array::from_fn(|k| rows.nu[i * N + k].clone()),
            states: [state(&rows.states[0]), state(&rows.states[1])],
        },
        [ball(&rows.balls[0]), ball(&rows.balls[1])],
    )
}

impl<T: Scalar, const N: usize, const S: usize> PairBatch<T, N, S> {
    /// Write every item `[body 1, body 2]` of the batch into contact rows `0..len` of `out`
    /// (body `b` into `out[b]`): the compact entries as the full skew matrix
    /// (`U_rr = +0`, `U_rc` for `r < c`, `U_cr = 0 - U_rc`) and the velocity, as
    /// [`Batch::get`](super::Batch::get) returns them.
    ///
    /// # Panics
    /// If `out[b]` does not hold exactly `len` contacts (`n^2` and `n` entries each).
    pub fn write_rows(&self, out: [StateRowsMut<'_, T>; 2]) {
        let len = self.len();
        let pairs: [(usize, usize); S] = {
            let mut p = [(0, 0); S];
            for (x, rc) in p.iter_mut().zip(skew_pairs(N)) {
                *x = rc;
            }
            p
        };
        let mut out = out;
        for o in &out {
            assert_eq!(o.spin.len(), len * N * N, "spin: n^2 per contact");
            assert_eq!(o.velocity.len(), len * N, "velocity: n per contact");
        }
        for (b, block) in self.blocks().iter().enumerate() {
            let start = b * LANES;
            for l in 0..(len - start).min(LANES) {
                for (k, o) in out.iter_mut().enumerate() {
                    scatter_state(&block[k], o, &pairs, start + l, l);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::batch::Batch;
    use rand::{Rng as _, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Random row-major arrays of `len` contacts (not physical: any numbers are moved
    /// alike); `shared[b]`: body `b`'s parameters one value for all.
    struct Arrays {
        nu: Vec<f64>,
        spin: [Vec<f64>; 2],
        velocity: [Vec<f64>; 2],
        params: [[Vec<f64>; 3]; 2],
    }

    fn arrays<const N: usize>(seed: u64, len: usize, shared: [bool; 2]) -> Arrays {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut v =
            |k: usize| -> Vec<f64> { (0..k).map(|_| rng.random_range(-1.0..1.0)).collect() };
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

    fn rows(a: &Arrays) -> FreeRows<'_, f64> {
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
    fn by_hand<const N: usize, const S: usize>(
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
}
