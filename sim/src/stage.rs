//! The calendar's changes to its buckets held back a few events ([`crate::queue`]).
//!
//! Where the buckets outgrow the caches (a block of 64 bytes for every two balls: 1 MiB from
//! `2^14 + 1` balls on, 32 MiB at `10^6`), putting a ball into its bucket or taking it out
//! starts with a miss on the bucket's block, and the change waits for it: at `10^6` balls in
//! 3D the first load of a block held 9 % of a `perf` profile's samples. A change is known before it is needed,
//! though: a bucket is read only when the calendar reaches it. So the calendar asks the CPU
//! to load the block and keeps the change here, a ring of [`STAGED`] changes in the order
//! they came; a change reaches its block when the ring is full and it is the oldest (its
//! block asked for [`STAGED`] changes, a few events, before), or when the calendar reaches
//! its bucket, or when every change is flushed (a re-basing, a jump over empty buckets).
//!
//! Changes reach their blocks in the order they came, so a ball taken out of a bucket and
//! put back into it leaves the block as the changes one by one would. A staged insertion
//! that is cancelled (the ball's event changes again first) becomes a hole and never reaches
//! its block. What the calendar pops is unchanged: a bucket is read only after every change
//! to it has reached it.

/// The changes held back: a few events' worth (an event sets the times of one or two balls,
/// each a removal from one bucket and an insertion into another).
pub(crate) const STAGED: usize = 32;

/// A change to a bucket's block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Change {
    /// The bucket `b = floor(t / delta)`, not yet reduced mod `B`.
    pub bucket: u64,
    /// The ball, or [`HOLE`] for a cancelled insertion.
    pub ball: u32,
    /// An insertion (else a removal).
    pub insert: bool,
}

/// A cancelled change's ball.
const HOLE: u32 = u32::MAX;

/// The ring of changes held back (module docs).
#[derive(Debug)]
pub(crate) struct Stage {
    ring: [Change; STAGED],
    /// The oldest change's index.
    head: usize,
    /// The changes held, holes included.
    len: usize,
    /// The insertions held, holes excluded.
    inserts: usize,
    /// The removals held.
    removes: usize,
}

impl Default for Stage {
    fn default() -> Self {
        Stage {
            ring: [Change {
                bucket: 0,
                ball: HOLE,
                insert: false,
            }; STAGED],
            head: 0,
            len: 0,
            inserts: 0,
            removes: 0,
        }
    }
}

impl Stage {
    /// Holds `change`, returning its index in the ring and, if the ring was full, the oldest
    /// change, which must now reach its block (`None` if it was a hole).
    #[inline]
    pub(crate) fn push(&mut self, change: Change) -> (u32, Option<Change>) {
        let evicted = if self.len == STAGED {
            self.pop_oldest()
        } else {
            None
        };
        let at = (self.head + self.len) % STAGED;
        self.ring[at] = change;
        self.len += 1;
        self.count(change, true);
        (at as u32, evicted)
    }

    /// The oldest change, out of the ring (`None` for a hole; the ring must not be empty).
    #[inline]
    fn pop_oldest(&mut self) -> Option<Change> {
        let change = self.ring[self.head];
        self.head = (self.head + 1) % STAGED;
        self.len -= 1;
        (change.ball != HOLE).then(|| {
            self.count(change, false);
            change
        })
    }

    /// Counts `change` in (`held`) or out of the counts of held insertions and removals.
    #[inline]
    fn count(&mut self, change: Change, held: bool) {
        let n = if change.insert {
            &mut self.inserts
        } else {
            &mut self.removes
        };
        if held {
            *n += 1;
        } else {
            *n -= 1;
        }
    }

    /// The bucket of the insertion held at `at` (from [`Stage::push`]).
    #[inline]
    pub(crate) fn bucket(&self, at: u32) -> u64 {
        self.ring[at as usize].bucket
    }

    /// Cancels the insertion held at `at`: it never reaches its block.
    #[inline]
    pub(crate) fn cancel(&mut self, at: u32) {
        let change = &mut self.ring[at as usize];
        debug_assert!(change.insert && change.ball != HOLE, "a held insertion");
        change.ball = HOLE;
        self.inserts -= 1;
        self.drop_holes();
    }

    /// Frees the holes at the ring's head.
    #[inline]
    fn drop_holes(&mut self) {
        while self.len > 0 && self.ring[self.head].ball == HOLE {
            self.head = (self.head + 1) % STAGED;
            self.len -= 1;
        }
    }

    /// Gives `apply` every change to `bucket`, in the order they came, and lets them go.
    #[inline]
    pub(crate) fn take(&mut self, bucket: u64, mut apply: impl FnMut(Change)) {
        for k in 0..self.len {
            let at = (self.head + k) % STAGED;
            let change = self.ring[at];
            if change.ball != HOLE && change.bucket == bucket {
                self.count(change, false);
                self.ring[at].ball = HOLE;
                apply(change);
            }
        }
        self.drop_holes();
    }

    /// Gives `apply` every change, in the order they came, and empties the ring.
    pub(crate) fn flush(&mut self, mut apply: impl FnMut(Change)) {
        while self.len > 0 {
            if let Some(change) = self.pop_oldest() {
                apply(change);
            }
        }
    }

    /// Balls the held changes add to the buckets (insertions less removals).
    #[inline]
    pub(crate) fn net(&self) -> isize {
        self.inserts as isize - self.removes as isize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::rng::Rng;

    fn below(rng: &mut Rng, n: usize) -> usize {
        rng.integer(0..=n as u64 - 1) as usize
    }

    /// Pushes, cancellations, takes and flushes against a plain list of the changes held:
    /// every change comes out once (unless cancelled), in the order it came, and the counts
    /// agree.
    #[test]
    fn changes_come_out_once_in_their_order() {
        let mut stage = Stage::default();
        // The changes held, in order, with their indices in the ring.
        let mut model: Vec<(u32, Change)> = Vec::new();
        let mut rng = Rng::new(7);
        for ball in 0..20_000 {
            match below(&mut rng, 8) {
                0..=3 => {
                    let change = Change {
                        bucket: below(&mut rng, 5) as u64,
                        ball,
                        insert: below(&mut rng, 2) == 0,
                    };
                    let full = stage.len == STAGED;
                    let (at, evicted) = stage.push(change);
                    if let Some(oldest) = evicted {
                        assert!(full, "a change comes out only of a full ring");
                        assert_eq!(model.remove(0).1, oldest, "the oldest first");
                    }
                    model.push((at, change));
                }
                4 => {
                    let inserts: Vec<usize> =
                        (0..model.len()).filter(|&k| model[k].1.insert).collect();
                    if !inserts.is_empty() {
                        let (at, change) = model.remove(inserts[below(&mut rng, inserts.len())]);
                        assert_eq!(stage.bucket(at), change.bucket);
                        stage.cancel(at);
                    }
                }
                5 | 6 => {
                    let bucket = below(&mut rng, 5) as u64;
                    let mut got = Vec::new();
                    stage.take(bucket, |c| got.push(c));
                    let want: Vec<Change> = model
                        .iter()
                        .map(|&(_, c)| c)
                        .filter(|c| c.bucket == bucket)
                        .collect();
                    model.retain(|&(_, c)| c.bucket != bucket);
                    assert_eq!(got, want);
                }
                _ => {
                    let mut got = Vec::new();
                    stage.flush(|c| got.push(c));
                    let want: Vec<Change> = model.drain(..).map(|(_, c)| c).collect();
                    assert_eq!(got, want);
                }
            }
            assert!(model.len() <= stage.len && stage.len <= STAGED);
            let inserts = model.iter().filter(|(_, c)| c.insert).count() as isize;
            assert_eq!(stage.net(), 2 * inserts - model.len() as isize);
        }
    }
}
