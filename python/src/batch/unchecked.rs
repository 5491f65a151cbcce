//! The rows of `collide_batch` without validation: the batch kernels
//! (`collision_core::batch`, blocks of 8 contacts, the instruction set chosen at run time)
//! on a chunk of rows at a time, in a blocked scratch kept per thread.
//!
//! Each row runs the kernel `collision_core::collide_unchecked` runs on it: `fixed` when a
//! body is immovable (`inv_mass = 0`; bodies swapped and `nu` negated when it is body 2,
//! whose state then comes back unchanged), `free` otherwise; so a row's result is
//! `collide_unchecked`'s bit for bit.

use super::inputs::{nu_row, Inputs};
use super::outputs::{put, state_rows_mut, Outputs};
use super::CHUNK;
use collision_core::batch::BatchKernel;
use collision_core::batch::FreeRows;
use collision_core::batch::{Contact, Exec, FixedBatch, FreeBatch, PairBatch, StateBatch};
use collision_core::{BodyState, Generated, RefArith, Scalar};
use num_traits::Float;
use std::any::Any;
use std::cell::RefCell;

/// The blocked batches of one chunk, reused from chunk to chunk.
pub(super) struct Scratch<T, const N: usize, const S: usize> {
    free: FreeBatch<T, N, S>,
    fixed: FixedBatch<T, N, S>,
    pairs: PairBatch<T, N, S>,
    moved: StateBatch<T, N, S>,
    /// Local rows of `free`'s contacts, in order.
    free_rows: Vec<usize>,
    /// Local rows of `fixed`'s contacts, and whether body 2 is the immovable one.
    fixed_rows: Vec<(usize, bool)>,
}

thread_local! {
    /// This thread's scratches kept between calls, of any type (`Scratch<T, N, S>` boxed),
    /// the most recently used last, at most [`KEPT_SCRATCHES`]. Scratches allocated by each
    /// call and freed at its end went back to the system (the allocator trims or unmaps
    /// them), so their pages faulted in again on every call: a split batch took 2x the
    /// serial time at n = 6, 1024 rows (15-20 faults a call). Per thread, so that a scratch
    /// stays in the L2 of the core that last used it, and rayon's workers live as long as
    /// the process.
    static SCRATCHES: RefCell<Vec<Box<dyn Any>>> = const { RefCell::new(Vec::new()) };
}

/// At most this many scratches are kept per thread: one per type (`f32`, `f64` and n = 2..6,
/// 15 to 130 kB each), so a program alternating between all ten types still reuses them.
const KEPT_SCRATCHES: usize = 10;

impl<T: Scalar + 'static, const N: usize, const S: usize> Scratch<T, N, S> {
    /// This thread's kept scratch of this type, or a new one with room for a chunk.
    pub(super) fn take() -> Self {
        let kept = SCRATCHES.with_borrow_mut(|kept| {
            let i = kept.iter().rposition(|s| s.is::<Self>())?;
            kept.remove(i).downcast::<Self>().ok()
        });
        kept.map_or_else(|| Self::new(CHUNK), |scratch| *scratch)
    }

    /// Keeps this scratch on this thread for a later call; the least recently used one goes
    /// if [`KEPT_SCRATCHES`] are kept.
    pub(super) fn give_back(self) {
        SCRATCHES.with_borrow_mut(|kept| {
            if kept.len() >= KEPT_SCRATCHES {
                kept.remove(0);
            }
            kept.push(Box::new(self));
        });
    }
}

impl<T: Scalar, const N: usize, const S: usize> Scratch<T, N, S> {
    /// Room for `rows` contacts (a chunk, or a shorter batch).
    fn new(rows: usize) -> Self {
        Scratch {
            free: FreeBatch::with_capacity(rows),
            fixed: FixedBatch::with_capacity(rows),
            pairs: PairBatch::with_capacity(rows),
            moved: StateBatch::with_capacity(rows),
            free_rows: Vec::with_capacity(rows),
            fixed_rows: Vec::with_capacity(rows),
        }
    }
}

/// Put row `i` (local row `j`) into `fixed` when a body is immovable, as `collide` does
/// (body 2 immovable: bodies swapped, `nu` negated); `false` when both bodies move.
fn push_fixed<T, const N: usize, const S: usize>(
    input: &Inputs<'_, T>,
    i: usize,
    j: usize,
    (fixed, fixed_rows): (&mut FixedBatch<T, N, S>, &mut Vec<(usize, bool)>),
    pairs: &[(usize, usize); S],
) -> bool
where
    T: Scalar + Copy,
{
    let [a, b] = &input.bodies;
    let (b1, b2) = (a.ball(i), b.ball(i));
    if !b1.is_immovable() && !b2.is_immovable() {
        return false;
    }
    let nu = nu_row::<T, N>(input, i);
    let (s1, s2) = (a.state(i, pairs), b.state(i, pairs));
    if b1.is_immovable() {
        let contact = Contact {
            nu,
            states: [s1, s2],
        };
        fixed.push((contact, b1.radius, b2));
        fixed_rows.push((j, false));
    } else {
        let contact = Contact {
            nu: nu.map(|x| -x),
            states: [s2, s1],
        };
        fixed.push((contact, b2.radius, b1));
        fixed_rows.push((j, true));
    }
    true
}

/// Run `fixed` on the rows [`push_fixed`] put there and write both bodies of each (the
/// immovable one unchanged) into local row `j` of `out`.
fn run_fixed<T, const N: usize, const S: usize>(
    exec: &Exec,
    input: &Inputs<'_, T>,
    start: usize,
    out: &mut Outputs<'_, T>,
    sc: &mut Scratch<T, N, S>,
    pairs: &[(usize, usize); S],
) where
    T: Scalar + Copy + Send + Sync,
    for<'x> &'x T: RefArith<T>,
    Generated: BatchKernel<T, N, S>,
{
    if sc.fixed.is_empty() {
        return;
    }
    exec.fixed(&sc.fixed, &mut sc.moved);
    for (k, &(j, body2_fixed)) in sc.fixed_rows.iter().enumerate() {
        if let Some(moved) = sc.moved.get(k) {
            let (still, moving) = if body2_fixed { (1, 0) } else { (0, 1) };
            put(out, j, moving, &moved, pairs);
            let state: BodyState<T, N, S> = input.bodies[still].state(start + j, pairs);
            put(out, j, still, &state, pairs);
        }
    }
}

/// Rows `start..start + out.velocity[0].len() / N` of the batch, from row-major arrays:
/// every row run by `free` straight from the arrays into `out` (`Exec::free_rows`: a pass of
/// a few blocks at a time, gathered, run and scattered by code compiled for the CPU's
/// instruction set); then the rows with an immovable body, [`CHUNK`] rows at a time, run
/// again by `fixed` and overwritten.
pub(super) fn run_rows<T, const N: usize, const S: usize>(
    exec: &Exec,
    input: &Inputs<'_, T>,
    rows: &FreeRows<'_, T>,
    start: usize,
    mut out: Outputs<'_, T>,
    sc: &mut Scratch<T, N, S>,
    pairs: &[(usize, usize); S],
) where
    T: Scalar + Float + Send + Sync,
    for<'x> &'x T: RefArith<T>,
    Generated: BatchKernel<T, N, S>,
{
    let len = out.velocity[0].len() / N;
    {
        let Outputs {
            spin: [s1, s2],
            velocity: [v1, v2],
        } = &mut out;
        let part = rows.slice::<N>(start..start + len);
        exec.free_rows(&part, state_rows_mut([s1, s2], [v1, v2]));
    }
    // The rows with an immovable body (`inv_mass = 0`); none to look for when both
    // bodies share a finite mass.
    let [w1, w2] = rows.balls.each_ref().map(|b| b.inv_mass);
    let zero = T::zero();
    let immovable = |w: &[T], i: usize| w[if w.len() == 1 { 0 } else { i }] == zero;
    if w1.len() == 1 && w2.len() == 1 && w1[0] != zero && w2[0] != zero {
        return;
    }
    for first in (0..len).step_by(CHUNK) {
        sc.fixed.clear();
        sc.fixed_rows.clear();
        for j in first..(first + CHUNK).min(len) {
            let i = start + j;
            if immovable(w1, i) || immovable(w2, i) {
                push_fixed(input, i, j, (&mut sc.fixed, &mut sc.fixed_rows), pairs);
            }
        }
        run_fixed(exec, input, start, &mut out, sc, pairs);
    }
}

/// Rows `start..start + out.velocity[0].len() / N` of the batch, from arrays of any
/// strides, row by row through the batch's items (`push`, `get`).
pub(super) fn run_chunk<T, const N: usize, const S: usize>(
    exec: &Exec,
    input: &Inputs<'_, T>,
    start: usize,
    mut out: Outputs<'_, T>,
    sc: &mut Scratch<T, N, S>,
    pairs: &[(usize, usize); S],
) where
    T: Scalar + Copy + Send + Sync,
    for<'x> &'x T: RefArith<T>,
    Generated: BatchKernel<T, N, S>,
{
    let rows = out.velocity[0].len() / N;
    sc.free.clear();
    sc.fixed.clear();
    sc.free_rows.clear();
    sc.fixed_rows.clear();
    let [a, b] = &input.bodies;
    for j in 0..rows {
        let i = start + j;
        if !push_fixed(input, i, j, (&mut sc.fixed, &mut sc.fixed_rows), pairs) {
            let contact = Contact {
                nu: nu_row::<T, N>(input, i),
                states: [a.state(i, pairs), b.state(i, pairs)],
            };
            sc.free.push((contact, [a.ball(i), b.ball(i)]));
            sc.free_rows.push(j);
        }
    }
    exec.free(&sc.free, &mut sc.pairs);
    for (k, &j) in sc.free_rows.iter().enumerate() {
        if let Some([p1, p2]) = sc.pairs.get(k) {
            put(&mut out, j, 0, &p1, pairs);
            put(&mut out, j, 1, &p2, pairs);
        }
    }
    run_fixed(exec, input, start, &mut out, sc, pairs);
}
