//! Contacts that keep coming at one instant: an inelastic collapse the run cannot get past.
//!
//! Without the TC model a dissipative law can make contacts accumulate at one instant, as
//! in exact dynamics they accumulate before a finite time (McNamara & Young's inelastic
//! collapse): a ball driven into an acute corner of walls at `e < 1`, or pressed into a
//! corner of the box by another ball at `e = 0`, or three balls left touching at `e = 0`.
//! Once the flight times between the contacts round to 0 (the speeds shrink geometrically
//! towards subnormal numbers, or the states stop changing), every further contact comes at
//! the same time and the run never ends (it used to loop forever with `--time` and no event
//! limit). Balls in contact at one instant are few at once (at most the kissing number, 72
//! in 6D, and the walls), so a ball in more than [`MAX_CONTACTS_AT_ONCE`] contacts at one
//! instant, its centre not moving, is caught in such a loop. The run loop ([`crate::run`]) stops there with a
//! [`Collapse`], which the front ends report as an error naming the balls (exit 2, a Python
//! `InputError`); the TC model (`[contact] tc`) is the cure: a contact within `t_c` of a
//! ball's previous one is elastic.

use crate::Event;
use std::collections::HashMap;
use std::fmt;

/// Contacts of one ball at one instant beyond which the run stops (module docs).
pub const MAX_CONTACTS_AT_ONCE: u32 = 1000;

/// Contacts within this many ulps of the first contact's time are at one instant.
const SAME_INSTANT_ULPS: u64 = 4;

/// An inelastic collapse: contacts at one instant, `time`, that did not end.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Collapse {
    /// The absolute time of the instant.
    pub time: f64,
    /// The contacts made at it.
    pub contacts: u64,
    /// The balls in at least a tenth as many contacts at it as the busiest, the busiest
    /// first (at most 16).
    pub balls: Vec<usize>,
}

impl fmt::Display for Collapse {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        let balls: Vec<String> = self.balls.iter().map(|b| b.to_string()).collect();
        write!(
            f,
            "inelastic collapse at t = {}: {} contacts at that instant (ball{} {}, their \
             centres not moving), and more would follow without end, which an event-driven run \
             cannot get past; set [contact] tc, or a longer t_c if it is set (the TC model: a \
             contact within t_c of a ball's previous one is elastic), or raise e \
             (docs/granular.md)",
            self.time,
            self.contacts,
            if self.balls.len() == 1 { "" } else { "s" },
            balls.join(", ")
        )
    }
}

/// Balls of one instant found by a linear search up to this many; beyond, through an index.
const LINEAR: usize = 16;

/// The contacts of the current instant, per ball: their count, and the ball's centre at the
/// first of them (its bits). Nothing is allocated once the lists have grown, and nothing is
/// hashed while an instant holds at most 16 balls (every instant but a lattice
/// start's or a collapse's): a run records every contact here.
#[derive(Debug, Default)]
pub struct Streak {
    start: f64,
    contacts: u64,
    /// The balls of the instant, in the order met, each with its contacts at it.
    balls: Vec<(usize, u32)>,
    /// Ball `balls[k]`'s centre (the bits of its `n` coordinates) at `centres[k n..(k + 1) n]`.
    centres: Vec<u64>,
    /// Where each ball is in `balls`, once the instant holds more than [`LINEAR`] balls.
    index: HashMap<usize, usize>,
}

impl Streak {
    /// Takes the next contact; a [`Collapse`] once a ball has more than
    /// [`MAX_CONTACTS_AT_ONCE`] contacts at one instant.
    pub fn record<const N: usize, const S: usize>(&mut self, e: &Event<N, S>) -> Option<Collapse> {
        let within =
            f64::from_bits(self.start.abs().to_bits() + SAME_INSTANT_ULPS) - self.start.abs();
        // A later time (or a NaN one) starts a new instant.
        let same = e.time - self.start <= within;
        if self.contacts == 0 || !same {
            self.start = e.time;
            self.contacts = 0;
            self.balls.clear();
            self.centres.clear();
            if !self.index.is_empty() {
                self.index.clear();
            }
        }
        self.contacts += 1;
        let mut busiest = 0;
        for (k, b) in e.contact.balls().enumerate() {
            // A ball counts only while its centre stays put: at a huge absolute time a few ulps
            // of it hold many true flights, which move the centre (an elastic run at `t =
            // 1e61` was once taken for a collapse).
            let at = e.position[k].map(f64::to_bits);
            let c = match self.find(b) {
                Some(p) => {
                    let centre = &mut self.centres[p * N..(p + 1) * N];
                    let count = &mut self.balls[p].1;
                    if *centre != at {
                        centre.copy_from_slice(&at);
                        *count = 0;
                    }
                    *count += 1;
                    *count
                }
                None => {
                    self.balls.push((b, 1));
                    self.centres.extend_from_slice(&at);
                    let p = self.balls.len() - 1;
                    if !self.index.is_empty() {
                        self.index.insert(b, p);
                    } else if self.balls.len() > LINEAR {
                        self.index
                            .extend(self.balls.iter().enumerate().map(|(p, &(b, _))| (b, p)));
                    }
                    1
                }
            };
            busiest = busiest.max(c);
        }
        (busiest > MAX_CONTACTS_AT_ONCE).then(|| self.collapse())
    }

    /// Ball `b`'s place in `balls`, if it has a contact at this instant.
    fn find(&self, b: usize) -> Option<usize> {
        if self.index.is_empty() {
            self.balls.iter().position(|&(x, _)| x == b)
        } else {
            self.index.get(&b).copied()
        }
    }

    fn collapse(&self) -> Collapse {
        let most = self.balls.iter().map(|v| v.1).max().unwrap_or(0);
        let mut balls: Vec<(usize, u32)> = (self.balls.iter())
            .filter(|&&(_, c)| 10 * c >= most)
            .copied()
            .collect();
        balls.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        Collapse {
            time: self.start,
            contacts: self.contacts,
            balls: balls.iter().take(16).map(|&(b, _)| b).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Streak, MAX_CONTACTS_AT_ONCE};
    use crate::{Contact, Event};

    fn event(time: f64, contact: Contact) -> Event<2, 1> {
        Event::at_rest_but(time, contact, [0.0, 0.0])
    }

    #[test]
    fn a_ball_caught_at_one_instant_is_named_and_a_moving_clock_resets() {
        let wall = |i| Contact::Boundary { i, boundary: 0 };
        let pair = |i, j| Contact::Ball { i, j };
        let mut streak = Streak::default();
        // Contacts at advancing times never collapse, however many.
        for k in 0..5000 {
            assert_eq!(
                streak.record(&event(1.0 + k as f64 * 1e-9, pair(1, 2))),
                None
            );
        }
        // Many balls at one instant, a few contacts each (a lattice start): no collapse.
        for b in 0..10_000 {
            assert_eq!(streak.record(&event(2.0, pair(b, b + 1))), None);
        }
        // Ball 7 with ball 3 and a wall at one instant, within an ulp or two.
        let t: f64 = 3.0;
        let mut found = None;
        for k in 0..(2 * MAX_CONTACTS_AT_ONCE) {
            let time = f64::from_bits(t.to_bits() + u64::from(k % 3));
            let c = if k % 2 == 0 { pair(3, 7) } else { wall(7) };
            if let Some(c) = streak.record(&event(time, c)) {
                found = Some((k, c));
                break;
            }
        }
        let (k, c) = found.expect("a collapse");
        assert_eq!(k, MAX_CONTACTS_AT_ONCE);
        assert_eq!(
            (c.time, c.contacts),
            (t, u64::from(MAX_CONTACTS_AT_ONCE) + 1)
        );
        assert_eq!(c.balls, vec![7, 3]);
        let m = c.to_string();
        assert!(
            m.contains("balls 7, 3") && m.contains("[contact] tc"),
            "{m}"
        );
        // A later time starts a new instant.
        assert_eq!(streak.record(&event(3.5, wall(7))), None);
        // An instant of more balls than the linear search holds: ball 25, met after 40 others
        // (found through the index), is caught; a move of its centre restarts its count.
        for b in 0..40 {
            assert_eq!(streak.record(&event(4.0, wall(100 + b))), None);
        }
        let mut moved = event(4.0, wall(25));
        moved.position = [[1.0, 0.0], [1.0, 0.0]];
        for _ in 0..MAX_CONTACTS_AT_ONCE {
            assert_eq!(streak.record(&moved), None);
        }
        let mut found = None;
        for k in 0..=MAX_CONTACTS_AT_ONCE {
            if let Some(c) = streak.record(&event(4.0, wall(25))) {
                found = Some((k, c));
                break;
            }
        }
        let (k, c) = found.expect("a collapse");
        assert_eq!(k, MAX_CONTACTS_AT_ONCE);
        assert_eq!(c.balls, vec![25]);
        assert_eq!(c.contacts, 40 + 2 * u64::from(MAX_CONTACTS_AT_ONCE) + 1);
        // At a huge absolute time a few ulps hold many true flights: one time, moving centres
        // (an elastic pair at t = 1e61): not a collapse.
        for k in 0..(3 * MAX_CONTACTS_AT_ONCE) {
            let mut e = event(1e61, pair(5, 6));
            e.position = [[k as f64, 0.0], [k as f64 + 1.0, 0.0]];
            assert_eq!(streak.record(&e), None);
        }
    }
}
