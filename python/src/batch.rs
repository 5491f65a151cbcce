//! `noslip.collide_batch`: the collision map on every row of NumPy arrays, by the batch
//! kernels (`collision_core::batch`: blocks of 8 contacts, the instruction set chosen at
//! run time), with the GIL released and the rows split across rayon's threads.
//!
//! The inputs are read in place (any strides, no copy of the arrays) chunk by chunk into a
//! blocked scratch batch of [`CHUNK`] rows per task, the kernels run on the scratch, and the
//! results are written into the new output arrays. Beyond the outputs, memory is that
//! scratch: about `CHUNK` x 0.5 kB per running task, whatever the number of rows.
//!
//! Each row runs the kernel [`collision_core::collide`] runs on it: `fixed` when a body is
//! immovable (`inv_mass = 0`; bodies swapped and `nu` negated when it is body 2, whose
//! state then comes back unchanged), `free` otherwise; so a row's result is
//! `collision_core::collide_unchecked`'s bit for bit. With `validate`, every row first
//! passes `collide`'s checks (`collision_core::validate_parts`, the rounding allowance
//! included), and the first bad row is an error naming the row and the field.

use crate::error::input_error;
use collision_core::batch::BatchKernel;
use collision_core::batch::{Contact, Exec, FixedBatch, FreeBatch, PairBatch, StateBatch};
use collision_core::RefArith;
use collision_core::{skew_pairs, validate_parts, Ball, BodyState, Generated, Kernel, Scalar};
use noslip_case::CaseError;
use numpy::ndarray::{ArrayView1, ArrayView2, ArrayView3};
use numpy::{
    Element, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyReadonlyArray3,
};
use pyo3::prelude::*;
use rayon::prelude::*;
use std::time::Instant;

/// Rows per task: 128 blocks of 8, the chunk the batch kernels' own threading uses.
pub const CHUNK: usize = 1024;

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
type BodyViews<'a, T> = (
    ArrayView3<'a, T>,
    ArrayView2<'a, T>,
    ArrayView1<'a, T>,
    ArrayView1<'a, T>,
    ArrayView1<'a, T>,
);

/// Every input of a batch, shapes checked.
struct Inputs<'a, T> {
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
    fn new(nu: ArrayView2<'a, T>, bodies: [BodyViews<'a, T>; 2]) -> PyResult<Self> {
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

/// A bad row: its index and the message (`row 17: bodies[1].gamma2: ...`).
type RowError = (usize, String);

/// Rows `start..start + out.velocity[0].len() / N` of the batch.
fn run_chunk<T, const N: usize, const S: usize>(
    exec: &Exec,
    input: &Inputs<'_, T>,
    validate: bool,
    start: usize,
    out: Outputs<'_, T>,
    scratch: &mut Scratch<T, N, S>,
    pairs: &[(usize, usize); S],
) -> Result<(), RowError>
where
    T: Scalar + Copy + Send + Sync,
    for<'x> &'x T: RefArith<T>,
    Generated: BatchKernel<T, N, S>,
{
    let rows = out.velocity[0].len() / N;
    let sc = scratch;
    sc.free.clear();
    sc.fixed.clear();
    sc.free_rows.clear();
    sc.fixed_rows.clear();
    let [a, b] = &input.bodies;
    for j in 0..rows {
        let i = start + j;
        let nu: [T; N] = match input.nu.as_slice() {
            Some(nu) => std::array::from_fn(|k| nu[i * N + k]),
            None => std::array::from_fn(|k| input.nu[[i, k]]),
        };
        let balls = [a.ball(i), b.ball(i)];
        let states: [BodyState<T, N, S>; 2] = [a.state(i, pairs), b.state(i, pairs)];
        if validate {
            let checked = a
                .check_skew::<N, S>(i, 0)
                .and_then(|()| b.check_skew::<N, S>(i, 1))
                .and_then(|()| {
                    validate_parts(
                        &nu,
                        [&balls[0], &balls[1]],
                        [0, 1].map(|k| (states[k].spin.as_slice(), states[k].velocity.as_slice())),
                    )
                });
            if let Err(e) = checked {
                return Err((i, format!("row {i}: {}", CaseError::from(e))));
            }
        }
        let [b1, b2] = balls;
        let [s1, s2] = states;
        if b1.is_immovable() {
            sc.fixed.push((
                Contact {
                    nu,
                    states: [s1, s2],
                },
                b1.radius,
                b2,
            ));
            sc.fixed_rows.push((j, false));
        } else if b2.is_immovable() {
            let minus_nu = nu.map(|x| -x);
            sc.fixed.push((
                Contact {
                    nu: minus_nu,
                    states: [s2, s1],
                },
                b2.radius,
                b1,
            ));
            sc.fixed_rows.push((j, true));
        } else {
            sc.free.push((
                Contact {
                    nu,
                    states: [s1, s2],
                },
                [b1, b2],
            ));
            sc.free_rows.push(j);
        }
    }
    exec.free(&sc.free, &mut sc.pairs);
    exec.fixed(&sc.fixed, &mut sc.moved);
    let Outputs {
        spin: [spin1, spin2],
        velocity: [vel1, vel2],
    } = out;
    let mut put = |j: usize, body: usize, s: &BodyState<T, N, S>| {
        let (spin, vel) = if body == 0 {
            (&mut *spin1, &mut *vel1)
        } else {
            (&mut *spin2, &mut *vel2)
        };
        write_state(
            s,
            pairs,
            &mut spin[j * N * N..(j + 1) * N * N],
            &mut vel[j * N..(j + 1) * N],
        );
    };
    for (k, &j) in sc.free_rows.iter().enumerate() {
        if let Some([p1, p2]) = sc.pairs.get(k) {
            put(j, 0, &p1);
            put(j, 1, &p2);
        }
    }
    for (k, &(j, body2_fixed)) in sc.fixed_rows.iter().enumerate() {
        let i = start + j;
        if let Some(moved) = sc.moved.get(k) {
            let (still, moving) = if body2_fixed { (1, 0) } else { (0, 1) };
            put(j, moving, &moved);
            put(j, still, &input.bodies[still].state(i, pairs));
        }
    }
    Ok(())
}

/// The whole batch, into `out` (`rows` rows), chunk by chunk; on rayon's pool when
/// `parallel` and there is more than one chunk.
fn run_all<T, const N: usize, const S: usize>(
    input: &Inputs<'_, T>,
    validate: bool,
    parallel: bool,
    out: Outputs<'_, T>,
) -> Result<(), String>
where
    T: Scalar + Copy + Send + Sync,
    for<'x> &'x T: RefArith<T>,
    Generated: BatchKernel<T, N, S>,
{
    let exec = Exec::auto().serial();
    let pairs: [(usize, usize); S] = {
        let all: Vec<(usize, usize)> = skew_pairs(N).collect();
        std::array::from_fn(|k| all[k])
    };
    let Outputs {
        spin: [s1, s2],
        velocity: [v1, v2],
    } = out;
    // A piece: consecutive chunks run on one thread with one scratch (allocated once per
    // piece, a few pieces per thread: rayon's per-split `map_init` allocated it per chunk).
    let piece = |start: usize, s1: &mut [T], s2: &mut [T], v1: &mut [T], v2: &mut [T]| {
        let mut scratch = Scratch::<T, N, S>::new((v1.len() / N).min(CHUNK));
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
                run_chunk(
                    &exec,
                    input,
                    validate,
                    start + c * CHUNK,
                    out,
                    &mut scratch,
                    &pairs,
                )
            })
    };
    let chunks = input.rows.div_ceil(CHUNK);
    let first_error = if parallel && chunks > 1 {
        let pieces = (4 * rayon::current_num_threads()).min(chunks);
        let rows = chunks.div_ceil(pieces) * CHUNK;
        s1.par_chunks_mut(rows * N * N)
            .zip(s2.par_chunks_mut(rows * N * N))
            .zip(v1.par_chunks_mut(rows * N))
            .zip(v2.par_chunks_mut(rows * N))
            .enumerate()
            .map(|(p, (((s1, s2), v1), v2))| piece(p * rows, s1, s2, v1, v2))
            .filter_map(Result::err)
            .min_by_key(|e: &RowError| e.0)
    } else {
        piece(0, s1, s2, v1, v2).err()
    };
    first_error.map_or(Ok(()), |(_, m)| Err(m))
}

/// One body's arrays as Python passes them: `angular_velocity`, `velocity`, `inv_mass`,
/// `radius`, `gamma2`.
type BodyIn<'py, T> = (
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

fn views<'a, T: Element>(b: &'a BodyIn<'_, T>) -> BodyViews<'a, T> {
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
) -> PyResult<BatchOut<'py, T>>
where
    T: Element + Scalar + Copy + Send + Sync,
    for<'x> &'x T: RefArith<T>,
{
    let input = Inputs::new(normal.as_array(), [views(&body1), views(&body2)])?;
    let (rows, n) = (input.rows, input.dim);
    // Every element of the new arrays is written below (each row's both bodies, whichever
    // kernel ran it) before Python sees them, or the arrays are dropped with the error.
    let spin = [0, 1].map(|_| unsafe { PyArray3::<T>::new(py, [rows, n, n], false) });
    let velocity = [0, 1].map(|_| unsafe { PyArray2::<T>::new(py, [rows, n], false) });
    let slice = |e: numpy::NotContiguousError| input_error(format!("internal error: {e}"));
    let [s1, s2] = &spin;
    let [v1, v2] = &velocity;
    let out = unsafe {
        Outputs {
            spin: [
                s1.as_slice_mut().map_err(slice)?,
                s2.as_slice_mut().map_err(slice)?,
            ],
            velocity: [
                v1.as_slice_mut().map_err(slice)?,
                v2.as_slice_mut().map_err(slice)?,
            ],
        }
    };
    let done = py.detach(|| {
        collision_core::with_dim!(
            n,
            |N, S| run_all::<T, N, S>(&input, validate, parallel, out),
            Err(format!("dimension {n} has no batch kernels"))
        )
    });
    done.map_err(input_error)?;
    let [s1, s2] = spin;
    let [v1, v2] = velocity;
    Ok((s1, v1, s2, v2))
}

/// `collide_batch` on `float64` arrays (see the Python docstring).
#[pyfunction]
#[pyo3(signature = (normal, body1, body2, validate, parallel))]
pub fn collide_batch_f64<'py>(
    py: Python<'py>,
    normal: PyReadonlyArray2<'py, f64>,
    body1: BodyIn<'py, f64>,
    body2: BodyIn<'py, f64>,
    validate: bool,
    parallel: bool,
) -> PyResult<BatchOut<'py, f64>> {
    collide_batch::<f64>(py, normal, body1, body2, validate, parallel)
}

/// `collide_batch` on `float32` arrays (see the Python docstring).
#[pyfunction]
#[pyo3(signature = (normal, body1, body2, validate, parallel))]
pub fn collide_batch_f32<'py>(
    py: Python<'py>,
    normal: PyReadonlyArray2<'py, f32>,
    body1: BodyIn<'py, f32>,
    body2: BodyIn<'py, f32>,
    validate: bool,
    parallel: bool,
) -> PyResult<BatchOut<'py, f32>> {
    collide_batch::<f32>(py, normal, body1, body2, validate, parallel)
}

/// The benchmark's reference: the same `float64` rows (both bodies free) built once into a
/// `FreeBatch` (not timed), then `Exec::auto().free` (the batch kernel, run-time ISA,
/// rayon threads from `PARALLEL_FROM` rows) timed `repeats` times; the seconds of each run.
#[pyfunction]
#[pyo3(signature = (normal, body1, body2, repeats))]
pub fn batch_kernel_seconds(
    py: Python<'_>,
    normal: PyReadonlyArray2<'_, f64>,
    body1: BodyIn<'_, f64>,
    body2: BodyIn<'_, f64>,
    repeats: usize,
) -> PyResult<Vec<f64>> {
    let input = Inputs::new(normal.as_array(), [views(&body1), views(&body2)])?;
    let n = input.dim;
    let seconds = py.detach(|| {
        collision_core::with_dim!(
            n,
            |N, S| time_free::<N, S>(&input, repeats),
            Err(format!("dimension {n} has no batch kernels"))
        )
    });
    seconds.map_err(input_error)
}

fn time_free<const N: usize, const S: usize>(
    input: &Inputs<'_, f64>,
    repeats: usize,
) -> Result<Vec<f64>, String>
where
    Generated: BatchKernel<f64, N, S> + Kernel<f64, N, S>,
{
    let pairs: Vec<(usize, usize)> = skew_pairs(N).collect();
    let pairs: [(usize, usize); S] = std::array::from_fn(|k| pairs[k]);
    let [a, b] = &input.bodies;
    let mut batch = FreeBatch::<f64, N, S>::with_capacity(input.rows);
    for i in 0..input.rows {
        let balls = [a.ball(i), b.ball(i)];
        if balls.iter().any(Ball::is_immovable) {
            return Err(format!(
                "row {i}: the reference times `free`: both bodies must move"
            ));
        }
        let nu: [f64; N] = std::array::from_fn(|k| input.nu[[i, k]]);
        batch.push((
            Contact {
                nu,
                states: [a.state(i, &pairs), b.state(i, &pairs)],
            },
            balls,
        ));
    }
    let exec = Exec::auto();
    let mut out = PairBatch::<f64, N, S>::new();
    exec.free::<f64, N, S>(&batch, &mut out);
    Ok((0..repeats)
        .map(|_| {
            let t = Instant::now();
            exec.free::<f64, N, S>(&batch, &mut out);
            std::hint::black_box(&out);
            t.elapsed().as_secs_f64()
        })
        .collect())
}

/// The instruction set the batch kernels run on here (`Exec::auto`): `sse2`, `avx2`, `avx512`.
#[pyfunction]
pub fn isa() -> &'static str {
    Exec::auto().isa().name()
}
