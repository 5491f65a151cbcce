//! `noslip.collide_batch`: the collision map on every row of NumPy arrays, with the GIL
//! released and the rows split across rayon's threads in runs of whole chunks (`run.rs`).
//!
//! - With `validate` (the default), each row goes through `collision_core::collide`
//!   itself (`checked.rs`): accepted or refused, and its result rounded, exactly as
//!   `noslip.collide` does it; the first bad row's error names the row and the field.
//! - Without, the batch kernels run the rows (`unchecked.rs`: blocks of 8 contacts, the
//!   instruction set chosen at run time): `collision_core::collide_unchecked`'s result bit
//!   for bit. Row-major arrays (NumPy's default) go through `Exec::free_rows`, which
//!   gathers a few blocks at a time straight from the arrays, runs them and scatters them
//!   straight into the outputs, each step compiled for the CPU's instruction set; other
//!   strides go row by row. Beyond the outputs, memory is the scratch: about `CHUNK` x
//!   0.25 kB per running thread, whatever the number of rows, kept by that thread between
//!   calls.
//!
//! With a contact law (`contact=`), `law.rs` runs the rows under the rough-ball family.
//!
//! The inputs' shapes are checked and their rows read by `inputs.rs`. The outputs are new
//! arrays, or the caller's (`out=`, `outputs.rs`: shapes and layout checked, borrowed
//! read-write, so an output sharing memory with an input or another output is refused).

mod checked;
mod fixed_law;
mod inputs;
mod law;
mod outputs;
pub mod params;
mod run;
mod unchecked;

use crate::error::input_error;
use crate::signals::Signals;
use collision_core::batch::{Exec, RestitutionRows, WaltonRows};
use collision_core::{RefArith, Scalar};
pub(crate) use inputs::{BodyViews, Inputs};
use num_traits::Float;
use numpy::{Element, PyArray2, PyArray3, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArray3};
pub(crate) use outputs::state_rows_mut;
use outputs::{borrow_out, check_out, OutIn, Outputs};
use pyo3::prelude::*;
pub(crate) use run::piece_rows;
use run::{run_all, Stop};

/// Rows per chunk: the unit of the split between threads (runs of whole chunks), of the
/// validated rows' first error, and of the scratch of the rows with an immovable body and of
/// arrays that are not row-major (64 blocks of 8, 30 to 130 kB in `f64`, in the core's L2
/// cache).
const CHUNK: usize = 512;

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
    let n = input.dim;
    into_outputs(py, &input, out, |out, fresh, interrupted| {
        collision_core::with_dim!(
            n,
            |N, S| run_all::<T, N, S>(&input, validate, parallel, fresh, out, interrupted),
            Err(Stop::Refused(format!("dimension {n} has no batch kernels")))
        )
    })
}

/// `run` on the outputs of `input` (`out`, checked, or new arrays), the GIL released; the
/// arrays, or the error `run` stopped with (a Python signal first). `run`'s second argument
/// says whether the outputs are new arrays (memory never written, which the row path writes
/// from the last rows to the first: `Exec::last_rows_first`).
fn into_outputs<'py, T>(
    py: Python<'py>,
    input: &Inputs<'_, T>,
    out: Option<OutIn<'py, T>>,
    run: impl FnOnce(Outputs<'_, T>, bool, &(dyn Fn() -> bool + Sync)) -> Result<(), Stop> + Send,
) -> PyResult<BatchOut<'py, T>>
where
    T: Element + Scalar + Send + Sync,
{
    let (rows, n) = (input.rows, input.dim);
    let fresh = out.is_none();
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
        // Asked before each run of 4096 rows (0.1-0.4 ms without validation, 5-10 ms with):
        // the clock is read every time, far below the cost of a run.
        let signals = Signals::new(1);
        let interrupted = || signals.interrupted();
        let done = py.detach(|| run(out, fresh, &interrupted));
        match (done, signals.raised()) {
            (_, Some(e)) => Err(e),
            (Err(Stop::Refused(m)), None) => Err(input_error(m)),
            (Err(Stop::Interrupted), None) => {
                Err(input_error("internal error: stopped without a signal"))
            }
            (Ok(()), None) => Ok(()),
        }
    };
    done?;
    let [s1, s2] = spin;
    let [v1, v2] = velocity;
    Ok((s1, v1, s2, v2))
}

/// `collide_batch` under a law of the rough-ball family (`law.rs`): `kind` `"rough"` with
/// the columns `[e, beta]` or `"walton"` with `[e, mu, beta0]`, each 1-D, C-contiguous, of
/// the rows' length or 1.
#[allow(clippy::too_many_arguments)]
fn collide_batch_law<'py, T>(
    py: Python<'py>,
    normal: PyReadonlyArray2<'py, T>,
    body1: BodyIn<'py, T>,
    body2: BodyIn<'py, T>,
    kind: &str,
    law: Vec<PyReadonlyArray1<'py, T>>,
    validate: bool,
    parallel: bool,
    out: Option<OutIn<'py, T>>,
) -> PyResult<BatchOut<'py, T>>
where
    T: Element + Scalar + collision_core::ScalarRoot + Float + Send + Sync + 'static,
    T::Unbounded: collision_core::ScalarRoot,
    for<'x> &'x T: RefArith<T>,
    for<'x> &'x T::Unbounded: RefArith<T::Unbounded>,
{
    let input = Inputs::new(normal.as_array(), [views(&body1), views(&body2)])?;
    let names: &[&str] = match kind {
        "rough" => &["e", "beta"],
        "walton" => &["e", "mu", "beta0"],
        _ => return Err(input_error(format!("contact: unknown law {kind:?}"))),
    };
    if law.len() != names.len() {
        return Err(input_error(format!(
            "contact: {} columns for the {kind} law, expected {}",
            law.len(),
            names.len()
        )));
    }
    let columns: Vec<&[T]> = law
        .iter()
        .zip(names)
        .map(|(c, name)| {
            c.as_slice()
                .map_err(|_| input_error(format!("contact.{name}: must be C-contiguous")))
        })
        .collect::<PyResult<_>>()?;
    let laws = match columns[..] {
        [e, beta] => inputs::LawColumns::Rough(RestitutionRows { e, beta }),
        [e, mu, beta0] => inputs::LawColumns::Walton(WaltonRows { e, mu, beta0 }),
        _ => unreachable!("two or three columns"),
    };
    let n = input.dim;
    into_outputs(py, &input, out, |out, fresh, _| {
        collision_core::with_dim!(
            n,
            |N, S| law::run_law::<T, N, S>(&input, &laws, validate, parallel, fresh, out)
                .map_err(Stop::Refused),
            Err(Stop::Refused(format!("dimension {n} has no batch kernels")))
        )
    })
}

/// ``collide_batch`` with ``contact=`` on ``float64`` arrays (see the Python docstring).
#[pyfunction]
#[pyo3(signature = (normal, body1, body2, kind, law, validate, parallel, out=None))]
#[allow(clippy::too_many_arguments)]
pub fn collide_batch_law_f64<'py>(
    py: Python<'py>,
    normal: PyReadonlyArray2<'py, f64>,
    body1: BodyIn<'py, f64>,
    body2: BodyIn<'py, f64>,
    kind: &str,
    law: Vec<PyReadonlyArray1<'py, f64>>,
    validate: bool,
    parallel: bool,
    out: Option<OutIn<'py, f64>>,
) -> PyResult<BatchOut<'py, f64>> {
    collide_batch_law::<f64>(py, normal, body1, body2, kind, law, validate, parallel, out)
}

/// ``collide_batch`` with ``contact=`` on ``float32`` arrays (see the Python docstring).
#[pyfunction]
#[pyo3(signature = (normal, body1, body2, kind, law, validate, parallel, out=None))]
#[allow(clippy::too_many_arguments)]
pub fn collide_batch_law_f32<'py>(
    py: Python<'py>,
    normal: PyReadonlyArray2<'py, f32>,
    body1: BodyIn<'py, f32>,
    body2: BodyIn<'py, f32>,
    kind: &str,
    law: Vec<PyReadonlyArray1<'py, f32>>,
    validate: bool,
    parallel: bool,
    out: Option<OutIn<'py, f32>>,
) -> PyResult<BatchOut<'py, f32>> {
    collide_batch_law::<f32>(py, normal, body1, body2, kind, law, validate, parallel, out)
}

/// ``collide_batch`` on ``float64`` arrays (see the Python docstring).
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

/// ``collide_batch`` on ``float32`` arrays (see the Python docstring).
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

/// The instruction set the batch kernels run on here (``Exec::auto``): ``sse2``, ``avx2``, ``avx512``.
#[pyfunction]
pub fn isa() -> &'static str {
    Exec::auto().isa().name()
}
