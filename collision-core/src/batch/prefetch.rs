//! Software prefetch of the blocks ahead: out of cache, the kernels touch a block's lane
//! arrays in the order of the computation, not in address order, and the hardware
//! prefetchers alone fall behind.

/// How far ahead of the block being computed its input is prefetched, in bytes: about
/// what must be in flight to cover the memory latency at full bandwidth (~25 GB/s x ~150 ns).
pub const PREFETCH_BYTES: usize = 4096;

/// Blocks of type `B` in [`PREFETCH_BYTES`] (at least 1).
#[inline(always)]
pub const fn prefetch_distance<B>() -> usize {
    let size = std::mem::size_of::<B>();
    if size == 0 || size >= PREFETCH_BYTES {
        1
    } else {
        PREFETCH_BYTES.div_ceil(size)
    }
}

/// Ask the CPU to bring every cache line of `block` into cache (`None`: nothing). A hint:
/// no effect on results; off x86-64 it does nothing.
#[inline(always)]
pub fn prefetch<B>(block: Option<&B>) {
    #[cfg(target_arch = "x86_64")]
    if let Some(b) = block {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let p = (b as *const B).cast::<i8>();
        for offset in (0..std::mem::size_of::<B>()).step_by(64) {
            // SAFETY: `p + offset` lies within `*b`; a prefetch never faults and has no
            // architectural effect (SSE is part of the x86-64 baseline).
            unsafe { _mm_prefetch::<_MM_HINT_T0>(p.add(offset)) }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = block;
}
