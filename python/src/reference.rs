//! The benchmark's references for `collide_batch` (python/benches/batch.py): the Rust
//! batch kernel timed in Rust on the same `float64` rows, two ways.
//!
//! - `rows`: what a Rust program with the same row-major arrays does with
//!   `collision_core::batch` at its best: chunks of rows split across rayon's threads, each
//!   gathered into a `FreeBatch` (`fill_from_rows`), run by `Exec::free` (run-time ISA) and
//!   scattered into row-major output arrays (`PairBatch::write_rows`); no validation. The
//!   output arrays are allocated and touched once, before the timed runs, and reused: a
//!   Rust program can keep them, while `collide_batch` must return new arrays, whose first
//!   touch (the kernel's page faults and zeroing, about 200 bytes a contact in 3D) it pays
//!   and this reference does not. The ratio to it is the target's.
//! - `kernel`: `Exec::auto().free` alone (rayon threads) on the rows laid out once, untimed,
//!   in its blocked batch, into a reused output batch: the kernel's floor, without reading
//!   or writing the row-major arrays.

use crate::batch::{views, BodyIn, Inputs};
use crate::error::input_error;
use collision_core::batch::{BatchKernel, Exec, FreeBatch, FreeRows, PairBatch, StateRowsMut};
use collision_core::Generated;
use numpy::PyReadonlyArray2;
use pyo3::prelude::*;
use rayon::prelude::*;
use std::time::Instant;

/// Rows per rayon task of the `rows` reference.
const CHUNK: usize = 512;

/// The seconds of each of `repeats` runs of both references, `(rows, kernel)`, on the same
/// `float64` rows (every body must move: `inv_mass > 0`). Arrays must be C-contiguous.
#[pyfunction]
#[pyo3(signature = (normal, body1, body2, repeats))]
pub fn reference_seconds(
    py: Python<'_>,
    normal: PyReadonlyArray2<'_, f64>,
    body1: BodyIn<'_, f64>,
    body2: BodyIn<'_, f64>,
    repeats: usize,
) -> PyResult<(Vec<f64>, Vec<f64>)> {
    let input = Inputs::new(normal.as_array(), [views(&body1), views(&body2)])?;
    let rows = input
        .rows()
        .ok_or_else(|| input_error("the references read C-contiguous arrays"))?;
    let n = normal.as_array().dim().1;
    let seconds = py.detach(|| {
        collision_core::with_dim!(
            n,
            |N, S| time_both::<N, S>(&rows, repeats),
            Err(format!("dimension {n} has no batch kernels"))
        )
    });
    seconds.map_err(input_error)
}

/// Both references' seconds per run.
fn time_both<const N: usize, const S: usize>(
    rows: &FreeRows<'_, f64>,
    repeats: usize,
) -> Result<(Vec<f64>, Vec<f64>), String>
where
    Generated: BatchKernel<f64, N, S>,
{
    let len = rows.len::<N>();
    if rows.balls.iter().any(|b| b.inv_mass.contains(&0.0)) {
        return Err("the references time `free`: every body must move".into());
    }
    let time = |f: &mut dyn FnMut()| {
        let t = Instant::now();
        f();
        t.elapsed().as_secs_f64()
    };
    let mut outputs = [
        vec![0.0; len * N * N],
        vec![0.0; len * N],
        vec![0.0; len * N * N],
        vec![0.0; len * N],
    ];
    rows_to_rows::<N, S>(rows, &mut outputs);
    let mut rows_seconds = Vec::with_capacity(repeats);
    for _ in 0..repeats {
        rows_seconds.push(time(&mut || {
            rows_to_rows::<N, S>(rows, &mut outputs);
            std::hint::black_box(&outputs);
        }));
    }
    let exec = Exec::auto();
    let mut batch = FreeBatch::<f64, N, S>::with_capacity(len);
    batch.fill_from_rows(rows, 0..len);
    let mut out = PairBatch::<f64, N, S>::new();
    exec.free::<f64, N, S>(&batch, &mut out);
    let kernel_seconds = (0..repeats)
        .map(|_| {
            time(&mut || {
                exec.free::<f64, N, S>(&batch, &mut out);
                std::hint::black_box(&out);
            })
        })
        .collect();
    Ok((rows_seconds, kernel_seconds))
}

/// The `rows` reference, into the row-major outputs `[spin_1, velocity_1, spin_2,
/// velocity_2]`.
fn rows_to_rows<const N: usize, const S: usize>(rows: &FreeRows<'_, f64>, out: &mut [Vec<f64>; 4])
where
    Generated: BatchKernel<f64, N, S>,
{
    let exec = Exec::auto().serial();
    let [s1, v1, s2, v2] = out;
    s1.par_chunks_mut(CHUNK * N * N)
        .zip(s2.par_chunks_mut(CHUNK * N * N))
        .zip(v1.par_chunks_mut(CHUNK * N))
        .zip(v2.par_chunks_mut(CHUNK * N))
        .enumerate()
        .for_each_init(
            || (FreeBatch::<f64, N, S>::new(), PairBatch::<f64, N, S>::new()),
            |(batch, pairs), (c, (((s1, s2), v1), v2))| {
                let start = c * CHUNK;
                batch.fill_from_rows(rows, start..start + v1.len() / N);
                exec.free::<f64, N, S>(batch, pairs);
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
            },
        );
}
