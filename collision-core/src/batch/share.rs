//! Sharing a batch between the calling thread and rayon's workers without waiting for them.
//!
//! The batch is cut into `chunks` equal runs of blocks, handed out by an atomic counter. The
//! calling thread posts one helper job per other rayon thread (`rayon::spawn`, which only
//! queues it and wakes a parked worker), then takes chunks itself until none is left; a
//! helper takes chunks from the same counter whenever it starts. So the caller never sleeps
//! on a worker that has not started: a helper that wakes late finds fewer chunks, or none,
//! and the call costs at most the serial time plus the posting. The caller then waits only
//! for the chunks a helper is running (each a short run of blocks). A helper that starts
//! after the call has returned touches nothing but the counters (module item `Shared`).
//!
//! A call through rayon's own parallel iterators from a thread outside the pool instead
//! queues the whole batch and puts the caller to sleep until the workers are done: on the
//! 2-core VM of docs/batch.md that costs 12-20 µs a call, more than a batch within the L2
//! takes on one thread.
//!
//! **Protocol.** A helper registers (`inside += 1`), then reads `closed`; the caller, once
//! the counter is spent, sets `closed`, then waits until `inside == 0`. Both orders are
//! sequentially consistent, so either the helper sees `closed` and leaves without reading a
//! block, or the caller sees it inside and waits for it; a helper's leaving (`inside -= 1`)
//! orders its writes before the caller's return. A helper leaves even if it unwinds (a drop
//! guard), and the caller waits for the helpers even while it unwinds (another), so no
//! helper outlives the borrowed blocks and no caller waits forever. The caller spins while
//! waiting (a helper inside has at most one chunk left), then yields its core after a
//! thousand rounds, in case the helper was preempted. A panic in a chunk is caught where it
//! happens, the remaining chunks are still claimed (and skipped), and the caller resumes the
//! first panic after every helper has left.

use std::any::Any;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::SeqCst};
use std::sync::{Arc, Mutex};

/// Runs `run(first, count)` for the `chunks` chunks `[k chunk, min((k + 1) chunk, len))` of
/// a batch of `len` blocks, `chunk` blocks each, on the calling thread and on up to
/// `helpers` rayon workers; returns when every chunk has run. `run` must only touch the
/// blocks of the chunk it is given (the chunks are disjoint), and must not wait on rayon
/// (`join`, `scope`, parallel iterators): a helper's caller spins, it does not run other
/// rayon jobs. `Exec` passes `threads - 1` helpers: the caller is the other thread.
pub(crate) fn share(len: usize, chunk: usize, helpers: usize, run: &(dyn Fn(usize, usize) + Sync)) {
    let chunk = chunk.max(1);
    let chunks = len.div_ceil(chunk);
    if chunks <= 1 || helpers == 0 {
        if len > 0 {
            run(0, len);
        }
        return;
    }
    // SAFETY: only the pointer's lifetime bound changes (the same fat pointer); it is
    // dereferenced only while `share` runs (`Shared::run`).
    let run = unsafe {
        std::mem::transmute::<
            *const (dyn Fn(usize, usize) + Sync + '_),
            *const (dyn Fn(usize, usize) + Sync + 'static),
        >(run)
    };
    let shared = Arc::new(Shared {
        run,
        len,
        chunk,
        chunks,
        next: AtomicUsize::new(0),
        closed: AtomicBool::new(false),
        inside: AtomicUsize::new(0),
        panic: Mutex::new(None),
    });
    let close = Close(&shared);
    for _ in 0..helpers.min(chunks - 1) {
        let helper = Arc::clone(&shared);
        rayon::spawn(move || helper.help());
    }
    shared.work();
    drop(close);
    let panic = shared
        .panic
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .take();
    if let Some(payload) = panic {
        resume_unwind(payload);
    }
}

/// Runs `run(first, arrays)` on runs of `chunk` rows of `K` row-aligned arrays, on the
/// calling thread and rayon's other threads, handed out as in the module's notes. Row `r` of
/// array `k` is `arrays[k][r w_k..(r + 1) w_k]` with `w_k = widths[k]`; the batch has
/// `min_k(arrays[k].len() / w_k)` rows (0 for `K = 0`). Each call gets, in every array, the
/// rows `[first, first + count)` of its run (`1 <= count <= max(chunk, 1)`, also with one
/// rayon thread), and every row goes to exactly one call. `run` must not wait on rayon (`join`, `scope`, parallel iterators).
///
/// This is the safe form of the split for callers outside the crate (the Python package's
/// `collide_batch` over NumPy arrays); it costs the caller no hand-over, unlike a parallel
/// iterator called from outside rayon's pool (the module's notes).
///
/// # Panics
/// If a width is 0; a panic in `run` is resumed in the caller once every helper has left.
pub fn share_rows<T: Send, const K: usize>(
    arrays: [&mut [T]; K],
    widths: [usize; K],
    chunk: usize,
    run: &(dyn Fn(usize, [&mut [T]; K]) + Sync),
) {
    assert!(widths.iter().all(|&w| w > 0), "row widths must be positive");
    let rows = (0..K)
        .map(|k| arrays[k].len() / widths[k])
        .min()
        .unwrap_or(0);
    let starts = RowStarts(arrays.map(|a| a.as_mut_ptr()));
    let starts = &starts;
    let (chunk, helpers) = (chunk.max(1), rayon::current_num_threads().saturating_sub(1));
    share(rows, chunk, helpers, &|start, len| {
        // `share` gives the whole batch at once when it has no helper: cut it here too.
        for first in (start..start + len).step_by(chunk) {
            let count = chunk.min(start + len - first);
            let arrays = std::array::from_fn(|k| {
                // SAFETY: rows `[first, first + count)` lie within array `k` (`first + count
                // <= rows <= len_k / w_k`), no other call gets them (`share` hands out
                // disjoint runs), and the arrays stay borrowed until `share` returns.
                unsafe {
                    std::slice::from_raw_parts_mut(
                        starts.0[k].add(first * widths[k]),
                        count * widths[k],
                    )
                }
            });
            run(first, arrays);
        }
    });
}

/// The arrays' starts, shared by the calls of `share_rows` (each writes its own rows).
struct RowStarts<T, const K: usize>([*mut T; K]);

// SAFETY: the calls touch disjoint rows, each from one thread, and `T: Send` lets a row be
// written from another thread.
unsafe impl<T: Send, const K: usize> Sync for RowStarts<T, K> {}

/// What the caller and its helpers share.
struct Shared {
    /// The caller's `run`, its lifetime erased. It is called only by the caller and by
    /// helpers between registering and leaving, and `Close` does not let `share` return or
    /// unwind past its frame while a helper is registered; after that it is never read.
    run: *const (dyn Fn(usize, usize) + Sync),
    len: usize,
    chunk: usize,
    chunks: usize,
    /// The next chunk to hand out.
    next: AtomicUsize,
    /// Set by the caller once every chunk is handed out: no helper may start after it.
    closed: AtomicBool,
    /// Helpers between registering and leaving.
    inside: AtomicUsize,
    /// The first panic of a chunk.
    panic: Mutex<Option<Box<dyn Any + Send>>>,
}

// SAFETY: `run` points to a `Sync` closure, called from several threads only while `share`
// keeps it alive (`Shared::run`); the rest is atomics and a mutex.
unsafe impl Send for Shared {}
// SAFETY: as above.
unsafe impl Sync for Shared {}

impl Shared {
    /// Takes chunks until none is left; a panicking chunk is recorded and the rest skipped.
    fn work(&self) {
        loop {
            let k = self.next.fetch_add(1, SeqCst);
            if k >= self.chunks {
                return;
            }
            let first = k * self.chunk;
            let count = self.chunk.min(self.len - first);
            // SAFETY: a thread working here is the caller or a registered helper of an open
            // call (`Shared::run`).
            let run = unsafe { &*self.run };
            if let Err(payload) = catch_unwind(AssertUnwindSafe(|| run(first, count))) {
                // Hand out the rest as done, and keep the first panic (a later one is
                // dropped outside the lock).
                self.next.fetch_max(self.chunks, SeqCst);
                let mut first_panic = self.panic.lock().unwrap_or_else(|e| e.into_inner());
                let later = match *first_panic {
                    None => {
                        *first_panic = Some(payload);
                        None
                    }
                    Some(_) => Some(payload),
                };
                drop(first_panic);
                drop(later);
            }
        }
    }

    /// A helper's job: register, and work unless the call is already closed; leave even if
    /// that unwinds (a caller waiting for it would wait forever).
    fn help(&self) {
        self.inside.fetch_add(1, SeqCst);
        let _leave = Leave(&self.inside);
        if !self.closed.load(SeqCst) {
            self.work();
        }
    }
}

/// A helper's leaving: `inside -= 1`, on return and on unwinding.
struct Leave<'a>(&'a AtomicUsize);

impl Drop for Leave<'_> {
    fn drop(&mut self) {
        self.0.fetch_sub(1, SeqCst);
    }
}

/// Closes the call and waits for the helpers inside it, on return and on unwinding.
struct Close<'a>(&'a Shared);

impl Drop for Close<'_> {
    fn drop(&mut self) {
        // Nothing is left to hand out once `closed` is set (a caller that unwinds has not
        // spent the counter: spend it, so that a helper inside stops after its chunk).
        self.0.next.fetch_max(self.0.chunks, SeqCst);
        self.0.closed.store(true, SeqCst);
        // A helper inside runs at most one chunk more; spin briefly, then give the core
        // away in case the helper was preempted (two threads on two cores).
        let mut spins = 0u32;
        while self.0.inside.load(SeqCst) != 0 {
            if spins < 1 << 10 {
                spins += 1;
                std::hint::spin_loop();
            } else {
                std::thread::yield_now();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicU64;

    /// A slice's start, written by the chunks of a test (each its own elements).
    struct Start(*mut u64);
    // SAFETY: the chunks write disjoint elements.
    unsafe impl Sync for Start {}

    #[test]
    fn every_block_runs_once_and_its_writes_reach_the_caller() {
        // Plain (not atomic) writes from whichever thread runs a chunk, read by the caller
        // after `share` returns: the helpers' leaving orders them before the return.
        for len in [0usize, 1, 7, 8, 9, 100, 1000] {
            for chunk in [1usize, 3, 16, 2000] {
                for helpers in [0usize, 1, 3] {
                    let mut out = vec![0u64; len];
                    let start = Start(out.as_mut_ptr());
                    let start = &start;
                    share(len, chunk, helpers, &|first, count| {
                        // One run of the whole batch without helpers, chunks otherwise.
                        assert!(helpers == 0 || count <= chunk.max(1));
                        assert!(first + count <= len);
                        for k in first..first + count {
                            // SAFETY: k < len, and no other chunk writes element k.
                            unsafe { *start.0.add(k) += k as u64 + 1 };
                        }
                    });
                    let expected: Vec<u64> = (1..=len as u64).collect();
                    assert_eq!(
                        out, expected,
                        "{len} blocks, chunk {chunk}, {helpers} helpers"
                    );
                }
            }
        }
    }

    /// `share_rows` on two arrays of widths 3 and 1 (the second longer: the batch is the
    /// shorter), written by whichever thread runs a run of rows; checked after the call.
    fn rows_once(rows: usize, chunk: usize) {
        let mut wide = vec![0u64; 3 * rows];
        let mut narrow = vec![0u64; rows + 2];
        share_rows([&mut wide, &mut narrow], [3, 1], chunk, &|first, [w, n]| {
            assert_eq!(w.len(), 3 * n.len());
            assert!(!n.is_empty() && n.len() <= chunk.max(1) && first + n.len() <= rows);
            for (r, (w, n)) in w.chunks_mut(3).zip(n.iter_mut()).enumerate() {
                let row = (first + r) as u64;
                w.iter_mut().for_each(|x| *x += 10 * row + 1);
                *n += row + 1;
            }
        });
        let want_wide: Vec<u64> = (0..rows as u64).flat_map(|r| [10 * r + 1; 3]).collect();
        let mut want_narrow: Vec<u64> = (1..=rows as u64).collect();
        want_narrow.extend([0, 0]);
        assert_eq!(wide, want_wide, "{rows} rows, chunk {chunk}");
        assert_eq!(narrow, want_narrow, "{rows} rows, chunk {chunk}");
    }

    #[test]
    fn share_rows_gives_each_row_of_every_array_once() {
        // On the global pool, and on a pool of one thread (no helper: `share` gives the
        // whole batch at once, and `share_rows` must still cut it into runs of `chunk`).
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        for rows in [0usize, 1, 5, 64, 1000] {
            for chunk in [0usize, 1, 7, 512, 5000] {
                rows_once(rows, chunk);
                one.install(|| rows_once(rows, chunk));
            }
        }
        // No arrays: no rows, no call.
        share_rows::<u64, 0>([], [], 4, &|_, _| panic!("called without rows"));
    }

    #[test]
    #[should_panic(expected = "row widths must be positive")]
    fn share_rows_refuses_a_zero_width() {
        share_rows([&mut [0u64; 4][..]], [0], 1, &|_, _| {});
    }

    #[test]
    fn a_helper_takes_chunks_when_the_caller_is_slow() {
        // 64 chunks of 1 ms each: a rayon worker wakes within that time and takes some.
        let caller = std::thread::current().id();
        let elsewhere = AtomicU64::new(0);
        share(64, 1, 1, &|_, _| {
            std::thread::sleep(std::time::Duration::from_millis(1));
            if std::thread::current().id() != caller {
                elsewhere.fetch_add(1, SeqCst);
            }
        });
        assert!(elsewhere.load(SeqCst) > 0, "no chunk ran on a helper");
    }

    /// Whether a call of the test below is running, and calls of its chunks outside one.
    static OPEN: AtomicBool = AtomicBool::new(false);
    static LATE: AtomicUsize = AtomicUsize::new(0);
    static HITS: [AtomicU64; 37] = [const { AtomicU64::new(0) }; 37];

    #[test]
    fn no_chunk_runs_after_its_call_returned() {
        // The chunk closure captures nothing (a late call would be harmless here), counts
        // its blocks in statics and any call made after its `share` returned; helpers of
        // earlier calls may still be starting during later ones.
        let chunk = |first: usize, count: usize| {
            if !OPEN.load(SeqCst) {
                LATE.fetch_add(1, SeqCst);
                return;
            }
            for hit in &HITS[first..first + count] {
                hit.fetch_add(1, SeqCst);
            }
        };
        for round in 0..2000 {
            let len = 1 + round % 37;
            for hit in &HITS {
                hit.store(0, SeqCst);
            }
            OPEN.store(true, SeqCst);
            share(len, 1, 1, &chunk);
            OPEN.store(false, SeqCst);
            assert!(
                HITS[..len].iter().all(|h| h.load(SeqCst) == 1),
                "round {round}"
            );
        }
        // Let helpers still queued run (they must find their calls closed).
        std::thread::sleep(std::time::Duration::from_millis(50));
        assert_eq!(LATE.load(SeqCst), 0);
    }

    #[test]
    fn a_panic_in_a_chunk_reaches_the_caller() {
        let ran = AtomicU64::new(0);
        let result = catch_unwind(AssertUnwindSafe(|| {
            share(64, 1, 1, &|first, _| {
                ran.fetch_add(1, SeqCst);
                if first == 5 {
                    panic!("chunk 5");
                }
            })
        }));
        let payload = result.expect_err("the panic is resumed in the caller");
        assert_eq!(payload.downcast_ref::<&str>(), Some(&"chunk 5"));
        // Chunks 0..=5 were handed out before the panic, so they ran.
        assert!(ran.load(SeqCst) >= 6 && ran.load(SeqCst) <= 64);
    }
}
