//! The calendar (`queue.rs`) against a sorted set of `(t, key, ball)`: an event loop of new
//! times (near, far, tied, none), removals and re-basings pops in the set's order; and empty
//! buckets are jumped over.

use super::*;
use std::collections::BTreeSet;

/// A calendar with its slots and keys in a plain list (the engine keeps them in its
/// balls' records).
struct Keyed {
    cal: Calendar,
    slots: Vec<(Slot, Key)>,
}

impl Slots for Vec<(Slot, Key)> {
    fn slot(&self, ball: usize) -> &Slot {
        &self[ball].0
    }
    fn slot_mut(&mut self, ball: usize) -> &mut Slot {
        &mut self[ball].0
    }
    fn key(&self, ball: usize) -> Key {
        self[ball].1
    }
}

impl Keyed {
    fn new(balls: usize) -> Self {
        Keyed {
            cal: Calendar::new(),
            slots: vec![(Slot::EMPTY, 0); balls],
        }
    }
    /// Ball `ball`'s event at `time` with `key`: the key changed first, in its slot (as
    /// the engine does), then the calendar told (in place where it can); for odd times'
    /// bits the event removed first (as before it changed).
    fn set(&mut self, ball: usize, time: f64, key: Key) {
        if time.to_bits() & 1 == 1 {
            self.cal.remove(&mut self.slots, ball);
        }
        self.slots[ball].1 = key;
        self.cal.set(&mut self.slots, ball, time);
    }
    fn remove(&mut self, ball: usize) {
        self.cal.remove(&mut self.slots, ball);
    }
    fn peek(&mut self) -> Option<(f64, usize)> {
        self.cal.peek(&mut self.slots)
    }
    fn rebuild(&mut self, shift: f64) {
        self.cal.rebuild(&mut self.slots, shift);
    }
    fn len(&self) -> usize {
        self.cal.len()
    }
}

/// A reference: the set of `(t_i, key_i, i)`, ordered as the calendar must pop them.
#[derive(Default)]
struct Reference {
    set: BTreeSet<(u64, Key, usize)>,
    time: std::collections::HashMap<usize, (f64, Key)>,
}

/// `t >= 0` (and +0.0) orders as its bits.
fn bits(t: f64) -> u64 {
    t.to_bits()
}

impl Reference {
    fn set(&mut self, i: usize, t: f64, key: Key) {
        self.remove(i);
        self.set.insert((bits(t), key, i));
        self.time.insert(i, (t, key));
    }
    fn remove(&mut self, i: usize) {
        if let Some((t, key)) = self.time.remove(&i) {
            self.set.remove(&(bits(t), key, i));
        }
    }
    fn first(&self) -> Option<(f64, usize)> {
        self.set
            .iter()
            .next()
            .map(|&(t, _, i)| (f64::from_bits(t), i))
    }
}

/// A small deterministic generator (xorshift64*).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Runs an event loop on both: pop the earliest, give its ball (and now and then another)
/// a new time ahead (near, far, tied, or none), re-base now and then; every pop agrees.
/// With `staged`, the calendar holds back its changes to the buckets ([`crate::stage`]),
/// whatever their size.
fn agree(balls: usize, steps: usize, seed: u64, staged: bool) {
    let mut rng = Rng(seed);
    let mut cal = Keyed::new(balls);
    cal.cal.force_staging(&mut cal.slots, Some(staged));
    let mut reference = Reference::default();
    let ahead = |rng: &mut Rng| match rng.below(10) {
        0 => 1e3 * rng.unit(),           // far: the overflow
        1 => 0.0,                        // now
        2 => 0.25 * rng.below(4) as f64, // ties
        _ => rng.unit(),
    };
    // Few keys, so that equal times often have equal keys too (then the ball decides).
    let key = |rng: &mut Rng| rng.below(4) as Key;
    for i in 0..balls {
        let (t, k) = (ahead(&mut rng), key(&mut rng));
        cal.set(i, t, k);
        reference.set(i, t, k);
    }
    cal.rebuild(0.0);
    let mut now = 0.0;
    for step in 0..steps {
        let got = cal.peek();
        assert_eq!(got, reference.first(), "step {step}");
        let Some((t, i)) = got else { break };
        assert!(t >= now);
        now = t;
        assert_eq!(cal.len(), reference.set.len());
        match rng.below(20) {
            0 => {
                cal.remove(i);
                reference.remove(i);
            }
            1 => {
                // Re-base: every time moves back by now; half the time through an open
                // calendar with a few balls re-predicted meanwhile (the engine's way).
                if rng.below(2) == 0 {
                    cal.cal.open(&mut cal.slots);
                    for _ in 0..3 {
                        let j = rng.below(balls);
                        let (t, k) = (now + ahead(&mut rng), key(&mut rng));
                        cal.set(j, t, k);
                        reference.set(j, t, k);
                    }
                }
                cal.rebuild(now);
                reference.set.clear();
                let times: Vec<(usize, (f64, Key))> = reference.time.drain().collect();
                for (j, (tj, k)) in times {
                    reference.set(j, (tj - now).max(0.0), k);
                }
                now = 0.0;
            }
            _ => {
                let (t, k) = (now + ahead(&mut rng), key(&mut rng));
                cal.set(i, t, k);
                reference.set(i, t, k);
            }
        }
        // Another ball re-predicted (a partner), or one that had none gets one.
        let j = rng.below(balls);
        if rng.below(3) == 0 {
            let (t, k) = (now + ahead(&mut rng), key(&mut rng));
            cal.set(j, t, k);
            reference.set(j, t, k);
        }
    }
}

#[test]
fn pops_in_time_then_key_then_ball_order_like_a_sorted_set() {
    for (balls, seed) in [(1, 1), (2, 2), (7, 3), (100, 4), (1000, 5)] {
        agree(balls, 20_000, seed, false);
    }
}

#[test]
fn changes_held_back_pop_in_the_same_order() {
    // The ring holds 32 changes: with 1000 balls many are held, evicted and taken as their
    // buckets are reached; with 7, a ball's insertion is often cancelled while held.
    for (balls, seed) in [(1, 1), (2, 2), (7, 3), (100, 4), (1000, 5), (5000, 6)] {
        agree(balls, 20_000, seed, true);
    }
}

#[test]
fn far_events_and_empty_buckets_are_reached() {
    let mut cal = Keyed::new(3);
    cal.set(0, 1.0, 0);
    cal.set(1, 2.0, 0);
    cal.rebuild(0.0);
    // Far beyond the horizon, then the near ones go away: a jump over empty buckets.
    cal.set(2, 1e12, 0);
    assert_eq!(cal.peek(), Some((1.0, 0)));
    cal.remove(0);
    cal.remove(1);
    assert_eq!(cal.peek(), Some((1e12, 2)));
    cal.set(2, f64::INFINITY, 0);
    assert_eq!(cal.peek(), Some((f64::INFINITY, 2)));
    cal.remove(2);
    assert_eq!((cal.peek(), cal.len()), (None, 0));
}
