//! Scratch memory kept by each thread between calls: [`Kept::take`] returns this thread's
//! kept value of a type (or a new one), and dropping the [`Kept`] keeps it again, the most
//! recently used last, at most [`KEPT_MOST`] values per thread.
//!
//! A scratch allocated by each call and freed at its end goes back to the system when it is
//! large (glibc unmaps or trims it), so its pages fault in again on every call: a 64 KiB
//! scratch per call of `Exec::free_rows` on 512 contacts made the call 2x slower
//! (docs/batch.md). Per thread, so that a scratch stays in the cache of the core that last
//! used it, and rayon's workers live as long as the process.

use std::any::Any;
use std::cell::RefCell;
use std::ops::{Deref, DerefMut};

/// At most this many values are kept per thread (one per type: `f32`, `f64` and
/// n = 2..6 make ten).
pub(crate) const KEPT_MOST: usize = 10;

thread_local! {
    /// This thread's kept values, of any type, the most recently used last.
    static KEPT: RefCell<Vec<Box<dyn Any>>> = const { RefCell::new(Vec::new()) };
}

/// A value of type `X` taken from this thread's kept values, kept again when dropped.
pub(crate) struct Kept<X: 'static> {
    value: Option<Box<X>>,
}

impl<X: Default + 'static> Kept<X> {
    /// This thread's kept `X`, or `X::default()`.
    pub(crate) fn take() -> Self {
        let kept = KEPT
            .try_with(|kept| {
                let mut kept = kept.borrow_mut();
                let i = kept.iter().rposition(|x| x.is::<X>())?;
                kept.remove(i).downcast::<X>().ok()
            })
            .ok()
            .flatten();
        Kept {
            value: Some(kept.unwrap_or_default()),
        }
    }
}

impl<X: 'static> Deref for Kept<X> {
    type Target = X;
    fn deref(&self) -> &X {
        self.value.as_deref().expect("a value until dropped")
    }
}

impl<X: 'static> DerefMut for Kept<X> {
    fn deref_mut(&mut self) -> &mut X {
        self.value.as_deref_mut().expect("a value until dropped")
    }
}

impl<X: 'static> Drop for Kept<X> {
    fn drop(&mut self) {
        if let Some(value) = self.value.take() {
            // During the thread's teardown the value is simply freed.
            let _ = KEPT.try_with(|kept| {
                let mut kept = kept.borrow_mut();
                if kept.len() >= KEPT_MOST {
                    kept.remove(0);
                }
                kept.push(value);
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_is_kept_by_its_thread_by_type() {
        {
            let mut a = Kept::<Vec<u8>>::take();
            assert!(a.is_empty());
            a.extend([1, 2, 3]);
            let b = Kept::<Vec<u16>>::take();
            assert!(b.is_empty());
        }
        assert_eq!(*Kept::<Vec<u8>>::take(), [1, 2, 3]);
        // Another thread has its own.
        std::thread::spawn(|| assert!(Kept::<Vec<u8>>::take().is_empty()))
            .join()
            .expect("joined");
        // At most `KEPT_MOST` values: the least recently used goes.
        macro_rules! fill {
            ($($t:ty),*) => {$(
                Kept::<Vec<$t>>::take().push(Default::default());
            )*};
        }
        fill!(i8, i16, i32, i64, i128, u32, u64, u128, f32, f64);
        assert!(Kept::<Vec<u8>>::take().is_empty());
    }
}
