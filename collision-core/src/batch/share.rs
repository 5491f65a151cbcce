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
//! block, or the caller sees it inside and waits for it. A panic in a chunk is caught where
//! it happens, the remaining chunks are still claimed (and skipped), and the caller resumes
//! the first panic after every helper has left; the caller waits for the helpers even while
//! it unwinds (a drop guard), so no helper outlives the borrowed blocks.

use std::any::Any;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::SeqCst};
use std::sync::{Arc, Mutex};

/// Runs `run(first, count)` for the `chunks` chunks `[k chunk, min((k + 1) chunk, len))` of
/// a batch of `len` blocks, `chunk` blocks each, on the calling thread and on up to
/// `helpers` rayon workers; returns when every chunk has run. `run` must only touch the
/// blocks of the chunk it is given (the chunks are disjoint).
pub(crate) fn share(len: usize, chunk: usize, helpers: usize, run: &(dyn Fn(usize, usize) + Sync)) {
    let chunk = chunk.max(1);
    let chunks = len.div_ceil(chunk);
    if chunks <= 1 || helpers == 0 {
        if len > 0 {
            run(0, len);
        }
        return;
    }
    // SAFETY (lifetime): the helpers reach `run` only between registering and leaving, and
    // `Close` (below) does not return, nor unwind past this frame, while one is registered.
    let run: &'static (dyn Fn(usize, usize) + Sync) = unsafe { std::mem::transmute(run) };
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

/// What the caller and its helpers share.
struct Shared {
    run: &'static (dyn Fn(usize, usize) + Sync),
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
            if let Err(payload) = catch_unwind(AssertUnwindSafe(|| (self.run)(first, count))) {
                self.panic
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .get_or_insert(payload);
                // Hand out the rest as done.
                self.next.fetch_max(self.chunks, SeqCst);
            }
        }
    }

    /// A helper's job: register, and work unless the call is already closed.
    fn help(&self) {
        self.inside.fetch_add(1, SeqCst);
        if !self.closed.load(SeqCst) {
            self.work();
        }
        self.inside.fetch_sub(1, SeqCst);
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
        while self.0.inside.load(SeqCst) != 0 {
            std::hint::spin_loop();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicU64;

    #[test]
    fn every_block_runs_once_whatever_the_chunks_and_helpers() {
        for len in [0usize, 1, 7, 8, 9, 100, 1000] {
            for chunk in [1usize, 3, 16, 2000] {
                for helpers in [0usize, 1, 3] {
                    let hits: Vec<AtomicU64> = (0..len).map(|_| AtomicU64::new(0)).collect();
                    share(len, chunk, helpers, &|first, count| {
                        // One run of the whole batch without helpers, chunks otherwise.
                        assert!(helpers == 0 || count <= chunk.max(1));
                        assert!(first + count <= len);
                        for hit in &hits[first..first + count] {
                            hit.fetch_add(1, SeqCst);
                        }
                    });
                    for (b, hit) in hits.iter().enumerate() {
                        assert_eq!(hit.load(SeqCst), 1, "block {b} of {len}, chunk {chunk}");
                    }
                }
            }
        }
    }

    #[test]
    fn many_short_calls_leave_no_helper_behind() {
        // Helpers that start after their call returned must not touch its (dropped) data:
        // each call owns a fresh vector, checked and freed right after the call.
        for round in 0..2000 {
            let len = 1 + round % 37;
            let out: Vec<AtomicU64> = (0..len).map(|_| AtomicU64::new(0)).collect();
            share(len, 1, 1, &|first, count| {
                for x in &out[first..first + count] {
                    x.fetch_add(round as u64 + 1, SeqCst);
                }
            });
            assert!(out.iter().all(|x| x.load(SeqCst) == round as u64 + 1));
        }
    }

    #[test]
    fn a_panicking_chunk_reaches_the_caller_after_the_helpers_leave() {
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
        assert!(ran.load(SeqCst) >= 6 && ran.load(SeqCst) <= 64);
    }
}
