//! The calendar's buckets ([`crate::queue`]): `B` unordered lists of ball indices, each kept
//! in one 64-byte block (its length and its first [`INLINE`] balls), the rest of a long list
//! in a spill list of its own.
//!
//! A bucket holds about 8 balls on average (the calendar's width is chosen so), so a list
//! longer than [`INLINE`] is rare (under 1 % of buckets for a Poisson count of mean 8), and
//! putting a ball into a bucket or taking it out reads and writes one cache line. A list of
//! its own per bucket (a `Vec`) cost two dependent loads, the list's header then its
//! elements; and a ball's index in its list, kept in the ball's record for the swap-remove,
//! made every removal write the record of the ball moved into the hole. Here a ball is found
//! by a search of its block (at most [`INLINE`] indices in one cache line), so a removal
//! touches no other ball's record. Where the balls outnumber the caches' lines, each of those
//! was a miss: the calendar's insertions and removals held 17 % of a `perf` profile's samples
//! at 10^6 balls in 3D (docs/benchmarks.md, "The calendar's buckets in blocks").
//!
//! The order within a bucket is not kept (the calendar sorts a bucket when it reaches it, on
//! a total order), so the events do not depend on it.

use collision_core::batch::prefetch;

/// Balls kept in a bucket's block: a block is its length and these, 64 bytes.
pub(crate) const INLINE: usize = 15;

/// One bucket's length and its first [`INLINE`] balls, one cache line.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Block {
    len: u32,
    balls: [u32; INLINE],
}

const EMPTY: Block = Block {
    len: 0,
    balls: [0; INLINE],
};

/// The buckets (module docs).
#[derive(Debug)]
pub(crate) struct Buckets {
    blocks: Vec<Block>,
    /// Per bucket: its balls beyond the first [`INLINE`] (empty but for long lists).
    spill: Vec<Vec<u32>>,
    /// The balls in all the buckets.
    len: usize,
}

impl Buckets {
    /// `count` empty buckets.
    pub(crate) fn new(count: usize) -> Self {
        Buckets {
            blocks: vec![EMPTY; count],
            spill: vec![Vec::new(); count],
            len: 0,
        }
    }

    /// The number of buckets.
    #[inline]
    pub(crate) fn count(&self) -> usize {
        self.blocks.len()
    }

    /// The memory of the blocks, in bytes.
    #[inline]
    pub(crate) fn bytes(&self) -> usize {
        self.blocks.len() * std::mem::size_of::<Block>()
    }

    /// The number of balls in all the buckets.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Makes them `count` buckets; every bucket must be empty.
    pub(crate) fn resize(&mut self, count: usize) {
        assert_eq!(self.len, 0, "the buckets are emptied first");
        self.blocks.resize(count, EMPTY);
        self.spill.resize_with(count, Vec::new);
    }

    /// Asks the CPU to start loading `bucket`'s block (a hint: nothing changes).
    #[inline]
    pub(crate) fn prefetch(&self, bucket: usize) {
        prefetch(self.blocks.get(bucket));
    }

    /// Puts `ball` into `bucket`.
    #[inline]
    pub(crate) fn push(&mut self, bucket: usize, ball: u32) {
        let block = &mut self.blocks[bucket];
        let len = block.len as usize;
        if len < INLINE {
            block.balls[len] = ball;
        } else {
            self.spill[bucket].push(ball);
        }
        block.len += 1;
        self.len += 1;
    }

    /// Takes `ball` out of `bucket`, where it must be: the bucket's last ball takes its
    /// place.
    #[inline]
    pub(crate) fn remove(&mut self, bucket: usize, ball: u32) {
        let block = &mut self.blocks[bucket];
        let len = block.len as usize;
        let inline = len.min(INLINE);
        let found = block.balls[..inline].iter().position(|&b| b == ball);
        let last = if len > INLINE {
            self.spill[bucket].pop()
        } else {
            Some(block.balls[len - 1])
        };
        let last = last.expect("a bucket holding a ball is not empty");
        match found {
            Some(at) => block.balls[at] = last,
            None => {
                // In the spill list (the last one already popped if it was the one).
                if last != ball {
                    let spill = &mut self.spill[bucket];
                    let at = spill
                        .iter()
                        .position(|&b| b == ball)
                        .expect("the ball is in its bucket");
                    spill[at] = last;
                }
            }
        }
        block.len -= 1;
        self.len -= 1;
    }

    /// Empties `bucket`, giving each of its balls to `take`.
    #[inline]
    pub(crate) fn drain(&mut self, bucket: usize, mut take: impl FnMut(u32)) {
        let block = &mut self.blocks[bucket];
        let len = block.len as usize;
        for &ball in &block.balls[..len.min(INLINE)] {
            take(ball);
        }
        if len > INLINE {
            for ball in self.spill[bucket].drain(..) {
                take(ball);
            }
        }
        block.len = 0;
        self.len -= len;
    }

    /// Empties every bucket, giving each ball to `take`.
    pub(crate) fn drain_all(&mut self, mut take: impl FnMut(u32)) {
        if self.len == 0 {
            return;
        }
        for bucket in 0..self.blocks.len() {
            self.drain(bucket, &mut take);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::rng::Rng;
    use std::collections::BTreeSet;

    /// Pushes, removals (inline and spilled, the last ball and others) and drains, against
    /// a set per bucket.
    #[test]
    fn buckets_hold_what_a_set_holds() {
        let mut buckets = Buckets::new(4);
        let mut model: Vec<BTreeSet<u32>> = vec![BTreeSet::new(); 4];
        let mut rng = Rng::new(0x2545_f491_4f6c_dd1d);
        let mut next = |n: u64| rng.integer(0..=n - 1);
        let mut ball = 0u32;
        for round in 0..20_000 {
            let b = next(4) as usize;
            // The lists grow far past INLINE (to about 100) in the first half of every 4000
            // rounds, and shrink to nothing in the second.
            let push = if round % 4000 < 2000 { 60 } else { 40 };
            if next(100) < push || model[b].is_empty() {
                buckets.push(b, ball);
                model[b].insert(ball);
                ball += 1;
            } else {
                let held: Vec<u32> = model[b].iter().copied().collect();
                let gone = held[next(held.len() as u64) as usize];
                buckets.remove(b, gone);
                model[b].remove(&gone);
            }
            if round % 7000 == 6999 {
                let mut got = BTreeSet::new();
                buckets.drain(b, |x| assert!(got.insert(x)));
                assert_eq!(got, std::mem::take(&mut model[b]));
            }
            assert_eq!(
                buckets.len(),
                model.iter().map(BTreeSet::len).sum::<usize>()
            );
        }
        for (b, want) in model.iter().enumerate() {
            let mut got = BTreeSet::new();
            buckets.drain(b, |x| assert!(got.insert(x)));
            assert_eq!(&got, want, "bucket {b}");
        }
        assert_eq!(buckets.len(), 0);
        buckets.resize(8);
        assert_eq!(buckets.count(), 8);
    }

    #[test]
    fn a_block_is_one_cache_line() {
        assert_eq!(std::mem::size_of::<Block>(), 64);
        assert_eq!(std::mem::align_of::<Block>(), 64);
    }
}
