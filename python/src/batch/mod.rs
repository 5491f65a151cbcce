//! `noslip.collide_batch`: the collision map on every row of NumPy arrays, by the batch
//! kernels (`collision_core::batch`: blocks of 8 contacts, the instruction set chosen at
//! run time), with the GIL released and the rows split across rayon's threads.
//!
//! The inputs are read in place, chunk by chunk ([`CHUNK`] rows), into a blocked scratch
//! batch, the kernels run on the scratch, and the results are written into the new output
//! arrays. Row-major arrays (NumPy's default) take the direct path: each chunk is gathered
//! straight into the kernel's lane arrays (`FreeBatch::fill_from_rows`) and scattered
//! straight into the outputs (`PairBatch::write_rows`); other strides go row by row through
//! the batch's items. Beyond the outputs, memory is the scratch: about `CHUNK` x 0.25 kB per
//! running thread, whatever the number of rows, kept by that thread between calls (at
//! most [`KEPT_SCRATCHES`] of them, one per type).
//!
//! Each row runs the kernel [`collision_core::collide`] runs on it: `fixed` when a body is
//! immovable (`inv_mass = 0`; bodies swapped and `nu` negated when it is body 2, whose
//! state then comes back unchanged), `free` otherwise; so a row's result is
//! `collision_core::collide_unchecked`'s bit for bit. With `validate`, every row first
//! passes `collide`'s checks (the rounding allowance included): a cheap test in the batch's
//! own float type, on the lane arrays of the gathered chunk, accepts the rows that are
//! clearly valid ([`valid`]), and only the others go through `collide`'s own checks
//! (`collision_core::validate_parts`), whose error, for the first bad row, names the row and
//! the field.
//!
//! The outputs are new arrays, or the caller's (`out=`: shapes and layout checked, borrowed
//! read-write, so an output sharing memory with an input or another output is refused).

mod valid;

use crate::error::input_error;
use collision_core::batch::BatchKernel;
use collision_core::batch::{share_rows, BallRows, FreeRows, StateRows, StateRowsMut, LANES};
use collision_core::batch::{Contact, Exec, FixedBatch, FreeBatch, PairBatch, StateBatch};
use collision_core::RefArith;
use collision_core::{skew_pairs, validate_parts, Ball, BodyState, Generated, Scalar};
use collision_core::{BodyField, Field};
use noslip_case::CaseError;
use num_traits::Float;
use numpy::ndarray::{ArrayView1, ArrayView2, ArrayView3};
use numpy::{
    Element, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyReadonlyArray3, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use std::any::Any;
use std::cell::RefCell;
use std::sync::Mutex;

/// Rows per chunk: 64 blocks of 8, whose scratch (inputs and outputs in the blocked
/// layout, 30 to 130 kB for n = 2..6 in `f64`) stays in the core's L2 cache between the
/// gather, the kernel and the scatter.
pub const CHUNK: usize = 512;

/// The arrays of one body: `angular_velocity` `(N, n, n)`, `velocity` `(N, n)`, and the
/// kernel parameters `inv_mass`, `radius`, `gamma2`, each of length `N` or 1 (shared).
struct BodyArrays<'a, T> {
    spin: ArrayView3<'a, T>,
    velocity: ArrayView2<'a, T>,
    inv_mass: ArrayView1<'a, T>,
    radius: ArrayView1<'a, T>,
    gamma2: ArrayView1<'a, T>,
}

/// One body's arrays as views: angular velocity, velocity, `inv_mass`, `radius`, `gamma2`.
pub(crate) type BodyViews<'a, T> = (
    ArrayView3<'a, T>,
    ArrayView2<'a, T>,
    ArrayView1<'a, T>,
    ArrayView1<'a, T>,
    ArrayView1<'a, T>,
);

/// Every input of a batch, shapes checked.
pub(crate) struct Inputs<'a, T> {
    rows: usize,
    dim: usize,
    nu: ArrayView2<'a, T>,
    bodies: [BodyArrays<'a, T>; 2],
}

/// The output arrays' memory: per body, the `(N, n, n)` angular velocities and the `(N, n)`
/// velocities, row-major.
struct Outputs<'a, T> {
    spin: [&'a mut [T]; 2],
    velocity: [&'a mut [T]; 2],
}

fn shape_error(field: &str, expected: String, got: &[usize]) -> PyErr {
    input_error(format!("{field}: expected shape {expected}, got {got:?}"))
}

impl<'a, T: Copy> Inputs<'a, T> {
    pub(crate) fn new(nu: ArrayView2<'a, T>, bodies: [BodyViews<'a, T>; 2]) -> PyResult<Self> {
        let (rows, dim) = nu.dim();
        if !collision_core::DIMS.contains(&dim) {
            return Err(input_error(format!(
                "normal: expected shape (N, n) with n in {:?} (the batch kernels), got {:?}",
                collision_core::DIMS,
                nu.shape()
            )));
        }
        let mut checked = Vec::with_capacity(2);
        for (b, (spin, velocity, inv_mass, radius, gamma2)) in bodies.into_iter().enumerate() {
            let field = |k: &str| format!("bodies[{b}].{k}");
            if spin.dim() != (rows, dim, dim) {
                return Err(shape_error(
                    &field("angular_velocity"),
                    format!("({rows}, {dim}, {dim})"),
                    spin.shape(),
                ));
            }
            if velocity.dim() != (rows, dim) {
                return Err(shape_error(
                    &field("velocity"),
                    format!("({rows}, {dim})"),
                    velocity.shape(),
                ));
            }
            for (name, p) in [
                ("inv_mass", &inv_mass),
                ("radius", &radius),
                ("gamma2", &gamma2),
            ] {
                if p.len() != rows && p.len() != 1 {
                    return Err(shape_error(
                        &field(name),
                        format!("({rows},) or a scalar"),
                        p.shape(),
                    ));
                }
            }
            checked.push(BodyArrays {
                spin,
                velocity,
                inv_mass,
                radius,
                gamma2,
            });
        }
        let [b1, b2]: [BodyArrays<'a, T>; 2] = checked
            .try_into()
            .unwrap_or_else(|_| unreachable!("two bodies"));
        Ok(Inputs {
            rows,
            dim,
            nu,
            bodies: [b1, b2],
        })
    }
}

impl<'a, T> Inputs<'a, T> {
    /// The arrays as row-major slices (`collision_core::batch::FreeRows`), when every one is
    /// in standard layout (C-contiguous).
    pub(crate) fn rows(&self) -> Option<FreeRows<'a, T>> {
        let state = |b: &BodyArrays<'a, T>| {
            Some(StateRows {
                spin: b.spin.to_slice()?,
                velocity: b.velocity.to_slice()?,
            })
        };
        let ball = |b: &BodyArrays<'a, T>| {
            Some(BallRows {
                inv_mass: b.inv_mass.to_slice()?,
                radius: b.radius.to_slice()?,
                gamma2: b.gamma2.to_slice()?,
            })
        };
        let [a, b] = &self.bodies;
        Some(FreeRows {
            nu: self.nu.to_slice()?,
            states: [state(a)?, state(b)?],
            balls: [ball(a)?, ball(b)?],
        })
    }
}

/// Parameter `p` of row `i` (a length-1 array is shared by every row).
fn param<T: Copy>(p: &ArrayView1<'_, T>, i: usize) -> T {
    p[if p.len() == 1 { 0 } else { i }]
}

impl<T: Scalar + Copy> BodyArrays<'_, T> {
    fn ball(&self, i: usize) -> Ball<T> {
        Ball {
            inv_mass: param(&self.inv_mass, i),
            radius: param(&self.radius, i),
            gamma2: param(&self.gamma2, i),
        }
    }

    /// Row `i`'s state: the compact entries `U_rc`, `r < c` (upper triangle), and `u`.
    fn state<const N: usize, const S: usize>(
        &self,
        i: usize,
        pairs: &[(usize, usize); S],
    ) -> BodyState<T, N, S> {
        // Row-major arrays (the usual case) are read as slices, without ndarray's
        // per-element index arithmetic and bounds checks.
        if let (Some(spin), Some(velocity)) = (self.spin.as_slice(), self.velocity.as_slice()) {
            let (spin, velocity) = (
                &spin[i * N * N..(i + 1) * N * N],
                &velocity[i * N..(i + 1) * N],
            );
            return BodyState {
                spin: pairs.map(|(r, c)| spin[r * N + c]),
                velocity: std::array::from_fn(|k| velocity[k]),
            };
        }
        BodyState {
            spin: pairs.map(|(r, c)| self.spin[[i, r, c]]),
            velocity: std::array::from_fn(|k| self.velocity[[i, k]]),
        }
    }

    /// `collide`'s check that row `i`'s angular velocity is skew (as `BodyState::from_matrix`).
    fn check_skew<const N: usize, const S: usize>(
        &self,
        i: usize,
        b: usize,
    ) -> Result<(), collision_core::InputError> {
        let m: [[T; N]; N] = std::array::from_fn(|r| std::array::from_fn(|c| self.spin[[i, r, c]]));
        BodyState::<T, N, S>::from_matrix(b, &m, [T::zero(); N]).map(|_| ())
    }
}

/// Both bodies' row-major outputs, as `PairBatch::write_rows` takes them.
pub(crate) fn state_rows_mut<'a, T>(
    [s1, s2]: [&'a mut [T]; 2],
    [v1, v2]: [&'a mut [T]; 2],
) -> [StateRowsMut<'a, T>; 2] {
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

/// The compact entries as a full skew matrix, row-major, `m_cr = 0 - m_rc` (so a zero entry
/// is `+0` on both sides, as `noslip collide` prints it).
fn write_state<T: Scalar + Copy, const N: usize, const S: usize>(
    s: &BodyState<T, N, S>,
    pairs: &[(usize, usize); S],
    spin: &mut [T],
    velocity: &mut [T],
) {
    for (r, row) in spin.chunks_exact_mut(N).enumerate() {
        row[r] = T::zero();
    }
    for (&(r, c), &x) in pairs.iter().zip(&s.spin) {
        spin[r * N + c] = x;
        spin[c * N + r] = T::zero() - x;
    }
    velocity.copy_from_slice(&s.velocity);
}

/// The blocked batches of one chunk, reused from chunk to chunk.
struct Scratch<T, const N: usize, const S: usize> {
    free: FreeBatch<T, N, S>,
    fixed: FixedBatch<T, N, S>,
    pairs: PairBatch<T, N, S>,
    moved: StateBatch<T, N, S>,
    /// Local rows of `free`'s contacts, in order.
    free_rows: Vec<usize>,
    /// Local rows of `fixed`'s contacts, and whether body 2 is the immovable one.
    fixed_rows: Vec<(usize, bool)>,
    /// Per block of `free`, whether all its rows passed the cheap validity test
    /// ([`valid::chunk`]).
    valid: Vec<bool>,
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
    fn take() -> Self {
        let kept = SCRATCHES.with_borrow_mut(|kept| {
            let i = kept.iter().rposition(|s| s.is::<Self>())?;
            kept.remove(i).downcast::<Self>().ok()
        });
        kept.map_or_else(|| Self::new(CHUNK), |scratch| *scratch)
    }

    /// Keeps this scratch on this thread for a later call; the least recently used one goes
    /// if [`KEPT_SCRATCHES`] are kept.
    fn give_back(self) {
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
            valid: Vec::with_capacity(rows.div_ceil(LANES)),
        }
    }
}

/// A bad row: its index and the message (`row 17: bodies[1].gamma2: ...`).
type RowError = (usize, String);

/// Row `i`'s normal `nu`.
fn nu_row<T: Copy, const N: usize>(input: &Inputs<'_, T>, i: usize) -> [T; N] {
    match input.nu.as_slice() {
        Some(nu) => std::array::from_fn(|k| nu[i * N + k]),
        None => std::array::from_fn(|k| input.nu[[i, k]]),
    }
}

/// `collide`'s own checks on row `i` (skew `U` as `BodyState::from_matrix`, then
/// `validate_parts`); the error, built only here, names the row and the field.
fn check_row<T, const N: usize, const S: usize>(
    input: &Inputs<'_, T>,
    i: usize,
    pairs: &[(usize, usize); S],
) -> Result<(), RowError>
where
    T: Scalar + Copy,
{
    let [a, b] = &input.bodies;
    let nu = nu_row::<T, N>(input, i);
    let balls = [a.ball(i), b.ball(i)];
    let states: [BodyState<T, N, S>; 2] = [a.state(i, pairs), b.state(i, pairs)];
    a.check_skew::<N, S>(i, 0)
        .and_then(|()| b.check_skew::<N, S>(i, 1))
        .and_then(|()| {
            validate_parts(
                &nu,
                [&balls[0], &balls[1]],
                [0, 1].map(|k| (states[k].spin.as_slice(), states[k].velocity.as_slice())),
            )
        })
        .map_err(|e| (i, format!("row {i}: {}", row_error(e))))
}

/// `collide`'s error on a row, its field named by the batch's keys: the batch takes
/// `inv_mass` where `collide` takes `mass` (collision-core's `BodyField::Mass` stands for
/// both), so that field is `bodies[b].inv_mass`; the others are named as in a case.
fn row_error(e: collision_core::InputError) -> CaseError {
    match e.field {
        Field::Body(b, BodyField::Mass) => {
            CaseError::new(format!("bodies[{b}].inv_mass"), e.message)
        }
        _ => CaseError::from(e),
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

/// Write body `body`'s state into local row `j` of `out`.
fn put<T: Scalar + Copy, const N: usize, const S: usize>(
    out: &mut Outputs<'_, T>,
    j: usize,
    body: usize,
    s: &BodyState<T, N, S>,
    pairs: &[(usize, usize); S],
) {
    write_state(
        s,
        pairs,
        &mut out.spin[body][j * N * N..(j + 1) * N * N],
        &mut out.velocity[body][j * N..(j + 1) * N],
    );
}

/// Rows `start..start + out.velocity[0].len() / N` of the batch, from row-major arrays:
/// validated (a cheap test per row, `collide`'s checks only for the rows it does not
/// accept), gathered into the scratch's lane arrays, run by `free`, scattered into `out`;
/// then the rows with an immovable body are run again by `fixed` and overwritten.
#[allow(clippy::too_many_arguments)]
fn run_chunk_rows<T, const N: usize, const S: usize>(
    exec: &Exec,
    input: &Inputs<'_, T>,
    rows: &FreeRows<'_, T>,
    validate: bool,
    start: usize,
    mut out: Outputs<'_, T>,
    sc: &mut Scratch<T, N, S>,
    pairs: &[(usize, usize); S],
) -> Result<(), RowError>
where
    T: Scalar + Float + Send + Sync,
    for<'x> &'x T: RefArith<T>,
    Generated: BatchKernel<T, N, S>,
{
    let range = start..start + out.velocity[0].len() / N;
    sc.free.fill_from_rows(rows, range.clone());
    let lane_rows = |k: usize| (0..LANES).map(move |l| (l, range.start + k * LANES + l));
    if validate {
        let [r1, r2] = &rows.states;
        valid::chunk(
            exec.isa(),
            sc.free.blocks(),
            [r1, r2],
            range.start,
            &mut sc.valid,
        );
        let blocks = sc.free.blocks().iter().zip(&sc.valid).enumerate();
        for (k, (block, _)) in blocks.filter(|(_, (_, &ok))| !ok) {
            for (l, i) in lane_rows(k).take_while(|&(_, i)| i < range.end) {
                if !valid::row(block, [r1, r2], i, l) {
                    check_row::<T, N, S>(input, i, pairs)?;
                }
            }
        }
    }
    exec.free(&sc.free, &mut sc.pairs);
    {
        let Outputs {
            spin: [s1, s2],
            velocity: [v1, v2],
        } = &mut out;
        sc.pairs.write_rows(state_rows_mut([s1, s2], [v1, v2]));
    }
    // The rows with an immovable body (`inv_mass = 0` in a lane of the gathered batch).
    sc.fixed.clear();
    sc.fixed_rows.clear();
    let zero = T::zero();
    for (k, block) in sc.free.blocks().iter().enumerate() {
        let [b1, b2] = &block.balls;
        for (l, i) in lane_rows(k).take_while(|&(_, i)| i < range.end) {
            if b1.inv_mass[l] == zero || b2.inv_mass[l] == zero {
                let fixed = (&mut sc.fixed, &mut sc.fixed_rows);
                push_fixed(input, i, i - range.start, fixed, pairs);
            }
        }
    }
    run_fixed(exec, input, start, &mut out, sc, pairs);
    Ok(())
}

/// Rows `start..start + out.velocity[0].len() / N` of the batch, from arrays of any
/// strides, row by row through the batch's items (`push`, `get`).
fn run_chunk<T, const N: usize, const S: usize>(
    exec: &Exec,
    input: &Inputs<'_, T>,
    validate: bool,
    start: usize,
    mut out: Outputs<'_, T>,
    sc: &mut Scratch<T, N, S>,
    pairs: &[(usize, usize); S],
) -> Result<(), RowError>
where
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
        if validate {
            check_row::<T, N, S>(input, i, pairs)?;
        }
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
    Ok(())
}

/// `m`'s guard, also after a panic elsewhere (the first error stays usable).
fn lock<X>(m: &Mutex<X>) -> std::sync::MutexGuard<'_, X> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// Rows per run of a split batch of `chunks` chunks of `chunk` rows: whole chunks, about
/// four runs per rayon thread (one run per chunk when there are fewer chunks) and at most
/// [`RUN_CHUNKS`] chunks a run, so that a thread that wakes late still finds runs to take and
/// the threads finish within one short run of each other.
pub(crate) fn piece_rows(chunks: usize, chunk: usize) -> usize {
    let pieces = (4 * rayon::current_num_threads()).clamp(1, chunks.max(1));
    chunks.div_ceil(pieces).min(RUN_CHUNKS) * chunk
}

/// The most chunks in a run of a split batch: 8 chunks of 512 rows, 0.1-0.4 ms at n = 3..6.
/// A run costs two thread-local lookups of a scratch and one atomic step, far below that.
const RUN_CHUNKS: usize = 8;

/// The whole batch, into `out` (`rows` rows), chunk by chunk; shared with rayon's threads
/// when `parallel` and there is more than one chunk.
fn run_all<T, const N: usize, const S: usize>(
    input: &Inputs<'_, T>,
    validate: bool,
    parallel: bool,
    out: Outputs<'_, T>,
) -> Result<(), String>
where
    T: Scalar + Float + Send + Sync,
    for<'x> &'x T: RefArith<T>,
    Generated: BatchKernel<T, N, S>,
{
    let exec = Exec::auto().serial();
    let pairs: [(usize, usize); S] = {
        let all: Vec<(usize, usize)> = skew_pairs(N).collect();
        std::array::from_fn(|k| all[k])
    };
    let rows = input.rows();
    let Outputs {
        spin: [s1, s2],
        velocity: [v1, v2],
    } = out;
    // A piece: consecutive chunks run on one thread with one scratch.
    let piece = |start: usize,
                 scratch: &mut Scratch<T, N, S>,
                 s1: &mut [T],
                 s2: &mut [T],
                 v1: &mut [T],
                 v2: &mut [T]| {
        let (spin_len, vel_len) = (CHUNK * N * N, CHUNK * N);
        s1.chunks_mut(spin_len)
            .zip(s2.chunks_mut(spin_len))
            .zip(v1.chunks_mut(vel_len))
            .zip(v2.chunks_mut(vel_len))
            .enumerate()
            .try_for_each(|(c, (((s1, s2), v1), v2))| {
                let out = Outputs {
                    spin: [s1, s2],
                    velocity: [v1, v2],
                };
                let start = start + c * CHUNK;
                match &rows {
                    Some(rows) => {
                        run_chunk_rows(&exec, input, rows, validate, start, out, scratch, &pairs)
                    }
                    None => run_chunk(&exec, input, validate, start, out, scratch, &pairs),
                }
            })
    };
    let chunks = input.rows.div_ceil(CHUNK);
    let first_error = if parallel && chunks > 1 {
        // Runs of whole chunks, a few per thread, shared between this thread and rayon's
        // others without handing the batch over (`share_rows`); the first row's error wins.
        let first_error = Mutex::new(None::<RowError>);
        share_rows(
            [s1, s2, v1, v2],
            [N * N, N * N, N, N],
            piece_rows(chunks, CHUNK),
            &|first, [s1, s2, v1, v2]| {
                let mut scratch = Scratch::<T, N, S>::take();
                let result = piece(first, &mut scratch, s1, s2, v1, v2);
                scratch.give_back();
                if let Err(e) = result {
                    let mut kept = lock(&first_error);
                    if kept.as_ref().is_none_or(|k| e.0 < k.0) {
                        *kept = Some(e);
                    }
                }
            },
        );
        first_error.into_inner().unwrap_or_else(|p| p.into_inner())
    } else {
        let mut scratch = Scratch::<T, N, S>::take();
        let result = piece(0, &mut scratch, s1, s2, v1, v2);
        scratch.give_back();
        result.err()
    };
    first_error.map_or(Ok(()), |(_, m)| Err(m))
}

/// One body's arrays as Python passes them: `angular_velocity`, `velocity`, `inv_mass`,
/// `radius`, `gamma2`.
pub(crate) type BodyIn<'py, T> = (
    PyReadonlyArray3<'py, T>,
    PyReadonlyArray2<'py, T>,
    PyReadonlyArray1<'py, T>,
    PyReadonlyArray1<'py, T>,
    PyReadonlyArray1<'py, T>,
);

/// The new arrays: body 1's and body 2's angular velocities `(N, n, n)` and velocities `(N, n)`.
type BatchOut<'py, T> = (
    Bound<'py, PyArray3<T>>,
    Bound<'py, PyArray2<T>>,
    Bound<'py, PyArray3<T>>,
    Bound<'py, PyArray2<T>>,
);

pub(crate) fn views<'a, T: Element>(b: &'a BodyIn<'_, T>) -> BodyViews<'a, T> {
    (
        b.0.as_array(),
        b.1.as_array(),
        b.2.as_array(),
        b.3.as_array(),
        b.4.as_array(),
    )
}

/// Output arrays a caller passes in (`out=`): body 1's and body 2's angular velocities
/// `(N, n, n)` and velocities `(N, n)`, C-contiguous and writeable.
pub(crate) type OutIn<'py, T> = (
    Bound<'py, PyArray3<T>>,
    Bound<'py, PyArray2<T>>,
    Bound<'py, PyArray3<T>>,
    Bound<'py, PyArray2<T>>,
);

/// The caller's output arrays' shapes and layout (`out[b].angular_velocity`,
/// `out[b].velocity` named in the error); whether they can be written is checked when they
/// are borrowed.
fn check_out<T: Element>(out: &OutIn<'_, T>, rows: usize, n: usize) -> PyResult<()> {
    let (s1, v1, s2, v2) = out;
    for (b, spin, velocity) in [(0, s1, v1), (1, s2, v2)] {
        for (key, want, got, contiguous) in [
            (
                "angular_velocity",
                vec![rows, n, n],
                spin.shape(),
                spin.is_c_contiguous(),
            ),
            (
                "velocity",
                vec![rows, n],
                velocity.shape(),
                velocity.is_c_contiguous(),
            ),
        ] {
            let field = format!("out[{b}].{key}");
            if got != want.as_slice() {
                return Err(shape_error(&field, format!("{want:?}"), got));
            }
            if !contiguous {
                return Err(input_error(format!(
                    "{field}: must be C-contiguous (the rows are written in place)"
                )));
            }
        }
    }
    Ok(())
}

/// A read-write borrow of output `field`: refused (naming it) when the array is read-only
/// or shares memory with an input (borrowed read-only) or another output.
fn borrow_out<'py, T: Element, D: numpy::ndarray::Dimension>(
    array: &Bound<'py, numpy::PyArray<T, D>>,
    field: &str,
) -> PyResult<numpy::PyReadwriteArray<'py, T, D>> {
    array.try_readwrite().map_err(|e| {
        input_error(match e {
            numpy::BorrowError::NotWriteable => format!("{field}: must be writeable"),
            _ => format!(
                "{field}: shares memory with an input or another output (the outputs must \
                 be arrays of their own)"
            ),
        })
    })
}

fn collide_batch<'py, T>(
    py: Python<'py>,
    normal: PyReadonlyArray2<'py, T>,
    body1: BodyIn<'py, T>,
    body2: BodyIn<'py, T>,
    validate: bool,
    parallel: bool,
    out: Option<OutIn<'py, T>>,
) -> PyResult<BatchOut<'py, T>>
where
    T: Element + Scalar + Float + Send + Sync,
    for<'x> &'x T: RefArith<T>,
{
    let input = Inputs::new(normal.as_array(), [views(&body1), views(&body2)])?;
    let (rows, n) = (input.rows, input.dim);
    let (spin, velocity) = match out {
        Some(out) => {
            check_out(&out, rows, n)?;
            let (s1, v1, s2, v2) = out;
            ([s1, s2], [v1, v2])
        }
        // Every element of the new arrays is written below (each row's both bodies,
        // whichever kernel ran it) before Python sees them, or the arrays are dropped with
        // the error.
        None => (
            [0, 1].map(|_| unsafe { PyArray3::<T>::new(py, [rows, n, n], false) }),
            [0, 1].map(|_| unsafe { PyArray2::<T>::new(py, [rows, n], false) }),
        ),
    };
    let done = {
        let [s1, s2] = &spin;
        let [v1, v2] = &velocity;
        let mut w1 = borrow_out(s1, "out[0].angular_velocity")?;
        let mut w2 = borrow_out(s2, "out[1].angular_velocity")?;
        let mut x1 = borrow_out(v1, "out[0].velocity")?;
        let mut x2 = borrow_out(v2, "out[1].velocity")?;
        let slice = |e: numpy::NotContiguousError| input_error(format!("internal error: {e}"));
        let out = Outputs {
            spin: [
                w1.as_slice_mut().map_err(slice)?,
                w2.as_slice_mut().map_err(slice)?,
            ],
            velocity: [
                x1.as_slice_mut().map_err(slice)?,
                x2.as_slice_mut().map_err(slice)?,
            ],
        };
        py.detach(|| {
            collision_core::with_dim!(
                n,
                |N, S| run_all::<T, N, S>(&input, validate, parallel, out),
                Err(format!("dimension {n} has no batch kernels"))
            )
        })
    };
    done.map_err(input_error)?;
    let [s1, s2] = spin;
    let [v1, v2] = velocity;
    Ok((s1, v1, s2, v2))
}

/// `collide_batch` on `float64` arrays (see the Python docstring).
#[pyfunction]
#[pyo3(signature = (normal, body1, body2, validate, parallel, out=None))]
pub fn collide_batch_f64<'py>(
    py: Python<'py>,
    normal: PyReadonlyArray2<'py, f64>,
    body1: BodyIn<'py, f64>,
    body2: BodyIn<'py, f64>,
    validate: bool,
    parallel: bool,
    out: Option<OutIn<'py, f64>>,
) -> PyResult<BatchOut<'py, f64>> {
    collide_batch::<f64>(py, normal, body1, body2, validate, parallel, out)
}

/// `collide_batch` on `float32` arrays (see the Python docstring).
#[pyfunction]
#[pyo3(signature = (normal, body1, body2, validate, parallel, out=None))]
pub fn collide_batch_f32<'py>(
    py: Python<'py>,
    normal: PyReadonlyArray2<'py, f32>,
    body1: BodyIn<'py, f32>,
    body2: BodyIn<'py, f32>,
    validate: bool,
    parallel: bool,
    out: Option<OutIn<'py, f32>>,
) -> PyResult<BatchOut<'py, f32>> {
    collide_batch::<f32>(py, normal, body1, body2, validate, parallel, out)
}

/// The instruction set the batch kernels run on here (`Exec::auto`): `sse2`, `avx2`, `avx512`.
#[pyfunction]
pub fn isa() -> &'static str {
    Exec::auto().isa().name()
}
