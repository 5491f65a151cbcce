//! Rows into blocks: contact `i` of row-major arrays into lane `i mod 8` of block `i / 8`,
//! compiled for each instruction-set level (`dispatch::at_level`).
//!
//! A full block (8 rows) is a transpose of fixed shape: `nu` and the velocities are 8 rows
//! of `n` entries into `n` lane arrays, the angular velocities 8 rows of `n^2` entries of
//! which the `S` above the diagonal (fixed offsets `r n + c`) go into `S` lane arrays, and a
//! parameter given per row is 8 consecutive values, one lane array copied as it is. Only a
//! last, partial block pads: its lanes past the end repeat its first contact, as
//! [`Batch::push`](crate::batch::Batch::push) pads.

use super::{pairs, BallRows, FreeRows, StateRows};
use crate::batch::dispatch::{at_level, AtLevel, Isa};
use crate::batch::lanes::{BallLanes, Contact, FreeLanes, Lanes, StateLanes, LANES};
use crate::batch::FreeBatch;
use crate::{Ball, BodyState};
use std::ops::Range;

/// `lanes[k][l] = rows[l n + k]`: 8 rows of `n` entries into `n` lane arrays.
#[inline(always)]
fn transpose<T: Clone, const N: usize>(rows: &[T], lanes: &mut [Lanes<T>; N]) {
    assert_eq!(rows.len(), LANES * N);
    for l in 0..LANES {
        for (k, lane) in lanes.iter_mut().enumerate() {
            lane[l] = rows[l * N + k].clone();
        }
    }
}

/// One body's states of 8 rows (from `start`) into a state block.
#[inline(always)]
fn full_state<T: Clone, const N: usize, const S: usize>(
    rows: &StateRows<'_, T>,
    start: usize,
    lanes: &mut StateLanes<T, N, S>,
) {
    let spin = &rows.spin[start * N * N..(start + LANES) * N * N];
    let offsets = const { offsets::<N, S>() };
    for l in 0..LANES {
        for (lane, &o) in lanes.spin.iter_mut().zip(&offsets) {
            lane[l] = spin[l * N * N + o].clone();
        }
    }
    transpose(
        &rows.velocity[start * N..(start + LANES) * N],
        &mut lanes.velocity,
    );
}

/// One body's parameters of 8 rows (from `start`): 8 consecutive values, or a shared one.
#[inline(always)]
fn full_ball<T: Clone>(rows: &BallRows<'_, T>, start: usize, lanes: &mut BallLanes<T>) {
    for (lane, p) in [
        (&mut lanes.inv_mass, rows.inv_mass),
        (&mut lanes.radius, rows.radius),
        (&mut lanes.gamma2, rows.gamma2),
    ] {
        if p.len() == 1 {
            lane.fill(p[0].clone());
        } else {
            lane.clone_from_slice(&p[start..start + LANES]);
        }
    }
}

/// Contacts `start..start + 8` of `rows` into `block`.
#[inline(always)]
fn full_block<T: Clone, const N: usize, const S: usize>(
    rows: &FreeRows<'_, T>,
    start: usize,
    block: &mut FreeLanes<T, N, S>,
) {
    transpose(
        &rows.nu[start * N..(start + LANES) * N],
        &mut block.contact.nu,
    );
    for k in 0..2 {
        full_state(&rows.states[k], start, &mut block.contact.states[k]);
        full_ball(&rows.balls[k], start, &mut block.balls[k]);
    }
}

/// Contacts `start..end` (fewer than 8) into `block`, the lanes past `end` repeating
/// contact `start`.
fn partial_block<T: Clone, const N: usize, const S: usize>(
    rows: &FreeRows<'_, T>,
    start: usize,
    end: usize,
    block: &mut FreeLanes<T, N, S>,
) {
    let offsets = const { offsets::<N, S>() };
    for l in 0..LANES {
        let i = if start + l < end { start + l } else { start };
        for (lane, x) in block
            .contact
            .nu
            .iter_mut()
            .zip(&rows.nu[i * N..(i + 1) * N])
        {
            lane[l] = x.clone();
        }
        for k in 0..2 {
            let (s, lanes) = (&rows.states[k], &mut block.contact.states[k]);
            let spin = &s.spin[i * N * N..(i + 1) * N * N];
            for (lane, &o) in lanes.spin.iter_mut().zip(&offsets) {
                lane[l] = spin[o].clone();
            }
            let velocity = &s.velocity[i * N..(i + 1) * N];
            for (lane, x) in lanes.velocity.iter_mut().zip(velocity) {
                lane[l] = x.clone();
            }
            let (p, ball) = (&rows.balls[k], &mut block.balls[k]);
            let at = |x: &[T]| x[if x.len() == 1 { 0 } else { i }].clone();
            ball.inv_mass[l] = at(p.inv_mass);
            ball.radius[l] = at(p.radius);
            ball.gamma2[l] = at(p.gamma2);
        }
    }
}

/// Contacts `range` of `rows` into the first `range.len().div_ceil(8)` of `blocks` (the
/// contact part of each: a [`FreeLanes`], or that of a block with its laws,
/// [`WithLaw`](crate::batch::WithLaw)).
#[inline(always)]
pub(super) fn gather<T: Clone, const N: usize, const S: usize, B: AsMut<FreeLanes<T, N, S>>>(
    rows: &FreeRows<'_, T>,
    range: Range<usize>,
    blocks: &mut [B],
) {
    for (b, block) in blocks.iter_mut().enumerate() {
        let block = block.as_mut();
        let start = range.start + b * LANES;
        if start >= range.end {
            break;
        }
        if range.end - start >= LANES {
            full_block(rows, start, block);
        } else {
            partial_block(rows, start, range.end, block);
        }
    }
}

/// [`gather`] as work compiled per level.
pub(super) struct Gather<'r, 'b, T, B, const N: usize, const S: usize> {
    pub(super) rows: &'r FreeRows<'r, T>,
    pub(super) range: Range<usize>,
    pub(super) blocks: &'b mut [B],
}

impl<
        T: Clone + 'static,
        const N: usize,
        const S: usize,
        B: AsMut<FreeLanes<T, N, S>> + 'static,
    > AtLevel for Gather<'_, '_, T, B, N, S>
{
    type Output = ();
    #[inline(always)]
    fn run<const W: usize>(self) {
        // The permutes take plain `f64` blocks (not a block with its laws).
        #[cfg(all(target_arch = "x86_64", noslip_avx512_intrinsics))]
        if W == crate::batch::dispatch::AVX512_WIDTH
            && N <= super::avx512::PERMUTES_UP_TO
            && std::any::TypeId::of::<T>() == std::any::TypeId::of::<f64>()
            && std::any::TypeId::of::<B>() == std::any::TypeId::of::<FreeLanes<f64, N, S>>()
            && Isa::Avx512.is_available()
        {
            let full = self.range.len() / LANES;
            let (head, tail) = self.blocks.split_at_mut(full);
            // SAFETY: `T` is `f64` and `B` is `FreeLanes<f64, N, S>` (same type ids), so the
            // casts change no type.
            let (rows, head) = unsafe {
                (
                    &*(self.rows as *const FreeRows<'_, T>).cast::<FreeRows<'_, f64>>(),
                    std::slice::from_raw_parts_mut(
                        head.as_mut_ptr().cast::<FreeLanes<f64, N, S>>(),
                        head.len(),
                    ),
                )
            };
            // SAFETY: the CPU has AVX-512F (checked just now).
            unsafe { super::avx512::gather(rows, self.range.start, head) };
            let start = self.range.start + full * LANES;
            if start < self.range.end {
                partial_block(self.rows, start, self.range.end, tail[0].as_mut());
            }
            return;
        }
        gather::<T, N, S, B>(self.rows, self.range, self.blocks)
    }
}

/// Offsets `r n + c` of the compact entries `U_rc`, `r < c`, in the order of
/// [`BodyState::spin`](crate::BodyState::spin).
const fn offsets<const N: usize, const S: usize>() -> [usize; S] {
    let pairs = pairs::<N, S>();
    let mut out = [0; S];
    let mut k = 0;
    while k < S {
        out[k] = pairs[k].0 * N + pairs[k].1;
        k += 1;
    }
    out
}

/// Contact `i` of `rows` as a batch item.
pub(super) fn item<T: Clone, const N: usize, const S: usize>(
    rows: &FreeRows<'_, T>,
    i: usize,
) -> (Contact<T, N, S>, [Ball<T>; 2]) {
    let offsets = const { offsets::<N, S>() };
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

impl<T: Clone + 'static, const N: usize, const S: usize> FreeBatch<T, N, S> {
    /// Replace the batch's contacts by contacts `range` of `rows`, in order, reusing the
    /// blocks already allocated: the batch that [`Batch::push`](crate::batch::Batch::push)
    /// of each row's `(Contact, [Ball; 2])` would build (`Contact::states[b].spin` the
    /// entries `U_rc`, `r < c`, of body `b`'s matrix row), padding lanes included. Compiled
    /// for each instruction-set level; runs on [`Isa::detect`]'s.
    ///
    /// # Panics
    /// If the lengths of `rows` do not fit ([`FreeRows::len`]) or `range` is not within
    /// `0..rows.len()`.
    pub fn fill_from_rows(&mut self, rows: &FreeRows<'_, T>, range: Range<usize>) {
        self.fill_from_rows_on(Isa::detect(), rows, range)
    }

    /// [`fill_from_rows`](Self::fill_from_rows) compiled for `isa` (the baseline when this
    /// CPU lacks it): every level gives the same batch.
    pub fn fill_from_rows_on(&mut self, isa: Isa, rows: &FreeRows<'_, T>, range: Range<usize>) {
        let total = rows.len::<N>();
        assert!(
            range.start <= range.end && range.end <= total,
            "range {range:?} of {total} contacts"
        );
        if range.is_empty() {
            self.clear();
            return;
        }
        // New blocks start as copies of contact `range.start` (every lane is overwritten).
        let first = item(rows, range.start);
        self.resize_with(range.len(), || crate::batch::Lanewise::splat(&first));
        let blocks = self.blocks_mut();
        at_level(
            isa,
            Gather::<T, _, N, S> {
                rows,
                range,
                blocks,
            },
        );
    }
}
