//! Deciding that no contact will ever happen again (`crate::no_contact`), and noticing long
//! stretches without one, as the cell engine does: a gas whose balls all fly at one velocity,
//! or a single ball, would otherwise leave and draw its shells forever. Checked at the first
//! step and then after `max(1024, 2 balls)`, twice, four times that many events without a
//! contact; the exact pair test is run when its cost is at most `max(2^20, 16 quiet)` pair
//! checks, so `O(1)` per event. The notices come at the checks once the slowest moving ball
//! has flown 1000, 2000, 4000 ... box lengths (the longest side) since the last contact.

use super::ListSimulation;
use crate::canonical::fold;
use crate::no_contact::{slowest, Flight, NoContact};
use crate::PairKernels;

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> ListSimulation<N, S, K> {
    /// Events without a contact before the first check after a contact.
    pub(super) fn first_check(&self) -> u64 {
        (2 * self.len() as u64).max(1024)
    }

    /// Box lengths (the longest side) the slowest moving ball flew since the last contact (0
    /// if every ball is at rest).
    pub(super) fn quiet_travel(&self) -> f64 {
        let longest = self.size.iter().copied().fold(0.0, f64::max);
        slowest((0..self.len()).map(|s| self.speed2_of(s)))
            .map_or(0.0, |v| (self.now - self.last_contact) * v / longest)
    }

    /// Whether no contact can happen again ([`NoContact`]).
    pub(super) fn no_contact(&self) -> Option<NoContact> {
        // The balls in slot order: the decision is about the set of flights.
        let position = |s: usize| {
            let x = self.flights[s].motion.at(self.now);
            fold(&x, &self.size, &self.periodic)
        };
        let velocity = |s: usize| self.balls[s].state.velocity;
        let radius = |s: usize| self.flights[s].motion.radius;
        let flight = Flight {
            size: self.size,
            periodic: self.periodic,
            position: &position,
            velocity: &velocity,
            radius: &radius,
            balls: self.len(),
            obstacles: &[],
        };
        flight.decide(self.quiet, true)
    }
}
