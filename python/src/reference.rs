//! The benchmark's references for `collide_batch` (python/benches/batch.py): the Rust
//! batch path and the memory floor, timed in Rust on the same `float64` rows.
//!
//! - `rows`: what a Rust program with the same row-major arrays does with
//!   `collision_core::batch` at its best: `Exec::free_rows` (a pass of a few blocks at a
//!   time gathered from the arrays, run and scattered into row-major outputs, each step
//!   compiled for the run-time ISA; split across rayon's threads, or on the calling thread
//!   when serial); no validation. The output arrays are allocated and touched once, before
//!   the timed runs, and reused: the reference of `collide_batch(..., out=)`.
//! - `rows_new`: the same into new output memory on each run, allocated as NumPy allocates
//!   a large array (`mmap`, advised for huge pages), so that it pays the first touch (the
//!   kernel's page faults and zeroing) as `collide_batch` does when it returns new arrays,
//!   and written as it writes them, from the last rows to the first
//!   (`Exec::last_rows_first`): the reference of new arrays.
//! - `steps`: the three steps a program ran before `free_rows`: chunks of 512 rows, each
//!   gathered into a `FreeBatch` (`fill_from_rows`), run by `Exec::free` and scattered
//!   (`PairBatch::write_rows`), into reused outputs.
//! - `copy`: the copy floor of any implementation on these arrays: every input element read
//!   once (summed) and every output element written once (each body's angular velocity and
//!   velocity copied from its input), in one pass, chunk by chunk, into reused outputs.
//! - `copy_new`: the same into new output memory on each run, allocated as for `rows_new`:
//!   the copy floor of a call that returns new arrays.
//! - `kernel`: `Exec::auto().free` alone (rayon threads, or serial) on the rows laid out
//!   once, untimed, in its blocked batch, into a reused output batch: the kernel without
//!   reading or writing the row-major arrays.
//!
//! Serial runs are timed in CPU time of the calling thread (`CLOCK_THREAD_CPUTIME_ID`), which a loaded machine disturbs far less than the wall
//! clock; parallel runs in wall-clock time.

use crate::batch::{piece_rows, state_rows_mut, views, BodyIn, Inputs};
use crate::error::{input_error, unsigned};
use collision_core::batch::{share_rows, BatchKernel, Exec, FreeBatch, FreeRows, PairBatch};
use collision_core::Generated;
use numpy::PyReadonlyArray2;
use pyo3::prelude::*;
use std::collections::BTreeMap;
use std::sync::Mutex;
use std::time::Instant;

/// The seconds of each run of each reference, by name (`rows`, `rows_new`, `steps`,
/// `copy`, `copy_new`, `kernel`).
type Seconds = BTreeMap<&'static str, Vec<f64>>;

/// New output memory as NumPy gets it for a large array: anonymous pages from `mmap`
/// (glibc's `malloc` above its threshold), advised for transparent huge pages
/// (`madvise(MADV_HUGEPAGE)`, as NumPy does for arrays of 4 MB and more), zero-filled by the
/// kernel at the first touch, which the timed run pays; unmapped on drop.
struct Fresh {
    ptr: *mut f64,
    len: usize,
}

impl Fresh {
    fn new(len: usize) -> Fresh {
        let bytes = (len * 8).max(1);
        // SAFETY: an anonymous private mapping of `bytes` bytes; checked for failure below.
        let ptr = unsafe {
            libc::mmap(
                std::ptr::null_mut(),
                bytes,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                -1,
                0,
            )
        };
        assert!(ptr != libc::MAP_FAILED, "mmap of {bytes} bytes failed");
        // SAFETY: `ptr..ptr + bytes` is the mapping just made. A refused advice is harmless.
        unsafe { libc::madvise(ptr, bytes, libc::MADV_HUGEPAGE) };
        Fresh {
            ptr: ptr.cast(),
            len,
        }
    }

    /// The memory as `f64`s (zero-filled pages: every element is `0.0` until written).
    fn slice(&mut self) -> &mut [f64] {
        // SAFETY: `len` f64s of a live, writable, zero-filled mapping owned by `self`.
        unsafe { std::slice::from_raw_parts_mut(self.ptr, self.len) }
    }
}

impl Drop for Fresh {
    fn drop(&mut self) {
        // SAFETY: the mapping made in `new`, unmapped once.
        unsafe { libc::munmap(self.ptr.cast(), (self.len * 8).max(1)) };
    }
}

/// Chunk `c` of the four outputs: `(c, (((spin_1, spin_2), velocity_1), velocity_2))`.
type OutChunk<'a> = (
    usize,
    (
        ((&'a mut [f64], &'a mut [f64]), &'a mut [f64]),
        &'a mut [f64],
    ),
);

/// Rows per chunk of the `rows` reference (runs of whole chunks are shared between threads).
const CHUNK: usize = 512;

/// The seconds of each of ``repeats`` runs of each reference on the same
/// ``float64`` rows (every body must move: ``inv_mass > 0``). Arrays must be C-contiguous.
/// With ``parallel`` on rayon's threads (wall clock), else on the calling thread (its CPU
/// time).
#[pyfunction]
#[pyo3(signature = (normal, body1, body2, repeats, parallel=true))]
pub fn reference_seconds(
    py: Python<'_>,
    normal: PyReadonlyArray2<'_, f64>,
    body1: BodyIn<'_, f64>,
    body2: BodyIn<'_, f64>,
    repeats: &Bound<'_, PyAny>,
    parallel: bool,
) -> PyResult<Seconds> {
    let repeats = unsigned(repeats, "repeats", 0, usize::MAX)?;
    let input = Inputs::new(normal.as_array(), [views(&body1), views(&body2)])?;
    let rows = input
        .rows()
        .ok_or_else(|| input_error("the references read C-contiguous arrays"))?;
    let n = normal.as_array().dim().1;
    let seconds = py.detach(|| {
        collision_core::with_dim!(
            n,
            |N, S| time_both::<N, S>(&rows, repeats, parallel),
            Err(format!("dimension {n} has no batch kernels"))
        )
    });
    seconds.map_err(input_error)
}

/// Every reference's seconds per run.
fn time_both<const N: usize, const S: usize>(
    rows: &FreeRows<'_, f64>,
    repeats: usize,
    parallel: bool,
) -> Result<Seconds, String>
where
    Generated: BatchKernel<f64, N, S>,
{
    let len = rows.len::<N>();
    if rows.balls.iter().any(|b| b.inv_mass.contains(&0.0)) {
        return Err("the references time `free`: every body must move".into());
    }
    let time = |f: &mut dyn FnMut()| {
        if parallel {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        } else {
            let t = thread_seconds();
            f();
            thread_seconds() - t
        }
    };
    let exec = if parallel {
        Exec::auto()
    } else {
        Exec::auto().serial()
    };
    let sizes = [len * N * N, len * N, len * N * N, len * N];
    let mut outputs = sizes.map(|k| vec![0.0; k]);
    let free_rows = |out: [&mut [f64]; 4]| {
        let [s1, v1, s2, v2] = out;
        exec.free_rows::<f64, N, S>(rows, state_rows_mut([s1, s2], [v1, v2]));
    };
    free_rows(outputs.each_mut().map(|v| v.as_mut_slice()));
    let mut seconds = Seconds::new();
    let mut timed = |name: &'static str, f: &mut dyn FnMut()| {
        let runs = (0..repeats).map(|_| time(&mut *f)).collect();
        seconds.insert(name, runs);
    };
    timed("rows", &mut || {
        free_rows(outputs.each_mut().map(|v| v.as_mut_slice()));
        std::hint::black_box(&outputs);
    });
    timed("rows_new", &mut || {
        let mut fresh = sizes.map(Fresh::new);
        let [s1, v1, s2, v2] = fresh.each_mut().map(Fresh::slice);
        // New memory, as `collide_batch` writes its new arrays (`Exec::last_rows_first`).
        exec.last_rows_first()
            .free_rows::<f64, N, S>(rows, state_rows_mut([s1, s2], [v1, v2]));
        std::hint::black_box(&fresh);
    });
    timed("steps", &mut || {
        steps_to_rows::<N, S>(rows, outputs.each_mut().map(|v| v.as_mut_slice()), parallel);
        std::hint::black_box(&outputs);
    });
    timed("copy", &mut || {
        std::hint::black_box(copy_floor::<N>(
            rows,
            outputs.each_mut().map(|v| v.as_mut_slice()),
            parallel,
        ));
        std::hint::black_box(&outputs);
    });
    timed("copy_new", &mut || {
        let mut fresh = sizes.map(Fresh::new);
        std::hint::black_box(copy_floor::<N>(
            rows,
            fresh.each_mut().map(Fresh::slice),
            parallel,
        ));
        std::hint::black_box(&fresh);
    });
    let mut batch = FreeBatch::<f64, N, S>::with_capacity(len);
    batch.fill_from_rows(rows, 0..len);
    let mut out = PairBatch::<f64, N, S>::new();
    exec.free::<f64, N, S>(&batch, &mut out);
    timed("kernel", &mut || {
        exec.free::<f64, N, S>(&batch, &mut out);
        std::hint::black_box(&out);
    });
    Ok(seconds)
}

/// CPU seconds this thread has run: `clock_gettime(CLOCK_THREAD_CPUTIME_ID)`, the clock of
/// Python's `time.thread_time` (wall-clock seconds where it fails).
fn thread_seconds() -> f64 {
    static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec to write into.
    if unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) } == 0 {
        t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
    } else {
        START.get_or_init(Instant::now).elapsed().as_secs_f64()
    }
}

/// The sum of `x` with eight accumulators: vectorised, so that summing the inputs costs no
/// more than reading them (a single running sum is one dependent add per element, 4 cycles
/// each: it made this floor 1.9x NumPy's own copy at n = 2).
fn sum(x: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let chunks = x.chunks_exact(8);
    let rest: f64 = chunks.remainder().iter().sum();
    for c in chunks {
        for (a, y) in acc.iter_mut().zip(c) {
            *a += y;
        }
    }
    acc.iter().sum::<f64>() + rest
}

/// The `copy` floor: per chunk of [`CHUNK`] rows, the sum of its normals and parameters, and
/// each body's angular velocities and velocities copied into the outputs
/// `[spin_1, velocity_1, spin_2, velocity_2]`; on rayon's threads (`parallel`) or this one.
fn copy_floor<const N: usize>(
    rows: &FreeRows<'_, f64>,
    out: [&mut [f64]; 4],
    parallel: bool,
) -> f64 {
    over_chunks::<N, _>(
        out,
        parallel,
        || (),
        |(), (c, (((s1, s2), v1), v2))| {
            let range = c * CHUNK..c * CHUNK + v1.len() / N;
            let mut total = sum(&rows.nu[range.start * N..range.end * N]);
            for b in rows.balls {
                for p in [b.inv_mass, b.radius, b.gamma2] {
                    // A shared parameter (one value) is read once.
                    let rows = if p.len() == 1 { 0..1 } else { range.clone() };
                    total += sum(&p[rows]);
                }
            }
            for (state, (spin, velocity)) in rows.states.iter().zip([(s1, v1), (s2, v2)]) {
                spin.copy_from_slice(&state.spin[range.start * N * N..range.end * N * N]);
                velocity.copy_from_slice(&state.velocity[range.start * N..range.end * N]);
            }
            total
        },
    )
}

/// The `steps` reference, into the row-major outputs `[spin_1, velocity_1, spin_2,
/// velocity_2]`, chunk by chunk on rayon's threads (`parallel`) or on this thread.
fn steps_to_rows<const N: usize, const S: usize>(
    rows: &FreeRows<'_, f64>,
    out: [&mut [f64]; 4],
    parallel: bool,
) where
    Generated: BatchKernel<f64, N, S>,
{
    let exec = Exec::auto().serial();
    let scratch = || (FreeBatch::<f64, N, S>::new(), PairBatch::<f64, N, S>::new());
    over_chunks::<N, _>(
        out,
        parallel,
        scratch,
        |(batch, pairs), (c, (((s1, s2), v1), v2))| {
            let start = c * CHUNK;
            batch.fill_from_rows(rows, start..start + v1.len() / N);
            exec.free::<f64, N, S>(batch, pairs);
            pairs.write_rows(state_rows_mut([s1, s2], [v1, v2]));
            0.0
        },
    );
}

/// `f(scratch, chunk)` over the chunks of [`CHUNK`] rows of the outputs
/// `[spin_1, velocity_1, spin_2, velocity_2]`, shared with rayon's threads (`parallel`, runs
/// of whole chunks as `collide_batch` splits them, a scratch from `init` per run) or on this
/// thread (one scratch); the sum of the results.
fn over_chunks<const N: usize, I>(
    out: [&mut [f64]; 4],
    parallel: bool,
    init: impl Fn() -> I + Send + Sync,
    f: impl Fn(&mut I, OutChunk<'_>) -> f64 + Send + Sync,
) -> f64 {
    let [s1, v1, s2, v2] = out;
    // The chunks of one run of rows, from chunk `first`, with one scratch.
    let run = |first: usize, s1: &mut [f64], s2: &mut [f64], v1: &mut [f64], v2: &mut [f64]| {
        let mut scratch = init();
        s1.chunks_mut(CHUNK * N * N)
            .zip(s2.chunks_mut(CHUNK * N * N))
            .zip(v1.chunks_mut(CHUNK * N))
            .zip(v2.chunks_mut(CHUNK * N))
            .enumerate()
            .map(|(c, chunk)| f(&mut scratch, (first + c, chunk)))
            .sum::<f64>()
    };
    if !parallel {
        return run(0, s1, s2, v1, v2);
    }
    let chunks = (v1.len() / N).div_ceil(CHUNK);
    let total = Mutex::new(0.0);
    share_rows(
        [s1, s2, v1, v2],
        [N * N, N * N, N, N],
        piece_rows(chunks, CHUNK),
        &|first, [s1, s2, v1, v2]| {
            let sum = run(first / CHUNK, s1, s2, v1, v2);
            *total.lock().unwrap_or_else(|p| p.into_inner()) += sum;
        },
    );
    total.into_inner().unwrap_or_else(|p| p.into_inner())
}
