//! The whole batch, chunk by chunk ([`CHUNK`](super::CHUNK) rows), on the calling thread or shared with
//! rayon's threads in runs of whole chunks (`collision_core::batch::share_rows`); each run
//! validated row by row (`checked.rs`), or run by the batch kernels (`unchecked.rs`: straight
//! from row-major arrays, or row by row from others).

use super::checked::{run_chunk_checked, RowError};
use super::inputs::Inputs;
use super::outputs::Outputs;
use super::unchecked::{run_chunk, run_rows, Scratch};
use super::CHUNK;
use collision_core::batch::{share_rows, BatchKernel, Exec};
use collision_core::{skew_pairs, Generated, Kernel, RefArith, Scalar};
use num_traits::Float;
use std::sync::Mutex;

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

/// The chunks in a run of the serial path for row-major arrays without validation: 64
/// chunks (32768 rows, 0.5-3.5 ms at n = 2..6). `Exec::free_rows` picks its passes by the
/// size of its call, and a run of [`RUN_CHUNKS`] chunks at n = 2 (1 MiB of rows) took the
/// short passes meant for arrays in cache: out of cache (10^6 rows, one thread) that cost
/// 1.26x the one call of the Rust reference on the same arrays (docs/python.md).
const ROW_RUN_CHUNKS: usize = 64;

/// Output bytes from which results are streamed past the caches
/// ([`Exec::streamed_results`]), into `out=` arrays and new ones alike: 16 MiB, half the L3
/// cache of the AVX-512 host measured. Below it the caller may well read the results from
/// the cache; above it they leave the caches anyway, and ordinary stores read each output
/// line before writing it (docs/python.md, "Figures").
pub(super) const STREAM_FROM_BYTES: usize = 16 << 20;

/// `exec` for the row path on `rows` rows of `T` at dimension `N`: passes from the last
/// rows to the first into new memory (`fresh`), and results streamed from
/// [`STREAM_FROM_BYTES`] of outputs (two states of `n^2 + n` values a row). Both apply to
/// large new arrays: where the stream applies (AVX-512, n = 2 and 3) it writes them in
/// 0.93-0.96x the time of the backward passes alone, and elsewhere the backward passes
/// remain (docs/python.md, "Figures").
pub(super) fn row_exec<T, const N: usize>(exec: Exec, fresh: bool, rows: usize) -> Exec {
    let out_bytes = std::mem::size_of::<T>() * 2 * rows * (N * N + N);
    let exec = if fresh { exec.last_rows_first() } else { exec };
    if out_bytes >= STREAM_FROM_BYTES {
        exec.streamed_results()
    } else {
        exec
    }
}

/// Why a batch stopped before its last row.
#[derive(Debug, PartialEq)]
pub(super) enum Stop {
    /// A row was refused: the message names the row and the field.
    Refused(String),
    /// `interrupted()` answered true (Ctrl-C): the rows of the runs not yet started are
    /// left as they were.
    Interrupted,
}

/// The whole batch, into `out` (`rows` rows), chunk by chunk; shared with rayon's threads
/// when `parallel` and there is more than one chunk. `interrupted()` is asked before each run
/// of at most [`RUN_CHUNKS`] chunks (0.1-0.4 ms of work; [`ROW_RUN_CHUNKS`], 0.5-3.5 ms, on
/// the serial path of row-major arrays without validation); once it
/// answers true the runs not yet started are skipped.
///
/// `fresh`: `out` is new memory, never written. Row-major arrays without validation are then
/// written from the last rows to the first (the runs of the serial path in reverse, and each
/// run's passes, [`Exec::last_rows_first`]): the kernel zeroes each huge page at its first
/// write from start to end, so its end is what the cache holds (docs/benchmarks.md, session
/// 52). The results are the same; only the order of the rows' writes changes.
pub(super) fn run_all<T, const N: usize, const S: usize>(
    input: &Inputs<'_, T>,
    validate: bool,
    parallel: bool,
    fresh: bool,
    out: Outputs<'_, T>,
    interrupted: &(dyn Fn() -> bool + Sync),
) -> Result<(), Stop>
where
    T: Scalar + Float + Send + Sync,
    for<'x> &'x T: RefArith<T>,
    Generated: BatchKernel<T, N, S> + Kernel<T::Unbounded, N, S>,
{
    let pairs: [(usize, usize); S] = {
        let all: Vec<(usize, usize)> = skew_pairs(N).collect();
        std::array::from_fn(|k| all[k])
    };
    let rows = input.rows();
    let exec = if validate || rows.is_none() {
        Exec::auto().serial()
    } else {
        row_exec::<T, N>(Exec::auto().serial(), fresh, out.velocity[0].len() / N)
    };
    // The runs go in reverse exactly when their passes do (new memory, the row path).
    let backward = exec.is_backward();
    let Outputs {
        spin: [s1, s2],
        velocity: [v1, v2],
    } = out;
    // A piece: consecutive chunks run on one thread with one scratch. Row-major arrays
    // without validation go through the batch kernels in one call (`run_rows`), the others
    // chunk by chunk.
    let piece = |start: usize,
                 scratch: &mut Scratch<T, N, S>,
                 s1: &mut [T],
                 s2: &mut [T],
                 v1: &mut [T],
                 v2: &mut [T]| {
        if let (false, Some(rows)) = (validate, &rows) {
            let out = Outputs {
                spin: [s1, s2],
                velocity: [v1, v2],
            };
            run_rows(&exec, input, rows, start, out, scratch, &pairs);
            return Ok(());
        }
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
                if validate {
                    return run_chunk_checked(input, start, out, &pairs);
                }
                run_chunk(&exec, input, start, out, scratch, &pairs);
                Ok(())
            })
    };
    let chunks = input.rows.div_ceil(CHUNK);
    let stopped = std::sync::atomic::AtomicBool::new(false);
    let go_on = || {
        let stop = interrupted();
        if stop {
            stopped.store(true, std::sync::atomic::Ordering::Relaxed);
        }
        !stop
    };
    let first_error = if parallel && chunks > 1 {
        // Runs of whole chunks, a few per thread, shared between this thread and rayon's
        // others without handing the batch over (`share_rows`); the first row's error wins.
        let first_error = Mutex::new(None::<RowError>);
        share_rows(
            [s1, s2, v1, v2],
            [N * N, N * N, N, N],
            piece_rows(chunks, CHUNK),
            &|first, [s1, s2, v1, v2]| {
                if !go_on() {
                    return;
                }
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
        // The same runs, one after the other on this thread.
        let run_chunks = match (validate, &rows) {
            (false, Some(_)) => ROW_RUN_CHUNKS,
            _ => RUN_CHUNKS,
        };
        let run_rows = run_chunks * CHUNK;
        let mut scratch = Scratch::<T, N, S>::take();
        let mut runs: Vec<_> = s1
            .chunks_mut(run_rows * N * N)
            .zip(s2.chunks_mut(run_rows * N * N))
            .zip(v1.chunks_mut(run_rows * N))
            .zip(v2.chunks_mut(run_rows * N))
            .enumerate()
            .collect();
        if backward {
            runs.reverse();
        }
        let result = runs
            .into_iter()
            .take_while(|_| go_on())
            .try_for_each(|(r, run)| {
                let (((s1, s2), v1), v2) = run;
                piece(r * run_rows, &mut scratch, s1, s2, v1, v2)
            });
        scratch.give_back();
        result.err()
    };
    match first_error {
        Some((_, m)) => Err(Stop::Refused(m)),
        None if stopped.into_inner() => Err(Stop::Interrupted),
        None => Ok(()),
    }
}
