//! Results copied into large output arrays with non-temporal (streaming) stores: written
//! straight to memory, without first reading each output line into the cache (the
//! write-allocate of ordinary stores), as `memcpy` (so `np.copyto`) writes a large copy.
//!
//! Out of cache, the ordinary stores of the scatter read every output line before writing
//! it: the outputs cost a read and a write, against one write for the copy floor, and the
//! row-major batch ran at 1.6x (n = 2) NumPy's copy of the same bytes (docs/batch.md).

/// Output bytes of a call of `Exec::free_rows` from which its results are streamed: 16 MiB,
/// half the 32 MiB L3 of the machine in docs/batch.md. Below, the outputs may still be in
/// the cache when the caller reads them, and ordinary stores keep them there.
pub const STREAM_FROM_BYTES: usize = 16 << 20;

/// `dst = src`, with non-temporal stores when `T` is moved by copying its bytes (no drop
/// glue), `dst` starts on 16 bytes and both hold a whole number of 16-byte words; else by
/// `clone_from_slice`. Call [`fence`] before the stores must be seen by another thread.
///
/// # Panics
/// If the lengths differ.
pub(super) fn stream_copy<T: Clone>(dst: &mut [T], src: &[T]) {
    assert_eq!(dst.len(), src.len());
    let bytes = std::mem::size_of_val(src);
    #[cfg(target_arch = "x86_64")]
    if !std::mem::needs_drop::<T>() && bytes % 16 == 0 && dst.as_ptr() as usize % 16 == 0 {
        use std::arch::x86_64::{__m128i, _mm_loadu_si128, _mm_stream_si128};
        let (d, s) = (
            dst.as_mut_ptr().cast::<__m128i>(),
            src.as_ptr().cast::<__m128i>(),
        );
        for k in 0..bytes / 16 {
            // SAFETY: word `k` lies within both slices (`bytes` is a multiple of 16, the
            // lengths are equal), `d` is 16-byte aligned (checked), the load is unaligned,
            // and overwriting `dst`'s values with `src`'s bytes is a copy of values without
            // drop glue (SSE2 is part of the x86-64 baseline).
            unsafe { _mm_stream_si128(d.add(k), _mm_loadu_si128(s.add(k))) }
        }
        return;
    }
    dst.clone_from_slice(src);
}

/// Orders the streaming stores before every later store (`sfence`), so that a thread that
/// sees the call return sees the results.
pub(super) fn fence() {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: `sfence` has no operands (SSE, part of the x86-64 baseline).
    unsafe {
        std::arch::x86_64::_mm_sfence()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_streamed_copy_is_a_copy_at_every_alignment_and_length() {
        let src: Vec<f64> = (0..67).map(|k| k as f64 * 0.5 - 3.0).collect();
        for start in 0..3 {
            for len in [0, 1, 2, 3, 8, 33, 64] {
                let mut dst = vec![f64::NAN; 70];
                stream_copy(&mut dst[start..start + len], &src[..len]);
                fence();
                assert_eq!(&dst[start..start + len], &src[..len]);
                assert!(dst[..start]
                    .iter()
                    .chain(&dst[start + len..])
                    .all(|x| x.is_nan()));
            }
        }
        let words: Vec<String> = (0..5).map(|k| k.to_string()).collect();
        let mut dst = vec![String::new(); 5];
        stream_copy(&mut dst, &words);
        assert_eq!(dst, words);
    }
}
