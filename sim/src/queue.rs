//! The event queue: one pending event per ball, in a calendar (Paul, J. Comput. Phys. 221,
//! 615 (2007); Smallenburg, Eur. Phys. J. E 45, 22 (2022)).
//!
//! Ball `i`'s pending event has a time `t_i >= 0` (on the engine's local clock) and a bucket
//! `b_i = floor(t_i / delta)`. The calendar keeps a current bucket `c` and:
//! - every ball with `b_i <= c` in one list sorted on `(t_i, key_i, i)` (the key orders the
//!   events of one time, [`crate::canonical`]), each entry with a copy of `t_i`;
//! - every ball with `c < b_i < c + B` in bucket `b_i mod B`, an unordered list (`B`, a power
//!   of two, the number of buckets);
//! - every later ball in an overflow list, moved into the buckets each time `c` reaches a
//!   multiple of `B` (before it can reach their bucket).
//!
//! Since `t < t'` implies `b <= b'`, the sorted list's first `(t_i, key_i, i)` is the least
//! over all balls: the pop order is exactly that order, whatever `delta` and `B`
//! (deterministic). When the list is empty the next bucket is loaded into it and sorted once
//! (or, if every bucket is empty, `c` jumps to the overflow's earliest bucket).
//!
//! **Costs.** Setting or removing a ball's event is `O(1)` in a bucket (one cache line, the
//! ball found by a search of it: [`crate::buckets`]) or the overflow (a swap-remove; each
//! ball there knows its place), and in place (its time written, nothing moved)
//! when the new time stays in the same bucket or in the overflow. The earliest event leaves
//! the sorted list by one step of its start (`head`), moving nothing; another ball leaves or
//! enters it by moving the shorter side of the list by one (a binary search for an entry's
//! place), `O(h)` for `h` balls in it, against `O(log h)` in the binary heap this list
//! replaced (issue 30, session 40: 4 % fewer instructions at `phi` 0.1 in 3D, 7 % in 2D;
//! docs/benchmarks.md, "The calendar"). With `delta` chosen at each [`Calendar::rebuild`] so
//! that a bucket holds a few events on average (8) and `B delta` spans several times the
//! mean time to the next event, `h` is a few and the overflow small: the cost per event does
//! not grow with the number of balls. A bucket that holds many balls (events bunched far
//! more than at the last rebuild) makes the list's insertions `O(h)` each until the next
//! rebuild. Re-predicting every ball (the start, a re-basing) goes through
//! [`Calendar::open`]: the new times are kept unordered and placed once by the rebuild.
//! Nothing is allocated once the lists have grown.
//!
//! **Held back.** Where the buckets outgrow the caches ([`STAGE_FROM_BYTES`]), a change to a
//! bucket (a ball put in or taken out) is held back a few events while its block is loaded
//! ([`crate::stage`]); the changes to a bucket reach it, in their order, before the calendar
//! reads it, so the pop order is the same.

use crate::buckets::Buckets;
use crate::canonical::{order, Key};
use crate::stage::{Change, Stage};

/// The size of the buckets' blocks from which their changes are held back ([`crate::stage`]):
/// 1 MiB (`2^14` buckets, from `2^14 + 1` pending events on), a core's L2 cache on the hosts
/// measured.
/// Below it the blocks stay cached and holding back costs more than it saves
/// (docs/benchmarks.md, "The calendar's changes held back").
const STAGE_FROM_BYTES: usize = 1 << 20;

/// What ball `i` will meet.
#[derive(Clone, Copy, Debug)]
pub(crate) enum What<const N: usize> {
    /// Ball `j` as of `j`'s counter `count`, at image `image`: box lengths on periodic axes,
    /// in the owner's record coordinates (`crate::canonical`).
    Ball {
        j: u32,
        count: u32,
        image: [i16; N],
    },
    /// Obstacle `o` at image `image` (box lengths, in the owner's record coordinates).
    Obstacle {
        o: u32,
        image: [i16; N],
    },
    Wall {
        axis: u8,
        upper: bool,
    },
    /// Boundary `b` of the table (it never moves).
    Boundary {
        b: u32,
    },
    /// The boundary of its cell along `axis`, moving `up` or down.
    Cell {
        axis: u8,
        up: bool,
    },
}

/// Where a ball's pending event is kept.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Place {
    /// No pending event.
    None,
    /// At this index of the current bucket's sorted list.
    Now(u32),
    /// In its bucket (`b_i mod B`; [`crate::buckets`]).
    Bucket,
    /// On its way to its bucket: the insertion held back at this index ([`crate::stage`]).
    Staged(u32),
    /// At this index of the overflow list.
    Overflow(u32),
}

/// A ball's pending time `t_i` and where its event is kept: 16 bytes, held in the ball's
/// own record by the calendar's owner ([`Slots`]), so that an event reads one record.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Slot {
    time: f64,
    place: Place,
}

impl Slot {
    /// No pending event.
    pub(crate) const EMPTY: Slot = Slot {
        time: f64::INFINITY,
        place: Place::None,
    };
}

/// The balls' slots and their events' keys, kept by the calendar's owner (the engine keeps
/// each slot in its ball's record, beside what the event is): the calendar orders balls by
/// `(t_i, key_i, i)` and reads `key_i` only when two times are equal.
pub(crate) trait Slots {
    /// Ball `ball`'s slot.
    fn slot(&self, ball: usize) -> &Slot;
    /// Ball `ball`'s slot, to change.
    fn slot_mut(&mut self, ball: usize) -> &mut Slot;
    /// The key of ball `ball`'s pending event ([`crate::canonical::key`]).
    fn key(&self, ball: usize) -> Key;
}

/// A ball of the current bucket with its pending time `t_i` (a copy of its slot's), so that
/// ordering them reads the list alone and a ball's record only when two times tie.
#[derive(Clone, Copy, Debug)]
struct Entry {
    time: f64,
    ball: u32,
}

/// The calendar of pending events, one per ball (module docs). It holds the order (the
/// current bucket's sorted list, the buckets, the overflow); the slots are its owner's
/// ([`Slots`]), passed to every call.
#[derive(Debug)]
pub(crate) struct Calendar {
    /// Balls with `b_i <= current` at `now[head..]`, sorted on `(t_i, key_i, i)`; the popped
    /// prefix `now[..head]` is dropped when the list empties.
    now: Vec<Entry>,
    /// The first pending entry of `now`.
    head: usize,
    /// Balls with `current < b_i < current + B`, in bucket `b_i mod B`.
    buckets: Buckets,
    overflow: Vec<u32>,
    /// The current bucket `c`.
    current: u64,
    /// `1 / delta`.
    inv_width: f64,
    /// A scratch list (no allocation per event).
    scratch: Vec<u32>,
    /// Between [`Calendar::open`] and [`Calendar::rebuild`]: every event goes to the
    /// overflow, to be placed once by the rebuild.
    filling: bool,
    /// The changes to the buckets held back, if `staging` ([`crate::stage`]).
    stage: Stage,
    /// Whether changes to the buckets are held back: chosen at each rebuild by the blocks'
    /// size ([`STAGE_FROM_BYTES`]), unless `forced`.
    staging: bool,
    /// Staging on or off whatever the size (tests).
    forced: Option<bool>,
}

impl Calendar {
    /// An empty calendar (every slot [`Slot::EMPTY`]).
    pub(crate) fn new() -> Self {
        Calendar {
            now: Vec::new(),
            head: 0,
            buckets: Buckets::new(1),
            overflow: Vec::new(),
            current: 0,
            inv_width: 1.0,
            scratch: Vec::new(),
            filling: false,
            stage: Stage::default(),
            staging: false,
            forced: None,
        }
    }

    /// Holds back the changes to the buckets (`Some(true)`) or not (`Some(false)`) whatever
    /// their size, or as the size decides (`None`): a test of both ways on small setups.
    #[cfg(test)]
    pub(crate) fn force_staging(&mut self, slots: &mut (impl Slots + ?Sized), on: Option<bool>) {
        self.flush_stage(slots);
        self.forced = on;
        self.staging = on.unwrap_or(self.staging);
    }

    /// Every held change reaches its block, in their order.
    fn flush_stage(&mut self, slots: &mut (impl Slots + ?Sized)) {
        let mask = self.mask();
        let buckets = &mut self.buckets;
        self.stage
            .flush(|change| apply(buckets, mask, slots, change));
    }

    /// Holds `change` back ([`crate::stage`]), its block asked for; the oldest held change
    /// reaches its block if the ring was full. Returns its index in the ring.
    #[inline]
    fn hold(&mut self, slots: &mut (impl Slots + ?Sized), change: Change) -> u32 {
        let mask = self.mask();
        self.buckets.prefetch((change.bucket & mask) as usize);
        let (at, oldest) = self.stage.push(change);
        if let Some(oldest) = oldest {
            apply(&mut self.buckets, mask, slots, oldest);
        }
        at
    }

    /// Opens the calendar for a refill, every ball re-predicted before the next
    /// [`Calendar::rebuild`]: until then the pending events are kept unordered (in the
    /// overflow), so that the refill is `O(1)` a ball whatever the clock did meanwhile.
    pub(crate) fn open(&mut self, slots: &mut (impl Slots + ?Sized)) {
        self.flush_stage(slots);
        self.overflow
            .extend(self.now[self.head..].iter().map(|e| e.ball));
        self.now.clear();
        self.head = 0;
        let overflow = &mut self.overflow;
        self.buckets.drain_all(|ball| overflow.push(ball));
        for (k, &ball) in self.overflow.iter().enumerate() {
            slots.slot_mut(ball as usize).place = Place::Overflow(k as u32);
        }
        self.filling = true;
    }

    /// The number of balls with a pending event.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        let buckets = self.buckets.len() as isize + self.stage.net();
        self.now.len() - self.head + buckets as usize + self.overflow.len()
    }

    fn mask(&self) -> u64 {
        self.buckets.count() as u64 - 1
    }

    /// `b = floor(t / delta)` (saturating at `2^63 - 1`; 0 for `t <= 0`): a cast to a
    /// signed integer, a few instructions fewer than to an unsigned one; `t < t'` still
    /// implies `b <= b'`.
    #[inline]
    fn bucket(&self, t: f64) -> u64 {
        (t * self.inv_width) as i64 as u64
    }

    /// The order of entries `a` and `b`: `(t_a, key_a, a)` against `(t_b, key_b, b)`
    /// ([`order`]), the keys read only for equal times. Times that compare unequal as floats
    /// decide at once (one compare each way); the rest go to [`order`], whose `total_cmp`
    /// also orders `-0` against `+0` and NaN (which [`order`]'s times never are), so the
    /// order is its own.
    #[inline]
    fn cmp(slots: &(impl Slots + ?Sized), a: &Entry, b: &Entry) -> std::cmp::Ordering {
        if a.time < b.time {
            return std::cmp::Ordering::Less;
        }
        if a.time > b.time {
            return std::cmp::Ordering::Greater;
        }
        let (ka, kb) = (slots.key(a.ball as usize), slots.key(b.ball as usize));
        order((a.time, ka), (b.time, kb)).then_with(|| a.ball.cmp(&b.ball))
    }

    /// Ball `ball`'s pending event is now at `time` (replacing any it had); its key is
    /// `slots.key(ball)`, already the new event's (the old key is never read: a ball is
    /// compared only at its new time).
    ///
    /// In place when the new time keeps the ball in the same bucket or in the overflow
    /// (`b >= c + B`); else a removal and an insertion.
    pub(crate) fn set(&mut self, slots: &mut (impl Slots + ?Sized), ball: usize, time: f64) {
        let b = self.bucket(time);
        let slot = *slots.slot(ball);
        let stays = match slot.place {
            Place::Bucket => b == self.bucket(slot.time),
            Place::Staged(at) => b == self.stage.bucket(at),
            Place::Overflow(_) => b.saturating_sub(self.current) >= self.buckets.count() as u64,
            _ => false,
        };
        slots.slot_mut(ball).time = time;
        if !stays {
            self.take_out(slots, ball, slot);
            self.insert(slots, ball as u32, b);
        }
    }

    /// Ball `ball` (pending at `time`) goes into bucket `b`'s place: the current bucket's
    /// list, a bucket or the overflow.
    #[inline]
    fn insert(&mut self, slots: &mut (impl Slots + ?Sized), ball: u32, b: u64) {
        if self.filling {
            slots.slot_mut(ball as usize).place = Place::Overflow(self.overflow.len() as u32);
            self.overflow.push(ball);
        } else if b <= self.current {
            let time = slots.slot(ball as usize).time;
            self.put_now(slots, Entry { time, ball });
        } else if b - self.current < self.buckets.count() as u64 {
            if self.staging {
                let insert = Change {
                    bucket: b,
                    ball,
                    insert: true,
                };
                let at = self.hold(slots, insert);
                slots.slot_mut(ball as usize).place = Place::Staged(at);
            } else {
                slots.slot_mut(ball as usize).place = Place::Bucket;
                self.buckets.push((b & self.mask()) as usize, ball);
            }
        } else {
            slots.slot_mut(ball as usize).place = Place::Overflow(self.overflow.len() as u32);
            self.overflow.push(ball);
        }
    }

    /// Ball `ball` has no pending event any more.
    pub(crate) fn remove(&mut self, slots: &mut (impl Slots + ?Sized), ball: usize) {
        let slot = *slots.slot(ball);
        self.take_out(slots, ball, slot);
    }

    /// Takes ball `ball`, whose slot was `slot`, out of its place (its place becomes
    /// [`Place::None`]).
    #[inline]
    fn take_out(&mut self, slots: &mut (impl Slots + ?Sized), ball: usize, slot: Slot) {
        slots.slot_mut(ball).place = Place::None;
        match slot.place {
            Place::None => {}
            Place::Now(at) => self.take_now(slots, at as usize),
            Place::Bucket if self.staging => {
                let remove = Change {
                    bucket: self.bucket(slot.time),
                    ball: ball as u32,
                    insert: false,
                };
                self.hold(slots, remove);
            }
            Place::Bucket => {
                let b = self.bucket(slot.time) & self.mask();
                self.buckets.remove(b as usize, ball as u32);
            }
            Place::Staged(at) => self.stage.cancel(at),
            Place::Overflow(at) => {
                self.overflow.swap_remove(at as usize);
                if let Some(&moved) = self.overflow.get(at as usize) {
                    slots.slot_mut(moved as usize).place = Place::Overflow(at);
                }
            }
        }
    }

    /// Notes the places of the current bucket's entries `from..to`.
    #[inline]
    fn renumber(&self, slots: &mut (impl Slots + ?Sized), from: usize, to: usize) {
        for (k, e) in self.now[from..to].iter().enumerate() {
            slots.slot_mut(e.ball as usize).place = Place::Now((from + k) as u32);
        }
    }

    /// Removes the entry at `at` of the current bucket, the shorter side moved up to close
    /// the gap (the earliest, at `head`, moves nothing).
    fn take_now(&mut self, slots: &mut (impl Slots + ?Sized), at: usize) {
        let (head, len) = (self.head, self.now.len());
        if at == head {
            // The earliest (a popped event's ball, set again): nothing moves.
            self.head = head + 1;
        } else if at - head < len - 1 - at {
            self.now.copy_within(head..at, head + 1);
            self.head = head + 1;
            self.renumber(slots, head + 1, at + 1);
        } else {
            self.now.copy_within(at + 1..len, at);
            self.now.pop();
            self.renumber(slots, at, len - 1);
        }
        if self.head == self.now.len() {
            self.now.clear();
            self.head = 0;
        }
    }

    /// Puts `entry` into the current bucket's sorted list at its place (a binary search),
    /// the shorter side moved aside to make room.
    fn put_now(&mut self, slots: &mut (impl Slots + ?Sized), entry: Entry) {
        let (head, len) = (self.head, self.now.len());
        let p = head + self.now[head..].partition_point(|e| Self::cmp(slots, e, &entry).is_lt());
        if head > 0 && p - head < len - p {
            self.now.copy_within(head..p, head - 1);
            self.head = head - 1;
            self.now[p - 1] = entry;
            self.renumber(slots, head - 1, p);
        } else {
            self.now.insert(p, entry);
            self.renumber(slots, p, len + 1);
        }
    }

    /// The earliest pending event `(t_i, i)` (least `(t_i, key_i, i)`), if any.
    pub(crate) fn peek(&mut self, slots: &mut (impl Slots + ?Sized)) -> Option<(f64, usize)> {
        while self.head == self.now.len() {
            if self.buckets.len() as isize + self.stage.net() == 0 {
                // The held changes (if any) leave every bucket empty.
                self.flush_stage(slots);
                // Every bucket is empty: jump to the overflow's earliest bucket.
                let first = self
                    .overflow
                    .iter()
                    .map(|&i| self.bucket(slots.slot(i as usize).time));
                self.current = first.min()?;
                self.reschedule_overflow(slots);
                continue;
            }
            self.current += 1;
            if self.current & self.mask() == 0 {
                // Balls of the overflow may reach the current bucket: merged in below.
                self.reschedule_overflow(slots);
            }
            let slot = (self.current & self.mask()) as usize;
            let mask = self.mask();
            let buckets = &mut self.buckets;
            self.stage
                .take(self.current, |change| apply(buckets, mask, slots, change));
            self.load(slots, slot);
        }
        let top = self.now[self.head];
        Some((top.time, top.ball as usize))
    }

    /// The ball whose event comes `k` after the earliest's, if the current bucket holds it
    /// (after [`Calendar::peek`]; `k = 0` is the earliest). Only as a hint of what comes
    /// next: the events between may change it.
    #[inline]
    pub(crate) fn upcoming(&self, k: usize) -> Option<usize> {
        self.now.get(self.head + k).map(|e| e.ball as usize)
    }

    /// Adds the balls of bucket `bucket` (just reached) to the current bucket's list, sorted
    /// once: a few comparisons a ball for the few balls of a bucket, and popping the earliest
    /// then moves nothing.
    fn load(&mut self, slots: &mut (impl Slots + ?Sized), bucket: usize) {
        let (keys, now) = (&*slots, &mut self.now);
        self.buckets.drain(bucket, |ball| {
            now.push(Entry {
                time: keys.slot(ball as usize).time,
                ball,
            })
        });
        self.sort_now(slots);
    }

    /// Sorts the current bucket's pending entries and notes their places.
    fn sort_now(&mut self, slots: &mut (impl Slots + ?Sized)) {
        let keys = &*slots;
        let pending = &mut self.now[self.head..];
        pending.sort_unstable_by(|a, b| Self::cmp(keys, a, b));
        self.renumber(slots, self.head, self.now.len());
    }

    /// Moves the overflow's balls within reach of the buckets into them (or the current
    /// bucket's list).
    fn reschedule_overflow(&mut self, slots: &mut (impl Slots + ?Sized)) {
        // The overflow and the (empty) scratch list trade places, so nothing is allocated.
        let scratch = std::mem::take(&mut self.scratch);
        let mut list = std::mem::replace(&mut self.overflow, scratch);
        for &ball in &list {
            let b = self.bucket(slots.slot(ball as usize).time);
            self.insert(slots, ball, b);
        }
        list.clear();
        self.scratch = list;
    }

    /// Sets every pending time `t_i` to `max(t_i - shift, 0)` (the clock's origin moved by
    /// `shift`) and chooses the bucket width again: `delta = 8 tbar / m` for `m` pending
    /// events whose mean time ahead is `tbar` (so about 8 per bucket), with `B >= m / 2`
    /// buckets, a power of two (a horizon `B delta` of 4 to 8 `tbar`). `O(balls)`.
    pub(crate) fn rebuild(&mut self, slots: &mut (impl Slots + ?Sized), shift: f64) {
        self.flush_stage(slots);
        self.filling = false;
        let mut pending = std::mem::take(&mut self.scratch);
        pending.clear();
        pending.extend(self.now[self.head..].iter().map(|e| e.ball));
        self.now.clear();
        self.head = 0;
        pending.append(&mut self.overflow);
        self.buckets.drain_all(|ball| pending.push(ball));
        let (mut sum, mut finite) = (0.0, 0usize);
        for &ball in &pending {
            let t = &mut slots.slot_mut(ball as usize).time;
            *t = (*t - shift).max(0.0);
            if t.is_finite() {
                sum += *t;
                finite += 1;
            }
        }
        let m = pending.len().max(1);
        let tbar = if finite > 0 { sum / finite as f64 } else { 0.0 };
        let width = 8.0 * tbar / m as f64;
        self.inv_width = if width > 0.0 && width.is_finite() {
            1.0 / width
        } else {
            1.0
        };
        let buckets = m.div_ceil(2).next_power_of_two();
        if self.buckets.count() != buckets {
            self.buckets.resize(buckets);
        }
        let bytes = self.buckets.bytes();
        self.staging = self.forced.unwrap_or(bytes >= STAGE_FROM_BYTES);
        self.current = 0;
        for &ball in &pending {
            let time = slots.slot(ball as usize).time;
            let b = self.bucket(time);
            if b == 0 {
                // The current bucket's list, sorted once below.
                self.now.push(Entry { time, ball });
            } else {
                self.insert(slots, ball, b);
            }
        }
        self.sort_now(slots);
        pending.clear();
        self.scratch = pending;
    }
}

/// A held change reaches its block (of the buckets `b mod B`, `mask = B - 1`).
#[inline]
fn apply(buckets: &mut Buckets, mask: u64, slots: &mut (impl Slots + ?Sized), change: Change) {
    let bucket = (change.bucket & mask) as usize;
    if change.insert {
        slots.slot_mut(change.ball as usize).place = Place::Bucket;
        buckets.push(bucket, change.ball);
    } else {
        buckets.remove(bucket, change.ball);
    }
}

#[cfg(test)]
#[path = "queue_tests.rs"]
mod tests;
