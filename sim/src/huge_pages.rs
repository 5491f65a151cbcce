//! [`HugePages`]: a global allocator that asks Linux for transparent huge pages (2 MiB) for
//! every allocation of at least [`THRESHOLD`] bytes, and is the system allocator otherwise.
//!
//! The engine's memory at `10^6` balls is hundreds of MB of per-ball records, calendar
//! slots and cell lists, read in an order no prefetcher follows: nearly every record an
//! event touches is a cache miss, and with 4 KiB pages a TLB miss too (a 4-level page walk).
//! With 2 MiB pages the TLB covers 512 times more memory. Linux backs anonymous memory with
//! huge pages only where the process asks (`madvise(MADV_HUGEPAGE)`) when the system's
//! setting is `madvise` (`/sys/kernel/mm/transparent_hugepage/enabled`, the default of
//! several distributions); this allocator asks right after each large allocation, before its
//! pages are first touched. Where the setting is `always` it changes nothing, where it is
//! `never` the advice is ignored, and on other systems it is the system allocator.
//!
//! A binary opts in with `#[global_allocator] static ALLOC: HugePages = HugePages;` (the
//! `noslip` command, the event-loop benchmarks and, since session 58, the Python extension
//! do). The cost: with the kernel's `defrag = madvise` a fault on an advised region may
//! compact memory to find a free 2 MiB page (setup of a `10^6`-ball gas takes longer), and
//! memory is committed in 2 MiB steps (at most one extra huge page per large allocation).
//! Measured in docs/benchmarks.md ("Huge pages"; for Python, session 58).

use std::alloc::{GlobalAlloc, Layout, System};

/// Allocations of at least this many bytes (4 MiB) are advised.
pub const THRESHOLD: usize = 4 << 20;

/// The allocator (see the module docs).
#[derive(Clone, Copy, Debug, Default)]
pub struct HugePages;

/// Ask for huge pages on the 4 KiB pages that `[p, p + size)` touches; failures are ignored
/// (the memory stays on small pages).
///
/// The range is widened to whole pages, not narrowed to them: a block this large is its own
/// `mmap` (glibc puts a 16-byte header before it, so `p` is not page-aligned), and advising
/// only the block's whole pages split the mapping into two, after which glibc's `realloc`
/// could no longer `mremap` it (`EFAULT`) and copied the block instead, so that growing a
/// 286 MB cell slab briefly held a second one (docs/benchmarks.md, session 55). Advising the
/// header's page and the tail of the last page changes how they are backed, nothing else.
fn advise(p: *mut u8, size: usize) {
    #[cfg(target_os = "linux")]
    {
        const PAGE: usize = 4096;
        let start = (p as usize) / PAGE * PAGE;
        let end = (p as usize + size).next_multiple_of(PAGE);
        if !p.is_null() && end > start {
            // SAFETY: the range covers an allocation this allocator just made and the rest
            // of the pages it lies on, which are mapped (pages are mapped whole); the advice
            // changes how pages are backed, never their contents.
            unsafe {
                libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (p, size);
}

// SAFETY: every call is forwarded to `System` with the same arguments; `advise` only changes
// how the pages of a block `System` returned are backed.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if layout.size() >= THRESHOLD {
            advise(p, layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if layout.size() >= THRESHOLD {
            advise(p, layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if new_size >= THRESHOLD {
            advise(p, new_size);
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Blocks from the allocator are usable and aligned as asked, small and large, through
    /// alloc, alloc_zeroed and realloc (the contents kept).
    #[test]
    fn blocks_are_the_system_allocators() {
        let a = HugePages;
        for (size, align) in [(64, 8), (THRESHOLD, 4096), (3 * THRESHOLD + 5, 64)] {
            let layout = Layout::from_size_align(size, align).unwrap();
            unsafe {
                let p = a.alloc_zeroed(layout);
                assert!(!p.is_null() && p as usize % align == 0);
                assert!((0..size).step_by(4093).all(|k| *p.add(k) == 0));
                for k in (0..size).step_by(4093) {
                    *p.add(k) = (k % 251) as u8;
                }
                let q = a.realloc(p, layout, 2 * size);
                assert!((0..size)
                    .step_by(4093)
                    .all(|k| *q.add(k) == (k % 251) as u8));
                a.dealloc(q, Layout::from_size_align(2 * size, align).unwrap());
            }
        }
    }

    /// The mapping of `/proc/self/maps` that holds address `p`: its start and end.
    #[cfg(target_os = "linux")]
    fn mapping_of(p: usize) -> (usize, usize) {
        let maps = std::fs::read_to_string("/proc/self/maps").unwrap();
        maps.lines()
            .filter_map(|line| {
                let (start, end) = line.split_whitespace().next()?.split_once('-')?;
                let range = (
                    usize::from_str_radix(start, 16).ok()?,
                    usize::from_str_radix(end, 16).ok()?,
                );
                (range.0..range.1).contains(&p).then_some(range)
            })
            .next()
            .expect("a mapped address")
    }

    /// A large block stays one mapping after its advice (advising only its whole pages split
    /// it after glibc's header, and `realloc` then copied the block instead of moving its
    /// pages): the mapping holding its first byte holds its last, before and after a
    /// `realloc` to twice the size. Where the advice is refused (huge pages `never`, or not
    /// Linux) nothing is split and the test shows nothing; this machine's setting is printed.
    #[cfg(target_os = "linux")]
    #[test]
    fn a_large_block_stays_one_mapping() {
        let setting = std::fs::read_to_string("/sys/kernel/mm/transparent_hugepage/enabled");
        eprintln!("transparent huge pages: {setting:?}");
        let a = HugePages;
        let size = 8 * THRESHOLD + 24;
        let layout = Layout::from_size_align(size, 8).unwrap();
        unsafe {
            let p = a.alloc(layout);
            let (start, end) = mapping_of(p as usize);
            assert!(
                start <= p as usize && p as usize + size <= end,
                "split: {start:x}-{end:x}"
            );
            let q = a.realloc(p, layout, 2 * size);
            let (start, end) = mapping_of(q as usize);
            assert!(
                start <= q as usize && q as usize + 2 * size <= end,
                "split after realloc"
            );
            a.dealloc(q, Layout::from_size_align(2 * size, 8).unwrap());
        }
    }
}
