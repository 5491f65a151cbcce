//! Ctrl-C in long native loops: [`Signals`] is the hook the loops of `simulate`,
//! `lyapunov`, `orbits` and `verify` ask ("stop now?") while the GIL is released.
//!
//! Python runs its signal handlers only in the main thread and only when asked
//! (`PyErr_CheckSignals`); a native loop that never asks is deaf to Ctrl-C. The hook is
//! asked up to millions of times a second, so it counts calls and reads the clock every
//! `every` calls (see [`Signals::new`]); once [`CHECK_PERIOD`] has passed since the last look it takes
//! the GIL and runs the handlers. An exception they raise (`KeyboardInterrupt`) is kept,
//! the hook answers "stop" from then on, and the binding raises the exception once the
//! loop has returned, discarding the partial result.
//!
//! Python runs signal handlers in its main thread only, so only the thread that made the
//! hook (the one that called into the extension) looks at them; on the other threads of a
//! loop shared with rayon (`collide_batch`) the hook answers from the stop flag alone.

use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;
use std::thread::ThreadId;
use std::time::{Duration, Instant};

/// How often the signal handlers run during a long loop: 50 ms, so that Ctrl-C is
/// answered well within a second while the GIL is taken at most 20 times a second.
pub const CHECK_PERIOD: Duration = Duration::from_millis(50);

/// The hook of one native call (see the module docs).
pub struct Signals {
    every: u64,
    /// The thread that made the hook: the only one that runs the handlers.
    owner: ThreadId,
    calls: AtomicU64,
    start: Instant,
    /// Nanoseconds from `start` to the last look at the signals.
    last: AtomicU64,
    stop: AtomicBool,
    error: Mutex<Option<PyErr>>,
}

impl Signals {
    /// A hook that reads the clock every `every` calls (about `CHECK_PERIOD` / 100 of
    /// the loop's work between reads keeps the clock's cost negligible).
    pub fn new(every: u64) -> Self {
        Signals {
            every: every.max(1),
            owner: std::thread::current().id(),
            calls: AtomicU64::new(0),
            start: Instant::now(),
            last: AtomicU64::new(0),
            stop: AtomicBool::new(false),
            error: Mutex::new(None),
        }
    }

    /// Whether the loop should stop: a signal handler raised an exception, now or before.
    pub fn interrupted(&self) -> bool {
        if self.stop.load(Ordering::Relaxed) {
            return true;
        }
        if std::thread::current().id() != self.owner {
            return false;
        }
        if self.calls.fetch_add(1, Ordering::Relaxed) % self.every != 0 {
            return false;
        }
        let now = self.start.elapsed().as_nanos() as u64;
        if now - self.last.load(Ordering::Relaxed) < CHECK_PERIOD.as_nanos() as u64 {
            return false;
        }
        self.last.store(now, Ordering::Relaxed);
        if let Err(e) = Python::attach(|py| py.check_signals()) {
            if let Ok(mut slot) = self.error.lock() {
                slot.get_or_insert(e);
            }
            self.stop.store(true, Ordering::Relaxed);
            return true;
        }
        false
    }

    /// The exception a signal handler raised during the loop, if any: the caller raises it
    /// instead of returning the (partial) result.
    pub fn raised(&self) -> Option<PyErr> {
        self.error.lock().ok().and_then(|mut slot| slot.take())
    }
}
