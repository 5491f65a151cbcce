//! A gas cooled out of the f64 range: the speeds whose squares underflow.
//!
//! The engine computes contact times and laws from squared speeds and distances. Scenes
//! refuse a start whose nonzero speeds square below the least normal f64 (`|u| <
//! sqrt(f64::MIN_POSITIVE)`, about `1.5e-154`); a dissipative run that cools for long enough
//! (one ball in a box at `e = 0.001` does in about 50 contacts) reaches that range on its own.
//! There the predictions fail (a ball seen outside its container, a Walton contact with the
//! wrong `beta`) and the clock overflows to infinity (a log of `null` times), where runs used
//! to go on and end with "every ball is at rest". The run loop ([`crate::run`]) checks the
//! balls of each contact and stops at the first whose speed is below that range, with a
//! [`BelowRange`] that the front ends report as an error (exit 2, a Python `InputError`).

use crate::Event;
use std::fmt;

/// Ball `ball` left the contact at absolute time `time` with speed `speed`, nonzero and below
/// `sqrt(f64::MIN_POSITIVE)` (or the time is not finite, `speed` then the ball's speed).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BelowRange {
    /// The ball's index.
    pub ball: usize,
    /// Its speed `|u|` after the contact.
    pub speed: f64,
    /// The absolute time of the contact.
    pub time: f64,
}

impl fmt::Display for BelowRange {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(
            f,
            "the gas cooled out of the f64 range: ball {} left its contact at t = {:e} with \
             speed {:e}, whose square is below the least normal f64 (speeds below {:e}, which \
             scenes refuse at the start), where contact times and laws lose their precision; \
             end the run earlier (--events, --time), or keep the gas from cooling without end \
             (a [thermostat], or the TC model's elastic contacts)",
            self.ball,
            self.time,
            self.speed,
            f64::MIN_POSITIVE.sqrt()
        )
    }
}

/// The first ball of contact `e` whose speed after it is nonzero and below the range, or any
/// ball of it if the contact's time is not finite.
pub fn below_range<const N: usize, const S: usize>(e: &Event<N, S>) -> Option<BelowRange> {
    e.contact.balls().enumerate().find_map(|(slot, ball)| {
        let u = &e.post[slot].velocity;
        let u2: f64 = u.iter().map(|x| x * x).sum();
        let moving = u.iter().any(|&x| x != 0.0);
        let slow = moving && u2 < f64::MIN_POSITIVE;
        (slow || !e.time.is_finite()).then(|| BelowRange {
            ball,
            // The largest component where the sum of squares underflows to 0.
            speed: u2.sqrt().max(u.iter().fold(0.0f64, |m, x| m.max(x.abs()))),
            time: e.time,
        })
    })
}

#[cfg(test)]
mod tests {
    use super::below_range;
    use crate::{Contact, Event};

    fn wall_contact(time: f64, u: [f64; 2]) -> Event<2, 1> {
        Event::at_rest_but(time, Contact::Boundary { i: 4, boundary: 0 }, u)
    }

    #[test]
    fn a_speed_whose_square_underflows_or_an_infinite_time_is_below_the_range() {
        let least = f64::MIN_POSITIVE.sqrt();
        // At rest, or at the least speed the start allows: in range.
        assert_eq!(below_range(&wall_contact(1.0, [0.0, 0.0])), None);
        assert_eq!(below_range(&wall_contact(1.0, [least * 1.0001, 0.0])), None);
        // One tiny component beside a normal speed: in range.
        assert_eq!(below_range(&wall_contact(1.0, [1.0, 1e-300])), None);
        // Below: named, with its speed.
        let b = below_range(&wall_contact(2.0, [1e-160, -1e-161])).expect("below");
        assert_eq!((b.ball, b.time), (4, 2.0));
        assert!((b.speed - 1e-160).abs() < 1e-161, "{b:?}");
        assert!(b.to_string().contains("ball 4") && b.to_string().contains("[thermostat]"));
        // An infinite clock.
        assert!(below_range(&wall_contact(f64::INFINITY, [1.0, 0.0])).is_some());
    }
}
