//! `noslip.collide_batch`: the collision map on every row of NumPy arrays, with the GIL
//! released and the rows split across rayon's threads, chunk by chunk ([`CHUNK`] rows).
//!
//! - With `validate` (the default), each row goes through `collision_core::collide`
//!   itself (`checked.rs`): accepted or refused, and its result rounded, exactly as
//!   `noslip.collide` does it; the first bad row's error names the row and the field.
//! - Without, the batch kernels run the rows (`unchecked.rs`: blocks of 8 contacts, the
//!   instruction set chosen at run time): `collision_core::collide_unchecked`'s result bit
//!   for bit. Row-major arrays (NumPy's default) are gathered straight into the kernel's
//!   lane arrays and scattered straight into the outputs; other strides go row by row.
//!   Beyond the outputs, memory is the scratch: about `CHUNK` x 0.25 kB per running thread,
//!   whatever the number of rows, kept by that thread between calls.
//!
//! The inputs' shapes are checked and their rows read by `inputs.rs`. The outputs are new
//! arrays, or the caller's (`out=`: shapes and layout checked, borrowed read-write, so an
//! output sharing memory with an input or another output is refused).

mod checked;
mod inputs;
mod unchecked;

use crate::error::input_error;
use checked::{run_chunk_checked, RowError};
use collision_core::batch::{share_rows, BatchKernel, Exec};
use collision_core::{skew_pairs, Generated, Kernel, RefArith, Scalar};
use inputs::{shape_error, Outputs};
pub(crate) use inputs::{state_rows_mut, BodyViews, Inputs};
use num_traits::Float;
use numpy::{
    Element, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyReadonlyArray3, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use std::sync::Mutex;
use unchecked::{run_chunk, run_chunk_rows, Scratch};

/// Rows per chunk: 64 blocks of 8, whose scratch (inputs and outputs in the blocked
/// layout, 30 to 130 kB for n = 2..6 in `f64`) stays in the core's L2 cache between the
/// gather, the kernel and the scatter.
pub const CHUNK: usize = 512;

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
    Generated: BatchKernel<T, N, S> + Kernel<T::Unbounded, N, S>,
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
                    _ if validate => return run_chunk_checked(input, start, out, &pairs),
                    Some(rows) => run_chunk_rows(&exec, input, rows, start, out, scratch, &pairs),
                    None => run_chunk(&exec, input, start, out, scratch, &pairs),
                }
                Ok(())
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
    for<'x> &'x T::Unbounded: RefArith<T::Unbounded>,
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
