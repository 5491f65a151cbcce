//! Run code that may panic on extreme inputs and turn the panic into `None`, printing
//! nothing: the command's contract is one error line, never a panic.
//!
//! The general-n reference of collision-core panics when its `f64` Gaussian elimination
//! meets an overflow (`linalg::echelon` compares pivots with `partial_cmp(..).expect`).
//! A panic hook installed once passes every other panic on to the previous hook.

use std::cell::Cell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;

thread_local! {
    static QUIET: Cell<bool> = const { Cell::new(false) };
}

static HOOK: Once = Once::new();

/// `f()`, or `None` if it panicked (silently).
pub fn quietly<R>(f: impl FnOnce() -> R) -> Option<R> {
    HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info)
            }
        }));
    });
    let was = QUIET.with(|q| q.replace(true));
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(was));
    result.ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_none() {
        assert_eq!(quietly(|| 2 + 2), Some(4));
        assert_eq!(quietly(|| -> i32 { panic!("overflow") }), None);
    }
}
